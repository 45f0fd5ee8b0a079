#include "saagen/scene/planner.hpp"

#include "saagen/emit/engines.hpp"
#include "saagen/error.hpp"
#include "saagen/io/input.hpp"
#include "saagen/products/glints.hpp"
#include "saagen/target/target.hpp"
#include "saagen/validate/compiler.hpp"
#include "saagen/validate/kernels.hpp"
#include "saagen/validate/validation.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>

namespace saagen {
namespace {

// ---------------------------------------------------------------------------------------------
// Rules

enum class Tri { no, yes, any };

struct Rule {
  const char* id;
  RenderPath path;
  Tri anisotropic;
  Tri tangents;
  std::optional<Preference> prefer;  // nullopt: any
  const char* variant;
  const char* why;
  // Content conditions (any when absent): the NDF and whether the material has normal maps.
  std::optional<Ndf> ndf = std::nullopt;
  Tri normal_maps = Tri::any;
};

// deferred-aniso with the tail-preserving filtered GGX the planner shades GGX with; what it measured
// against no SAA is the decision's own text (generator/data/advice.json), appended to the plan.
constexpr const char* kMeasuredDeferredAniso =
    "the G-buffer stores the normal-variation tensor 2 sigma^2 Dn^T Dn (3 values, its trace bounded by kappa as the papers' deferred clamp bounds theirs) and the "
    "lighting pass adds it to alpha^2 I as the roughness matrix of the tail-preserving filtered GGX, which keeps the kernel's "
    "orientation (across a tube, not along it) that the isotropic deferred kernels lose (docs/DEFERRED_KERNEL.md). Costs 3 "
    "G-buffer values and a matrix lobe, computed once per pixel from 4 lights on";

// Table 2 of Tokuyoshi & Kaplanyan 2019 (forward shading, Sponza / Bistro / San Miguel): time
// with the variant over time without SAA. deferred-avg x1.02-1.05, forward-* x1.13-1.31.
const std::vector<Rule>& rules() {
  static const std::vector<Rule> table = {
      {"F1", RenderPath::forward, Tri::yes, Tri::yes, Preference::accuracy, "forward-aniso-projected",
       "the full roughness matrix keeps the filtered lobe's orientation, and projected derivatives shrink the kernel as h_z "
       "at grazing angles where slope derivatives blow up (T&K 2019 Sec. 3.2); shade with the matrix BRDF"},
      {"F2", RenderPath::forward, Tri::yes, Tri::yes, Preference::speed, "forward-axis-projected",
       "axis-aligned filtering feeds the engine's own anisotropic BRDF (no matrix BRDF to evaluate) and is the more "
       "temporally stable form (T&K 2019); projected derivatives as in F1"},
      {"F3", RenderPath::forward, Tri::no, Tri::yes, Preference::accuracy, "forward-aniso-projected",
       "an isotropic material still filters to an anisotropic lobe along the pixel footprint; the matrix form keeps it "
       "(T&K 2019 Sec. 3.2); shade with the matrix BRDF"},
      {"F4", RenderPath::forward, Tri::no, Tri::yes, Preference::speed, "deferred-avg",
       "the cheapest filter (Table 2: x1.02-1.05 against x1.13-1.31 for forward-*), tangent-free, feeding the engine's "
       "isotropic BRDF; it works in a forward pass unchanged"},
      {"F5", RenderPath::forward, Tri::no, Tri::no, std::nullopt, "deferred-avg",
       "without tangents only the tangent-free filters apply; deferred-avg has the lowest error of them (T&K 2019 Eq. 5) "
       "and is the cheapest"},
      {"D0", RenderPath::deferred, Tri::no, Tri::any, Preference::accuracy, "deferred-aniso", kMeasuredDeferredAniso, Ndf::ggx, Tri::no},
      {"D1", RenderPath::deferred, Tri::any, Tri::any, Preference::accuracy, "deferred-avg",
       "tangent-free, from the G-buffer normal; the lowest error of the deferred filters (T&K 2019 Eq. 5)"},
      {"D2", RenderPath::deferred, Tri::any, Tri::any, Preference::speed, "deferred-avg",
       "also the cheapest deferred filter (Table 2: x1.02-1.05), so speed and accuracy agree; deferred-sum (Eq. 4, the "
       "conservative bound) is available with variant = \"deferred-sum\""},
  };
  return table;
}

// `saagen bench --preset medium --json T.json` (sigma^2 0.25), then `python3
// scripts/beats_baselines.py T.json` (docs/TEMPORAL.md, "The verdict with the validated
// criterion"); the narrower kernels were compared before the video metric only.
constexpr const char* kMeasuredGgxKernelGain =
    "saagen's decision beats no SAA and every engine's form beyond the 95 % intervals of the image error and ColorVideoVDP's JOD on 12 "
    "of 14 built-in scene x path rows at 0.25 (46 of 50 with the asset scenes and the maps' minification sweep; on the bump plane and "
    "pmndrs-0010 it beats no SAA only); 0.125 and 0.0625 were compared in LDR-FLIP and TDE only, where they did no better";

// `saagen bench --preset medium --taa --sigma2 X --json F` at 0.0625 and 0.25, the comparison
// under TAA it prints ("With TAA": the verdict's metrics and decision against none+taa; docs/TAA.md).
constexpr const char* kMeasuredTaaKernel =
    "under TAA saagen's verdict beats TAA alone in ColorVideoVDP's JOD (no worse in image error) on 25 of the 25 scenes of "
    "saagen's medium trade at sigma2 0.0625 (by 0.56 to 5.0 JOD) and on 25 at 0.25; between the two kernels the chosen "
    "configurations' video errors differ within their intervals on most scenes (0.25 lower on the sphere and torus, 0.0625 "
    "on the torus knot and bump plane; docs/TAA.md)";

bool matches(Tri tri, bool value) { return tri == Tri::any || (tri == Tri::yes) == value; }

const Rule& rule_for(const Material& material) {
  for (const Rule& rule : rules()) {
    if (rule.path == material.path && matches(rule.anisotropic, material.anisotropic) && matches(rule.tangents, material.tangents) &&
        (!rule.prefer || *rule.prefer == material.prefer) && (!rule.ndf || *rule.ndf == material.ndf) &&
        matches(rule.normal_maps, material.normal_maps)) {
      return rule;
    }
  }
  throw Error(fmt::format("internal error: no planner rule for material '{}'", material.name));
}

// ---------------------------------------------------------------------------------------------
// Eligibility

bool has_tangent_free_form(const Variant& variant) {
  return std::any_of(variant.functions.begin(), variant.functions.end(),
                     [](const std::string& name) { return name.find("tangent_free") != std::string::npos; });
}

// The functions of a variant's lighting pass (role evaluate): deferred-aniso's, which turn the
// tensor its wrapper writes into a roughness matrix and a BRDF value per light.
std::vector<std::string> lighting_pass(const Catalogue& catalogue, const Variant& variant) {
  std::vector<std::string> names;
  for (const std::string& name : variant.functions)
    if (catalogue.find_function(name)->role == FunctionRole::evaluate) names.push_back(name);
  return names;
}

// Empty when the material can use the variant, else why not.
std::string ineligibility(const Catalogue& catalogue, const Variant& variant, const Material& material) {
  if (!lighting_pass(catalogue, variant).empty()) {
    if (material.anisotropic) return fmt::format("{} filters isotropic roughness (its frame is built from the normal alone)", variant.id);
    if (material.ndf != Ndf::ggx)
      return fmt::format("{}'s lighting pass evaluates the tail-preserving filtered GGX; ndf = \"ggx\" only", variant.id);
  }
  if (variant.path == RenderPath::forward && material.path != RenderPath::forward) {
    return fmt::format("{} filters the half vector of each light in a forward pass; this material's path is deferred", variant.id);
  }
  if (variant.needs_tangents && !material.tangents && !has_tangent_free_form(variant)) {
    return fmt::format("{} needs tangents = true (it filters in the tangent frame)", variant.id);
  }
  if (material.anisotropic && material.path == RenderPath::forward && variant.path != RenderPath::forward) {
    return fmt::format("{} filters isotropic roughness; an anisotropic forward material takes a forward-* filter", variant.id);
  }
  return {};
}

// The resources (the glint dictionary) a variant's functions read; such a variant is planned
// only for a material that asks for it (glints = true), never as a screen-space filter.
std::vector<std::string> variant_resources(const Catalogue& catalogue, const Variant& variant) {
  return resources_read(catalogue, variant.functions);
}

std::vector<const Variant*> eligible_variants(const Catalogue& catalogue, const Material& material) {
  std::vector<const Variant*> eligible;
  for (const Variant& variant : catalogue.variants()) {
    if (is_screen_space_filter(catalogue, variant) && ineligibility(catalogue, variant, material).empty() &&
        variant_resources(catalogue, variant).empty()) {
      eligible.push_back(&variant);
    }
  }
  return eligible;
}

std::string ids_of(const std::vector<const Variant*>& variants) {
  std::vector<std::string> ids;
  for (const Variant* variant : variants) ids.push_back("\"" + variant->id + "\"");
  return fmt::format("{}", fmt::join(ids, ", "));
}

// The material's functions from the chosen variant: its fragment wrappers and their cores;
// for a variant with a tangent-free form, the form that matches the material's tangents.
// own_brdf: the manifest names an engine's preset, whose own BRDF the filtered roughness feeds.
// deferred-aniso's texture covariance (deferred_aniso_covariance, and the lighting pass's
// _with_covariance forms): planned where the material adds its normal map's texture term, the
// geometry pass's covariance function where that term is LEAN's (it reads the slope moments);
// an engine's scalar bake v = alpha'^2 - alpha^2 enters the lighting pass as the covariance
// (v, 0, v) (docs/DEFERRED_KERNEL.md, "A texture covariance").
bool is_covariance_function(const std::string& name) { return name.find("covariance") != std::string::npos; }

bool adds_texture_term(const Material& material, const MaterialPlan& plan) { return material.normal_maps && plan.prefilter != "none"; }

// A projected forward filter's wrapper in transported frames (docs/FORWARD_DERIVATIVES.md).
bool is_transported_wrapper(const std::string& name) { return name.ends_with("_transported_fragment"); }

bool has_transported_form(const Variant& variant) { return std::ranges::any_of(variant.functions, is_transported_wrapper); }

// The tail-preserving filtered GGX a filter's roughness feeds: the matrix form for a roughness
// matrix, the axis form for per-axis roughness, and for one isotropic alpha^2 (the deferred
// forms') from 4 lights on the form split into its per-pixel setup and its per-light BRDF,
// which pays per light only what depends on the light (docs/FILTERED_GGX.md). Both forms compute
// the same value; at one light the committed ISA table measures the one-pass form cheaper (ACO's
// estimate discounts the work behind a BRDF's early returns, where the one pass keeps it), at 4
// and 16 lights the split.
constexpr const char* kIsotropicLobeBrdf = "ggx_brdf_filtered_lobe";
constexpr const char* kIsotropicLobeSetup = "ggx_filtered_lobe_isotropic";
// deferred-aniso's lighting pass split the same way (templates/20-deferred.saa).
constexpr const char* kTensorLobeBrdf = "deferred_aniso_brdf_lobe";
constexpr const char* kTensorLobeSetup = "deferred_aniso_lobe";

// The split where the plan is costed at more than one light (MaterialPlan::cost_lights: with the
// committed table 4 lights or more), so that the form named is the one whose cost the plan reads.
bool splits_lobe(const MaterialPlan& plan) { return plan.cost_lights > 1; }

std::string tail_preserving_brdf(const Function& wrapper, bool per_axis, const MaterialPlan& plan) {
  if (wrapper.return_type == "real3") return "ggx_brdf_filtered_matrix";
  if (wrapper.return_type == "real" && !per_axis && splits_lobe(plan)) return kIsotropicLobeBrdf;
  return "ggx_brdf_filtered_axis";
}

// Whether a deferred-aniso lighting function belongs in the plan: the split pair where it splits
// (splits_lobe; with the tensor plus the texture covariance where there is one), else the one-pass
// BRDF (with or without the covariance); the roughness functions (for an engine's own matrix
// BRDF) as the texture term says. An engine's BRDF or a Beckmann material never takes the pair.
bool wanted_lighting_function(const std::string& name, const Function& function, bool texture_term, bool split) {
  if (name == kTensorLobeSetup || name == kTensorLobeBrdf) return split;
  if (is_covariance_function(name) != texture_term) return false;
  return !(split && function.return_type == "real");
}

// A projected forward filter calls the wrappers its measurement was taken with
// (MaterialPlan::forward_transported), never both.
void choose_functions(const Catalogue& catalogue, const Material& material, bool own_brdf, MaterialPlan& plan) {
  const Variant& variant = *catalogue.find_variant(plan.variant);
  const bool split = has_tangent_free_form(variant);
  const bool frames = has_transported_form(variant);
  const bool texture_term = adds_texture_term(material, plan);
  const auto wanted = [&](const std::string& name, const Function& function) {
    if (is_covariance_function(name) && !(texture_term && plan.prefilter == "lean")) return false;
    if (frames && function.role == FunctionRole::fragment && is_transported_wrapper(name) != plan.forward_transported) return false;
    if (!split) return true;
    return (name.find("tangent_free") != std::string::npos) == !material.tangents;
  };
  for (const std::string& name : variant.functions) {
    const Function& function = *catalogue.find_function(name);
    if (!wanted(name, function) || (function.role != FunctionRole::core && function.role != FunctionRole::fragment)) continue;
    plan.functions.push_back(name);
    if (function.role == FunctionRole::fragment && plan.wrapper.empty()) plan.wrapper = name;
  }
  if (plan.wrapper.empty()) throw Error(fmt::format("internal error: variant {} has no fragment wrapper", variant.id));
  plan.variants.push_back(variant.id);

  const Function& wrapper = *catalogue.find_function(plan.wrapper);
  if (const auto lighting = lighting_pass(catalogue, variant); !lighting.empty()) {
    // The wrapper writes a tensor for the G-buffer; the variant's lighting pass turns it into the
    // roughness matrix per light (deferred_aniso_roughness, for the engine's own matrix BRDF) and
    // shades with the tail-preserving filtered GGX (deferred_aniso_brdf; from 4 lights on
    // deferred_aniso_lobe once per pixel and deferred_aniso_brdf_lobe per light).
    const bool split = splits_lobe(plan) && material.ndf == Ndf::ggx && !own_brdf;
    for (const std::string& name : lighting) {
      const Function& function = *catalogue.find_function(name);
      if (!wanted_lighting_function(name, function, texture_term, split)) continue;
      plan.functions.push_back(name);
      if (function.return_type == "real" && material.ndf == Ndf::ggx && !own_brdf) plan.brdf = name;
    }
    return;
  }
  plan.per_axis = material.anisotropic && wrapper.return_type == "real";
  if (material.ndf == Ndf::ggx && !own_brdf && !material.glints) {  // the tail-preserving filtered GGX (docs/FILTERED_GGX.md)
    const std::string brdf = tail_preserving_brdf(wrapper, plan.per_axis, plan);
    if (!catalogue.find_function(brdf) || !catalogue.find_variant("brdf-ggx"))
      throw Error(fmt::format("internal error: the catalogue lacks {}", brdf));
    plan.brdf = brdf;
    if (brdf == kIsotropicLobeBrdf) plan.functions.push_back(kIsotropicLobeSetup);
    plan.functions.push_back(brdf);
    plan.variants.push_back("brdf-ggx");
  } else if (wrapper.return_type == "real3") {  // a roughness matrix: only the matrix BRDFs take it
    const std::string brdf = std::string(to_string(material.ndf)) + "_brdf_matrix";
    const std::string brdf_variant = "brdf-" + std::string(to_string(material.ndf));
    if (!catalogue.find_function(brdf) || !catalogue.find_function("ndf_clamp_tau") || !catalogue.find_variant(brdf_variant)) {
      throw Error(fmt::format("internal error: the catalogue lacks {} or ndf_clamp_tau", brdf));
    }
    plan.brdf = brdf;
    plan.functions.push_back(brdf);
    plan.functions.push_back("ndf_clamp_tau");
    plan.variants.push_back(brdf_variant);
  }
}

// Where a key of the material was written; its [[material]] header when it was not (or when
// the manifest was built in code rather than parsed).
SourcePosition key_position(const Material& material, std::string_view key) {
  const auto found = material.positions.find(key);
  return found != material.positions.end() ? found->second : material.position;
}

// The glint rules: the glinty BRDF (Chermain et al. 2020, with the 2021 slope correlation) is
// the material's specular BRDF; accuracy takes GGAA, speed the textureLod baseline.
constexpr const char* kGlintAccuracyReason =
    "glints = true, prefer accuracy: GGAA (the dictionary's MIP chain filtered over the footprint) lowers RMSE and flicker against a 1024-spp "
    "ground truth on both measured curved scenes (docs/GLINTS.md)";
constexpr const char* kGlintSpeedReason =
    "glints = true, prefer speed: the textureLod baseline, about 1.7x faster than GGAA on lavapipe, with more glint aliasing on "
    "curved surfaces (docs/GLINTS.md)";

void plan_glints(const Catalogue& catalogue, const Manifest& manifest, const Material& material, MaterialPlan& plan) {
  const bool speed = material.prefer == Preference::speed;
  plan.variant = speed ? "glints" : "glints-ggaa";
  plan.rule = speed ? "G2" : "G1";
  plan.reason = speed ? kGlintSpeedReason : kGlintAccuracyReason;
  const Variant* variant = catalogue.find_variant(plan.variant);
  if (!variant || variant_resources(catalogue, *variant).empty()) {
    throw Error(manifest.where(key_position(material, "glints")) +
                fmt::format("key 'glints' of material '{}': this catalogue has no glint variant \"{}\"; plan with the full catalogue "
                            "(saagen::glints::catalogue())",
                            material.name, plan.variant));
  }
  if (material.normal_maps) {
    plan.prefilter = "lean";
    plan.normal_advice =
        "LEAN: write the normal map's moments with `saagen glints lean`, sample both layers with the footprint, and pass "
        "lean_roughness(alpha, mean, second) as roughness and the mean as mean_slope";
  }
}

// The targets' text forms, where the plan text prints them.
std::vector<std::string> target_names(const std::vector<OutputTarget>& targets) {
  std::vector<std::string> names;
  for (const OutputTarget& target : targets) names.push_back(target.name());
  return names;
}

std::string fixed(double value) { return fmt::format("{:.4g}", value); }

// ---------------------------------------------------------------------------------------------
// Cost kernels

// A fragment-shader body in the dialect: a bumpy frame from the pixel position and the input
// buffer, so every derivative is live; {shade} defines `real value`.
constexpr const char* cost_body = R"(    real2 frag_coord = real2(saagen_frag_coord);
    real2 bump = frag_coord * real(SAAGEN_LOAD(0));
    real3 normal_ws = normalize(real3(sin(bump.x), cos(bump.y), real(SAAGEN_LOAD(1))));
    real3 tangent_ws = normalize(real3(normal_ws.z, real(SAAGEN_LOAD(2)), -normal_ws.x));
    real3 bitangent_ws = cross(normal_ws, tangent_ws);
    real3 light_ws = normalize(real3(real(SAAGEN_LOAD(3)), real(SAAGEN_LOAD(4)), real(SAAGEN_LOAD(5))));
    real3 view_ws = normalize(real3(frag_coord * real(SAAGEN_LOAD(6)), real(SAAGEN_LOAD(7))));
    real3 i_ts = real3(dot(light_ws, tangent_ws), dot(light_ws, bitangent_ws), dot(light_ws, normal_ws));
    real3 o_ts = real3(dot(view_ws, tangent_ws), dot(view_ws, bitangent_ws), dot(view_ws, normal_ws));
    real3 half_ts = normalize(i_ts + o_ts);
    real3 half_ws = normalize(light_ws + view_ws);
    real2 alpha2 = real2(real(SAAGEN_LOAD(8)), real(SAAGEN_LOAD(9)));
{shade}    SAAGEN_STORE(0, value);
)";

std::string call_with(const Function& function, const std::string& alpha2) {
  std::vector<std::string> arguments;
  for (const Parameter& parameter : function.parameters) {
    if (parameter.name == "alpha2")
      arguments.push_back(alpha2);
    else if (parameter.name == "half_ts" || parameter.name == "half_ws" || parameter.name == "normal_ws" ||
             parameter.name == "tangent_ws" || parameter.name == "bitangent_ws" || parameter.name == "frag_coord")
      arguments.push_back(parameter.name);
    else
      throw Error(fmt::format("internal error: the cost kernel has no value for parameter '{}' of {}", parameter.name, function.name));
  }
  return fmt::format("{}({})", function.name, fmt::join(arguments, ", "));
}

// Whether the plan shades with the tail-preserving filtered GGX (ggx_brdf_filtered_matrix / _axis).
bool shades_with_tail_preserving_ggx(const MaterialPlan& plan) {
  return plan.brdf && (plan.brdf->rfind("ggx_brdf_filtered_", 0) == 0 || plan.brdf->rfind("deferred_aniso_brdf", 0) == 0);
}

// Whether the plan's BRDF is a lighting pass that reads the G-buffer tensor (deferred_aniso_brdf).
bool shades_from_tensor(const Catalogue& catalogue, const MaterialPlan& plan) {
  if (!plan.brdf) return false;
  const Function& brdf = *catalogue.find_function(*plan.brdf);
  return std::any_of(brdf.parameters.begin(), brdf.parameters.end(), [](const Parameter& parameter) { return parameter.name == "tensor"; });
}

std::string shade_statements(const Catalogue& catalogue, const Material& material, const MaterialPlan* plan) {
  const std::string axis_brdf = std::string(to_string(material.ndf)) + "_brdf_axis";
  const std::string material_alpha2 = material.anisotropic ? "alpha2" : "real2(alpha2.x, alpha2.x)";
  if (!plan) return fmt::format("    real value = {}(i_ts, o_ts, {});\n", axis_brdf, material_alpha2);
  const Function& wrapper = *catalogue.find_function(plan->wrapper);
  if (shades_from_tensor(catalogue, *plan)) {  // the geometry pass's tensor, then the lighting pass per light
    const std::string tensor = fmt::format("    real3 tensor = {};\n", call_with(wrapper, "alpha2.x"));
    // The texture covariance: LEAN's from the texel's moments, or a scalar bake's (v, 0, v).
    const std::string covariance =
        !adds_texture_term(material, *plan) ? ""
        : plan->prefilter == "lean"
            ? "    real3 covariance = deferred_aniso_covariance(real2(real(SAAGEN_LOAD(10)), real(SAAGEN_LOAD(11))), "
              "real3(real(SAAGEN_LOAD(12)), real(SAAGEN_LOAD(13)), real(SAAGEN_LOAD(14))), tangent_ws, bitangent_ws, normal_ws);\n"
            : "    real3 covariance = real3(real(SAAGEN_LOAD(10)), 0.0, real(SAAGEN_LOAD(10)));\n";
    if (*plan->brdf == kTensorLobeBrdf) {  // the lobe of K (+ C) once per pixel, then per light
      const std::string kernel = covariance.empty() ? "tensor" : "tensor + covariance";
      return tensor + covariance + fmt::format("    real4 lobe = {}({}, alpha2.x);\n", kTensorLobeSetup, kernel) +
             fmt::format("    real value = {}(light_ws, view_ws, normal_ws, {}, alpha2.x, lobe);\n", kTensorLobeBrdf, kernel);
    }
    if (covariance.empty())
      return tensor + fmt::format("    real value = {}(light_ws, view_ws, normal_ws, tensor, alpha2.x);\n", *plan->brdf);
    return tensor + covariance +
           fmt::format("    real value = {}(light_ws, view_ws, normal_ws, tensor, covariance, alpha2.x);\n", *plan->brdf);
  }
  // The tail-preserving filtered GGX takes the filtered and the material's roughness; the other
  // BRDFs the filtered one (the matrix BRDFs with the determinant clamp of the material's).
  const bool tail = shades_with_tail_preserving_ggx(*plan);
  if (plan->brdf && *plan->brdf == kIsotropicLobeBrdf) {
    return fmt::format("    real filtered = {};\n", call_with(wrapper, "alpha2.x")) +
           fmt::format("    real4 lobe = {}(filtered, alpha2.x);\n", kIsotropicLobeSetup) +
           fmt::format("    real value = {}(i_ts, o_ts, filtered, alpha2.x, lobe);\n", kIsotropicLobeBrdf);
  }
  const auto value = [&](const std::string& filtered) {
    if (tail) return fmt::format("    real value = {}(i_ts, o_ts, {}, {});\n", *plan->brdf, filtered, material_alpha2);
    if (wrapper.return_type == "real3") {
      return fmt::format("    real value = {}(i_ts, o_ts, {}, ndf_clamp_tau({}));\n", *plan->brdf, filtered, material_alpha2);
    }
    return fmt::format("    real value = {}(i_ts, o_ts, {});\n", axis_brdf, filtered);
  };
  if (wrapper.return_type == "real3")
    return fmt::format("    real3 filtered = {};\n", call_with(wrapper, material_alpha2)) + value("filtered");
  if (wrapper.return_type == "real2")
    return fmt::format("    real2 filtered = {};\n", call_with(wrapper, material_alpha2)) + value("filtered");
  if (plan->per_axis) {
    return fmt::format("    real2 filtered = real2({}, {});\n", call_with(wrapper, "alpha2.x"), call_with(wrapper, "alpha2.y")) +
           value("filtered");
  }
  return fmt::format("    real filtered = {};\n", call_with(wrapper, "alpha2.x")) + value("real2(filtered, filtered)");
}

std::size_t kernel_instructions(const Catalogue& catalogue, const EmittedFile& file, const std::string& shade) {
  KernelRequest request;
  request.kind = KernelKind::fragment;
  request.body = cost_body;
  request.body.replace(request.body.find("{shade}"), 7, shade);
  request.output_stride = 1;
  request.width = 64;
  const CompileRequest compile = kernel_compile_request(catalogue, file.file_name, file.content, request);
  const CompileResult compiled = compile_to_spirv(compile);
  if (!compiled.ok) {
    throw Error(fmt::format("{}: the cost kernel failed to compile: {}", file.file_name, compiled.log.substr(0, compiled.log.find('\n'))));
  }
  const auto optimized = optimize_spirv(compiled.spirv, ClientApi::vulkan);
  if (optimized.empty()) throw Error(fmt::format("{}: spirv-opt failed on the cost kernel", file.file_name));
  return count_spirv_instructions(optimized);
}

std::string describe_choice(const std::vector<std::pair<double, const Variant*>>& ranked, std::string_view metric) {
  std::vector<std::string> parts;
  for (const auto& [value, variant] : ranked) parts.push_back(fmt::format("{} {}", variant->id, fixed(value)));
  return fmt::format("{} measured over the eligible variants: {}", metric, fmt::join(parts, ", "));
}

}  // namespace

