// The ISA cost model of the trade report: every SAA variant's shaders compiled by Mesa's ACO for
// real AMD GPU families on RADV's null-hardware devices (saagen/harness/isa.hpp), nothing
// executed. Per family, variant and target (GLSL, HLSL) it reads, for the forward-shading
// fragment shader bench_shading times (shading_scene.hpp) and for the deferred roughness-limiter
// compute pass, the ISA statistics and their ratio to the same shader without SAA. The forward
// shader is measured at every count of kMeasuredLightCounts (1, 4, 16 lights; shading_scene.hpp
// says what a form pays per pixel and per light), each against no SAA at the same count.
//
// `saagen bench --isa FAMILY[,FAMILY]` prints format_isa_table() and puts isa_json() into the trade
// JSON; the planner's committed table (generator/data/isa_cost.json) is isa_json() of vega10 and
// navi21 (`saagen bench --isa vega10,navi21 --isa-table FILE` regenerates it).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <saagen/harness/isa.hpp>
#include <saagen/scene/cost_tables.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace saagen::report {

// Which shader a row measures.
inline constexpr const char* isa_forward_shader = "forward";         // the bench_shading fragment shader
inline constexpr const char* isa_deferred_shader = "deferred-pass";  // the deferred compute pass
inline constexpr const char* isa_baseline = "no-saa";                // the variant id of the baselines

struct IsaCostRow {
  std::string family;
  std::string shader;   // isa_forward_shader or isa_deferred_shader
  std::string target;   // glsl or hlsl
  std::string variant;  // a catalogue variant, a deferred pass id, or isa_baseline
  harness::IsaStatistics statistics;
  harness::IsaStatistics baseline;  // the same shader without SAA (the copy pass for deferred-pass)
  std::uint32_t lights = 1;         // lights the forward shader shades (the deferred pass: always 1)
  double instructions_ratio() const { return statistics.instructions / baseline.instructions; }
  double inverse_throughput_ratio() const { return statistics.inverse_throughput / baseline.inverse_throughput; }
  double latency_ratio() const { return statistics.latency / baseline.latency; }
};

struct IsaCostTable {
  std::string driver;  // e.g. "Mesa 22.3.6"
  std::vector<std::string> families;
  std::vector<IsaCostRow> rows;  // baselines first per family, shader, target and light count
};

// Families from "vega10,navi21": each must be one of harness::isa_families(). Throws
// saagen::Error with the allowed names.
std::vector<std::string> parse_isa_families(const std::string& list);

using IsaProgressFn = std::function<void(const std::string&)>;
IsaCostTable measure_isa_costs(const std::vector<std::string>& families, const IsaProgressFn& progress = {});

// The measurement as the planner reads it: the rows of isa_json() in the one schema of an ISA
// cost table (saagen::IsaTable, saagen/scene/cost_tables.hpp), whose forward_ratio() is every
// mean ratio the report and the CLI print.
IsaTable isa_table(const IsaCostTable& table);

// Terminal tables: per family and shader, variant x target with instructions, VGPRs, SGPRs,
// subgroups per SIMD, latency, inverse throughput and the ratios to no SAA at one light, next to
// the paper's Table 2 ratio (forward shader); then format_light_count_table.
std::string format_isa_table(const IsaCostTable& table);
// The light-count table: every configuration x family x light count, its forward shader's
// inverse-throughput ratio to no SAA with the same lights (IsaTable::forward_ratio, all targets).
std::string format_light_count_table(const IsaCostTable& table);

// {"cost_model": "...", "driver", "rows": [{"family", "shader", "target", "variant",
// "instructions", "vgprs", "sgprs", "subgroups_per_simd", "latency", "inverse_throughput",
// "instructions_ratio", "inverse_throughput_ratio", "latency_ratio", "lights" (forward rows)}]}
nlohmann::json isa_json(const IsaCostTable& table);

}  // namespace saagen::report
