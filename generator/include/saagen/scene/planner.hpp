// The planner: picks, for every material of a scene manifest, the SAA variant and the
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
//   D0    deferred  no           any       accuracy  deferred-aniso           deferred_aniso_roughness, deferred_aniso_brdf
//         (GGX without normal maps: the G-buffer tensor; docs/DEFERRED_KERNEL.md)
//   D1    deferred  any          any       accuracy  deferred-avg             -
//   D2    deferred  any          any       speed     deferred-avg             -
//   GGX materials (no engine preset) are shaded with the tail-preserving filtered GGX instead:
//   ggx_brdf_filtered_matrix after forward-aniso-*, ggx_brdf_filtered_axis after every other
//   filter, except that from 4 lights on a filter of one alpha^2 on an isotropic material
//   takes ggx_brdf_filtered_lobe (with its per-pixel setup ggx_filtered_lobe_isotropic)
//   (docs/FILTERED_GGX.md); deferred-aniso with its own lighting pass, deferred_aniso_brdf (at
//   4 lights on deferred_aniso_brdf_lobe, with its per-pixel deferred_aniso_lobe).
//   GGX materials without a `variant` or `preset` are then decided by saagen's one decision
//   (saagen/decision.hpp through decide_material below; the bench's verdict uses the same) on their
//   content type's figures (`content`): a trade table's by_content rows for it (under TAA its
//   taa_by_content rows, against none+taa), else saagen's committed figures (saagen/advice.hpp;
//   the plan then says how they held on held-out content and how to measure one's own,
//   MaterialPlan::measure_advice). Only configurations that beat the baseline (no SAA; under TAA,
//   TAA alone) are eligible; accuracy takes the one with the largest temporal (video error) gain,
//   speed the cheapest (vega10 ISA) and never the most expensive form the material can use; no
//   filter (variant "none") where nothing is eligible (rule "advice" or "trade table" where that
//   changes the variant; `saagen plan --advice` prints what that gives per content). A normal-mapped
//   material that names its variant gets the same decision among that variant's feeds and bakes
//   (a bake sampled at advice::kPrefilterLodBias), or the normal-mapped normal without a bake where
//   the decision's pick does not hold on the held-out maps.
//   anisotropic = true with tangents = false is rejected (an anisotropic BRDF needs a frame).
//   G1    glints = true (forward, tangents)     accuracy  glints-ggaa   lean_roughness
//   G2    glints = true (forward, tangents)     speed     glints        lean_roughness
//   (glint variants need saagen::glints::catalogue(); their dictionary goes next to the bundle)
//
// `speed` picks the eligible variant of lowest GPU cost: ACO's inverse-throughput ratio of the
// forward-shading shader with the variant over the same shader without SAA, on the manifest's
// gpu_family (default vega10), from the trade table when it carries ISA figures for that family,
// else from the committed ISA table (generator/data/isa_cost.json; variants within 1 % of the
// cheapest tie, and ties keep the rule's choice).
// With a trade table, `accuracy` picks the one of lowest measured error (when the table has
// errors); the rules decide otherwise. lavapipe time never decides.
#pragma once