// ---------------------------------------------------------------------------------------------

namespace {

// A configuration id's parts: "deferred-avg:geometric+toksvig/tail" -> deferred-avg, geometric,
// toksvig, tail (the lobe the filtered roughness is evaluated with; "papers" when absent).
struct Configuration {
  std::string variant, feed = "shading", prefilter = "none", lobe = "papers";
};

Configuration parse_configuration(const std::string& id) {
  Configuration c;
  std::string rest = id;
  if (const auto slash = rest.find('/'); slash != std::string::npos) c.lobe = rest.substr(slash + 1), rest.resize(slash);
  if (const auto plus = rest.find('+'); plus != std::string::npos) c.prefilter = rest.substr(plus + 1), rest.resize(plus);
  if (const auto colon = rest.find(':'); colon != std::string::npos) c.feed = rest.substr(colon + 1), rest.resize(colon);
  c.variant = rest;
  return c;
}

// How a prefiltered material samples its normal map and the bake (saagen/advice.hpp): the trade's
// prefiltered rows are measured one MIP level coarser than the implicit LOD.
std::string sampling_advice(std::string_view prefilter) {
  return prefilter == "none" ? std::string() : fmt::format("; {}", advice::kPrefilterSamplingText);
}

// The lobe a material's plan shades with, as the trade names it: GGX the tail-preserving filtered
// GGX (advice::kLobe), Beckmann the papers' lobe.
std::string_view planned_lobe(const Material& material) { return material.ndf == Ndf::ggx ? advice::kLobe : "papers"; }

// The normal-mapped content rows the material may use: any eligible variant's when the planner
// chooses the variant by accuracy, else the plan's variant's; of the lobe the plan shades with
// where the rows have it (a table of an engine's own BRDF may not).
std::vector<ContentRow> allowed_normal_mapped_rows(const std::vector<ContentRow>& content_rows, const std::vector<const Variant*>& eligible,
                                                   bool choose_variant, std::string_view lobe, const MaterialPlan& plan) {
  const bool rows_have_lobe = std::any_of(content_rows.begin(), content_rows.end(),
                                          [&](const ContentRow& row) { return parse_configuration(row.configuration).lobe == lobe; });
  std::vector<ContentRow> rows;
  for (const ContentRow& row : content_rows) {
    if (row.content != "normal-mapped") continue;
    const Configuration c = parse_configuration(row.configuration);
    const bool allowed = choose_variant
                             ? std::any_of(eligible.begin(), eligible.end(), [&](const Variant* v) { return v->id == c.variant; })
                             : c.variant == plan.variant;
    if (allowed && (!rows_have_lobe || c.lobe == lobe)) rows.push_back(row);
  }
  return rows;
}

// A configuration's comparison with its baseline (no SAA; none+taa under TAA), as the plan states it.
std::string comparison_text(const decision::Comparison& c, std::string_view baseline = "no SAA") {
  return fmt::format("image error {}, video error {} against {}: {}", decision::describe(c.image), decision::describe(c.temporal), baseline,
                     decision::name(decision::outcome(c)));
}

// No SAA's normal-mapped row, when the rows have it (every table `saagen bench` writes does).
const ContentRow* normal_mapped_none(const std::vector<ContentRow>& content_rows) {
  const auto none = std::find_if(content_rows.begin(), content_rows.end(),
                                 [](const ContentRow& row) { return row.content == "normal-mapped" && row.configuration == "none"; });
  return none == content_rows.end() ? nullptr : &*none;
}

// saagen's one decision (decision.hpp, for accuracy) among `rows`, each against no SAA.
decision::Decision decide_among(const std::vector<ContentRow>& rows, const ContentRow& none) {
  std::vector<decision::Candidate> candidates;
  for (const ContentRow& row : rows)
    candidates.push_back({row.configuration, comparison_against(row, none), std::nullopt, true, row.loses_on, row.not_worse_than});
  return decision::decide(candidates, decision::Preference{});
}

std::vector<ContentRow> rows_with_prefilter(const std::vector<ContentRow>& rows, bool prefiltered) {
  std::vector<ContentRow> kept;
  for (const ContentRow& row : rows)
    if ((parse_configuration(row.configuration).prefilter != "none") == prefiltered) kept.push_back(row);
  return kept;
}

// "X (image error ..., video error ... against no SAA: beats)", or what beat nothing.
std::string decided_text(const std::vector<ContentRow>& rows, const ContentRow& none, std::string_view nothing) {
  const decision::Decision made = decide_among(rows, none);
  if (!made.chosen) return std::string(nothing);
  const ContentRow& row = rows[*made.chosen];
  return fmt::format("{} ({})", row.configuration, comparison_text(comparison_against(row, none)));
}

// The texture prefilter the decided configuration names, as the bake to run, next to what the
// decision takes without one; or, when the decision took none, the best prefiltered one it did
// not take. Both sides are the one decision's picks among their rows, with their intervals.
std::string prefilter_advice(const std::vector<ContentRow>& allowed, const ContentRow& none, const MaterialPlan& plan) {
  const std::vector<ContentRow> with = rows_with_prefilter(allowed, true), without = rows_with_prefilter(allowed, false);
  if (with.empty() || without.empty()) return "";
  if (plan.prefilter == "none") {
    return fmt::format("; no texture prefilter: the best prefiltered configuration is {}",
                       decided_text(with, none, "none (no prefiltered configuration beats no SAA)"));
  }
  const std::string bake =
      plan.prefilter == "lean"
          ? "saagen texture prefilter NORMAL_MAP -o OUT.ktx2 --method lean (slope moments)"
          : fmt::format("saagen texture prefilter NORMAL_MAP -o OUT.ktx2 --method {} --roughness R --gltf", plan.prefilter);
  return fmt::format("; bake the roughness with `{}` (docs/PREFILTER.md); without a prefilter the best is {}{}", bake,
                     decided_text(without, none, "nothing (no configuration without a prefilter beats no SAA)"),
                     sampling_advice(plan.prefilter));
}

// A table without no SAA's row (not written by `saagen bench`) has nothing to decide against:
// the lowest mean display error, said to be a mean without an interval.
void choose_lowest_mean(std::string_view source, const std::vector<ContentRow>& allowed, MaterialPlan& plan) {
  std::vector<std::string> figures;
  const ContentRow* best = nullptr;
  for (const ContentRow& row : allowed) {
    figures.push_back(fmt::format("{} {}", row.configuration, fixed(row.error)));
    if (!best || row.error < best->error) best = &row;
  }
  const Configuration c = parse_configuration(best->configuration);
  plan.variant = c.variant;
  plan.feed = c.feed;
  plan.prefilter = c.prefilter;
  plan.normal_advice = fmt::format("{} (lowest mean display error on normal-mapped content in {}, means without intervals: {})",
                                   best->configuration, source, fmt::join(figures, ", "));
}

// Whether the plan can give a configuration's prefilter: a normal map's bake. On bump content
// the trade's prefiltered rows (bump_plane "+lean") are the procedural shader band-limited to its
// footprint with its slope moments in closed form, code of the material's own shader that the
// plan does not write (docs/FILTERED_GGX.md, "Band-limited bumps"): they are not planned.
bool can_prefilter(const Material& material, const Configuration& c) { return c.prefilter == "none" || material.normal_maps; }

bool can_use(const std::vector<const Variant*>& eligible, std::string_view id) {
  return std::any_of(eligible.begin(), eligible.end(), [&](const Variant* variant) { return variant->id == id; });
}

std::string content_words(advice::Content content, bool taa) {
  return fmt::format("{} content{}", advice::name(content), taa ? " under TAA" : "");
}

// Recommends no filter: the material shades with the engine's own BRDF at its own roughness, and
// the bundle holds nothing for it.
void plan_no_filter(const Material& material, std::string rule, std::string reason, MaterialPlan& plan) {
  plan.variant = "none";
  plan.rule = std::move(rule);
  plan.reason = std::move(reason);
  plan.brdf.reset();
  plan.no_filter_advice.clear();
  if (material.normal_maps) {
    plan.feed = "shading";
    plan.prefilter = "none";
    plan.normal_advice = "no filter: shade the normal-mapped normal at the material's own roughness";
  }
}

// The measured configuration's feed and prefilter, for a normal-mapped material.
void take_normal_handling(const Material& material, const Configuration& c, std::string figures, MaterialPlan& plan) {
  if (!material.normal_maps) return;
  plan.feed = c.feed;
  plan.prefilter = c.prefilter;
  const std::string bake = c.prefilter == "none"
                               ? std::string("no texture prefilter")
                               : fmt::format(
                                     "bake the map into the roughness with `saagen texture prefilter NORMAL_MAP -o OUT.ktx2 --method {} "
                                     "--roughness R --gltf` (docs/PREFILTER.md)",
                                     c.prefilter);
  plan.normal_advice =
      fmt::format("feed the {} normal; {}{}; measured: {}", c.feed, bake, sampling_advice(c.prefilter), std::move(figures));
}

// saagen's committed measurement of a content type (generator/data/advice.json), the rows the
// table-free decision is made on: without TAA against no SAA, under TAA against none+taa; for
// normal maps seen no closer than `map_lod`, the scenes measured that far away where there are.
const AdviceMeasurement* advice_measurement(const AdviceTable& advice, advice::Content content, bool taa, int map_lod = 0) {
  return advice.find(advice::table_content(content), taa, map_lod);
}

// A table's by-content rows of one content: under TAA its taa_by_content rows (`saagen bench
// --taa`: each against none+taa).
std::vector<ContentRow> rows_of_content(const MeasuredTradeTable& table, bool taa, advice::Content content) {
  std::vector<ContentRow> rows;
  for (const ContentRow& row : taa ? table.taa_content_rows : table.content_rows)
    if (row.content == advice::table_content(content)) rows.push_back(row);
  return rows;
}

// A `saagen bench` table measured on other content: its by_content rows name none of this
// content's, so its error means say nothing about it and saagen's own figures decide.
bool lacks_content(const MeasuredTradeTable& table, bool taa, advice::Content content) {
  return !table.content_rows.empty() && rows_of_content(table, taa, content).empty();
}

// What a content's rows are compared with: no SAA, or TAA alone under TAA.
std::string_view baseline_of(bool taa) { return taa ? "none+taa" : "no SAA"; }

std::string scene_list(const std::vector<std::string>& scenes) {
  return scenes.empty() ? std::string("no scene") : fmt::format("{}", fmt::join(scenes, ", "));
}

// How to measure one's own asset instead of relying on saagen's scenes.
std::string measure_own_asset(bool taa) {
  if (taa)
    return fmt::format(
        "measure your own asset under TAA: `saagen bench --scene ASSET.glb --taa --sigma2 {} --json T.json` (or a scene of the presets "
        "like it), then `saagen plan MANIFEST --trade-table T.json`",
        advice::kTaaSigma2);
  return "measure your own asset: `saagen bench --scene ASSET.glb --json T.json` (or a scene of the presets like it), then "
         "`saagen plan MANIFEST --trade-table T.json`; or both in one step: `saagen plan --gltf ASSET.glb -o MANIFEST --measure`";
}

// Whether the table-free advice's choice loses to its baseline (no SAA; under TAA none+taa) beyond its interval, in either metric,
// on the held-out scenes pooled, or (Scenes::each) also on any one of them: then it is not given,
// whatever it measured on saagen's own (the held-out scenes check a choice, they never make one).
enum class Scenes { pooled, each };
bool fails_held_out(const AdviceMeasurement& measured, const std::string& chosen, Scenes scenes = Scenes::each) {
  const auto there = measured.held_out(chosen);
  if (!there) return false;
  const decision::Outcome outcome = decision::outcome(*there);
  if (outcome == decision::Outcome::loses || outcome == decision::Outcome::mixed) return true;
  return scenes == Scenes::each && !measured.held_out_loses_on(chosen).empty();
}

// "a, b: image error ..., video error ...[; it loses to no SAA beyond its interval on a]": how a
// measured choice fared on the held-out scenes.
std::string held_out_figures(const AdviceMeasurement& measured, const std::string& chosen) {
  std::string text =
      fmt::format("{}: {}", scene_list(measured.held_out_scenes), comparison_text(*measured.held_out(chosen), measured.baseline));
  if (const std::vector<std::string> losses = measured.held_out_loses_on(chosen); !losses.empty())
    text += fmt::format("; it loses to {} beyond its interval on {}", measured.baseline, scene_list(losses));
  return text;
}

// How the table-free advice fared on the held-out scenes it was not derived from.
std::string held_out_text(const AdviceMeasurement& measured, const std::optional<std::string>& chosen) {
  if (measured.held_out_scenes.empty())
    return fmt::format("this advice comes from saagen's own scenes ({}) and has no held-out {} content to be checked on; {}",
                       scene_list(measured.scenes), measured.content, measure_own_asset(measured.taa));
  const std::string held_out = fmt::format("held-out scenes {}", scene_list(measured.held_out_scenes));
  if (!chosen)
    return fmt::format("no filter chosen on saagen's scenes ({}); the {} are only reported on, never chosen on; {}",
                       scene_list(measured.scenes), held_out, measure_own_asset(measured.taa));
  const auto there = measured.held_out(*chosen);
  if (!there) return fmt::format("{} was not measured on the {}; {}", *chosen, held_out, measure_own_asset(measured.taa));
  return fmt::format("this advice {} on content it was not derived from (held-out scenes {}); {}",
                     !fails_held_out(measured, *chosen)                   ? "held"
                     : !fails_held_out(measured, *chosen, Scenes::pooled) ? "held pooled, not on each scene,"
                                                                          : "did not hold",
                     held_out_figures(measured, *chosen), measure_own_asset(measured.taa));
}

// The same trade on curved content in the deferred path, for a material that does not get
// deferred-aniso (prefer speed, or a variant named): the isotropic deferred kernels against the
// anisotropic one (docs/DEFERRED_KERNEL.md).
std::string deferred_curved_note(const AdviceTable& advice) {
  const AdviceMeasurement* measured = advice_measurement(advice, advice::Content::curved, false);
  const auto figures = [&](std::string_view configuration) {
    if (measured)
      for (const ContentRow& row : measured->rows)
        if (row.configuration == configuration && row.against_none) return comparison_text(*row.against_none);
    return std::string("not measured");
  };
  return fmt::format(
      "on curved content without normal maps, in saagen's trade ({}): deferred-avg/tail {}; deferred-aniso/tail (rule D0, "
      "prefer = \"accuracy\") {}, for 3 G-buffer values and a matrix BRDF per light (docs/DEFERRED_KERNEL.md)",
      measured ? scene_list(measured->scenes) : std::string("not measured"), figures("deferred-avg/tail"), figures("deferred-aniso/tail"));
}

// Where a material's normal-mapped rows come from: a trade table's, or saagen's committed
// measurement (with the held-out scenes it is checked on, never chosen on).
struct NormalMappedRows {
  const std::vector<ContentRow>& rows;
  std::string source;
  const AdviceMeasurement* advice = nullptr;
};

// The variant's own input, the normal-mapped normal without a bake: what a normal-mapped material
// gets where saagen's decision does not hold on the held-out maps, as no filter is for a material
// the planner chooses for.
void keep_shading_normal(const NormalMappedRows& from, const std::vector<ContentRow>& allowed, const ContentRow& none,
                         const std::string& chosen, MaterialPlan& plan) {
  plan.feed = "shading";
  plan.prefilter = "none";
  std::string own = "not measured";
  for (const ContentRow& row : allowed) {
    const Configuration c = parse_configuration(row.configuration);
    if (c.feed != "shading" || c.prefilter != "none") continue;
    const auto there = from.advice->held_out(row.configuration);
    own = fmt::format("{} ({}; held out: {})", row.configuration, comparison_text(comparison_against(row, none)),
                      there ? comparison_text(*there, from.advice->baseline) : std::string("not measured"));
  }
  plan.normal_advice = fmt::format(
      "feed the normal-mapped normal, no texture prefilter: on normal-mapped content in {} saagen's decision takes {}, but "
      "it does not hold on the held-out scenes ({}), so it is not given; measured: {}",
      from.source, chosen, held_out_figures(*from.advice, chosen), own);
}

// saagen's one decision among the normal-mapped configurations of the material's variant (of any
// eligible one when the planner chooses the variant by accuracy), in the lobe the plan shades
// with: the feed and the bake of what beats no SAA the most, or, where nothing does, no texture
// prefilter. On saagen's committed measurement a pick that does not hold on the held-out scenes
// is not given.
void choose_normal_handling(const NormalMappedRows& from, const std::vector<const Variant*>& eligible, bool choose_variant,
                            std::string_view lobe, MaterialPlan& plan) {
  const std::vector<ContentRow> allowed = allowed_normal_mapped_rows(from.rows, eligible, choose_variant, lobe, plan);
  if (allowed.empty()) return;
  const ContentRow* none = normal_mapped_none(from.rows);
  if (!none) return choose_lowest_mean(from.source, allowed, plan);
  const decision::Decision made = decide_among(allowed, *none);
  if (!made.chosen) {
    plan.prefilter = "none";
    plan.normal_advice = fmt::format("no texture prefilter; on normal-mapped content in {} {}", from.source, made.reason);
    return;
  }
  const std::string& chosen = allowed[*made.chosen].configuration;
  // Pooled only: a material that names its variant cannot be given no filter, and its own input
  // (keep_shading_normal) is what the decision found losing on saagen's own scenes.
  if (from.advice && fails_held_out(*from.advice, chosen, Scenes::pooled)) return keep_shading_normal(from, allowed, *none, chosen, plan);
  const Configuration c = parse_configuration(chosen);
  plan.variant = c.variant;
  plan.feed = c.feed;
  plan.prefilter = c.prefilter;
  plan.normal_advice =
      fmt::format("{} (on normal-mapped content in {}){}", made.reason, from.source, prefilter_advice(allowed, *none, plan));
  if (from.advice) plan.normal_advice += "; " + held_out_text(*from.advice, chosen);
}

// "0.05 (alpha 0.0025)" or "[0.05, 0.3] (alpha [0.0025, 0.09])": a material's roughness as the plan states it.
std::string roughness_words(const RoughnessRange& roughness) {
  if (roughness.low == roughness.high) return fmt::format("{:g} (alpha {:g})", roughness.low, roughness.low * roughness.low);
  return fmt::format("[{:g}, {:g}] (alpha [{:g}, {:g}])", roughness.low, roughness.high, roughness.low * roughness.low,
                     roughness.high * roughness.high);
}

// How the material's roughness entered the decision on rows measured at `alphas`: the measured
// alphas it was judged at (at_roughness), or, without `roughness`, the cells on which the choice,
// decided over every alpha pooled, loses to the baseline. Empty where the rows have no cells.
std::string roughness_text(const Material& material, const std::vector<ContentRow>& rows, const std::optional<std::string>& chosen,
                           const std::vector<double>& alphas, std::string_view baseline) {
  if (alphas.empty() && material.roughness)
    return fmt::format(
        "{}: these figures have no cells per alpha (a table written before the bench wrote them), so it is "
        "decided over every measured alpha pooled",
        roughness_words(*material.roughness));
  if (alphas.empty()) return "";
  if (const auto range = alpha_range(material))
    return fmt::format(
        "{}: decided on the measured cells (a scene at one alpha) at alpha {} (the measured alphas at and around it): a "
        "configuration that loses to {} beyond its interval on any of them is not taken",
        roughness_words(*material.roughness), fmt::join(bracketing_alphas(alphas, *range), ", "), baseline);
  if (!chosen) return "";
  const auto row = std::find_if(rows.begin(), rows.end(), [&](const ContentRow& r) { return r.configuration == *chosen; });
  if (row == rows.end() || row->loses_at.empty()) return "";
  const std::vector<std::string> lost = cells_lost_at(row->loses_at, alphas);
  return fmt::format(
      "{} beats {} over every measured alpha ({}) pooled, but loses to it beyond its interval on {} of the cells (a scene at one "
      "alpha): {}; state the material's `roughness` (perceptual, as glTF's roughnessFactor) to be planned at it",
      *chosen, baseline, fmt::join(alphas, ", "), lost.size(), fmt::join(lost, ", "));
}

// The plan of saagen's decision (decision.hpp) on a content's rows measured at `alphas`: the
// chosen configuration's variant, feed and prefilter, or no filter, with the decision's reason.
void apply_decision(const Catalogue& catalogue, const Manifest& manifest, const Material& material, const std::vector<ContentRow>& rows,
                    const std::vector<double>& alphas, std::string_view source, const AdviceMeasurement* advice,
                    const MeasuredTradeTable* timing, MaterialPlan& plan) {
  const MaterialDecision made =
      decide_material(catalogue, material, manifest.gpu_family, rows, plan.forward_transported, baseline_of(manifest.taa), timing);
  std::optional<std::string> decided;
  if (made.decision.chosen) decided = made.candidates[*made.decision.chosen].configuration;
  plan.roughness_advice = roughness_text(material, rows, decided, alphas, baseline_of(manifest.taa));
  const std::string where = fmt::format("{} in {}", content_words(content_of(material), manifest.taa), source);
  const std::string rule = advice ? "advice" : "trade table";
  if (advice) {
    std::optional<std::string> chosen;
    if (made.decision.chosen) chosen = made.candidates[*made.decision.chosen].configuration;
    plan.measure_advice = held_out_text(*advice, chosen);
    if (chosen && fails_held_out(*advice, *chosen)) {
      plan_no_filter(material, rule,
                     fmt::format("no filter: on {} {}, but it does not hold on the held-out scenes ({}), so it is not given", where,
                                 made.decision.reason, held_out_figures(*advice, *chosen)),
                     plan);
      return;
    }
  }
  if (!made.decision.chosen) {
    plan_no_filter(material, rule,
                   fmt::format("{}; on {}; name a variant (variant = \"...\") to filter anyway", made.decision.reason, where), plan);
    return;
  }
  const decision::Candidate& chosen = made.candidates[*made.decision.chosen];
  const Configuration c = parse_configuration(chosen.configuration);
  if (c.variant == plan.variant) {
    plan.reason += fmt::format(" [saagen's decision on {}: {}]", where, made.decision.reason);
  } else {
    plan.reason = fmt::format("saagen's decision on {}: {}; {} ({}) is not it", where, made.decision.reason, plan.variant, plan.rule);
    plan.variant = c.variant;
    plan.rule = rule;
    plan.no_filter_advice.clear();
  }
  take_normal_handling(material, c, made.decision.reason, plan);
}

void check_trade_table_ids(const Catalogue& catalogue, const MeasuredTradeTable& table) {
  for (std::size_t index = 0; index < table.rows.size(); ++index) {
    // Rows are configurations (`saagen bench`): a variant, with ":geometric" / "+toksvig" /
    // "+lean", or an engine's shipped form ("engine-NAME") measured as a baseline, or the
    // tangent-free form of a variant that has one ("deferred-max-tangent-free"), the transported
    // wrapper of one that has one ("forward-aniso-projected-transported/tail", bench_shading), or
    // the baseline: "none" in a trade table, kCostBaselineId in bench_shading's.
    const std::string& id = table.rows[index].variant;
    std::string base = parse_configuration(id).variant;
    const auto strip = [&](std::string_view suffix, bool (*has_form)(const Variant&)) {
      if (base.size() <= suffix.size() || !base.ends_with(suffix)) return;
      const Variant* variant = catalogue.find_variant(base.substr(0, base.size() - suffix.size()));
      if (variant && has_form(*variant)) base = variant->id;
    };
    strip("-tangent-free", has_tangent_free_form);
    strip("-transported", has_transported_form);
    const bool baseline = base == "none" || id == kCostBaselineId;
    if (!baseline && id.rfind("engine-", 0) != 0 && !catalogue.find_variant(base)) {
      throw Error(fmt::format(
          "{}: rows[{}]: unknown variant \"{}\"; allowed: the ids `saagen list` prints, \"none\" or what `saagen bench --json` and `bench_shading --json` write",
          table.source_name, index, id.substr(0, 40)));
    }
  }
}

}  // namespace

