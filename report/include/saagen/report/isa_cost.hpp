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

#include <functional>
#include <optional>
#include <saagen/scene/cost_tables.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace saagen::report {

// Which shader a row measures.
inline constexpr const char* isa_forward_shader = "forward";         // the bench_shading fragment shader
inline constexpr const char* isa_deferred_shader = "deferred-pass";  // the deferred compute pass
inline constexpr const char* isa_baseline = kCostBaselineId;         // the variant id of the baselines

// Families from "vega10,navi21": each must be one of harness::isa_families(). Throws
// saagen::Error with the allowed names.
std::vector<std::string> parse_isa_families(const std::string& list);

using IsaProgressFn = std::function<void(const std::string&)>;
// The measurement in the one schema of an ISA cost table (saagen::IsaTable,
// saagen/scene/cost_tables.hpp), which the planner, the report and the CLI read: per family the
// baselines first, then every variant, per shader, target and light count; each row's ratios are
// over its baseline, and `devices` names each family's device.
IsaTable measure_isa_costs(const std::vector<std::string>& families, const IsaProgressFn& progress = {});

// Terminal tables: per family and shader, variant x target with instructions, VGPRs, SGPRs,
// subgroups per SIMD, latency, inverse throughput and the ratios to no SAA at one light, next to
// the paper's Table 2 ratio (forward shader); then format_light_count_table.
std::string format_isa_table(const IsaTable& table);
// The light-count table: every configuration x family x light count, its forward shader's
// inverse-throughput ratio to no SAA with the same lights (IsaTable::forward_ratio, all targets).
std::string format_light_count_table(const IsaTable& table);

// The cost table (saagen/scene/cost_tables.hpp) of the ISA model: {"cost_model": "...", "driver",
// "devices": {FAMILY: DEVICE}, "families", "rows": [{"device": FAMILY, "shader", "target", "variant",
// "cost_ratio" (the inverse-throughput ratio), "lights" (forward rows), and the model's own
// "instructions", "vgprs", "sgprs", "subgroups_per_simd", "latency", "inverse_throughput",
// "instructions_ratio", "latency_ratio"}]}
nlohmann::json isa_json(const IsaTable& table);

}  // namespace saagen::report