#include "saagen/advice.hpp"
#include "saagen/emit/emitter.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/scene/cost_tables.hpp"
#include "saagen/scene/manifest.hpp"

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace saagen {

struct MaterialPlan {
  std::string material;                // its name in the manifest
  std::string variant;                 // the chosen filter variant
  std::string rule;                    // F1..D2, "manifest" (variant key), or "trade table"
  std::string reason;                  // why, in one or two sentences
  std::vector<std::string> functions;  // public functions the material calls (closure roots)
  std::vector<std::string> variants;   // the variants those functions belong to
  std::string wrapper;                 // the fragment wrapper to call
  // Whether a projected forward filter is called through its *_transported_fragment wrapper: as
  // the measurement that decides the material was taken (a trade table's "half_vector_frame",
  // else generator/data/advice.json's "forward_half_vector_frame"), and costed so.
  bool forward_transported = false;
  // The BRDF to shade with: for GGX the tail-preserving filtered GGX (ggx_brdf_filtered_matrix for
  // a roughness matrix, ggx_brdf_filtered_lobe for one isotropic alpha^2 from 4 lights on,
  // its setup ggx_filtered_lobe_isotropic in `functions` too, ggx_brdf_filtered_axis otherwise;
  // deferred-aniso's lighting pass deferred_aniso_brdf, or the pair deferred_aniso_lobe and
  // deferred_aniso_brdf_lobe from 4 lights on: where cost_lights > 1); for Beckmann the matrix BRDF of the
  // forward-aniso-* filters; none: the engine's own BRDF.
  std::optional<std::string> brdf;
  // Where saagen's trade measured no filter beating every filter for this material's content and
  // path: that advice with its figures (the filter is still planned and emitted); empty otherwise.
  std::string no_filter_advice;
  bool per_axis = false;  // isotropic filter on anisotropic roughness: once per axis
  Precision precision = Precision::fp32;
  std::map<OutputTarget, long> cost;  // target -> optimized SPIR-V instructions added (one light)
  // The material's `lights`, and the measured light count its ISA cost (prefer = "speed",
  // budget) was read at (IsaTable::cost_light_count: the nearest measured count not above it).
  int lights = 1;
  int cost_lights = 1;
  // Which normal feeds the filter ("shading": the normal-mapped normal, "geometric": the vertex
  // normal) and whether to prefilter the normal map ("none", "toksvig", "lean", or an engine's
  // bake: "unreal", "filament-vmf", "hdrp"; `saagen texture prefilter --method`), with the
  // measured figures that decide it: a prefilter only where the trade table says it wins.
  std::string feed = "shading";
  std::string prefilter = "none";
  std::string normal_advice;
  // Where the plan rests on saagen's committed figures (no trade table rows for the content): how
  // far they held on content they were not derived from, and how to measure the user's own.
  std::string measure_advice;
  // How the material's `roughness` entered saagen's decision (the measured alphas it was judged
  // at), or, without one, the cells (a scene at one alpha) on which the choice loses to no SAA.
  std::string roughness_advice;
};

struct ScenePlan {
  std::vector<MaterialPlan> materials;
  std::string trade_table;  // its file name when one was used
  // The emission options of the scene's bundles: the manifest's, plus the planner's choice of
  // sigma2 for all-GGX scenes that do not set it (kGgxSigma2), with the reason.
  std::map<std::string, double> option_values;
  std::string options_reason;
};

// The pixel-filter variance saagen plans for GGX, and under TAA (Manifest::taa, `plan --taa`):
// saagen's advice (saagen/advice.hpp, where the measurements behind them are).
inline constexpr double kGgxSigma2 = advice::kSigma2;
inline constexpr double kTaaSigma2 = advice::kTaaSigma2;

// saagen's decision (saagen/decision.hpp) for a material on its content's measured rows (a trade
// table's by_content rows of one content, or saagen's committed figures, advice.hpp), each row
// against the rows' "none" through comparison_against (cost_tables.hpp): every saagen
// configuration of the rows is a candidate, usable where the material can use its variant, feed,
// prefilter and lobe; its cost is the committed ISA model's (generator/data/isa_cost.json) on
// gpu_family (empty: vega10). The planner plans what it chooses; the bench's verdict decides for
// reference_material(path, content) with the same function, so the two give one answer.
struct MaterialDecision {
  std::vector<decision::Candidate> candidates;
  decision::Decision decision;
};
// `forward_transported`: the rows' projected forward filters were measured with their
// *_transported_fragment wrappers, which then cost them (the ISA model's "-transported" rows).
// `baseline` names what the rows' "none" is, as the reasons print it ("none+taa" for rows
// measured under TAA). `timing`: a device's timings (bench_shading's table, or the one a bench
// table was decided with: MeasuredTradeTable::timing()) that cost the configurations where they
// were taken at the material's light count, instead of the committed ISA model.
MaterialDecision decide_material(const Catalogue& catalogue, const Material& material, std::string_view gpu_family,
                                 const std::vector<ContentRow>& rows, bool forward_transported, std::string_view baseline = "no SAA",
                                 const MeasuredTradeTable* timing = nullptr);
// The material the bench's verdict decides for on a render path and content type: GGX, isotropic,
// tangents on the forward path (none on the deferred path's G-buffer), normal maps on
// normal-mapped content, prefer accuracy.
Material reference_material(RenderPath path, advice::Content content);

// Plans every material. Throws saagen::Error with the manifest position for contradictions
// (anisotropic without tangents, a `variant` the material cannot use).
ScenePlan plan_scene(const Catalogue& catalogue, const Manifest& manifest, const MeasuredTradeTable* table = nullptr);
// The same with another table-free measurement than saagen's committed one (committed_advice()):
// what the decision and its held-out check read where the manifest has no trade table.
ScenePlan plan_scene(const Catalogue& catalogue, const Manifest& manifest, const MeasuredTradeTable* table, const AdviceTable& advice);

// Fills MaterialPlan::cost: per target, the optimized SPIR-V instruction count of a fragment
// shader that filters and shades with the material's functions, minus the same shader shading
// the unfiltered roughness with the axis-aligned BRDF of the material's NDF.
void measure_costs(const Catalogue& catalogue, const Manifest& manifest, ScenePlan& plan);

// The rules table, as text.
std::string rules_text();
// saagen's table-free advice as a Markdown table: per content type, render path and preference,
// what `saagen plan` gives a GGX material it chooses for (reference_material: tangents on the
// forward path), the decision's comparison with no SAA on saagen's scenes and on the held-out
// scenes (generator/data/advice.json). `saagen plan --advice` prints it; examples/INTEGRATION.md
// holds it (a test checks they agree).
std::string advice_markdown(const Catalogue& catalogue);
// `saagen plan` output: per material, the variant, why, what to call and the cost.
std::string format_plan(const Catalogue& catalogue, const Manifest& manifest, const ScenePlan& plan);

// `saagen plan --json`: the plan as JSON, for tools that install what it says (the three.js
// module, examples/threejs/saagen-three.js): {"scene", "trade_table", "options", "materials": [
// {"material", "variant" ("none": no filter), "rule", "reason", "measure", "wrapper", "brdf",
// "functions", "feed", "prefilter", "per_axis", "precision"}]}.
std::string plan_json(const Manifest& manifest, const ScenePlan& plan);

// The emission options of a manifest for one target and precision.
EmitOptions emit_options(const Manifest& manifest, const ScenePlan& plan, const OutputTarget& target, Precision precision);

// The catalogue a manifest is planned and emitted over: the glint catalogue when a material has
// glints = true (it holds the SAA variants too), else `catalogue` (plans and bundles without
// glints stay byte for byte as they are).
const Catalogue& scene_catalogue(const Manifest& manifest, const Catalogue& catalogue);

// One bundle per target and precision used by the materials (fp32 first): files
// <prefix><name>[_<precision>].<ext>, holding only the closure of the materials' functions.
std::vector<EmittedFile> emit_scene(const Catalogue& catalogue, const Manifest& manifest, const ScenePlan& plan);

}  // namespace saagen
