// The measured cost of each variant that the report joins with the trade table, kept in the
// planner's two schemas (saagen/scene/cost_tables.hpp): bench_shading's rows (a MeasuredTradeTable:
// GPU time ratio and SPIR-V instruction delta per target) and the ISA table (an IsaTable: ACO's
// inverse-throughput ratios, `saagen bench --isa`). The report reads the same figures the planner
// ranks `prefer = "speed"` by; nothing here parses or stores a figure of its own.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <saagen/scene/cost_tables.hpp>
#include <string>
#include <string_view>

namespace saagen::report {

// One variant's cost, averaged over the targets the tables measured.
struct VariantCost {
  std::optional<double> time_ratio;          // GPU time with the variant / without SAA
  std::optional<double> delta_instructions;  // optimized SPIR-V instructions added
  // The primary cost model when measured: ACO's inverse throughput of the forward-shading
  // fragment shader with the variant / without SAA at one light (as the trade renders), on
  // CostTable::isa_family, mean over GLSL and HLSL (IsaTable::forward_ratio).
  std::optional<double> isa_ratio;
};

struct CostTable {
  std::string source;           // the bench_shading file `timing` was read from ("": none)
  MeasuredTradeTable timing;    // bench_shading --json
  std::optional<IsaTable> isa;  // `saagen bench --isa FAMILIES`
  std::string isa_family;       // the family of VariantCost::isa_ratio (the first of --isa)
  // The variant's means; nullopt when neither table has it.
  std::optional<VariantCost> find(std::string_view variant) const;
  // One line naming the cost model of each cost column.
  std::string describe() const;
  // The timing that costs the verdict's decisions (measure::TradeTable::decision_timing): `timing`
  // where it is a GPU's (bench_shading's baseline row on a device that is not a CPU); null
  // otherwise (lavapipe's ratios never decide; the committed ISA model does).
  std::shared_ptr<const MeasuredTradeTable> decision_timing() const;
};

// Reads bench_shading's --json output through the planner's parser; throws saagen::Error with the
// file name on bad input.
CostTable load_cost_table(const std::filesystem::path& path);

}  // namespace saagen::report
