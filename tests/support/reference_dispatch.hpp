// Shared by the suites that compare emitted code with the double reference: reading packed fp32
// inputs back as doubles, and evaluating by name a screen-space filter's core function and a
// fragment wrapper's reference on a 2x2 quad. The filters' references are found by naming
// convention from the templates' list (saagen/template_variants.hpp): filter `identifier`'s core
// function is ref::<identifier> and its fragment wrapper's ref::<identifier>_fragment_quad, read
// in the form their signatures have, so that a filter the templates add needs no line here.
#pragma once

#include "saagen/front/catalogue.hpp"
#include "saagen/reference/reference.hpp"
#include "saagen/reference/wrapper_forms.hpp"
#include "saagen/template_variants.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace saagen::test {

// Reads packed inputs back as doubles, in parameter order: fp32 as a device reads them
// (FloatReader), or doubles (the stability suite's pairs of inputs).
template <class Scalar>
class PackedReader {
 public:
  explicit PackedReader(const Scalar* data) : data_(data) {}
  double real() { return data_[next_++]; }
  ref::Vec2 vec2() {
    const double x = real();
    return {x, real()};
  }
  ref::Vec3 vec3() {
    const double x = real(), y = real();
    return {x, y, real()};
  }
  ref::Sym2 sym2() {
    const double x = real(), y = real();
    return {x, y, real()};
  }

 private:
  const Scalar* data_;
  std::size_t next_ = 0;
};
using FloatReader = PackedReader<float>;

// Whether a function reads a filtered matrix `a` next to the unfiltered `alpha2` it was filtered
// from (the tail-preserving filtered GGX): then `a` = diag(alpha2) + the roughness matrix, a
// kernel on top of the material, as the forward variants return.
inline bool takes_unfiltered_alpha2(const saagen::Function& function) {
  bool a = false, alpha2 = false;
  for (const saagen::Parameter& parameter : function.parameters) {
    a = a || parameter.name == "a";
    alpha2 = alpha2 || parameter.name == "alpha2";
  }
  return a && alpha2;
}

inline std::vector<double> output_values(double v) { return {v}; }
inline std::vector<double> output_values(ref::Vec2 v) { return {v.x, v.y}; }
inline std::vector<double> output_values(ref::Sym2 m) { return {m.xx, m.xy, m.yy}; }

// --- the screen-space filters' core functions (forward-*, deferred-*) ---------------------------

// The forms of a filter's core function, by the inputs it reads after the parameters: the
// unfiltered roughness per axis and two 2D derivatives (forward-*), alpha^2 and two 2D
// derivatives (deferred-previous, deferred-max), alpha^2 and two 3D normal derivatives.
template <class Core>
constexpr bool reads_forward_inputs = std::is_invocable_v<Core, const ref::Params&, ref::Vec2, ref::Vec2, ref::Vec2>;
template <class Core>
constexpr bool reads_planar_inputs = std::is_invocable_r_v<double, Core, const ref::Params&, double, ref::Vec2, ref::Vec2>;
template <class Core>
constexpr bool reads_spatial_inputs = std::is_invocable_r_v<double, Core, const ref::Params&, double, ref::Vec3, ref::Vec3>;
template <class Core>
constexpr bool is_filter_core_form = reads_forward_inputs<Core> || reads_planar_inputs<Core> || reads_spatial_inputs<Core>;

inline ref::Vec2 absolute(ref::Vec2 v) { return {std::fabs(v.x), std::fabs(v.y)}; }
inline ref::Vec3 absolute(ref::Vec3 v) { return {std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}; }

// Core function `Core` on inputs read in parameter order (In: real, vec2, vec3, sym2). With
// `magnitudes`, the magnitude scale of each output for the fp32 rounding bound (core_cases.hpp):
// the function on the absolute values of its derivative inputs, by absolute value.
template <class Core, class In>
std::vector<double> filter_core_on(const ref::Params& p, In& in, bool magnitudes) {
  const auto evaluate = [&](auto alpha2, auto dx, auto dy) {
    if (!magnitudes) return output_values(Core{}(p, alpha2, dx, dy));
    std::vector<double> scale = output_values(Core{}(p, alpha2, absolute(dx), absolute(dy)));
    for (double& v : scale) v = std::fabs(v);
    return scale;
  };
  if constexpr (reads_forward_inputs<Core>) {
    const ref::Vec2 alpha2 = in.vec2(), dx = in.vec2(), dy = in.vec2();
    return evaluate(alpha2, dx, dy);
  } else if constexpr (reads_planar_inputs<Core>) {
    const double alpha2 = in.real();
    const ref::Vec2 dx = in.vec2(), dy = in.vec2();
    return evaluate(alpha2, dx, dy);
  } else {
    static_assert(reads_spatial_inputs<Core>, "a filter's core function has none of the forms");
    const double alpha2 = in.real();
    const ref::Vec3 dx = in.vec3(), dy = in.vec3();
    return evaluate(alpha2, dx, dy);
  }
}