namespace {

bool is_taa(const std::string& configuration) { return configuration.find("+taa") != std::string::npos; }

// Whether the material can use a measured configuration (the decision's Candidate::usable): a
// saagen configuration (not no SAA, an engine's form or the exact-lobe yardstick) of a variant
// the material can use, of the lobe the planner shades GGX with where the rows have it (the
// others measure an engine's own BRDF), with a prefilter the plan can give (an anisotropic forward
// material can use the forward-* forms only: ineligibility()).
bool usable(const Material& material, const std::vector<const Variant*>& eligible, bool rows_have_lobe, const std::string& configuration) {
  const Configuration c = parse_configuration(configuration);
  if (c.variant == "none" || configuration.rfind("engine-", 0) == 0 || c.lobe == "exact" || !can_use(eligible, c.variant)) return false;
  if (rows_have_lobe && c.lobe != advice::kLobe) return false;
  return can_prefilter(material, c);
}

// A variant id's shading cost over no SAA ("deferred-avg", "deferred-avg/tail"), where known.
using RatioOf = std::function<std::optional<double>(const std::string&)>;

// `ratio` as a plan calls the filters: a variant with a transported wrapper, measured with it
// (forward_transported), costed by that wrapper's rows ("forward-aniso-projected-transported/tail",
// the ISA model's and bench_shading's); where the source has them only with the tail-preserving
// lobe, the papers' wrapper's cost plus the transported one's overhead there.
RatioOf as_called(const Catalogue& catalogue, RatioOf ratio, bool forward_transported) {
  if (!forward_transported) return ratio;
  return [&catalogue, ratio](const std::string& id) -> std::optional<double> {
    const std::size_t slash = id.find('/');
    const std::string variant = id.substr(0, slash), lobe = slash == std::string::npos ? "" : id.substr(slash);
    const Variant* found = catalogue.find_variant(variant);
    if (!found || !has_transported_form(*found)) return ratio(id);
    if (const auto own = ratio(variant + "-transported" + lobe)) return own;
    const std::string tail = fmt::format("/{}", advice::kLobe);
    const auto own_tail = ratio(variant + "-transported" + tail), papers_tail = ratio(variant + tail), papers = ratio(id);
    // A device timing taken before bench_shading timed the transported wrappers has neither row:
    // the papers' wrapper's time is all it knows.
    if (!own_tail) return papers;
    if (!papers_tail || !papers) return std::nullopt;
    return *papers + (*own_tail - *papers_tail);
  };
}

// The shading cost of a configuration over no SAA, read by `ratio_of`: of the variant with its
// lobe where the source has that (the feed and the prefilter change inputs, not code), and the
// tangent-free form without tangents. Where the source has the variant only with the papers'
// lobe, the lobe's overhead is added as the source measures it on the form that shares the
// lobe's BRDF: forward-aniso-projected's for the matrix forms (forward-aniso-*), deferred-avg's
// for the others (the axis BRDF).
std::optional<double> configuration_cost(const Catalogue& catalogue, const Material& material, const RatioOf& ratio,
                                         const std::string& configuration) {
  const Configuration c = parse_configuration(configuration);
  const Variant* variant = catalogue.find_variant(c.variant);
  std::string costed = c.variant;
  if (variant && !material.tangents && variant->needs_tangents && has_tangent_free_form(*variant)) costed += "-tangent-free";
  if (c.lobe != "papers")
    if (const auto with_lobe = ratio(costed + "/" + c.lobe)) return with_lobe;
  const auto papers = ratio(costed);
  if (c.lobe == "papers" || !papers) return papers;
  const std::string sharing = c.variant.rfind("forward-aniso-", 0) == 0 ? "forward-aniso-projected" : "deferred-avg";
  const auto shared_lobe = ratio(sharing + "/" + c.lobe), shared_papers = ratio(sharing);
  if (!shared_lobe || !shared_papers) return std::nullopt;
  return *papers + (*shared_lobe - *shared_papers);
}

// "at 4 lights", or "at 4 lights (the nearest measured count not above 10)": the light count a
// material's ISA cost is read at, as the plan states it.
std::string light_count_words(int lights, int measured) {
  const std::string at = fmt::format("at {} light{}", measured, measured == 1 ? "" : "s");
  return measured == lights ? at : fmt::format("{} (the nearest measured count not above {})", at, lights);
}

// The GPU family a manifest's costs are read on: its `gpu_family`, else kDefaultGpuFamily.
std::string cost_family(std::string_view gpu_family) {
  return gpu_family.empty() ? std::string(kDefaultGpuFamily) : std::string(gpu_family);
}

// Where the decision's costs come from, and how its reasons name that after "no SAA's shading
// cost": a device's timings (bench_shading's table given as the trade table) where they were
// taken at the material's light count, else the committed ISA model's forward-shader ratio on
// `family` (every target it has) at the nearest measured count not above it.
struct CostSource {
  RatioOf ratio;
  std::string basis;
};

CostSource cost_source(const Catalogue& catalogue, const Material& material, const std::string& family, const MeasuredTradeTable* timing,
                       bool forward_transported) {
  const int lights = material.lights;
  if (timing && timing->timed_at(lights)) {
    return {as_called(
                catalogue, [timing](const std::string& id) { return timing->device_time_ratio(id); }, forward_transported),
            fmt::format("{} on {} ({})", light_count_words(lights, lights), timing->device_name(), timing->source_name)};
  }
  const IsaTable& isa = committed_isa_costs();
  std::string basis = light_count_words(lights, isa.cost_light_count(family, lights));
  if (timing)
    basis += fmt::format(" ({}'s ISA model: {} was timed at {} light{})", family, timing->source_name, timing->lights,
                         timing->lights == 1 ? "" : "s");
  return {as_called(
              catalogue, [&isa, family, lights](const std::string& id) { return isa.forward_ratio(family, id, {}, lights); },
              forward_transported),
          basis};
}

}  // namespace

