// The planner (issue 6): picks, for every material of a scene manifest, the SAA variant and the
// functions it needs, from documented rules or from a measured trade table, and turns the plan
// into one bundle file per target (and precision) holding exactly the dependency closure.
//
// The rules (also printed by `saagen plan --rules`, documented in examples/INTEGRATION.md):
//
//   rule  path      anisotropic  tangents  prefer    variant                  also emitted
//   F1    forward   yes          yes       accuracy  forward-aniso-projected  <ndf>_brdf_matrix, ndf_clamp_tau
//   F2    forward   yes          yes       speed     forward-axis-projected   -
//   F3    forward   no           yes       accuracy  forward-aniso-projected  <ndf>_brdf_matrix, ndf_clamp_tau
//   F4    forward   no           yes       speed     deferred-avg             -
//   F5    forward   no           no        any       deferred-avg             -
//   D1    deferred  any          any       accuracy  deferred-avg             -
//   D2    deferred  any          any       speed     deferred-avg             -
//   anisotropic = true with tangents = false is rejected (an anisotropic BRDF needs a frame).
//   G1    glints = true (forward, tangents)     accuracy  glints-ggaa   lean_roughness
//   G2    glints = true (forward, tangents)     speed     glints        lean_roughness
//   (glint variants need saagen::glints::catalogue(); their dictionary goes next to the bundle)
//
// With a trade table, `speed` picks the eligible variant of lowest measured cost and `accuracy`
// the one of lowest measured error (when the table has errors); the rules decide otherwise.
#pragma once

#include "saagen/catalogue.hpp"
#include "saagen/emitter.hpp"
#include "saagen/manifest.hpp"

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace saagen {

// Measured trade-offs (issue 4): bench_shading --json writes {"rows": [{"target", "variant",
// "ratio_median", "delta_spirv_instructions", ...}]}; a row may also carry "error" (lower is
// better), which `saagen bench` is to write. Rows of several targets are averaged per variant.
struct TradeRow {
  std::string target;
  std::string variant;
  std::optional<double> cost_ratio;          // ratio_median: time with the variant / without SAA
  std::optional<double> delta_instructions;  // delta_spirv_instructions
  std::optional<double> error;               // error
};

// `saagen bench --json` also writes, per content type ("curved", "normal-mapped", "bump"), the
// mean display error of every measured configuration: a variant, "VARIANT:geometric" (fed the
// geometric normal) and "VARIANT[:geometric]+toksvig|+lean" (with a prefiltered normal map).
struct ContentRow {
  std::string content;
  std::string configuration;
  double error = 0.0;
};

struct TradeTable {
  std::string source_name;
  std::vector<TradeRow> rows;
  std::vector<ContentRow> content_rows;
  // Mean cost of a variant: the time ratio when any row has one, else the SPIR-V delta.
  std::optional<double> cost(std::string_view variant) const;
  std::optional<double> error(std::string_view variant) const;
  bool has_errors() const;
};

TradeTable parse_trade_table(std::string_view json_text, std::string_view source_name);
TradeTable load_trade_table(const std::filesystem::path& path);

struct MaterialPlan {
  std::string material;                // its name in the manifest
  std::string variant;                 // the chosen filter variant
  std::string rule;                    // F1..D2, "manifest" (variant key), or "trade table"
  std::string reason;                  // why, in one or two sentences
  std::vector<std::string> functions;  // public functions the material calls (closure roots)
  std::vector<std::string> variants;   // the variants those functions belong to
  std::string wrapper;                 // the fragment wrapper to call
  std::optional<std::string> brdf;     // the matrix BRDF to shade with (forward-aniso-*)
  bool per_axis = false;               // isotropic filter on anisotropic roughness: once per axis
  std::string precision = "fp32";
  std::map<std::string, long> cost;    // target -> optimized SPIR-V instructions added
  // Which normal feeds the filter ("shading": the normal-mapped normal, "geometric": the vertex
  // normal) and whether to prefilter the normal map ("none", "toksvig", "lean"), with the
  // measured figures that decide it.
  std::string feed = "shading";
  std::string prefilter = "none";
  std::string normal_advice;
};

struct ScenePlan {
  std::vector<MaterialPlan> materials;
  std::string trade_table;  // its file name when one was used
  // The emission options of the scene's bundles: the manifest's, plus the planner's choice of
  // sigma2 for all-GGX scenes that do not set it (kGgxSigma2), with the reason.
  std::map<std::string, double> option_values;
  std::string options_reason;
};

// The pixel-filter variance saagen measured best for GGX (a quarter of T&K 2019's Beckmann
// match 0.25): `saagen bench --sigma2 0.0625` against 0.25 (README "Measured").
inline constexpr double kGgxSigma2 = 0.0625;

// Plans every material. Throws saagen::Error with the manifest position for contradictions
// (anisotropic without tangents, a `variant` the material cannot use).
ScenePlan plan_scene(const Catalogue& catalogue, const Manifest& manifest, const TradeTable* table = nullptr);

// Fills MaterialPlan::cost: per target, the optimized SPIR-V instruction count of a fragment
// shader that filters and shades with the material's functions, minus the same shader shading
// the unfiltered roughness with the axis-aligned BRDF of the material's NDF.
void measure_costs(const Catalogue& catalogue, const Manifest& manifest, ScenePlan& plan);

// The rules table, as text.
std::string rules_text();
// `saagen plan` output: per material, the variant, why, what to call and the cost.
std::string format_plan(const Catalogue& catalogue, const Manifest& manifest, const ScenePlan& plan);

// The emission options of a manifest for one target and precision.
EmitOptions emit_options(const Manifest& manifest, const ScenePlan& plan, const std::string& target, const std::string& precision);

// The glint dictionary written next to the bundles when a material has glints = true:
// <prefix><name>_glint_dictionary.ktx2 (the default dictionary, matching the default options).
std::string glint_dictionary_file_name(const Manifest& manifest);
bool plans_glints(const Manifest& manifest);

// One bundle per target and precision used by the materials (fp32 first): files
// <prefix><name>[_<precision>].<ext>, holding only the closure of the materials' functions.
std::vector<EmittedFile> emit_scene(const Catalogue& catalogue, const Manifest& manifest, const ScenePlan& plan);

}  // namespace saagen
