// The measured cost of each variant that the report joins with the trade table: bench_shading's
// GPU time ratio and SPIR-V instruction delta, and ACO's inverse-throughput ratio
// (`saagen bench --isa`).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace saagen::report {

// One variant's cost, averaged over the targets bench_shading measured.
struct VariantCost {
  std::string variant;
  std::optional<double> time_ratio;          // GPU time with the variant / without SAA
  std::optional<double> delta_instructions;  // optimized SPIR-V instructions added
  // The primary cost model when measured (`saagen bench --isa`, isa_cost.hpp): ACO's inverse
  // throughput of the forward-shading fragment shader with the variant / without SAA, on
  // CostTable::isa_family, mean over GLSL and HLSL.
  std::optional<double> isa_ratio;
};

struct CostTable {
  std::string source;      // the file it was read from ("" when only ISA figures are known)
  std::string device;      // as bench_shading reported it
  std::string isa_family;  // the family of VariantCost::isa_ratio ("" when not measured)
  std::vector<VariantCost> rows;
  const VariantCost* find(std::string_view variant) const;
  // One line naming the cost model of each cost column.
  std::string describe() const;
};

// Adds the ISA inverse-throughput ratios of `family` (variant -> ratio) to `table`.
void add_isa_costs(CostTable& table, const std::string& family, const std::vector<std::pair<std::string, double>>& ratios);

// Reads bench_shading's --json output; throws saagen::Error with the file name on bad input.
CostTable load_cost_table(const std::filesystem::path& path);

}  // namespace saagen::report