MaterialDecision decide_material(const Catalogue& catalogue, const Material& material, std::string_view gpu_family,
                                 const std::vector<ContentRow>& rows, bool forward_transported, std::string_view baseline,
                                 const MeasuredTradeTable* timing) {
  MaterialDecision made;
  const std::string family = cost_family(gpu_family);
  const auto eligible = eligible_variants(catalogue, material);
  const CostSource costs = cost_source(catalogue, material, family, timing, forward_transported);
  const auto none = std::find_if(rows.begin(), rows.end(), [](const ContentRow& row) { return row.configuration == "none"; });
  const bool has_lobe = std::any_of(rows.begin(), rows.end(),
                                    [](const ContentRow& row) { return parse_configuration(row.configuration).lobe == advice::kLobe; });
  if (none == rows.end()) {
    made.decision.reason = "no filter: no configuration was measured against no SAA here";
    return made;
  }
  for (const ContentRow& row : rows) {
    const Configuration c = parse_configuration(row.configuration);
    // Rows under TAA (`saagen bench --taa`: "+taa") compare with none+taa, not with no SAA.
    if (c.variant == "none" || row.configuration.rfind("engine-", 0) == 0 || c.lobe == "exact" || is_taa(row.configuration)) continue;
    made.candidates.push_back({row.configuration, comparison_against(row, *none),
                               configuration_cost(catalogue, material, costs.ratio, row.configuration),
                               usable(material, eligible, has_lobe, row.configuration), row.loses_on, row.not_worse_than});
  }
  const decision::Prefer prefer = material.prefer == Preference::speed ? decision::Prefer::speed : decision::Prefer::accuracy;
  // A budget takes the most accurate configuration within it (prefer only orders without one).
  decision::Preference preference{material.budget ? decision::Prefer::accuracy : prefer, material.budget, std::string(baseline)};
  made.decision = decision::decide(made.candidates, preference, costs.basis);
  return made;
}

