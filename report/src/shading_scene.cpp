// The scene bench_shading times and `saagen bench --isa` compiles: one fragment kernel per
// variant that shades a bumpy sphere with the GGX specular term through the variant's fragment
// wrapper, and the same shading without SAA.
#include "saagen/report/shading_scene.hpp"

#include "saagen/error.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/target/target.hpp"
#include "saagen/validate/compiler.hpp"
#include "saagen/validate/kernels.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string_view>

namespace saagen::report {
namespace {

// The kernel body, written once in the template dialect: a parameter block (generated below from
// scene_parameters) followed by the scene. {shade} is replaced by the statements that compute
// `real value` from the scene quantities (a small table per variant).
//
// Camera at the origin looking down -z. A ray that misses the sphere uses the point of closest
// approach instead of the hit point, so every quantity (and every derivative of it) stays finite
// and the derivative intrinsics run in uniform control flow; such pixels store -1.
//
// {light}, {incident} and {half} hold the one light's statements (light_statements) in the
// one-light body, the form every committed one-light figure was measured with; with more lights
// they are empty and {shade} shades each light in a block of its own (lights_shade).
constexpr const char* scene_body = R"(    real2 ndc = saagen_frag_coord * inverse_size * 2.0 - 1.0;
    real3 ray = normalize(real3(ndc.x * tan_half_fov * inverse_size.y / inverse_size.x, -ndc.y * tan_half_fov, -1.0));
{light}    real3 centre = real3(0.0, 0.0, -centre_distance);
    real closest = dot(ray, centre);
    real discriminant = closest * closest - dot(centre, centre) + radius * radius;
    bool hit = discriminant > 0.0;
    real3 position = (closest - sqrt(max(discriminant, 0.0))) * ray;
    real3 sphere_normal = normalize(position - centre);
    // Procedural bumps: the normal tilts along the tangential part of the gradient cos(q) of
    // sin(q.x) + sin(q.y) + sin(q.z), q = frequency * object-space point.
    real3 gradient = cos(sphere_normal * bump_frequency);
    real3 normal = normalize(sphere_normal - bump_amplitude * (gradient - sphere_normal * dot(gradient, sphere_normal)));
    // Tangent frame: the longitude direction cross((0, 1, 0), normal), smooth away from the
    // poles (which lie just outside the visible hemisphere).
    real3 tangent = real3(normal.z, 0.0, -normal.x);
    tangent = tangent * rsqrt(max(dot(tangent, tangent), 1e-12));
    real3 bitangent = cross(normal, tangent);
    real3 view_ws = -ray;
{incident}    real3 o_ts = real3(dot(view_ws, tangent), dot(view_ws, bitangent), dot(view_ws, normal));
{half}    real2 alpha2 = real2(alpha2_material, alpha2_material);
{shade}    SAAGEN_STORE(0, hit ? value : -1.0);
)";

// A light's statements at `indent`: its direction (light_ws) from the parameter `direction`, the
// direction in the tangent frame (i_ts) and the half vector (half_ts).
struct LightStatements {
  std::string light, incident, half;
};

LightStatements light_statements(std::string_view direction, std::string_view indent) {
  return {fmt::format("{}real3 light_ws = normalize({});\n", indent, direction),
          fmt::format("{}real3 i_ts = real3(dot(light_ws, tangent), dot(light_ws, bitangent), dot(light_ws, normal));\n", indent),
          fmt::format("{}real3 half_ts = normalize(i_ts + o_ts);\n", indent)};
}

// The parameter holding light `index`'s direction: the one-light scene's light_direction, then
// light_direction_1, light_direction_2, ...
std::string light_parameter(std::uint32_t index) { return index == 0 ? "light_direction" : fmt::format("light_direction_{}", index); }

// Statements moved one level deeper (four more spaces on every line).
std::string indented(const std::string& statements) {
  std::string text;
  std::size_t start = 0;
  while (start < statements.size()) {
    const std::size_t end = std::min(statements.find('\n', start), statements.size() - 1) + 1;
    text += "    " + statements.substr(start, end - start);
    start = end;
  }
  return text;
}

// {shade} with `lights` > 1: the per-pixel statements once, then each light in a block of its
// own that adds the light's `value` to the sum the kernel stores.
std::string lights_shade(const SceneShading& shading, std::uint32_t lights) {
  std::string text = shading.per_pixel + "    real radiance = 0.0;\n";
  for (std::uint32_t index = 0; index < lights; ++index) {
    const LightStatements light = light_statements(light_parameter(index), "        ");
    text += "    {\n" + light.light + light.incident + light.half + indented(shading.per_light) + "        radiance += value;\n    }\n";
  }
  return text + "    real value = radiance;\n";
}

// Unit directions towards light k = 1, 2, ... (light 0 is the one-light scene's), in front of the
// sphere: a golden-ratio sequence in height and the golden angle around the view axis, so every
// direction is distinct whatever the light count.
std::array<float, 3> extra_light_direction(std::uint32_t index) {
  constexpr double golden_ratio = 1.618033988749895, golden_angle = 2.399963229728653;  // pi (3 - sqrt(5))
  const double fraction = static_cast<double>(index) * golden_ratio - std::floor(static_cast<double>(index) * golden_ratio);
  const double z = 0.1 + 0.9 * fraction, ring = std::sqrt(1.0 - z * z), angle = golden_angle * static_cast<double>(index);
  return {static_cast<float>(ring * std::cos(angle)), static_cast<float>(ring * std::sin(angle)), static_cast<float>(z)};
}

}  // namespace