// Calls visit(name, core) for every filter core function of the forms above, core being its
// reference as a callable object: the templates' filters, and deferred-max's tangent-free
// function. deferred-aniso's core reads a tensor's inputs: deferred_aniso_reference below.
template <class Visit>
void for_each_filter_core(Visit&& visit) {
  const auto visit_if_a_form = [&](const char* name, auto core) {
    if constexpr (is_filter_core_form<decltype(core)>) visit(name, core);
  };
#define SAAGEN_VISIT_FILTER_CORE(identifier, id) visit_if_a_form(#identifier, SAAGEN_REFERENCE_CALLABLE(identifier));
  SAAGEN_SAA_FILTERS(SAAGEN_VISIT_FILTER_CORE)
#undef SAAGEN_VISIT_FILTER_CORE
  visit_if_a_form("deferred_max_tangent_free", SAAGEN_REFERENCE_CALLABLE(deferred_max_tangent_free));
}

// The reference of filter core function `name` on inputs read in parameter order (In: real,
// vec2, vec3, sym2), or with `magnitudes` its magnitude scale (filter_core_on); nullopt for
// other functions. The one dispatch to the filters' core functions of every suite that compares
// them (core_cases.hpp, test_precision, test_stability_properties, test_spirv_library).
template <class In>
std::optional<std::vector<double>> filter_core_reference(const std::string& name, const ref::Params& p, In& in, bool magnitudes = false) {
  std::optional<std::vector<double>> result;
  for_each_filter_core([&](const char* core_name, auto core) {
    if (!result && name == core_name) result = filter_core_on<decltype(core)>(p, in, magnitudes);
  });
  return result;
}

// The names of the filter core functions that filter_core_reference evaluates.
inline std::vector<std::string> filter_core_names() {
  std::vector<std::string> names;
  for_each_filter_core([&](const char* name, auto) { names.push_back(name); });
  return names;
}

// --- the fragment wrappers ---------------------------------------------------------------------

// The fragment coordinates of the first quad (pixel centres at .5).
inline constexpr ref::Quad<ref::Vec2> kFirstQuadFragCoord{{0.5, 0.5}, {1.5, 0.5}, {0.5, 1.5}, {1.5, 1.5}};

// What a fragment wrapper's reference reads on a quad: the quad values of its vector parameters
// by parameter name (half_ts, half_ws, normal_ws, tangent_ws, bitangent_ws, i, o), and how it derives.
struct WrapperQuad {
  ref::Vec2 alpha2;
  std::map<std::string, ref::Quad<ref::Vec3>>& vectors;
  int pixel;
  ref::Derivative mode;
  ref::Derivative average;  // the quad-average normal's derivatives (deferred-previous, deferred-max)
  const ref::Quad<ref::Vec2>& frag;
};

// Wrapper reference `Wrapper` on a quad, in the form its signature has.
template <class Wrapper>
std::vector<double> filter_wrapper_on(const ref::Params& p, WrapperQuad q) {
  using namespace ref::wrapper_forms;  // the wrappers' forms, as the renderer's rows read them
  auto& v = q.vectors;
  if constexpr (reads_half_vectors<Wrapper>) {
    return output_values(Wrapper{}(p, q.alpha2, v["half_ts"], q.pixel, q.mode));
  } else if constexpr (reads_half_vectors_in_frames<Wrapper>) {
    return output_values(Wrapper{}(p, q.alpha2, v["half_ws"], v["normal_ws"], v["tangent_ws"], v["bitangent_ws"], q.pixel, q.mode));
  } else if constexpr (reads_normal_frame<Wrapper>) {
    return output_values(Wrapper{}(p, q.alpha2.x, v["normal_ws"], v["tangent_ws"], v["bitangent_ws"], q.frag, q.pixel, q.mode, q.average));
  } else if constexpr (reads_normals<Wrapper>) {
    return output_values(Wrapper{}(p, q.alpha2.x, v["normal_ws"], q.pixel, q.mode));
  } else {
    static_assert(reads_normals_alone<Wrapper>, "a filter's fragment wrapper reference has none of the forms");
    return output_values(Wrapper{}(p, v["normal_ws"], q.pixel, q.mode));
  }
}