Material reference_material(RenderPath path, advice::Content content) {
  Material material;
  material.name = "reference";
  material.path = path;
  material.tangents = path == RenderPath::forward;
  material.normal_maps = content == advice::Content::normal_mapped;
  material.content = content;
  return material;
}

namespace {

// saagen's committed measurement a material is decided on for a content: for normal maps seen no
// closer than its map_lod, the entry measured that far away (AdviceTable::find) where the decision
// there holds on its held-out maps; else the entry of every distance, whose scenes include those,
// with a note saying why.
struct MaterialAdvice {
  const AdviceMeasurement* measured = nullptr;
  std::string note;  // "" or "; with maps at LOD >= 4 (...) the decision takes ..., which does not hold ..."
};

MaterialAdvice material_advice(const Catalogue& catalogue, const Manifest& manifest, const Material& material, const AdviceTable& advice,
                               advice::Content content, const MeasuredTradeTable* timing = nullptr) {
  const AdviceMeasurement* far = advice_measurement(advice, content, manifest.taa, material.map_lod);
  if (!far || far->map_lod_min == 0) return {far, ""};
  const MaterialDecision made =
      decide_material(catalogue, material, manifest.gpu_family, far->rows, advice.forward_transported, baseline_of(manifest.taa), timing);
  if (!made.decision.chosen) return {far, ""};
  const std::string& chosen = made.candidates[*made.decision.chosen].configuration;
  if (!fails_held_out(*far, chosen)) return {far, ""};
  return {advice_measurement(advice, content, manifest.taa),
          fmt::format("; with maps at LOD >= {} ({}) the decision takes {}, which does not hold on their held-out maps ({}), so the advice "
                      "of every distance",
                      far->map_lod_min, scene_list(far->scenes), chosen, held_out_figures(*far, chosen))};
}

}  // namespace

ScenePlan plan_scene(const Catalogue& catalogue, const Manifest& manifest, const MeasuredTradeTable* table) {
  return plan_scene(catalogue, manifest, table, committed_advice());
}