std::vector<SceneParameter> scene_parameters(std::uint32_t width, std::uint32_t height, std::uint32_t lights) {
  check_light_count(lights);
  std::vector<SceneParameter> parameters = {
      {"real", "alpha2_material", {0.0025f}},  // alpha = 0.05
      {"real2", "inverse_size", {1.0f / static_cast<float>(width), 1.0f / static_cast<float>(height)}},
      {"real", "tan_half_fov", {0.5f}},                     // about 53 degrees vertically
      {"real3", "light_direction", {-0.45f, 0.55f, 0.7f}},  // towards the light: upper left, in front
      {"real", "centre_distance", {3.0f}},
      {"real", "radius", {1.25f}},           // the sphere covers about 65% of the frame
      {"real", "bump_amplitude", {0.25f}},   // normal tilt (radians, roughly)
      {"real", "bump_frequency", {120.0f}},  // bumps of about 20 px at 1000 px: strong specular aliasing
  };
  // The other lights' directions follow, so the one-light parameters keep their offsets.
  for (std::uint32_t index = 1; index < lights; ++index) {
    const std::array<float, 3> direction = extra_light_direction(index);
    parameters.push_back({"real3", light_parameter(index), {direction.begin(), direction.end()}});
  }
  return parameters;
}

// The input buffer: every parameter's components, then a sentinel 1.0.
std::vector<float> parameter_buffer(std::uint32_t width, std::uint32_t height, std::uint32_t lights) {
  std::vector<float> buffer;
  for (const SceneParameter& parameter : scene_parameters(width, height, lights)) {
    buffer.insert(buffer.end(), parameter.values.begin(), parameter.values.end());
  }
  buffer.push_back(1.0f);
  return buffer;
}

// The parameter block of the body. Every parameter is loaded (so nothing folds), but lavapipe
// (Mesa 22.3) returns 0 from buffer loads in helper invocations, which the quads along the
// internal edge of the clipped full-screen triangle (the diagonal x = y) use for derivatives; a
// loaded sentinel detects such lanes, which then take the same values as literals. On a driver
// that loads in helper lanes the literals are never selected.
static std::string parameter_block(std::uint32_t width, std::uint32_t height, std::uint32_t lights) {
  std::string block = fmt::format("    bool load_missing = SAAGEN_LOAD({}) == 0.0;\n", parameter_buffer(width, height, lights).size() - 1);
  std::uint32_t offset = 0;
  for (const SceneParameter& parameter : scene_parameters(width, height, lights)) {
    std::string literal, loaded;
    for (std::size_t component = 0; component < parameter.values.size(); ++component) {
      literal += fmt::format("{}{:.9e}", component == 0 ? "" : ", ", parameter.values[component]);
      loaded += fmt::format("{}SAAGEN_LOAD({})", component == 0 ? "" : ", ", offset++);
    }
    if (parameter.values.size() > 1) {
      literal = fmt::format("{}({})", parameter.type, literal);
      loaded = fmt::format("{}({})", parameter.type, loaded);
    }
    block += fmt::format("    {} {} = load_missing ? {} : {};\n", parameter.type, parameter.name, literal, loaded);
  }
  return block;
}

