// What the planner measures variants by: the trade table a run of `bench_shading --json` or
// `saagen bench --json` writes (`plan --trade-table`), and the ISA cost table committed as
// generator/data/isa_cost.json. Manifests name the table's GPU families (gpu_family).
#pragma once

#include "saagen/decision.hpp"
#include "saagen/io/marker.hpp"

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace saagen {

// The cost table: one JSON form for every cost the planner, the report and the scripts read, written
// by `bench_shading --json` (a device's time ratios) and `saagen bench --isa ... --isa-table` (ACO's
// ISA model, generator/data/isa_cost.json): {"cost_model": what the ratios measure, "rows":
// [{"device", "shader", "target", "variant", "lights", "cost_ratio", ...}]}, each row a shader
// ("forward": bench_shading's scene with `lights` lights; "deferred-pass") of one target and
// variant on one device (an ISA family or the timed device), and cost_ratio its cost over the
// same shader without SAA (kCostBaselineId) with as many lights. A model's own measures follow in
// the row (ISA: instructions, vgprs, inverse_throughput, ...; time: ms_median, ratio_p25, ...), and
// one parser reads the shared keys of both (cost_tables.cpp, read_cost_row). A trade table's
// summary "rows" (`saagen bench --json`) use the same keys for what they share ("variant",
// "target", "cost_ratio") and add the trade's own ("error", "isa_family",
// "isa_inverse_throughput_ratio", "delta_spirv_instructions"). Rows of several targets are
// averaged per variant.
struct MeasuredTradeRow {
  OutputTarget target;  // read once from the row's "target" text
  std::string variant;
  std::optional<double> cost_ratio;          // cost_ratio: time with the variant / without SAA
  std::optional<double> delta_instructions;  // delta_spirv_instructions
  std::optional<double> error;               // error
  std::optional<double> isa_ratio;           // isa_inverse_throughput_ratio (`saagen bench --isa`)
  std::string isa_family;                    // isa_family: the GPU family of isa_ratio
};

// One measured cell, a scene at one GGX alpha, on which a configuration loses to no SAA beyond the
// interval in either metric (loses or mixed there; `saagen bench --json`: a by_content row's
// "loses_at": [{"scene", "alpha"}]).
struct CellLoss {
  std::string scene;
  double alpha = 0.0;
};

// A material's GGX alpha range (alpha = perceptual roughness squared; one value: low = high).
struct AlphaRange {
  double low = 0.0, high = 0.0;
};

// The measured alphas a material's range is judged at: every measured alpha inside it and the
// nearest measured one on either side, so that an alpha between two measured ones is judged by
// both (below the smallest or above the largest: that one). A measured alpha within kAlphaMatch
// of an end counts as inside: a roughness written to three digits (0.316 for alpha 0.1) squares to
// within 0.2 % of the alpha it names. `measured` ascending; empty: none.
inline constexpr double kAlphaMatch = 0.01;
std::vector<double> bracketing_alphas(const std::vector<double>& measured, AlphaRange range);

// The losses among `losses` at the alphas `alphas` (bracketing_alphas), each as "SCENE at alpha A".
std::vector<std::string> cells_lost_at(const std::vector<CellLoss>& losses, const std::vector<double>& alphas);

// `saagen bench --json` also writes, per content type ("curved", "normal-mapped", "bump",
// "clearcoat": an asset's coat lobe), the verdict's mean errors of every measured configuration: a
// variant, "VARIANT:geometric" (fed the geometric normal) and "VARIANT[:geometric]+toksvig|+lean"
// (with a prefiltered normal map). One schema for a trade table's "by_content" and
// "taa_by_content" rows and the advice's rows, read by one parser (cost_tables.cpp,
// parse_content_row).
struct ContentRow {
  std::string content;
  std::string configuration;
  double error = 0.0;              // the image error ("image_error": LDR-FLIP per frame)
  std::optional<double> temporal;  // the temporal error ("video_error", else "flicker_error"), when the table has it
  // The row minus no SAA's with 95 % intervals, when the table carries one ("against_none":
  // {"image": {"mean", "low", "high"}, "temporal": {...}}); comparison_against prefers it.
  std::optional<decision::Comparison> against_none;
  // The content's scenes on which the row loses to no SAA beyond the interval ("loses_on"; the
  // decision never takes such a row for the content: decision::Candidate::loses_on).
  std::vector<std::string> loses_on = {};
  // The configurations the row is worse than beyond the interval in neither metric, paired on the
  // same cells ("not_worse_than": decision::Candidate::not_worse_than, the decision's ties).
  std::vector<std::string> not_worse_than = {};
  // Where the row beats no SAA over the content: the cells (a scene at one alpha) on which it
  // loses ("loses_at"). A material that states its roughness is not given a configuration that
  // loses at the alphas that bracket it (planner.hpp).
  std::vector<CellLoss> loses_at = {};
};

// The one adapter from a trade table's measurements to a decision's comparison
// (saagen/decision.hpp): `row` minus `baseline` (no SAA's row of the same content or scene, or an
// engine's). A row that carries its comparison with no SAA (ContentRow::against_none, intervals
// included) is compared with no SAA by that; otherwise each difference is the difference of the
// means, with low = high = mean, and a row without a temporal error compares as tied in the
// temporal metric.
decision::Comparison comparison_against(const ContentRow& row, const ContentRow& baseline);

// A row as a material judged at the measured `alphas` (bracketing_alphas) sees it: its loses_on
// also names its cells lost at those alphas ("SCENE at alpha A"), so that the one decision never
// gives it that material.
void add_cell_losses(ContentRow& row, const std::vector<double>& alphas);

struct MeasuredTradeTable {
  std::string source_name;
  std::string device = "unknown device";  // "device": what bench_shading timed on
  std::vector<MeasuredTradeRow> rows;
  std::vector<ContentRow> content_rows;
  // Under TAA (`saagen bench --taa`, "taa_by_content"): the configurations without "+taa", "none"
  // being none+taa, each compared with none+taa.
  std::vector<ContentRow> taa_content_rows;
  // The GGX alphas the by-content rows were measured at ("alphas", ascending; empty: not given).
  std::vector<double> alphas;
  // Whether its projected forward filters were measured with their *_transported_fragment
  // wrappers ("half_vector_frame": "transported", `saagen bench`'s default); a table without the
  // key was measured with the papers' wrappers.
  bool forward_transported = false;
  // Mean of one of a variant's figures over the rows (targets) that have it; nullopt when none has.
  std::optional<double> mean(std::string_view variant, std::optional<double> MeasuredTradeRow::*figure) const;
  // Mean cost of a variant: the time ratio when any row has one, else the SPIR-V delta.
  std::optional<double> cost(std::string_view variant) const;
  std::optional<double> error(std::string_view variant) const;
  // Mean ISA inverse-throughput ratio of a variant on `family`, when the table has one.
  std::optional<double> isa_cost(std::string_view variant, std::string_view family) const;
  bool has_errors() const;
  // "lights": the lights per pixel bench_shading timed (--lights; 1 where not given).
  int lights = 1;
  // Whether the rows are a device's timings: bench_shading's table, whose baseline row
  // (kCostBaselineId) carries a time ratio. `saagen bench --json` writes none; its ratios are the
  // trade's cost column (lavapipe's time by default), which the plan does not cost by.
  // parse_trade_table sets it.
  bool device_timing = false;
  bool is_device_timing() const { return device_timing; }
  // Whether the rows are a device's timings taken at `material_lights` lights per pixel: the
  // timings that cost a material's plan (at another count the ISA model does).
  bool timed_at(int material_lights) const { return device_timing && lights == material_lights; }
  // A timed variant's median time ratio to no SAA, the mean over its targets.
  std::optional<double> device_time_ratio(std::string_view variant) const;
  // The device's name without bench_shading's details ("NVIDIA H200").
  std::string device_name() const { return device.substr(0, device.find(" (")); }
  // Whether bench_shading timed a CPU device (lavapipe: "... (CPU, Vulkan ...)" in "device").
  bool timed_on_cpu() const { return device.find("(CPU, Vulkan") != std::string::npos; }
  // The device timing `saagen bench --cost FILE` decided its verdict with ("device_timing" in its
  // JSON: FILE as bench_shading wrote it, read by this parser), so that a plan of this table costs
  // its decisions as the bench did. Null where the bench decided by the ISA model.
  std::shared_ptr<const MeasuredTradeTable> decision_timing;
  // The device timing that costs this table's decisions: its own rows where it is bench_shading's
  // table, else the bench's decision_timing; null where the ISA model does.
  const MeasuredTradeTable* timing() const { return device_timing ? this : decision_timing.get(); }
};

// The GPU cost model of `prefer = "speed"`: ISA statistics of Mesa's ACO compiler for AMD GPU
// families (RADV null hardware), as `saagen bench --isa FAMILIES --isa-only --isa-table FILE`
// writes them. The planner runs where no Vulkan driver may be installed (a build machine, the
// CMake helper), so it reads the table committed as generator/data/isa_cost.json (embedded),
// regenerated by `saagen bench --isa vega10,navi21 --isa-only --isa-table generator/data/isa_cost.json`;
// test_isa_cost_table (ctest -L radv) checks it against a fresh compilation.
inline constexpr const char* kDefaultGpuFamily = "vega10";
// The id of the baseline row (the same shader without SAA) in bench_shading's JSON and the ISA
// table; a trade table names it "none".
inline constexpr const char* kCostBaselineId = "no-saa";
// The "cost_model" of a device's timings (bench_shading --json): cost_ratio is the median over
// rounds of the variant's time over no SAA's, measured back to back.
inline constexpr const char* kTimeCostModel = "time: the median over rounds of the frame's GPU time with the variant over without SAA";
// Speed ranks variants whose ISA ratios differ by less than this fraction as equally cheap (the
// rule's choice among them stands): one instruction of ACO's static estimate is ~0.5 %.
inline constexpr double kIsaTieTolerance = 0.01;

struct IsaRow {
  std::string family;   // vega10
  std::string shader;   // "forward" (the fragment shader bench_shading times) or "deferred-pass"
  OutputTarget target;  // a snippet of glsl or hlsl
  std::string variant;  // a variant id, a deferred pass id, or kCostBaselineId
  double instructions = 0, vgprs = 0, sgprs = 0, subgroups_per_simd = 0, latency = 0, inverse_throughput = 0;
  // Over the same shader without SAA (with as many lights; the copy pass for a deferred pass). A
  // table without instructions_ratio or latency_ratio (written before they were kept) reads 1.
  double inverse_throughput_ratio = 1, instructions_ratio = 1, latency_ratio = 1;
  // "lights": the lights the forward shader shades, 1 to kMaxLights; a row without it (a
  // table written before light counts were measured, or a deferred-pass row) is one light.
  int lights = 1;
};

// The most lights per pixel a manifest's `lights` and a cost table's row take (the cost scene,
// report/include/saagen/report/shading_scene.hpp, shades up to as many).
inline constexpr int kMaxLights = 64;
// The largest normal-map LOD a manifest's `map_lod` and the advice's map_lod_min take (a 64k
// texture's MIP chain has 17 levels).
inline constexpr int kMaxMapLod = 16;

struct IsaTable {
  std::string source_name;
  std::string driver;  // the Mesa version that compiled it
  std::vector<std::string> families;
  // Each family's device as RADV names it ("devices": {"vega10": "AMD RADV VEGA10"}; may be absent).
  std::map<std::string, std::string> devices;
  std::vector<IsaRow> rows;
  // The light counts the forward shader of `family` was measured at, ascending (the committed
  // table: 1, 4, 16); empty when the family has no forward rows.
  std::vector<int> light_counts(std::string_view family) const;
  // The measured light count a material shaded by `lights` lights is costed at: the largest
  // measured count not above it (the smallest measured count when all are above). Not an
  // interpolation: every cost the planner states is a figure the table holds at a count it
  // names, and the ratio moves monotonically between measured counts (from the one-light ratio
  // towards the per-light lobe's), so the light-count table bounds the error.
  int cost_light_count(std::string_view family, int lights) const;
  // Mean over `targets` (those the table has; all when empty) of the forward shader's
  // inverse-throughput ratio at cost_light_count(family, lights).
  std::optional<double> forward_ratio(std::string_view family, std::string_view variant, const std::vector<OutputTarget>& targets,
                                      int lights = 1) const;
};

IsaTable parse_isa_table(std::string_view json_text, std::string_view source_name);
const IsaTable& committed_isa_costs();

MeasuredTradeTable parse_trade_table(std::string_view json_text, std::string_view source_name);
MeasuredTradeTable load_trade_table(const std::filesystem::path& path);

// The measurement saagen's table-free advice is decided on (saagen/advice.hpp), committed as
// generator/data/advice.json (embedded) and written by scripts/advice_data.py from two
// `saagen bench --json` tables: one of the scenes the advice is derived from (the medium preset)
// and one of held-out scenes it is only reported on (scripts/held_out.sh), never chosen on.
struct AdviceMeasurement {
  std::string content;  // a trade table's by_content name ("curved", "bump", ...)
  bool taa = false;     // measured under TAA: "none" is none+taa, the baseline
  // The finest MIP level the scenes sample their normal maps at (their implicit LOD at the
  // centre): 0 for a content's scenes at every distance, K for scenes
  // whose maps are all seen at LOD K or coarser (measure::minification_sweep_scenes). A material's
  // `map_lod` takes the entry of the largest map_lod_min not above it.
  int map_lod_min = 0;
  std::string baseline = "no SAA";           // what against_none and held_out compare with
  std::vector<std::string> scenes;           // what the advice is derived from
  std::vector<std::string> held_out_scenes;  // what it is reported on
  // No SAA's row and every configuration's, as a trade table's by_content rows: error is the
  // image error, tde the flicker error, against_none the paired comparison with its intervals.
  std::vector<ContentRow> rows;
  // A configuration's comparison with no SAA on the held-out scenes, where measured.
  std::optional<decision::Comparison> held_out(std::string_view configuration) const;
  std::vector<std::pair<std::string, decision::Comparison>> held_out_rows;
  // The held-out scenes on which a configuration loses to no SAA beyond the interval in either
  // metric (loses or mixed there), where measured; empty: none.
  std::vector<std::string> held_out_loses_on(std::string_view configuration) const;
  std::vector<std::pair<std::string, std::vector<std::string>>> held_out_losses;
  // The GGX alphas both sets were measured at (ascending), and per configuration the held-out
  // cells (a scene at one alpha) on which it loses to no SAA beyond the interval, where measured.
  std::vector<double> alphas;
  std::vector<std::pair<std::string, std::vector<CellLoss>>> held_out_cell_losses;
};

struct AdviceTable {
  std::string source_name;
  std::string derived_from;  // the derivation table's command and configuration line
  std::string held_out_from;
  // Its projected forward filters were measured with their *_transported_fragment wrappers
  // (`saagen bench --half-vector-frame transported`; the file's "forward_half_vector_frame"),
  // so a plan calls those; else with the papers' *_fragment wrappers.
  bool forward_transported = false;
  std::vector<AdviceMeasurement> contents;
  // The entry of a content (under TAA or not) for a material whose normal maps are seen at LOD
  // map_lod or coarser: of those with map_lod_min <= map_lod, the largest map_lod_min.
  const AdviceMeasurement* find(std::string_view content, bool taa = false, int map_lod = 0) const;
};

AdviceTable parse_advice_table(std::string_view json_text, std::string_view source_name);
const AdviceTable& committed_advice();

}  // namespace saagen