namespace {

// A trade table as it applies to a material that states its roughness: each row also loses on
// the cells it loses on at the measured alphas that bracket the material's (bracketing_alphas),
// so that the one decision never gives it that material (decision.hpp: Candidate::loses_on).
// Without `roughness`: unchanged, decided over every measured alpha pooled.
MeasuredTradeTable at_roughness(MeasuredTradeTable table, const Material& material) {
  const auto range = alpha_range(material);
  if (!range) return table;
  const std::vector<double> judged = bracketing_alphas(table.alphas, *range);
  for (ContentRow& row : table.content_rows) add_cell_losses(row, judged);
  for (ContentRow& row : table.taa_content_rows) add_cell_losses(row, judged);
  return table;
}

// saagen's committed figures likewise, the held-out scenes' cells included (a choice that loses
// on a held-out cell at the material's alphas does not hold there).
AdviceTable at_roughness(AdviceTable advice, const Material& material) {
  const auto range = alpha_range(material);
  if (!range) return advice;
  for (AdviceMeasurement& measured : advice.contents) {
    const std::vector<double> judged = bracketing_alphas(measured.alphas, *range);
    for (ContentRow& row : measured.rows) add_cell_losses(row, judged);
    for (const auto& held_out : measured.held_out_cell_losses) {
      const std::string& configuration = held_out.first;
      std::vector<std::string> lost = cells_lost_at(held_out.second, judged);
      if (lost.empty()) continue;
      auto entry = std::find_if(measured.held_out_losses.begin(), measured.held_out_losses.end(),
                                [&](const auto& losses) { return losses.first == configuration; });
      if (entry == measured.held_out_losses.end()) entry = measured.held_out_losses.insert(entry, {configuration, {}});
      entry->second.insert(entry->second.end(), lost.begin(), lost.end());
    }
  }
  return advice;
}

// anisotropic = true without tangents: one line at the key that is wrong.
void check_tangents(const Manifest& manifest, const Material& material) {
  if (!material.anisotropic || material.tangents) return;
  const auto position = material.positions.count("tangents") ? key_position(material, "tangents") : key_position(material, "anisotropic");
  throw Error(manifest.where(position) + fmt::format("key 'tangents' of material '{}': anisotropic = true needs tangents = true (an "
                                                     "anisotropic BRDF is defined in a tangent frame); allowed: tangents = true, or "
                                                     "anisotropic = false",
                                                     material.name));
}

// The variant the manifest names (its `variant` key or its engine preset's), checked.
void plan_named_variant(const Catalogue& catalogue, const Manifest& manifest, const Material& material,
                        const std::vector<const Variant*>& eligible, MaterialPlan& plan) {
  const std::string context = fmt::format(" of material '{}'", material.name);
  const Variant* found = catalogue.find_variant(*material.variant);
  if (!found || !is_screen_space_filter(catalogue, *found)) {
    throw Error(manifest.where(key_position(material, "variant")) +
                fmt::format("key 'variant'{}: \"{}\" is not a filter variant; allowed: {}", context, *material.variant, ids_of(eligible)));
  }
  const Variant& variant = *found;
  if (const std::string why = ineligibility(catalogue, variant, material); !why.empty()) {
    throw Error(manifest.where(key_position(material, "variant")) +
                fmt::format("key 'variant'{}: {}; allowed: {}", context, why, ids_of(eligible)));
  }
  plan.variant = variant.id;
  plan.rule = "manifest";
  plan.reason = material.positions.count("variant") || !manifest.preset
                    ? "named by the manifest's `variant` key"
                    : fmt::format("the variant of the manifest's preset \"{}\" (the engine's own form)", *manifest.preset);
}

// The rule's variant, then, where a trade table decides or the material prefers speed (and
// saagen's decision does not cost it itself), the eligible variant with the lowest table error
// (accuracy) or ISA cost (speed): from the trade table when it has figures for the manifest's GPU
// family (`saagen bench` measures one light, so only for a material costed at one light), else
// from the committed table.
void plan_by_rule(const Catalogue& catalogue, const Manifest& manifest, const Material& material, const MeasuredTradeTable* table,
                  const std::vector<const Variant*>& eligible, MaterialPlan& plan) {
  const Rule& rule = rule_for(material);
  plan.variant = rule.variant;
  plan.rule = rule.id;
  plan.reason = rule.why;
  const bool speed = material.prefer == Preference::speed;
  // For speed, a GGX material the planner chooses for gets saagen's decision (plan_by_decision),
  // which costs every configuration itself; the ISA ranking here serves the others (Beckmann,
  // presets).
  const bool decision_costs = speed && material.ndf == Ndf::ggx && !manifest.preset;
  // A table without this material's content leaves a GGX material to saagen's decision on its
  // own figures: the table's error means, of other content, rank nothing here.
  const bool table_decides =
      table && !(material.ndf == Ndf::ggx && !manifest.preset && lacks_content(*table, manifest.taa, content_of(material)));
  if (!(table_decides || speed) || decision_costs) return;
  const std::string family = cost_family(manifest.gpu_family);
  const bool table_has_isa = plan.cost_lights == 1 && table &&
                             std::any_of(table->rows.begin(), table->rows.end(),
                                         [&](const MeasuredTradeRow& row) { return row.isa_ratio && row.isa_family == family; });
  // A device's timings (bench_shading's table, or the one a bench table was decided with) at the
  // material's light count rank speed first.
  const MeasuredTradeTable* timed =
      speed && table && table->timing() && table->timing()->timed_at(material.lights) ? table->timing() : nullptr;
  const bool table_timed = timed != nullptr;
  const std::string lights = light_count_words(material.lights, table_timed ? material.lights : plan.cost_lights);
  const std::string source =
      !speed          ? table->source_name
      : table_timed   ? fmt::format("{} ({} on {})", timed->source_name, lights, timed->device_name())
      : table_has_isa ? fmt::format("{} ({})", table->source_name, lights)
                      : fmt::format("{} ({}, {}, {})", committed_isa_costs().source_name, family, committed_isa_costs().driver, lights);
  const RatioOf isa_ratio = as_called(
      catalogue,
      [&](const std::string& id) {
        return table_has_isa ? table->isa_cost(id, family)
                             : committed_isa_costs().forward_ratio(family, id, manifest.targets, material.lights);
      },
      plan.forward_transported);
  const RatioOf timed_ratio = as_called(
      catalogue, [&](const std::string& id) { return timed->device_time_ratio(id); }, plan.forward_transported);
  std::vector<std::pair<double, const Variant*>> ranked;
  for (const Variant* variant : eligible) {
    // Without tangents a variant runs its tangent-free form, measured as "<id>-tangent-free".
    const std::string costed =
        !material.tangents && variant->needs_tangents && has_tangent_free_form(*variant) ? variant->id + "-tangent-free" : variant->id;
    const auto value = !speed ? table->error(variant->id) : table_timed ? timed_ratio(costed) : isa_ratio(costed);
    if (value) ranked.emplace_back(*value, variant);
  }
  // Ties keep the rule's choice first, then catalogue order.
  std::stable_sort(ranked.begin(), ranked.end(), [&](const auto& a, const auto& b) {
    if (a.first != b.first) return a.first < b.first;
    return a.second->id == rule.variant && b.second->id != rule.variant;
  });
  const char* metric = !speed ? "error" : table_timed ? "GPU time ratio" : "ISA inverse-throughput ratio";
  // ACO's estimate is static and counts whole instructions (one VALU instruction is ~0.5 % of
  // these shaders on GFX9); variants within kIsaTieTolerance of the cheapest are equally cheap,
  // and the rule, which orders equals by accuracy, keeps its choice among them.
  const auto rule_entry = std::find_if(ranked.begin(), ranked.end(), [&](const auto& entry) { return entry.second->id == rule.variant; });
  const bool rule_ties =
      speed && !ranked.empty() && rule_entry != ranked.end() && rule_entry->first <= ranked.front().first * (1.0 + kIsaTieTolerance);
  if (!ranked.empty() && !rule_ties && (!speed || ranked.front().second->id != rule.variant)) {
    plan.variant = ranked.front().second->id;
    plan.rule = speed && !table_has_isa && !table_timed ? "isa table" : "trade table";
    plan.reason =
        fmt::format("lowest {} in {} ({}); rule {} would pick {}", metric, source, describe_choice(ranked, metric), rule.id, rule.variant);
  } else if (!ranked.empty()) {
    plan.reason +=
        fmt::format(" [{} the lowest {} in {}: {}]", rule_ties && ranked.front().second->id != rule.variant ? "within 1 % of" : "also",
                    metric, source, describe_choice(ranked, metric));
  } else {
    plan.reason += fmt::format(" [{} has no {} for the eligible variants {}; rule {} applies]", source, metric, ids_of(eligible), rule.id);
  }
}

// A normal-mapped material's feed and prefilter: from the table's rows, else saagen's committed
// measurement of normal-mapped content. For a material the planner chooses for, saagen's decision
// (plan_by_decision) replaces this.
void plan_normal_maps(const Catalogue& catalogue, const Manifest& manifest, const Material& material, const MeasuredTradeTable* table,
                      const AdviceTable& advice, const std::vector<const Variant*>& eligible, MaterialPlan& plan) {
  const std::string_view lobe = planned_lobe(material);
  if (table && !table->content_rows.empty())
    choose_normal_handling({table->content_rows, table->source_name}, eligible,
                           !material.variant && material.prefer == Preference::accuracy, lobe, plan);
  const AdviceMeasurement* measured = material_advice(catalogue, manifest, material, advice, advice::Content::normal_mapped).measured;
  if (plan.normal_advice.empty() && measured)
    choose_normal_handling(
        {measured->rows, fmt::format("saagen's trade ({}; generator/data/advice.json)", scene_list(measured->scenes)), measured}, eligible,
        false, lobe, plan);
}

// saagen's decision (decision.hpp) for a GGX material the planner chooses for (no variant named,
// no engine preset): on the table's rows for the material's content, else on saagen's committed
// figures (advice.hpp), with how far those hold on content they were not made on.
void plan_by_decision(const Catalogue& catalogue, const Manifest& manifest, const Material& material, const MeasuredTradeTable* table,
                      const AdviceTable& advice, MaterialPlan& plan) {
  const std::string content(advice::table_content(content_of(material)));
  // A table without taa_by_content rows leaves a TAA decision to saagen's committed TAA figures.
  const std::vector<ContentRow> rows = table ? rows_of_content(*table, manifest.taa, content_of(material)) : std::vector<ContentRow>{};
  const bool has_none = std::any_of(rows.begin(), rows.end(), [](const ContentRow& row) { return row.configuration == "none"; });
  const bool other_content = table && lacks_content(*table, manifest.taa, content_of(material));
  if (has_none) {
    plan.forward_transported = table->forward_transported;
    apply_decision(catalogue, manifest, material, rows, table->alphas, table->source_name, nullptr, table->timing(), plan);
    return;
  }
  // Rows without no SAA's (a table not written by `saagen bench`): nothing to decide against; the
  // lowest error chosen by plan_by_rule stands.
  if (!rows.empty()) return;
  if (table && !manifest.taa && table->has_errors() && material.prefer != Preference::speed && !other_content) return;
  const MeasuredTradeTable* timing = table ? table->timing() : nullptr;
  const MaterialAdvice chosen_advice = material_advice(catalogue, manifest, material, advice, content_of(material), timing);
  const AdviceMeasurement* measured = chosen_advice.measured;
  static const AdviceMeasurement kNothingMeasured;
  const AdviceMeasurement& rows_of = measured ? *measured : kNothingMeasured;
  plan.forward_transported = advice.forward_transported;
  const std::string lacking =
      (other_content ? fmt::format("; {} has no {} rows", table->source_name, content) : std::string()) + chosen_advice.note;
  apply_decision(catalogue, manifest, material, rows_of.rows, rows_of.alphas,
                 measured ? fmt::format("saagen's trade ({}; generator/data/advice.json){}", scene_list(measured->scenes), lacking)
                          : fmt::format("saagen's trade (not measured){}", lacking),
                 measured, timing, plan);
}

// The wrappers a projected forward filter is planned with where no decision on rows says (a named
// variant, a rule): those of the trade table's measurement where it has by-content rows, else those
// of saagen's advice.
bool measured_frame(const MeasuredTradeTable* table, const AdviceTable& advice) {
  const bool measured_here = table && (!table->content_rows.empty() || !table->taa_content_rows.empty());
  return measured_here ? table->forward_transported : advice.forward_transported;
}

// One material's plan (plan_scene): `table` and `advice` as they apply to its roughness.
MaterialPlan plan_material(const Catalogue& catalogue, const Manifest& manifest, const Material& material, const MeasuredTradeTable* table,
                           const AdviceTable& advice) {
  check_tangents(manifest, material);
  MaterialPlan plan;
  plan.material = material.name;
  plan.precision = material.precision;
  plan.lights = material.lights;
  plan.cost_lights = committed_isa_costs().cost_light_count(cost_family(manifest.gpu_family), material.lights);
  plan.forward_transported = measured_frame(table, advice);
  if (material.glints) {
    plan_glints(catalogue, manifest, material, plan);
    choose_functions(catalogue, material, manifest.preset.has_value(), plan);
    plan.per_axis = false;  // the glinty BRDF takes (alpha_x, alpha_y, rho) itself
    return plan;
  }
  const auto eligible = eligible_variants(catalogue, material);
  if (material.variant)
    plan_named_variant(catalogue, manifest, material, eligible, plan);
  else
    plan_by_rule(catalogue, manifest, material, table, eligible, plan);
  if (material.normal_maps) plan_normal_maps(catalogue, manifest, material, table, advice, eligible, plan);
  if (material.path == RenderPath::deferred && material.ndf == Ndf::ggx && content_of(material) == advice::Content::curved &&
      !material.variant && plan.variant != "deferred-aniso")
    plan.no_filter_advice = deferred_curved_note(advice);
  if (!material.variant && material.ndf == Ndf::ggx && !manifest.preset)
    plan_by_decision(catalogue, manifest, material, table, advice, plan);
  if (plan.variant == "none") return plan;
  choose_functions(catalogue, material, manifest.preset.has_value(), plan);
  return plan;
}

}  // namespace

ScenePlan plan_scene(const Catalogue& catalogue, const Manifest& manifest, const MeasuredTradeTable* table, const AdviceTable& advice) {
  if (table) check_trade_table_ids(catalogue, *table);
  if (table && table->is_device_timing() && table->timed_on_cpu())
    throw Error(
        fmt::format("{}: bench_shading timed {}, a CPU: its time ratios do not stand for a GPU's; time it on your GPU "
                    "(bench_shading --device NAME --json FILE), or plan without it (vega10's ISA model)",
                    table->source_name, table->device_name()));
  ScenePlan scene;
  if (table) scene.trade_table = table->source_name;
  scene.option_values = manifest.option_values;
  const bool all_ggx =
      std::all_of(manifest.materials.begin(), manifest.materials.end(), [](const Material& m) { return m.ndf == Ndf::ggx; });
  if (manifest.taa && !manifest.option_values.count("sigma2")) {
    scene.option_values["sigma2"] = kTaaSigma2;
    scene.options_reason =
        fmt::format("sigma2 = {} (taa = true; {}; set sigma2 in the manifest to override)", kTaaSigma2, kMeasuredTaaKernel);
  } else if (all_ggx && !manifest.option_values.count("sigma2")) {
    scene.option_values["sigma2"] = kGgxSigma2;
    scene.options_reason = fmt::format(
        "sigma2 = {} (every material is GGX, shaded with the tail-preserving filtered GGX: the pixel filter's own variance; {}; "
        "set sigma2 in the manifest to override)",
        kGgxSigma2, kMeasuredGgxKernelGain);
  }
  // Manifests built in code (not parsed) get the checks that protect the emitted text.
  const auto identifier = [](std::string_view text, bool dash) {
    return !text.empty() && text.size() <= 64 && std::isalpha(static_cast<unsigned char>(text[0])) &&
           std::all_of(text.begin(), text.end(),
                       [&](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || (dash && c == '-'); });
  };
  if (!identifier(manifest.name, false)) throw Error(fmt::format("{}: the scene name must be an identifier", manifest.source_name));
  if (manifest.materials.empty()) throw Error(fmt::format("{}: the manifest has no material", manifest.source_name));
  for (const Material& material : manifest.materials) {
    if (!identifier(material.name, true) || material.path == RenderPath::any) {
      throw Error(manifest.where(material.position) + "a material needs an identifier name and a forward or deferred path");
    }
    std::optional<MeasuredTradeTable> table_at;
    if (table) table_at = at_roughness(*table, material);
    scene.materials.push_back(plan_material(catalogue, manifest, material, table ? &*table_at : nullptr, at_roughness(advice, material)));
  }
  return scene;
}