// Baseline (no SAA): the unfiltered alpha^2 through the axis-aligned GGX BRDF, per light.
const SceneShading baseline_shading = {"", "    real value = ggx_brdf_axis(i_ts, o_ts, alpha2);\n"};

// Paper, Table 2 (Tokuyoshi & Kaplanyan 2019): forward shading at 8K in ms, for Sponza, Bistro
// and San Miguel, without SAA and with each variant. The bench shows the range of the ratios.
const std::array<double, 3> paper_no_saa_ms = {1.80, 2.06, 3.65};

// How a case turns the filtered roughness into `real value`: the papers' GGX(alpha^2 + K)
// (ggx_brdf_matrix with the tau clamp, ggx_brdf_axis) or saagen's tail-preserving filtered GGX
// (ggx_brdf_filtered_matrix, ggx_brdf_filtered_axis; docs/FILTERED_GGX.md).
enum class Lobe { papers, tail };

// A forward wrapper's statements, all per light (the wrapper filters the light's half vector):
// `filtered` is a roughness matrix (real3) or per-axis (real2). `inputs`: the wrapper's
// arguments after alpha2, the tangent-space half vector (the papers' wrappers) by default.
SceneShading forward_shade(std::string_view wrapper, bool matrix, Lobe lobe, std::string_view inputs = "half_ts") {
  const std::string filter = fmt::format("    {} filtered = {}_fragment(alpha2, {});\n", matrix ? "real3" : "real2", wrapper, inputs);
  if (matrix) {
    return {"", filter + (lobe == Lobe::papers ? "    real value = ggx_brdf_matrix(i_ts, o_ts, filtered, ndf_clamp_tau(alpha2));\n"
                                               : "    real value = ggx_brdf_filtered_matrix(i_ts, o_ts, filtered, alpha2);\n")};
  }
  return {"", filter + (lobe == Lobe::papers ? "    real value = ggx_brdf_axis(i_ts, o_ts, filtered);\n"
                                             : "    real value = ggx_brdf_filtered_axis(i_ts, o_ts, filtered, alpha2);\n")};
}

SceneShading deferred_lobe_shading(const std::string& filtered, bool tail) {
  if (!tail) return {filtered, "    real value = ggx_brdf_axis(i_ts, o_ts, real2(filtered, filtered));\n"};
  return {filtered + "    real4 lobe = ggx_filtered_lobe_isotropic(filtered, alpha2_material);\n",
          "    real value = ggx_brdf_filtered_lobe(i_ts, o_ts, filtered, alpha2_material, lobe);\n",
          filtered + "    real value = ggx_brdf_filtered_axis(i_ts, o_ts, real2(filtered, filtered), alpha2);\n"};
}

// A deferred wrapper's statements: once per pixel (the G-buffer side) one filtered alpha^2 for
// both axes, from the G-buffer normal (with the tangent frame and the pixel position where the
// variant reads them); per light the lobe with it.
SceneShading deferred_shade(std::string_view wrapper, bool tangent_frame, Lobe lobe) {
  const std::string_view arguments =
      tangent_frame ? "alpha2_material, normal, tangent, bitangent, saagen_frag_coord" : "alpha2_material, normal";
  return deferred_lobe_shading(fmt::format("    real filtered = {}_fragment({});\n", wrapper, arguments), lobe == Lobe::tail);
}