// The reference of a filter's fragment wrapper `name` (<identifier>_fragment: the templates'
// filters, deferred-max's tangent-free function and the projected forms' transported ones) on a
// quad; nullopt for other functions.
inline std::optional<std::vector<double>> filter_wrapper_reference(const std::string& name, const ref::Params& p, WrapperQuad q) {
#define SAAGEN_FILTER_WRAPPER_CASE(identifier, id) \
  if (name == #identifier "_fragment") return filter_wrapper_on<decltype(SAAGEN_REFERENCE_CALLABLE(identifier##_fragment_quad))>(p, q);
  SAAGEN_SAA_FILTERS(SAAGEN_FILTER_WRAPPER_CASE)
#undef SAAGEN_FILTER_WRAPPER_CASE
  if (name == "deferred_max_tangent_free_fragment")
    return filter_wrapper_on<decltype(SAAGEN_REFERENCE_CALLABLE(deferred_max_tangent_free_fragment_quad))>(p, q);
  if (name == "forward_aniso_projected_transported_fragment")
    return filter_wrapper_on<decltype(SAAGEN_REFERENCE_CALLABLE(forward_aniso_projected_transported_fragment_quad))>(p, q);
  if (name == "forward_axis_projected_transported_fragment")
    return filter_wrapper_on<decltype(SAAGEN_REFERENCE_CALLABLE(forward_axis_projected_transported_fragment_quad))>(p, q);
  return std::nullopt;
}

// The reference of fragment wrapper `name` at `pixel` of a quad, given the quad values of its
// vector parameters by parameter name (half_ts, half_ws, normal_ws, tangent_ws, bitangent_ws, i, o): the
// one dispatch from a template's fragment wrapper to its CPU reference (saa.hpp, brdf.hpp) that
// every suite comparing wrappers uses (wrapper_cases.hpp too). `average`: how the quad-average
// normal of deferred-previous/-max takes its derivatives (fine in GLSL and HLSL; the plain
// derivative in GLSL ES, which has no fine one). Throws for a wrapper it does not know.
inline std::vector<double> wrapper_reference_on_quad(const std::string& name, const ref::Params& p, ref::Vec2 alpha2,
                                                     std::map<std::string, ref::Quad<ref::Vec3>>& vectors, int pixel,
                                                     ref::Derivative mode = ref::Derivative::coarse,
                                                     ref::Derivative average = ref::Derivative::fine,
                                                     const ref::Quad<ref::Vec2>& frag = kFirstQuadFragCoord) {
  if (auto filter = filter_wrapper_reference(name, p, {alpha2, vectors, pixel, mode, average, frag})) return *filter;
  if (name == "ggx_brdf_filtered_fragment")
    return output_values(ref::ggx_brdf_filtered_fragment_quad(p, vectors["i"], vectors["o"], alpha2, pixel, mode));
  if (name == "ggx_brdf_tail_filtered_fragment") {
    return output_values(ref::ggx_brdf_tail_filtered_fragment_quad(p, vectors["i"], vectors["o"], alpha2, pixel, mode));
  }
  if (name == "beckmann_brdf_filtered_fragment") {
    return output_values(ref::beckmann_brdf_filtered_fragment_quad(p, vectors["i"], vectors["o"], alpha2, pixel, mode));
  }
  throw std::runtime_error("no reference for " + name);
}

// --- normal-map prefiltering (templates/40-prefilter.saa), shared by the suites that iterate the
// catalogue: realistic inputs, the reference and a magnitude scale for fp32 rounding bounds.

// Realistic texel statistics: L = |mean normal| in [0.3, 1] (1 exactly one time in eight), E[s]
// with components in [-0.5, 0.5], a rotated covariance of trace 1e-6 .. 0.25 (eigenvalue ratio up
// to 100), and E[s s^T] = Sigma + E[s] E[s]^T. Deterministic in `index`.
struct PrefilterInputs {
  double mean_length = 1.0;
  ref::Vec2 slope_mean;
  ref::Sym2 slope_second;
};

inline PrefilterInputs prefilter_inputs(std::uint64_t index) {
  std::uint64_t state = index * 0x9E3779B97F4A7C15ull + 0x5EED;
  const auto unit = [&state] {
    state ^= state >> 33, state *= 0xFF51AFD7ED558CCDull, state ^= state >> 33, state *= 0xC4CEB9FE1A85EC53ull, state ^= state >> 33;
    return static_cast<double>(state >> 11) * 0x1p-53;
  };
  PrefilterInputs in;
  in.mean_length = index % 8 == 0 ? 1.0 : 0.3 + 0.7 * unit();
  in.slope_mean = {unit() - 0.5, unit() - 0.5};
  const double trace = std::pow(10.0, -6.0 + 5.4 * unit()), ratio = 0.01 + 0.99 * unit(), angle = 3.14159 * unit();
  const double l1 = trace / (1.0 + ratio), l2 = l1 * ratio, c = std::cos(angle), s = std::sin(angle);
  const ref::Sym2 covariance{l1 * c * c + l2 * s * s, (l1 - l2) * c * s, l1 * s * s + l2 * c * c};
  const ref::Vec2 m = in.slope_mean;
  in.slope_second = covariance + ref::Sym2{m.x * m.x, m.x * m.y, m.y * m.y};
  return in;
}

inline bool is_prefilter_parameter(const std::string& name) {
  return name == "mean_length" || name == "slope_mean" || name == "slope_second";
}

// The tail-preserving filtered GGX (templates/30-brdf.saa; docs/FILTERED_GGX.md) on inputs read in
// parameter order; nullopt for other functions. With `magnitudes`, the magnitude scale S of the
// output for the 2e-5 S fp32 rounding bound: each lobe's magnitude times (1 + the conditioning of
// its matrix, + the exponent for the Beckmann core), summed, times (1 + the conditioning of the
// filtered matrix) for the BRDF's G2 (the matrix BRDFs' scale, core_cases.hpp).
template <class In>
std::optional<std::vector<double>> filtered_ggx_reference(const std::string& name, const ref::Params& p, In& in, bool magnitudes = false) {
  using ref::Sym2;
  using ref::Vec2;
  using ref::Vec3;
  const ref::Brdf brdf{p};
  const auto conditioning = [](Sym2 a) {
    const double mean = 0.5 * (a.xx + a.yy), spread = std::sqrt(0.25 * (a.xx - a.yy) * (a.xx - a.yy) + a.xy * a.xy);
    return (mean + spread) / std::max(mean - spread, 1e-30);
  };
  const auto ndf_scale = [&](Vec3 h, Sym2 a, Vec2 alpha2) {
    const ref::FilteredGgxLobes lobes = ref::filtered_ggx_lobes(brdf.filtered_ggx_ratio(a, alpha2));
    const Sym2 unfiltered{alpha2.x, 0.0, alpha2.y};
    const Sym2 tail = lobes.tail_scale * unfiltered;
    const double tau = alpha2.x * alpha2.y;
    const auto beckmann_part = [&](double weight, double matrix_scale) {
      const Sym2 m = matrix_scale * (unfiltered + lobes.core_kernel * (a - unfiltered));
      double exponent = 0.0;
      if (h.z > 0.0)
        exponent = ref::sym2_quadratic_form({m.yy, -m.xy, m.xx}, {h.x / h.z, h.y / h.z}) / std::max(ref::sym2_determinant(m), tau);
      return std::fabs(weight * brdf.beckmann_ndf_matrix(h, m, tau)) * (1.0 + conditioning(m) + exponent);
    };
    return std::fabs(lobes.tail_weight * brdf.ggx_ndf_axis(h, {tail.xx, tail.yy})) * (1.0 + conditioning(tail)) +
           beckmann_part((1.0 - lobes.tail_weight) * lobes.shoulder_fraction, ref::kFilteredShoulderScale) +
           beckmann_part((1.0 - lobes.tail_weight) * (1.0 - lobes.shoulder_fraction), 1.0);
  };
  const auto brdf_value = [&](Vec3 i, Vec3 o, Sym2 a, Vec2 alpha2) {
    if (!magnitudes) return brdf.ggx_brdf_filtered_matrix(i, o, a, alpha2);
    if (i.z <= 0.0 || o.z <= 0.0) return 0.0;
    const Vec3 h = ref::normalize(i + o);
    const double g2 = brdf.ggx_g2_matrix(i, o, h, a) / (4.0 * std::max(i.z, 1e-7) * std::max(o.z, 1e-7));
    return ndf_scale(h, a, alpha2) * g2 * (1.0 + conditioning(a));
  };
  if (name == "ggx_ndf_filtered_matrix") {
    const Vec3 h = in.vec3();
    const Sym2 a = in.sym2();
    const Vec2 alpha2 = in.vec2();
    return output_values(magnitudes ? ndf_scale(h, a, alpha2) * (1.0 + conditioning(a)) : brdf.ggx_ndf_filtered_matrix(h, a, alpha2));
  }
  if (name == "ggx_brdf_filtered_matrix") {
    const Vec3 i = in.vec3(), o = in.vec3();
    const Sym2 a = in.sym2();
    return output_values(brdf_value(i, o, a, in.vec2()));
  }
  if (name == "ggx_brdf_filtered_axis") {
    const Vec3 i = in.vec3(), o = in.vec3();
    const Vec2 filtered = in.vec2(), alpha2 = in.vec2();
    return output_values(magnitudes ? brdf_value(i, o, {filtered.x, 0.0, filtered.y}, alpha2)
                                    : brdf.ggx_brdf_filtered_axis(i, o, filtered, alpha2));
  }
  if (name == "ggx_filtered_lobe_isotropic") {
    const double filtered = in.real(), alpha2 = in.real();
    const ref::IsotropicLobe lobe = brdf.ggx_filtered_lobe_isotropic(filtered, alpha2);
    if (!magnitudes) return std::vector<double>(lobe.begin(), lobe.end());
    // Every parameter carries the rounding of the kernel filtered - alpha^2 (relative to |filtered|
    // + |alpha^2|) into u lambda = u + 1.2536 k and into the core m = alpha^2 + c k (c <= 1.33):
    // relative to them, 1.2536 (|f| + |a|) / (u lambda) and 1.33 (|f| + |a|) / m; w = u / (u lambda),
    // 1 / (4 m) and f / 2 (|d ln(f / 2) / d ln w| <= 2.3) amplify it at most 3 times.
    const double cancelled = std::fabs(filtered) + std::fabs(alpha2);
    const double spread = 1.0 + 3.0 * cancelled * (1.2536 / std::fabs(lobe[0]) + 1.33 * 4.0 * std::fabs(lobe[2]));
    return std::vector<double>{std::fabs(lobe[0]) * spread, std::fabs(lobe[1]) * spread, std::fabs(lobe[2]) * spread,
                               std::fabs(lobe[3]) * spread};
  }
  if (name == "ggx_brdf_filtered_lobe") {
    const Vec3 i = in.vec3(), o = in.vec3();
    const double filtered = in.real(), alpha2 = in.real();
    const ref::IsotropicLobe lobe{in.real(), in.real(), in.real(), in.real()};
    // The lobe as the device read it; the scale is the axis form's of (filtered, filtered), the same lobe.
    return output_values(magnitudes ? brdf_value(i, o, {filtered, 0.0, filtered}, {alpha2, alpha2})
                                    : brdf.ggx_brdf_filtered_lobe(i, o, filtered, alpha2, lobe));
  }
  if (name == "ggx_filtered_alpha2") {
    const double a = in.real(), kernel = in.real();
    return output_values(magnitudes ? std::fabs(brdf.ggx_filtered_alpha2(std::fabs(a), std::fabs(kernel)))
                                    : brdf.ggx_filtered_alpha2(a, kernel));
  }
  return std::nullopt;
}

// The reference of prefilter function `name` on inputs read in parameter order (In: real, vec2,
// vec3, sym2); nullopt for other functions. With `magnitudes`, the magnitude scale of each output
// instead: the same expression with every term taken by absolute value (|E[s s^T]| + E[s]^2 for the
// covariance, whose subtraction cancels), so that 2e-5 times it bounds fp32 rounding.
template <class In>
std::optional<std::vector<double>> prefilter_reference(const std::string& name, const ref::Params& p, In& in, bool magnitudes = false) {
  using ref::Sym2;
  using ref::Vec2;
  using ref::Vec3;
  const auto abs2 = [](Vec2 v) { return Vec2{std::fabs(v.x), std::fabs(v.y)}; };
  const auto abs3 = [](Vec3 v) { return Vec3{std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}; };
  const auto covariance_scale = [](Vec2 m, Sym2 e) {
    const double xx = std::fabs(e.xx) + m.x * m.x, yy = std::fabs(e.yy) + m.y * m.y;
    return Sym2{xx, std::fabs(e.xy) + std::fabs(m.x * m.y) + std::sqrt(xx * yy), yy};
  };
  const auto kernel_scale = [&](Vec3 dx, Vec3 dy) { return ref::min(2.0 * ref::isotropic_kernel_sum(p, abs3(dx), abs3(dy)), p.kappa); };
  if (name == "toksvig_variance") {
    const double l = in.real();
    return output_values(ref::toksvig_variance(p, l));
  }
  if (name == "lean_covariance") {
    const Vec2 m = in.vec2();
    const Sym2 e = in.sym2();
    return output_values(magnitudes ? covariance_scale(m, e) : ref::lean_covariance(p, m, e));
  }
  if (name == "prefilter_toksvig") {
    const double a = in.real(), l = in.real();
    return output_values(magnitudes ? std::fabs(a) + 2.0 * ref::toksvig_variance(p, l) : ref::prefilter_toksvig(p, a, l));
  }
  if (name == "prefilter_toksvig_sum" || name == "prefilter_toksvig_projected") {
    const double a = in.real(), l = in.real();
    const Vec3 dx = in.vec3(), dy = in.vec3();
    if (magnitudes) return output_values(std::fabs(a) + 2.0 * ref::toksvig_variance(p, l) + kernel_scale(dx, dy));
    return output_values(name == "prefilter_toksvig_sum" ? ref::prefilter_toksvig_sum(p, a, l, dx, dy)
                                                         : ref::prefilter_toksvig_projected(p, a, l, dx, dy));
  }
  if (name == "prefilter_lean") {
    const Vec2 a = in.vec2(), m = in.vec2();
    const Sym2 e = in.sym2();
    if (magnitudes) return output_values(Sym2{std::fabs(a.x), 0.0, std::fabs(a.y)} + 2.0 * covariance_scale(m, e));
    return output_values(ref::prefilter_lean(p, a, m, e));
  }
  if (name == "prefilter_lean_aniso_slope") {
    const Vec2 a = in.vec2(), m = in.vec2();
    const Sym2 e = in.sym2();
    const Vec2 du = in.vec2(), dv = in.vec2();
    if (magnitudes) {
      const Sym2 k = ref::filter_roughness_matrix(p, abs2(a), abs2(du), abs2(dv));
      return output_values(Sym2{k.xx, std::fabs(k.xy) + std::sqrt(k.xx * k.yy), k.yy} + 2.0 * covariance_scale(m, e));
    }
    return output_values(ref::prefilter_lean_aniso_slope(p, a, m, e, du, dv));
  }
  if (name == "prefilter_lean_sum" || name == "prefilter_lean_projected") {
    const double a = in.real();
    const Vec2 m = in.vec2();
    const Sym2 e = in.sym2();
    const Vec3 dx = in.vec3(), dy = in.vec3();
    if (magnitudes) {
      const Sym2 c = covariance_scale(m, e);
      return output_values(std::fabs(a) + c.xx + c.yy + kernel_scale(dx, dy));
    }
    return output_values(name == "prefilter_lean_sum" ? ref::prefilter_lean_sum(p, a, m, e, dx, dy)
                                                      : ref::prefilter_lean_projected(p, a, m, e, dx, dy));
  }
  return std::nullopt;
}

// A list of doubles read as the inputs of a reference (the `In` of the dispatchers below).
struct ValueList {
  std::vector<double> values;
  std::size_t next = 0;
  double real() { return values.at(next++); }
  ref::Vec2 vec2() {
    const double x = real();
    return {x, real()};
  }
  ref::Vec3 vec3() {
    const double x = real(), y = real();
    return {x, y, real()};
  }
  ref::Sym2 sym2() {
    const double xx = real(), xy = real();
    return {xx, xy, real()};
  }
};

// A texture frame for deferred_aniso_covariance's inputs: unit tangent and bitangent orthogonal
// to the unit normal n, the tangent turned by `angle` about n from an axis picked from n, the
// bitangent sign * (n x t) (sign -1: a mirrored uv layout).
struct TextureFrame {
  ref::Vec3 tangent, bitangent;
};

inline TextureFrame texture_frame(ref::Vec3 n, double angle, double sign) {
  const ref::Vec3 axis = std::fabs(n.x) < 0.9 ? ref::Vec3{1.0, 0.0, 0.0} : ref::Vec3{0.0, 1.0, 0.0};
  const ref::Vec3 t0 = ref::normalize(ref::cross(axis, n)), b0 = ref::cross(n, t0);
  const ref::Vec3 t = std::cos(angle) * t0 + std::sin(angle) * b0;
  return {t, sign * ref::cross(n, t)};
}

// deferred-aniso's core and evaluate functions (templates/20-deferred.saa) on inputs read in
// parameter order (In: real, vec2, vec3, sym2); nullopt for other functions. With `magnitudes`,
// the magnitude scale S of each output for the 2e-5 S fp32 rounding bound (core_cases.hpp):
//  - deferred_aniso: the unclamped trace 2 sigma^2 (|dn_dx|^2 + |dn_dy|^2), which bounds every
//    entry: the products round relative to it, and where the kappa clamp acts the smaller
//    eigenvalue of a nearly rank-1 matrix is known only to eps times the trace;
//  - deferred_aniso_covariance: 2 (|S|xx + 2 |S|xy + |S|yy) max(1, |t|, |b|)^2 with |S| the
//    covariance's magnitude (|E[s s^T]| + |E[s]|^2 per entry, its subtraction cancels): each
//    entry of R (2 Sigma) R^T is a sum of four products of two entries of R, each at most
//    |t| or |b| (the frame built from n is unit), with one entry of 2 Sigma;
//  - deferred_aniso_roughness: alpha^2 + |Kxx| + |Kyy|, and _with_covariance + |Cxx| + |Cyy|;
//  - deferred_aniso_lobe: deferred_aniso_lobe_magnitudes;
//  - deferred_aniso_brdf (_with_covariance, _lobe): the filtered GGX's scale, plus the frame: the directions enter through
//    dot products with a frame built in fp32 (a few ulps of absolute error delta in i_ts, o_ts,
//    h_ts), which moves the NDF's quadratic form h.xy^T M^-1 h.xy / h_z^2 by at most
//    2 |h.xy| delta / (alpha^2 h_z^2) for every lobe M >= alpha^2 I (the GGX lobe's relative
//    error is twice that) and the cosines i.z, o.z by delta:
//    S += |f| (4 |h.xy| / (alpha^2 h_z^2) + 1 / i.z + 1 / o.z).
// deferred_aniso_lobe's magnitudes: every value carries the rounding of the kernel A - alpha^2 I
// that the template takes back out of A = alpha^2 I + K (relative to |alpha^2| + |Kxx| + |Kyy|)
// into u lambda = u + 0.6268 tr K, amplified at most 3 times (as ggx_filtered_lobe_isotropic's);
// 1 / sqrt(det 2 M) also carries det(M) = M00 M11 - M01^2, which cancels for a nearly rank-1 kernel
// to (|M00 M11| + M01^2) / det(M) of its rounding.
inline std::vector<double> deferred_aniso_lobe_magnitudes(ref::Sym2 tensor, double alpha2, const ref::IsotropicLobe& lobe) {
  const double cancelled = std::fabs(alpha2) + std::fabs(tensor.xx) + std::fabs(tensor.yy);
  const double spread = 1.0 + 3.0 * cancelled * 1.2536 / std::fabs(lobe[0]);
  const ref::Sym2 core = ref::Sym2{alpha2, 0.0, alpha2} + ref::filtered_ggx_core_kernel(lobe[1]) * tensor;
  const double det = 0.25 / (lobe[2] * lobe[2]);
  const double conditioning = (std::fabs(core.xx * core.yy) + core.xy * core.xy) / det;
  return {std::fabs(lobe[0]) * spread, std::fabs(lobe[1]) * spread, std::fabs(lobe[2]) * (spread + conditioning),
          std::fabs(lobe[3]) * spread};
}

template <class In>
std::optional<std::vector<double>> deferred_aniso_reference(const std::string& name, const ref::Params& p, In& in,
                                                            bool magnitudes = false) {
  if (name == "deferred_aniso") {
    const ref::Vec3 dx = in.vec3(), dy = in.vec3(), normal = in.vec3();
    if (magnitudes) return std::vector<double>(3, 2.0 * ref::isotropic_kernel_sum(p, dx, dy));
    return output_values(ref::deferred_aniso(p, dx, dy, normal));
  }
  if (name == "deferred_aniso_covariance") {
    const ref::Vec2 m = in.vec2();
    const ref::Sym2 e = in.sym2();
    const ref::Vec3 tangent = in.vec3(), bitangent = in.vec3(), normal = in.vec3();
    if (!magnitudes) return output_values(ref::deferred_aniso_covariance(p, m, e, tangent, bitangent, normal));
    const double xx = std::fabs(e.xx) + m.x * m.x, yy = std::fabs(e.yy) + m.y * m.y;
    const double xy = std::fabs(e.xy) + std::fabs(m.x * m.y) + std::sqrt(xx * yy);
    const double frame = std::max({1.0, ref::length(tangent), ref::length(bitangent)});
    return std::vector<double>(3, 2.0 * (xx + 2.0 * xy + yy) * frame * frame);
  }
  const bool with_covariance = name == "deferred_aniso_roughness_with_covariance" || name == "deferred_aniso_brdf_with_covariance";
  if (name == "deferred_aniso_lobe") {
    const ref::Sym2 tensor = in.sym2();
    const double alpha2 = in.real();
    const ref::IsotropicLobe lobe = ref::deferred_aniso_lobe(p, tensor, alpha2);
    if (!magnitudes) return std::vector<double>(lobe.begin(), lobe.end());
    return deferred_aniso_lobe_magnitudes(tensor, alpha2, lobe);
  }
  const bool split = name == "deferred_aniso_brdf_lobe";
  if (name != "deferred_aniso_roughness" && name != "deferred_aniso_brdf" && !with_covariance && !split) return std::nullopt;
  const ref::Vec3 light = in.vec3(), view = in.vec3(), normal = in.vec3();
  const ref::Sym2 tensor = in.sym2();
  const ref::Sym2 covariance = with_covariance ? in.sym2() : ref::Sym2{};
  const double alpha2 = in.real();
  if (name == "deferred_aniso_roughness" || name == "deferred_aniso_roughness_with_covariance") {
    if (magnitudes)
      return std::vector<double>(
          3, std::fabs(alpha2) + std::fabs(tensor.xx) + std::fabs(tensor.yy) + std::fabs(covariance.xx) + std::fabs(covariance.yy));
    return output_values(with_covariance ? ref::deferred_aniso_roughness_with_covariance(p, light, view, normal, tensor, covariance, alpha2)
                                         : ref::deferred_aniso_roughness(p, light, view, normal, tensor, alpha2));
  }
  // The split form's lobe as the device read it.
  const ref::IsotropicLobe lobe = split ? ref::IsotropicLobe{in.real(), in.real(), in.real(), in.real()} : ref::IsotropicLobe{};
  const double value = split             ? ref::deferred_aniso_brdf_lobe(p, light, view, normal, tensor, alpha2, lobe)
                       : with_covariance ? ref::deferred_aniso_brdf_with_covariance(p, light, view, normal, tensor, covariance, alpha2)
                                         : ref::deferred_aniso_brdf(p, light, view, normal, tensor, alpha2);
  if (!magnitudes) return output_values(value);
  const ref::Vec3 t = ref::normal_frame_tangent(normal), b = ref::normal_frame_bitangent(normal);
  const ref::Vec3 i = ref::to_tangent_space(light, t, b, normal), o = ref::to_tangent_space(view, t, b, normal);
  const ref::Sym2 a = ref::deferred_aniso_tail_roughness(tensor + covariance, alpha2);
  ValueList lobe_inputs{{i.x, i.y, i.z, o.x, o.y, o.z, a.xx, a.xy, a.yy, alpha2, alpha2}};
  const double lobes = filtered_ggx_reference("ggx_brdf_filtered_matrix", p, lobe_inputs, true)->at(0);
  if (i.z <= 0.0 || o.z <= 0.0) return std::vector<double>{lobes};
  const ref::Vec3 h = ref::normalize(i + o);
  const double frame = 4.0 * std::sqrt(h.x * h.x + h.y * h.y) / std::max(alpha2 * h.z * h.z, 1e-30) + 1.0 / i.z + 1.0 / o.z;
  return std::vector<double>{lobes + std::fabs(value) * frame};
}

// The reference of a BRDF core function in matrix form (the GGX and Beckmann NDF, Lambda and
// BRDF, GGX's G2) on inputs read in parameter order; nullopt for other functions.
template <class In>
std::optional<std::vector<double>> brdf_matrix_reference(const std::string& name, const ref::Params& p, In& in) {
  const ref::Brdf brdf{p};
  const bool ggx = name.rfind("ggx_", 0) == 0;
  if (name == "ggx_ndf_matrix" || name == "beckmann_ndf_matrix") {
    const ref::Vec3 h = in.vec3();
    const ref::Sym2 a = in.sym2();
    const double tau = in.real();
    return output_values(ggx ? brdf.ggx_ndf_matrix(h, a, tau) : brdf.beckmann_ndf_matrix(h, a, tau));
  }
  if (name == "ggx_lambda_matrix" || name == "beckmann_lambda_matrix") {
    const ref::Vec3 w = in.vec3();
    const ref::Sym2 a = in.sym2();
    return output_values(ggx ? brdf.ggx_lambda_matrix(w, a) : brdf.beckmann_lambda_matrix(w, a));
  }
  if (name == "ggx_g2_matrix") {
    const ref::Vec3 i = in.vec3(), o = in.vec3(), h = in.vec3();
    return output_values(brdf.ggx_g2_matrix(i, o, h, in.sym2()));
  }
  if (name == "ggx_brdf_matrix" || name == "beckmann_brdf_matrix") {
    const ref::Vec3 i = in.vec3(), o = in.vec3();
    const ref::Sym2 a = in.sym2();
    const double tau = in.real();
    return output_values(ggx ? brdf.ggx_brdf_matrix(i, o, a, tau) : brdf.beckmann_brdf_matrix(i, o, a, tau));
  }
  return std::nullopt;
}

// The reference of a BRDF core function in axis form (alpha^2 per axis: the GGX NDF, Lambda and
// BRDF, Beckmann's NDF and BRDF) on inputs read in parameter order; nullopt for other functions.
template <class In>
std::optional<std::vector<double>> brdf_axis_reference(const std::string& name, const ref::Params& p, In& in) {
  const ref::Brdf brdf{p};
  if (name == "ggx_ndf_axis" || name == "ggx_lambda_axis" || name == "beckmann_ndf_axis") {
    const ref::Vec3 direction = in.vec3();
    const ref::Vec2 alpha2 = in.vec2();
    if (name == "ggx_ndf_axis") return output_values(brdf.ggx_ndf_axis(direction, alpha2));
    if (name == "ggx_lambda_axis") return output_values(brdf.ggx_lambda_axis(direction, alpha2));
    return output_values(brdf.beckmann_ndf_axis(direction, alpha2));
  }
  if (name == "ggx_brdf_axis" || name == "beckmann_brdf_axis") {
    const ref::Vec3 i = in.vec3(), o = in.vec3();
    const ref::Vec2 alpha2 = in.vec2();
    return output_values(name == "ggx_brdf_axis" ? brdf.ggx_brdf_axis(i, o, alpha2) : brdf.beckmann_brdf_axis(i, o, alpha2));
  }
  return std::nullopt;
}

// The reference of any core or evaluate function of the built-in catalogue on one element's
// packed inputs (fp32 as a device reads them, or doubles), by name. The one dispatch of the
// suites that run every such function on packed inputs (test_precision,
// test_stability_properties); throws for a function without a reference.
template <class Scalar>
std::vector<double> core_function_reference(const std::string& name, const ref::Params& p, const Scalar* packed) {
  PackedReader<Scalar> in(packed);
  if (auto prefiltered = prefilter_reference(name, p, in)) return *prefiltered;
  if (auto filtered = filtered_ggx_reference(name, p, in)) return *filtered;
  if (auto tensor = deferred_aniso_reference(name, p, in)) return *tensor;
  if (auto filter = filter_core_reference(name, p, in)) return *filter;
  if (name == "ndf_clamp_tau") return output_values(ref::ndf_clamp_tau(in.vec2()));
  if (auto matrix = brdf_matrix_reference(name, p, in)) return *matrix;
  if (auto axis = brdf_axis_reference(name, p, in)) return *axis;
  throw std::runtime_error("no reference for " + name);
}

}  // namespace saagen::test