namespace {

// The normal-map distances saagen's advice has a content's figures for: 0 (every distance), then
// each map_lod_min it was also measured at, in increasing order.
std::vector<int> map_lods_measured(const AdviceTable& advice, advice::Content content, bool taa) {
  std::vector<int> lods = {0};
  for (const AdviceMeasurement& entry : advice.contents)
    if (entry.content == advice::table_content(content) && entry.taa == taa && entry.map_lod_min > 0) lods.push_back(entry.map_lod_min);
  std::sort(lods.begin(), lods.end());
  lods.erase(std::unique(lods.begin(), lods.end()), lods.end());
  return lods;
}

// "beats" figures of a comparison as the advice table prints them, or "-".
std::string advice_figures(const std::optional<decision::Comparison>& c) {
  return c ? fmt::format("{} / {}: {}", decision::describe(c->image), decision::describe(c->temporal),
                         decision::name(decision::outcome(*c)))
           : std::string("-");
}

// One row of `saagen plan --advice`: what the plan gives a reference material of the content, path
// and preference (its normal maps seen no closer than map_lod), and the decision's figures.
std::string advice_row(const Catalogue& catalogue, advice::Content content, bool taa, int map_lod, RenderPath path, Preference prefer) {
  Manifest manifest;
  manifest.source_name = "advice";
  manifest.targets = {OutputTarget::named("glsl")};
  manifest.taa = taa;
  Material material = reference_material(path, content);
  material.prefer = prefer;
  material.map_lod = map_lod;
  manifest.materials = {material};
  const MaterialPlan plan = plan_scene(catalogue, manifest).materials.front();
  const MaterialAdvice chosen_advice = material_advice(catalogue, manifest, material, committed_advice(), content);
  const AdviceMeasurement* measured = chosen_advice.measured;
  const std::string baseline(baseline_of(taa));
  std::string configuration = "none", nothing = fmt::format("nothing beats {}", baseline);
  std::optional<decision::Comparison> derived, held_out;
  std::vector<std::string> held_out_losses;
  if (measured) {
    const MaterialDecision made =
        decide_material(catalogue, material, manifest.gpu_family, measured->rows, committed_advice().forward_transported, baseline);
    for (std::size_t i = 0; i < made.candidates.size(); ++i)
      if (made.candidates[i].usable && made.decision.outcomes[i] == decision::Outcome::beats)
        nothing = fmt::format("only the most expensive form beats {}, which prefer = \"speed\" never takes", baseline);
    if (made.decision.chosen) {
      const decision::Candidate& chosen = made.candidates[*made.decision.chosen];
      configuration = chosen.configuration;
      derived = chosen.against_none;
      held_out = measured->held_out(configuration);
      held_out_losses = measured->held_out_loses_on(configuration);
    }
  }
  const std::string planned = plan.variant == "none" ? std::string("**no filter**") : fmt::format("`{}`", configuration);
  const std::string why = configuration == "none"  ? nothing
                          : plan.variant == "none" ? fmt::format("`{}` {}", configuration, advice_figures(derived))
                                                   : advice_figures(derived);
  const std::string content_name =
      map_lod > 0 ? fmt::format("{} (map_lod >= {}{})", advice::name(content), map_lod,
                                chosen_advice.note.empty() ? "" : ": its own choice does not hold held out, every distance's is given")
                  : std::string(advice::name(content));
  const std::string held_out_cell =
      advice_figures(held_out) + (held_out_losses.empty() ? "" : fmt::format("; loses on {}", scene_list(held_out_losses)));
  return fmt::format("| {} | {} | {} | {} | {} | {} | {} |\n", content_name, taa ? "yes" : "no", to_string(path), to_string(prefer),
                     planned, why, held_out_cell);
}

// What the plan gives a reference material of the content and path (prefer accuracy) whose
// roughness is sqrt(alpha): "no filter", or its variant with the feed and the bake it is given.
std::string plan_at_alpha(const Catalogue& catalogue, advice::Content content, bool taa, RenderPath path, double alpha) {
  Manifest manifest;
  manifest.source_name = "advice";
  manifest.targets = {OutputTarget::named("glsl")};
  manifest.taa = taa;
  Material material = reference_material(path, content);
  material.roughness = RoughnessRange{std::sqrt(alpha), std::sqrt(alpha)};
  manifest.materials = {material};
  const MaterialPlan plan = plan_scene(catalogue, manifest).materials.front();
  if (plan.variant == "none") return "no filter";
  return fmt::format("`{}{}{}`", plan.variant, plan.feed == "geometric" ? ":geometric" : "",
                     plan.prefilter == "none" ? "" : "+" + plan.prefilter);
}

// The plan per measured alpha (a material's `roughness` = sqrt(alpha)), per content and path:
// where the decision over every alpha pooled loses on some cells, what a material of one roughness gets.
std::string advice_by_alpha_markdown(const Catalogue& catalogue) {
  const AdviceMeasurement* curved = committed_advice().find(advice::table_content(advice::Content::curved));
  if (!curved || curved->alphas.empty()) return "";
  std::string head = "\n| content | TAA | path |", rule = "|---|---|---|";
  for (const double alpha : curved->alphas) {
    head += fmt::format(" roughness {:.3g} (alpha {:g}) |", std::sqrt(alpha), alpha);
    rule += "---|";
  }
  std::string text = head + "\n" + rule + "\n";
  for (const bool taa : {false, true})
    for (const advice::Content content :
         {advice::Content::curved, advice::Content::normal_mapped, advice::Content::bumps, advice::Content::clearcoat})
      for (const RenderPath path : {RenderPath::forward, RenderPath::deferred}) {
        text += fmt::format("| {} | {} | {} |", advice::name(content), taa ? "yes" : "no", to_string(path));
        for (const double alpha : curved->alphas) text += " " + plan_at_alpha(catalogue, content, taa, path, alpha) + " |";
        text += "\n";
      }
  return text;
}

}  // namespace

std::string advice_markdown(const Catalogue& catalogue) {
  std::string text =
      "| content | TAA | path | prefer | plan | its image / video error (10 - JOD) against its baseline on saagen's scenes (no SAA; "
      "under TAA none+taa) | on the held-out scenes |\n"
      "|---|---|---|---|---|---|---|\n";
  for (const bool taa : {false, true})
    for (const advice::Content content :
         {advice::Content::curved, advice::Content::normal_mapped, advice::Content::bumps, advice::Content::clearcoat})
      for (const int map_lod : map_lods_measured(committed_advice(), content, taa))
        for (const RenderPath path : {RenderPath::forward, RenderPath::deferred})
          for (const Preference prefer : {Preference::accuracy, Preference::speed})
            text += advice_row(catalogue, content, taa, map_lod, path, prefer);
  return text + advice_by_alpha_markdown(catalogue);
}

EmitOptions emit_options(const Manifest& manifest, const ScenePlan& plan, const OutputTarget& target, Precision precision) {
  EmitOptions options;
  options.target = target;
  options.prefix = manifest.prefix;
  options.option_values = plan.option_values;
  options.domain = manifest.domain;
  if (builtin_target(target.table).takes_import_path() && !manifest.import_path.empty()) {
    options.import_path = is_half(precision) ? manifest.import_path + "_" + std::string(to_string(precision)) : manifest.import_path;
  }
  const auto form = target_precision(target, precision);
  if (!form) throw Error(fmt::format("target {} has no {} form", target.name(), to_string(precision)));
  options.precision = *form;
  return options;
}

void measure_costs(const Catalogue& catalogue, const Manifest& manifest, ScenePlan& plan) {
  std::map<std::string, std::size_t> baselines;  // target|precision|ndf|anisotropic -> instructions
  // One compile per distinct configuration: materials that differ only by name (a manifest of
  // thousands repeats a few dozen configurations) share the cost of the first one.
  std::map<std::string, long> costs;
  for (std::size_t index = 0; index < plan.materials.size(); ++index) {
    MaterialPlan& material_plan = plan.materials[index];
    const Material& material = manifest.materials.at(index);
    if (material.glints || material_plan.variant == "none")
      continue;  // no SAA filter to cost: the glinty BRDF replaces the BRDF (docs/GLINTS.md, cost)
    const std::string axis_brdf = std::string(to_string(material.ndf)) + "_brdf_axis";
    BundleRequest request;
    request.name = "cost_" + material.name;
    request.functions = material_plan.functions;
    request.functions.push_back(axis_brdf);
    request.variants = material_plan.variants;
    request.variants.push_back("brdf-" + std::string(to_string(material.ndf)));
    for (const OutputTarget& target : manifest.targets) {
      // A module language (WGSL) is compiled by the WebGPU implementation (Tint), not here.
      if (!builtin_target(target.table).compiled_in_process()) continue;
      const std::string key =
          fmt::format("{}|{}|{}|{}", target.name(), to_string(material.precision), to_string(material.ndf), material.anisotropic);
      const std::string shade = shade_statements(catalogue, material, &material_plan);
      // Everything the cost depends on: the baseline's key, the bundle's closure, the kernel's body.
      const std::string configuration =
          fmt::format("{}\n{}\n{}\n{}", key, fmt::join(request.functions, ","), fmt::join(request.variants, ","), shade);
      if (const auto known = costs.find(configuration); known != costs.end()) {
        material_plan.cost[target] = known->second;
        continue;
      }
      const EmittedFile file = emit_bundle(catalogue, emit_options(manifest, plan, target, material.precision), request);
      // The bundle's functions are in the manifest's roughness domain (its wrappers included).
      const Catalogue& emitted = domain_catalogue(catalogue, manifest.domain);
      if (!baselines.count(key)) baselines[key] = kernel_instructions(emitted, file, shade_statements(catalogue, material, nullptr));
      const std::size_t with_filter = kernel_instructions(emitted, file, shade);
      material_plan.cost[target] = static_cast<long>(with_filter) - static_cast<long>(baselines[key]);
      costs.emplace(configuration, material_plan.cost[target]);
    }
  }
}

std::string rules_text() {
  std::string text =
      fmt::format("{:<5} {:<9} {:<12} {:<9} {:<9} {:<24} {}\n", "rule", "path", "anisotropic", "tangents", "prefer", "variant", "why");
  const auto tri = [](Tri value) { return value == Tri::any ? "any" : value == Tri::yes ? "yes" : "no"; };
  for (const Rule& rule : rules()) {
    text += fmt::format("{:<5} {:<9} {:<12} {:<9} {:<9} {:<24} {}\n", rule.id, to_string(rule.path), tri(rule.anisotropic),
                        tri(rule.tangents), rule.prefer ? to_string(*rule.prefer) : "any", rule.variant, rule.why);
  }
  text +=
      "D0 applies to GGX materials without normal maps (ndf = \"ggx\", normal_maps = false); its lighting pass\n"
      "(deferred_aniso_roughness, deferred_aniso_brdf) is emitted with it. A normal-mapped material that names deferred-aniso\n"
      "and prefilters its map gets the lighting pass with the texture covariance instead (deferred_aniso_roughness_with_covariance,\n"
      "deferred_aniso_brdf_with_covariance; deferred_aniso_covariance for LEAN's moments). From 4 lights on (lights >= 4)\n"
      "deferred_aniso_lobe once per pixel and deferred_aniso_brdf_lobe per light replace the lighting pass's BRDF.\n"
      "GGX materials also emit the tail-preserving filtered GGX to shade with (ggx_brdf_filtered_matrix after forward-aniso-*,\n"
      "ggx_brdf_filtered_axis otherwise; after a filter of one alpha^2 on an isotropic material from 4 lights on\n"
      "ggx_filtered_lobe_isotropic once per pixel and ggx_brdf_filtered_lobe per light), except under an engine's preset (its\n"
      "own BRDF); Beckmann forward-aniso-* emit beckmann_brdf_matrix and ndf_clamp_tau.\n"
      "anisotropic = true with tangents = false is rejected.\n"
      "glints = true (path = \"forward\", tangents = true): G1 prefer accuracy -> glints-ggaa, G2 prefer speed -> glints; the glinty\n"
      "BRDF replaces the specular BRDF, with lean_roughness for normal maps, and its dictionary is written next to the bundle.\n"
      "A deferred-* filter on anisotropic roughness is called once per axis (its kernel is isotropic).\n"
      "GGX materials without variant or preset are then decided by saagen's one decision (generator/include/saagen/decision.hpp,\n"
      "the bench's verdict's too) on their content's figures (content = \"curved\", \"normal-mapped\", \"bumps\", \"clearcoat\"):\n"
      "the trade table's rows, else saagen's (generator/data/advice.json); under taa = true the rows measured under TAA, against\n"
      "none+taa. Only what beats its baseline (no SAA; TAA alone) in image and video error beyond their intervals is eligible;\n"
      "accuracy takes the largest video-error gain, speed the cheapest (vega10 ISA at the material's lights) and never the most\n"
      "expensive form the material can use;\n"
      "no filter (variant none) where nothing is eligible (rule \"advice\" or \"trade table\" where that changes the variant;\n"
      "plan --advice prints what that gives per content). A normal-mapped material that\n"
      "names its variant is fed the geometric normal with the map baked into the roughness (hdrp), sampled one MIP level coarser.\n"
      "prefer = \"speed\" takes the eligible variant of lowest ISA inverse-throughput ratio (Mesa's ACO for the manifest's\n"
      "gpu_family, default vega10: the trade table's isa_inverse_throughput_ratio when it has them, else the committed\n"
      "generator/data/isa_cost.json; ties keep the rule's variant). With --trade-table, prefer = \"accuracy\" takes the one of\n"
      "lowest measured \"error\" when the table has errors.\n"
      "lights = N (scene-wide or per material, 1 to 64, default 1): the lights that shade a pixel. A forward filter and every lobe\n"
      "are paid per light, a deferred filter's roughness once per pixel, so speed and budget read the ISA ratio at the nearest\n"
      "measured count not above N (the committed table measures 1, 4 and 16 lights; the trade table's figures are one light's\n"
      "and serve materials costed at one light), and the plan says at which count.\n"
      "map_lod = K (normal-mapped materials, 0 to 16, default 0): the finest MIP level the normal maps are seen at; saagen's\n"
      "advice then pools its scenes with maps seen at LOD K' or coarser, K' the largest it measured that is not above K\n"
      "(plan --advice lists them), else every distance.\n";
  return text;
}