namespace {

// Paper, Table 2: each filter's forward shading time in ms, as paper_no_saa_ms; a filter the
// 2019 paper did not measure (deferred-projected-space: Tokuyoshi & Kaplanyan 2021) has none.
std::optional<std::array<double, 3>> paper_ms(std::string_view id) {
  static const std::map<std::string_view, std::array<double, 3>> table = {
      {"forward-aniso-slope", {2.34, 2.60, 4.16}}, {"forward-aniso-projected", {2.31, 2.57, 4.12}},
      {"forward-axis-slope", {2.35, 2.61, 4.15}},  {"forward-axis-projected", {2.30, 2.56, 4.12}},
      {"deferred-previous", {2.35, 2.58, 4.16}},   {"deferred-max", {2.40, 2.62, 4.19}},
      {"deferred-sum", {1.90, 2.16, 3.74}},        {"deferred-avg", {1.88, 2.17, 3.74}},
  };
  const auto found = table.find(id);
  if (found == table.end()) return std::nullopt;
  return found->second;
}

bool has_parameter(const Function& function, std::string_view name) {
  return std::any_of(function.parameters.begin(), function.parameters.end(), [&](const Parameter& p) { return p.name == name; });
}

// A template filter's case with the papers' lobe, in the form its fragment wrapper's type says:
// a forward wrapper filters each light's half vector into a matrix (real3) or per-axis (real2)
// roughness, a deferred one the G-buffer normal into one alpha^2 (real), reading the tangent
// frame when it takes one. Other forms (deferred-aniso's tensor) have cases of their own below.
std::optional<VariantCase> papers_case(const Catalogue& catalogue, const Variant& variant) {
  std::string wrapper = variant.id;
  std::replace(wrapper.begin(), wrapper.end(), '-', '_');
  const Function* fragment = catalogue.find_function(wrapper + "_fragment");
  if (!fragment) return std::nullopt;
  const std::string& type = fragment->return_type;
  if (variant.path == RenderPath::forward && (type == "real3" || type == "real2"))
    return VariantCase{variant.id, forward_shade(wrapper, type == "real3", Lobe::papers), paper_ms(variant.id)};
  if (variant.path == RenderPath::deferred && type == "real")
    return VariantCase{variant.id, deferred_shade(wrapper, has_parameter(*fragment, "tangent_ws"), Lobe::papers), paper_ms(variant.id)};
  return std::nullopt;
}

// Every template filter with the papers' lobe, in the templates' order: a new filter is timed
// without a line here.
std::vector<VariantCase> filter_cases() {
  std::vector<VariantCase> cases;
  const Catalogue& catalogue = Catalogue::builtin();
  for (const Variant& variant : catalogue.variants())
    if (is_screen_space_filter(catalogue, variant))
      if (std::optional<VariantCase> papers = papers_case(catalogue, variant)) cases.push_back(*std::move(papers));
  return cases;
}

// The transported wrappers' arguments after alpha2 (templates/10-forward.saa).
constexpr std::string_view kTransportedInputs = "normalize(light_ws + view_ws), normal, tangent, bitangent";

// The filters timed once more with another lobe, or in a form of their own.
std::vector<VariantCase> lobe_cases() {
  return {
      // saagen's lobes (docs/FILTERED_GGX.md): the tail-preserving filtered GGX BRDF, and the
      // single GGX roughness an engine keeping its own BRDF feeds.
      {"forward-aniso-projected/tail", forward_shade("forward_aniso_projected", true, Lobe::tail), std::nullopt},
      {"forward-axis-projected/tail", forward_shade("forward_axis_projected", false, Lobe::tail), std::nullopt},
      {"deferred-sum/tail", deferred_shade("deferred_sum", false, Lobe::tail), std::nullopt},
      {"deferred-avg/tail", deferred_shade("deferred_avg", false, Lobe::tail), std::nullopt},
      // deferred-aniso (docs/DEFERRED_KERNEL.md): the geometry pass's tensor and the lighting
      // pass in one shader, as a forward renderer would run both: its lobe once per pixel, then
      // the BRDF per light; at one light the BRDF in one pass.
      {"deferred-aniso/tail",
       {"    real3 tensor = deferred_aniso_fragment(normal);\n    real4 lobe = deferred_aniso_lobe(tensor, alpha2_material);\n",
        "    real value = deferred_aniso_brdf_lobe(light_ws, view_ws, normal, tensor, alpha2_material, lobe);\n",
        "    real3 tensor = deferred_aniso_fragment(normal);\n"
        "    real value = deferred_aniso_brdf(light_ws, view_ws, normal, tensor, alpha2_material);\n"},
       std::nullopt},
      {"deferred-avg/mapped",
       {"    real filtered = ggx_filtered_alpha2(alpha2_material, deferred_avg_fragment(alpha2_material, normal) - alpha2_material);\n",
        "    real value = ggx_brdf_axis(i_ts, o_ts, real2(filtered, filtered));\n"},
       std::nullopt},
      // The other deferred kernels the advice may choose with saagen's lobe (generator/data/advice.json).
      {"deferred-max/tail", deferred_shade("deferred_max", true, Lobe::tail), std::nullopt},
      {"deferred-projected-space/tail", deferred_shade("deferred_projected_space", false, Lobe::tail), std::nullopt},
      // The projected forward forms' transported wrappers with saagen's lobe, which saagen plans
      // (docs/FORWARD_DERIVATIVES.md): the world-space half vector with the pixel's frame.
      {"forward-aniso-projected-transported/tail",
       forward_shade("forward_aniso_projected_transported", true, Lobe::tail, kTransportedInputs), std::nullopt},
      {"forward-axis-projected-transported/tail",
       forward_shade("forward_axis_projected_transported", false, Lobe::tail, kTransportedInputs), std::nullopt},
  };
}

}  // namespace

const std::vector<VariantCase>& variant_cases() {
  static const std::vector<VariantCase> cases = [] {
    std::vector<VariantCase> all = filter_cases();
    const std::vector<VariantCase> lobes = lobe_cases();
    all.insert(all.end(), lobes.begin(), lobes.end());
    return all;
  }();
  return cases;
}

std::string catalogue_variant(const VariantCase& variant) {
  std::string id = variant.id.substr(0, variant.id.find('/'));
  constexpr std::string_view transported = "-transported";
  if (id.ends_with(transported)) id.resize(id.size() - transported.size());
  return id;
}

void check_light_count(std::uint32_t lights) {
  if (lights < 1 || lights > kMaxSceneLights)
    throw Error(fmt::format("the shading scene takes 1 to {} lights, not {}", kMaxSceneLights, lights));
}

std::string body_with(const SceneShading& shading, std::uint32_t width, std::uint32_t height, std::uint32_t lights) {
  check_light_count(lights);
  const bool one = lights == 1;
  const LightStatements light = one ? light_statements(light_parameter(0), "    ") : LightStatements{};
  std::string body = scene_body;
  const auto fill = [&](std::string_view slot, const std::string& text) { body.replace(body.find(slot), slot.size(), text); };
  fill("{light}", light.light);
  fill("{incident}", light.incident);
  fill("{half}", light.half);
  const std::string one_light = shading.one_light.empty() ? shading.per_pixel + shading.per_light : shading.one_light;
  fill("{shade}", one ? one_light : lights_shade(shading, lights));
  return parameter_block(width, height, lights) + body;
}

std::vector<std::uint32_t> scene_shader_spirv(const std::string& target, const std::string& file_name, const std::string& content,
                                              const std::string& body, std::uint32_t width) {
  KernelRequest request;
  request.kind = KernelKind::fragment;
  request.body = body;
  request.output_stride = 1;
  request.width = width;
  CompileRequest compile;
  compile.language = builtin_target(target).language;
  compile.stage = ShaderStage::fragment;
  compile.sources = kernel_sources(Catalogue::builtin(), file_name, content, request);
  const CompileResult compiled = compile_to_spirv(compile);
  if (!compiled.ok)
    throw Error(
        fmt::format("{} {}: the scene shader does not compile: {}", target, file_name, compiled.log.substr(0, compiled.log.find('\n'))));
  std::vector<std::uint32_t> optimized = optimize_spirv(compiled.spirv, ClientApi::vulkan);
  if (optimized.empty()) throw Error(fmt::format("{} {}: spirv-opt failed on the scene shader", target, file_name));
  return optimized;
}

const char* deferred_copy_source(std::string_view target) {
  const auto& skeleton = builtin_target(target).deferred_pass;
  const auto baseline = skeleton.find("baseline");
  if (baseline == skeleton.end()) throw Error(fmt::format("the deferred pass's baseline is not written in target '{}'", target));
  return baseline->second.c_str();
}

}  // namespace saagen::report