namespace {

// "forward, anisotropic, tangents, ggx, normal maps, fp32, prefer accuracy, 1 light": what the plan
// was made for.
std::string material_traits(const Material& material) {
  std::vector<std::string> traits = {std::string(to_string(material.path)), material.anisotropic ? "anisotropic" : "isotropic",
                                     material.tangents ? "tangents" : "no tangents", std::string(to_string(material.ndf))};
  if (material.normal_maps)
    traits.push_back(material.map_lod > 0 ? fmt::format("normal maps at LOD >= {}", material.map_lod) : "normal maps");
  traits.emplace_back(to_string(material.precision));
  traits.push_back("prefer " + std::string(to_string(material.prefer)));
  traits.push_back(fmt::format("{} light{}", material.lights, material.lights == 1 ? "" : "s"));
  if (material.roughness) traits.push_back("roughness " + roughness_words(*material.roughness));
  if (material.glints) traits.push_back("glints");
  return fmt::format("{}", fmt::join(traits, ", "));
}

// deferred-aniso's texture covariance as the shade lines name it: LEAN's from the texel's moments,
// or a scalar bake's (v, 0, v).
std::string texture_covariance_words(const std::string& prefix, const MaterialPlan& material_plan) {
  if (material_plan.prefilter == "lean")
    return fmt::format("C = {}(slope_mean, slope_second, tangent_ws, bitangent_ws, normal_ws) of the texel's LEAN moments",
                       prefixed_name(prefix, "deferred_aniso_covariance"));
  return fmt::format("C = (v, 0, v) of the {} bake, v = its alpha'^2 - alpha^2", material_plan.prefilter);
}

// The "  shade" line (and the glints' "  resource" line): what the engine does with the call's result.
std::string shade_lines(const Catalogue& catalogue, const Manifest& manifest, const Material& material, const MaterialPlan& material_plan,
                        bool converted) {
  const std::string& prefix = manifest.prefix;
  if (material.glints) {
    return "  shade     the returned f(i, o) is the specular BRDF: multiply by Fresnel, i.z and the light\n" +
           fmt::format(
               "  resource  the dictionary {}: bind it as the variant's glint_dictionary (`saagen list --json` shows the declaration)\n",
               glint_dictionary_file_name(manifest));
  }
  if (material_plan.brdf && *material_plan.brdf == kTensorLobeBrdf) {
    const bool texture_term = adds_texture_term(material, material_plan);
    return fmt::format(
        "  shade     lobe = {}(K, alpha2) once per pixel, then {}(light_ws, view_ws, normal_ws, K, alpha2, lobe) per light in "
        "the lighting pass, with K the tensor the call above stored (3 G-buffer values: K00, K11 in [0, kappa], K01 in "
        "[-kappa/2, kappa/2]){} and the normal it read (the tail-preserving filtered GGX of A = diag(alpha^2) + K{}; {} "
        "returns diag(alpha^2) + (n.h)^2 K{} for an engine's own matrix BRDF)\n",
        prefixed_name(prefix, kTensorLobeSetup), prefixed_name(prefix, kTensorLobeBrdf),
        !texture_term ? ""
        : material_plan.prefilter == "lean"
            ? fmt::format(" plus the texture covariance {} (3 more G-buffer values, 16-bit float: not bounded by kappa)",
                          texture_covariance_words(prefix, material_plan))
            : " plus the texture covariance " + texture_covariance_words(prefix, material_plan),
        texture_term ? " + C" : "",
        prefixed_name(prefix, texture_term ? "deferred_aniso_roughness_with_covariance" : "deferred_aniso_roughness"),
        texture_term ? " + C" : "");
  }
  if (shades_from_tensor(catalogue, material_plan) && is_covariance_function(*material_plan.brdf)) {
    return fmt::format(
        "  shade     {}(light_ws, view_ws, normal_ws, tensor, covariance, alpha2) per light in the lighting pass, with the tensor "
        "the call above stored (3 G-buffer values: K00, K11 in [0, kappa], K01 in [-kappa/2, kappa/2]), the texture covariance "
        "{} (3 more G-buffer values, 16-bit float: not bounded by kappa) and the normal it read (the tail-preserving filtered "
        "GGX of A = diag(alpha^2) + K + C; {} returns diag(alpha^2) + (n.h)^2 K + C for an engine's own matrix BRDF)\n",
        prefixed_name(prefix, *material_plan.brdf), texture_covariance_words(prefix, material_plan),
        prefixed_name(prefix, "deferred_aniso_roughness_with_covariance"));
  }
  if (shades_from_tensor(catalogue, material_plan)) {
    return fmt::format(
        "  shade     {}(light_ws, view_ws, normal_ws, tensor, alpha2) per light in the lighting pass, with the tensor the "
        "call above stored (3 G-buffer values: K00, K11 in [0, kappa], K01 in [-kappa/2, kappa/2]) and the normal it "
        "read (the tail-preserving filtered GGX of A = diag(alpha^2) + K; {} returns diag(alpha^2) + (n.h)^2 K for an engine's "
        "own matrix BRDF)\n",
        prefixed_name(prefix, *material_plan.brdf), prefixed_name(prefix, "deferred_aniso_roughness"));
  }
  if (material_plan.brdf && *material_plan.brdf == "ggx_brdf_filtered_matrix") {
    return fmt::format(
        "  shade     {}(i, o, a, alpha2) with the filtered matrix a and the material's (ax^2, ay^2) (the tail-preserving filtered GGX)\n",
        prefixed_name(prefix, *material_plan.brdf));
  }
  if (material_plan.brdf && *material_plan.brdf == kIsotropicLobeBrdf) {
    return fmt::format(
        "  shade     lobe = {}(filtered, alpha2) once per pixel, then {}(i, o, filtered, alpha2, lobe) per light, with the "
        "filtered alpha'^2 and the material's alpha^2, alpha^2 domain (the tail-preserving filtered GGX)\n",
        prefixed_name(prefix, kIsotropicLobeSetup), prefixed_name(prefix, *material_plan.brdf));
  }
  if (material_plan.brdf && *material_plan.brdf == "ggx_brdf_filtered_axis") {
    return fmt::format(
        "  shade     {}(i, o, filtered, alpha2) with the filtered (ax'^2, ay'^2) (both axes from an isotropic filter) and the "
        "material's (ax^2, ay^2), alpha^2 domain (the tail-preserving filtered GGX)\n",
        prefixed_name(prefix, *material_plan.brdf));
  }
  if (material_plan.brdf) {
    return fmt::format("  shade     {}(i, o, a, {}(alpha2)) with the filtered matrix a\n", prefixed_name(prefix, *material_plan.brdf),
                       prefixed_name(prefix, "ndf_clamp_tau"));
  }
  return fmt::format("  shade     the engine's own BRDF with the filtered roughness ({} domain)\n",
                     converted ? to_string(manifest.domain) : "alpha^2");
}

// The "  cost" lines: the optimized SPIR-V instructions per target, and the targets not measured.
std::string cost_lines(const Manifest& manifest, const Material& material, const MaterialPlan& material_plan) {
  std::string text;
  if (!material_plan.cost.empty()) {
    std::vector<std::string> costs;
    for (const OutputTarget& target : manifest.targets) {
      if (material_plan.cost.count(target)) costs.push_back(fmt::format("{} {:+}", target.name(), material_plan.cost.at(target)));
    }
    text += fmt::format("  cost      {} optimized SPIR-V instructions ({}, one light; filter{} vs the unfiltered {}_brdf_axis)\n",
                        fmt::join(costs, ", "), to_string(material.precision),
                        !material_plan.brdf                              ? " + axis BRDF"
                        : shades_with_tail_preserving_ggx(material_plan) ? " + the tail-preserving filtered GGX"
                                                                         : " + matrix BRDF",
                        to_string(material.ndf));
  }
  for (const OutputTarget& target : manifest.targets) {
    if (!builtin_target(target.table).compiled_in_process() && !material.glints) {
      text += fmt::format("  cost      {}: not measured (the WebGPU implementation's compiler, Tint, is not in-process)\n", target.name());
    }
  }
  return text;
}

// One material's block of the plan.
std::string format_material_plan(const Catalogue& catalogue, const Manifest& manifest, const Material& material,
                                 const MaterialPlan& material_plan) {
  std::string text = fmt::format("\nmaterial {} ({})\n", material.name, material_traits(material));
  text += fmt::format("  variant   {}  [{}]\n", material_plan.variant, material_plan.rule);
  text += fmt::format("  why       {}\n", material_plan.reason);
  if (!material_plan.roughness_advice.empty()) text += fmt::format("  roughness {}\n", material_plan.roughness_advice);
  if (!material_plan.measure_advice.empty()) text += fmt::format("  measure   {}\n", material_plan.measure_advice);
  if (material_plan.variant == "none") {
    text += "  shade     the engine's own BRDF at the material's own roughness: no SAA filter, nothing in the bundle\n";
    if (material.normal_maps) text += fmt::format("  normal    {}\n", material_plan.normal_advice);
    return text;
  }

  // Under another roughness domain the material calls the wrapper's converting form.
  const Function& planned = *catalogue.find_function(material_plan.wrapper);
  const bool converted = manifest.domain != Domain::alpha2 && takes_and_returns_roughness(planned);
  const Function& wrapper =
      converted ? *domain_catalogue(catalogue, manifest.domain).find_function(domain_function_name(planned.name, manifest.domain))
                : planned;
  std::vector<std::string> parameters;
  for (const Parameter& parameter : wrapper.parameters) parameters.push_back(parameter.name);
  text += fmt::format("  call      {}({}) -> {}{}\n", prefixed_name(manifest.prefix, wrapper.name), fmt::join(parameters, ", "),
                      wrapper.return_meaning, material_plan.per_axis ? "; once per axis (ax^2, ay^2)" : "");
  text += shade_lines(catalogue, manifest, material, material_plan, converted);
  if (material.normal_maps) text += fmt::format("  normal    {}\n", material_plan.normal_advice);
  if (!material_plan.no_filter_advice.empty()) text += fmt::format("  advice    {}\n", material_plan.no_filter_advice);
  return text + cost_lines(manifest, material, material_plan);
}

}  // namespace

std::string format_plan(const Catalogue& catalogue, const Manifest& manifest, const ScenePlan& plan) {
  std::string text = fmt::format("scene '{}' from {}: targets {}, prefix {}", manifest.name, manifest.source_name,
                                 fmt::join(target_names(manifest.targets), ", "), manifest.prefix);
  for (const auto& [option, value] : resolve_options(catalogue, plan.option_values)) text += fmt::format(", {} = {}", option, value);
  text += plan.trade_table.empty() ? "; rules (no trade table)\n" : fmt::format("; trade table {}\n", plan.trade_table);
  if (!plan.options_reason.empty()) text += fmt::format("options: {}\n", plan.options_reason);
  for (std::size_t index = 0; index < plan.materials.size(); ++index)
    text += format_material_plan(catalogue, manifest, manifest.materials.at(index), plan.materials[index]);

  text += "\nfiles\n";
  for (const EmittedFile& file : emit_scene(catalogue, manifest, plan)) {
    const auto functions = domain_catalogue(catalogue, file.marker.domain).closure(file.marker.functions);
    text += fmt::format("  {}  {} public function(s), {} in the closure\n", file.file_name, file.marker.functions.size(), functions.size());
  }
  return text;
}

std::string plan_json(const Manifest& manifest, const ScenePlan& plan) {
  nlohmann::json materials = nlohmann::json::array();
  for (const MaterialPlan& m : plan.materials) {
    materials.push_back({{"material", m.material},
                         {"variant", m.variant},
                         {"rule", m.rule},
                         {"reason", m.reason},
                         {"measure", m.measure_advice},
                         {"roughness", m.roughness_advice},
                         {"wrapper", m.wrapper},
                         {"brdf", m.brdf ? nlohmann::json(*m.brdf) : nlohmann::json()},
                         {"functions", m.functions},
                         {"feed", m.feed},
                         {"prefilter", m.prefilter},
                         {"per_axis", m.per_axis},
                         {"lights", m.lights},
                         {"cost_lights", m.cost_lights},
                         {"precision", std::string(to_string(m.precision))}});
  }
  nlohmann::json options = nlohmann::json::object();
  for (const auto& [option, value] : plan.option_values) options[option] = value;
  return nlohmann::json{{"scene", manifest.name}, {"trade_table", plan.trade_table}, {"options", options}, {"materials", materials}}.dump(
             2) +
         "\n";
}

std::vector<EmittedFile> emit_scene(const Catalogue& catalogue, const Manifest& manifest, const ScenePlan& plan) {
  std::vector<Precision> precisions;
  for (const MaterialPlan& material_plan : plan.materials) {
    if (material_plan.variant == "none") continue;  // advised no filter: nothing to emit
    if (std::find(precisions.begin(), precisions.end(), material_plan.precision) == precisions.end())
      precisions.push_back(material_plan.precision);
  }
  std::stable_partition(precisions.begin(), precisions.end(), [](Precision precision) { return !is_half(precision); });

  std::vector<EmittedFile> files;
  for (const OutputTarget& target : manifest.targets) {
    for (const Precision precision : precisions) {
      BundleRequest request;
      request.name = manifest.name;
      for (std::size_t index = 0; index < plan.materials.size(); ++index) {
        const MaterialPlan& material_plan = plan.materials[index];
        if (material_plan.precision != precision || material_plan.variant == "none") continue;
        for (const std::string& name : material_plan.functions) {
          if (std::find(request.functions.begin(), request.functions.end(), name) == request.functions.end())
            request.functions.push_back(name);
        }
        for (const std::string& id : material_plan.variants) {
          if (std::find(request.variants.begin(), request.variants.end(), id) == request.variants.end()) request.variants.push_back(id);
        }
        // Under another roughness domain the material calls the wrapper's converting form.
        const Function* wrapper = catalogue.find_function(material_plan.wrapper);
        const std::string called = manifest.domain != Domain::alpha2 && wrapper && takes_and_returns_roughness(*wrapper)
                                       ? domain_function_name(material_plan.wrapper, manifest.domain)
                                       : material_plan.wrapper;
        std::string note =
            fmt::format("{} ({}): {} -> {}{}", material_plan.material, to_string(manifest.materials[index].path), material_plan.variant,
                        prefixed_name(manifest.prefix, called), material_plan.per_axis ? " once per axis" : "");
        if (material_plan.brdf) note += ", shade with " + prefixed_name(manifest.prefix, *material_plan.brdf);
        request.notes.push_back(note);
      }
      files.push_back(emit_bundle(catalogue, emit_options(manifest, plan, target, precision), request));
    }
  }
  return files;
}

const Catalogue& scene_catalogue(const Manifest& manifest, const Catalogue& catalogue) {
  return plans_glints(manifest) ? glints::catalogue() : catalogue;
}

}  // namespace saagen
