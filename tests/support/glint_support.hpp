// Shared plumbing for the glint suites: the default dictionary (generated once per process), its
// texture as the reference's software sampler sees it, and what the GPU suites (test_glints_gpu on
// Vulkan, test_wgsl on WebGPU, test_webgl in WebGL2) share to run the emitted glint functions
// against the double-precision reference: the inputs, the reference per function, and the
// per-output bounds.
//
// Error bounds (docs/GLINTS.md, "Precision"): the device evaluates in fp32; the bound of each
// element is its sensitivity to fp32-sized perturbations of the inputs, estimated from the
// reference itself: B = 3 max_k |f(x (1 + e_k)) - f(x)| + 4e-6 |f(x)| + 1e-12 scale, over six
// random sign patterns e_k with |e_k| = 2^-21 per input component. This covers the rounding of
// u * width, of the cell coordinates, of the rotation and of the sampler's arithmetic (backward
// errors of a few ulps), and grows by itself where a discontinuity (a cell, a LOD or the edge of
// the dictionary) lies within rounding distance.
// Added to it, T = max |f' - f| over the reference f' whose transcendentals sit at either end of
// what the Vulkan specification allows ("Precision and Operation of SPIR-V Instructions"; WGSL's
// table, section 15.7.4, and GLSL ES 3.00's highp, section 4.5.1, are the same): the footprint
// LOD's log2(size) off by 3 ulp (|log2 size| 3 2^-23; 2^-21 absolute inside [0.5, 2]), the cell
// scale exp2(x), x = log_density / (2 ln 2) - level (up to ~14), and the EWA weights
// exp(-2 r^2), off by a factor 1 +- (3 + 2|x|) 2^-23 (g::Dictionary::log2_side, exp2_side): up
// to ~30 ulp, far more than the 2^-21 input perturbations cover. Plus T_trig, the same for each
// cell's rotation: cos and sin within 2^-11 absolute of the exact value in [-pi, pi] (the
// snippet's angle lies in that range; outside it the spec bounds nothing), every cell's product
// at the low or high end of that box (g::Dictionary::trig_side). Division (2.5 ulp), inversesqrt
// (2 ulp) and sqrt (inherited) stay within the 4e-6 |f| term and the perturbations.
//
// The sampler is held to what the Vulkan specification lets any implementation do
// (ref::glints::SamplerTolerance, from mipmapPrecisionBits and subTexelPrecisionBits): lambda
// anywhere in [log2 rho - 2^-mip, log2 rho + 1/2 + 2^-mip], level weights snapped to
// 2^-mipmapPrecisionBits, the texel coordinate to 2^-subTexelPrecisionBits. The reference is
// evaluated at both ends of that range (every lookup at its low, then its high end: the glint
// functions are non-negative sums of products of non-negative lookups) and the device must lie
// in between, plus the fp32 bound above and T_trig (Comparison::spec_*). The snippets read the
// dictionary at integer levels only (the GGAA lookup computes its LOD and blends two levels
// itself), so of that freedom only the texel coordinate and the result's rounding apply
// (ref::glints::texture_level_range): no LOD rule, LOD accuracy or level weight of the device
// enters. A tighter check (Comparison::expected, bounds) takes the exact sampler and leaves
// T_trig out.
#pragma once

#include "saagen/front/catalogue.hpp"
#include "saagen/products/glints.hpp"
#include "saagen/reference/glints.hpp"
#include "saagen/reference/quad.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace saagen::test {

// The dictionary with the paper's defaults (N = 192, L = 16, R = 64, alpha = 0.5), generated once.
inline const glints::Dictionary& default_dictionary() {
  static const glints::Dictionary dictionary = glints::generate_dictionary({});
  return dictionary;
}

inline const glints::DictionaryTexture& default_texture() {
  static const glints::DictionaryTexture texture = glints::dictionary_texture(default_dictionary(), true);
  return texture;
}

// The half texels as doubles: exactly what the GPU filters (lavapipe filters RGBA16F in fp32).
inline ref::glints::Texture1DArray reference_texture(const glints::DictionaryTexture& texture) {
  ref::glints::Texture1DArray result;
  result.width = static_cast<int>(texture.width);
  result.layers = static_cast<int>(texture.layers);
  for (const auto& level : texture.levels) {
    std::vector<double> values(level.size());
    for (std::size_t k = 0; k < level.size(); ++k) values[k] = glints::from_half(level[k]);
    result.levels.push_back(std::move(values));
  }
  return result;
}

inline const ref::glints::Texture1DArray& default_reference_texture() {
  static const ref::glints::Texture1DArray texture = reference_texture(default_texture());
  return texture;
}

inline ref::glints::Dictionary default_reference_dictionary() {
  ref::glints::Dictionary dictionary;
  dictionary.texture = &default_reference_texture();
  return dictionary;
}

namespace glint {

namespace g = saagen::ref::glints;
using saagen::ref::Sym2;
using saagen::ref::Vec2;
using saagen::ref::Vec3;

// ---------------------------------------------------------------------------------------------
// The core functions: random inputs, packed as the kernels load them, and their reference

struct Scenario {
  Vec2 slope, uv, duv_dx, duv_dy, dh_dx, dh_dy, mean;
  Vec3 i, o;
  g::Roughness roughness;
  double log_density = 15.0;
  Vec2 alpha;  // LEAN inputs
  Sym2 second;
};

inline Vec3 unit_vector(double z, double phi) {
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

inline std::vector<Scenario> scenarios(std::size_t count) {
  std::mt19937_64 random(20210504);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const g::Params params;
  const double x_max = g::dictionary_range(params);
  std::vector<Scenario> all;
  while (all.size() < count) {
    Scenario s;
    s.roughness = {0.03 + 0.47 * unit(random), 0.03 + 0.47 * unit(random), -0.95 + 1.9 * unit(random)};
    if (all.size() % 5 == 0) s.roughness.rho = 0.0;
    s.log_density = 10.0 + 10.0 * unit(random);
    // Footprint: l_P uniform in [-0.5, 16] (clamped at both ends), random shape.
    const double lod = -0.5 + 16.5 * unit(random);
    const double size = std::exp2(lod - s.log_density * 0.721347520444482);
    // One in eight beyond the 8:1 anisotropy clamp (2020 Alg. 1 line 4), the rest up to 5:1.
    const double angle = 6.283185307179586 * unit(random);
    const double shape = all.size() % 8 == 1 ? 0.01 + 0.11 * unit(random) : 0.2 + 0.8 * unit(random);
    s.duv_dx = {size * std::cos(angle), size * std::sin(angle)};
    s.duv_dy = {-shape * size * std::sin(angle + 0.3), shape * size * std::cos(angle + 0.3)};
    // Three in four near the uv origin; one in four anywhere in [-0.2, 1.2]^2, where the cell
    // coordinate uv * density^(1/2) reaches 2^14 and fp32 keeps ~1e-3 of a cell: the bound
    // (sensitivity to the inputs' rounding) widens there, by itself.
    if (all.size() % 4 == 0)
      s.uv = {-0.2 + 1.4 * unit(random), -0.2 + 1.4 * unit(random)};
    else
      s.uv = {0.002 * unit(random), 0.002 * unit(random)};
    // A half vector whose slope lands inside the dictionary (so that lobes are hit).
    const double radius = 0.9 * x_max * std::sqrt(unit(random)), phi = 6.283185307179586 * unit(random);
    const Vec2 q{radius * std::cos(phi), radius * std::sin(phi)};
    // slope = A q with A of Eq. 18
    const double c = std::sqrt(1.0 - s.roughness.rho * s.roughness.rho);
    s.slope = {(s.roughness.alpha_x * c * q.x + s.roughness.rho * s.roughness.alpha_x * q.y) / params.alpha_dict,
               s.roughness.alpha_y * q.y / params.alpha_dict};
    s.mean = all.size() % 3 == 0 ? Vec2{0.0, 0.0} : Vec2{0.1 * (unit(random) - 0.5), 0.1 * (unit(random) - 0.5)};
    // Directions with that half-vector slope (plus the mean slope, which the BRDF subtracts).
    const Vec2 full = s.slope + s.mean;
    const Vec3 h = saagen::ref::normalize(Vec3{-full.x, -full.y, 1.0});
    const Vec3 o = unit_vector(0.05 + 0.95 * unit(random), 6.283185307179586 * unit(random));
    const double oh = saagen::ref::dot(o, h);
    const Vec3 i = 2.0 * oh * h - o;
    if (oh < 0.05 || i.z < 0.02) continue;
    s.i = i;
    s.o = o;
    // GGAA kernels from a tenth of a texel to the whole range: lambda in [-3, 8].
    const double kernel = std::exp2(-3.0 + 11.0 * unit(random)) * x_max / (64.0 * params.kernel_scale) * 0.5 *
                          (s.roughness.alpha_x + s.roughness.alpha_y) / params.alpha_dict;
    const double dangle = 6.283185307179586 * unit(random);
    s.dh_dx = {kernel * std::cos(dangle), kernel * std::sin(dangle)};
    s.dh_dy = {-0.6 * kernel * std::sin(dangle), 0.4 * kernel * std::cos(dangle)};
    s.alpha = {0.02 + 0.4 * unit(random), 0.02 + 0.4 * unit(random)};
    const Vec2 mean{0.3 * (unit(random) - 0.5), 0.3 * (unit(random) - 0.5)};
    const double vx = 0.05 * unit(random), vy = 0.05 * unit(random), r = -0.9 + 1.8 * unit(random);
    s.second = {vx + mean.x * mean.x, r * std::sqrt(vx * vy) + mean.x * mean.y, vy + mean.y * mean.y};
    s.mean = all.size() % 7 == 0 ? mean : s.mean;
    all.push_back(s);
  }
  return all;
}

inline void push(std::vector<float>& out, double v) { out.push_back(static_cast<float>(v)); }
inline void push(std::vector<float>& out, Vec2 v) { push(out, v.x), push(out, v.y); }
inline void push(std::vector<float>& out, Vec3 v) { push(out, v.x), push(out, v.y), push(out, v.z); }

inline void pack(const saagen::Function& function, const Scenario& s, std::vector<float>& out) {
  for (const saagen::Parameter& parameter : function.parameters) {
    const std::string& name = parameter.name;
    if (name == "slope")
      push(out, s.slope);
    else if (name == "uv")
      push(out, s.uv);
    else if (name == "duv_dx")
      push(out, s.duv_dx);
    else if (name == "duv_dy")
      push(out, s.duv_dy);
    else if (name == "dh_dx")
      push(out, s.dh_dx);
    else if (name == "dh_dy")
      push(out, s.dh_dy);
    else if (name == "roughness")
      push(out, Vec3{s.roughness.alpha_x, s.roughness.alpha_y, s.roughness.rho});
    else if (name == "log_density")
      push(out, s.log_density);
    else if (name == "i")
      push(out, s.i);
    else if (name == "o")
      push(out, s.o);
    else if (name == "mean_slope" || name == "mean")
      push(out, s.mean);
    else if (name == "alpha")
      push(out, s.alpha);
    else if (name == "second")
      push(out, Vec3{s.second.xx, s.second.xy, s.second.yy});
    else
      throw std::runtime_error("no input for parameter " + name + " of " + function.name);
  }
}

// Reads packed fp32 inputs back as doubles.
class Inputs {
 public:
  explicit Inputs(std::vector<double> data) : data_(std::move(data)) {}
  double real() { return data_.at(next_++); }
  Vec2 vec2() {
    const double x = real();
    return {x, real()};
  }
  Vec3 vec3() {
    const double x = real(), y = real();
    return {x, y, real()};
  }
  g::Roughness roughness() {
    const Vec3 v = vec3();
    return {v.x, v.y, v.z};
  }

 private:
  std::vector<double> data_;
  std::size_t next_ = 0;
};

using ReferenceFunction = std::function<std::vector<double>(Inputs&)>;

inline std::map<std::string, ReferenceFunction> reference_functions(const g::Dictionary& d) {
  std::map<std::string, ReferenceFunction> table;
  table["glint_sdf"] = [d](Inputs& in) {
    const Vec2 slope = in.vec2(), uv = in.vec2(), dx = in.vec2(), dy = in.vec2();
    const g::Roughness r = in.roughness();
    return std::vector<double>{g::sdf(d, slope, uv, dx, dy, r, in.real())};
  };
  table["glint_sdf_filtered"] = [d](Inputs& in) {
    const Vec2 slope = in.vec2(), hx_ = in.vec2(), hy = in.vec2(), uv = in.vec2(), dx = in.vec2(), dy = in.vec2();
    const g::Roughness r = in.roughness();
    return std::vector<double>{g::sdf_filtered(d, slope, hx_, hy, uv, dx, dy, r, in.real())};
  };
  table["glint_brdf"] = [d](Inputs& in) {
    const Vec3 i = in.vec3(), o = in.vec3();
    const Vec2 mean = in.vec2(), uv = in.vec2(), dx = in.vec2(), dy = in.vec2();
    const g::Roughness r = in.roughness();
    return std::vector<double>{g::brdf(d, i, o, mean, uv, dx, dy, r, in.real())};
  };
  table["glint_brdf_filtered"] = [d](Inputs& in) {
    const Vec3 i = in.vec3(), o = in.vec3();
    const Vec2 mean = in.vec2(), hx_ = in.vec2(), hy = in.vec2(), uv = in.vec2(), dx = in.vec2(), dy = in.vec2();
    const g::Roughness r = in.roughness();
    return std::vector<double>{g::brdf_filtered(d, i, o, mean, hx_, hy, uv, dx, dy, r, in.real())};
  };
  table["lean_roughness"] = [](Inputs& in) {
    const Vec2 alpha = in.vec2(), mean = in.vec2();
    const Vec3 second = in.vec3();
    const g::Roughness r = g::lean_roughness(alpha, mean, Sym2{second.x, second.y, second.z});
    return std::vector<double>{r.alpha_x, r.alpha_y, r.rho};
  };
  return table;
}

// Emission options other than the defaults (the reference gets the same).
struct Options {
  double relative_area = 1.0;
  double max_anisotropy = 8.0;
};

inline g::Dictionary configured(g::Dictionary dictionary, const Options& options) {
  dictionary.params.relative_area = options.relative_area;
  dictionary.params.max_anisotropy = options.max_anisotropy;
  return dictionary;
}

// The outputs of one run against the reference, per output in the device's order.
struct Comparison {
  // The tight check: the reference with the exact sampler, and the fp32 bound (no cos / sin allowance).
  std::vector<double> expected, bounds;
  // The specification check: the centre and half-width of [low, high], widened by the fp32 bound
  // and the cos / sin allowance.
  std::vector<double> spec_expected, spec_bounds;
  // Outputs whose exact-LOD reference lies outside [low, high]: the monotonicity the bound relies on.
  std::size_t outside = 0;
};

// Per element: the interval [low, high] a conforming device may return, widened by `widening`.
inline void push_interval(std::vector<double>& expected, std::vector<double>& bounds, double low, double high, double widening) {
  if (low > high) std::swap(low, high);
  expected.push_back(0.5 * (low + high));
  bounds.push_back(0.5 * (high - low) + widening);
}

// The reference and bounds of `function` over `count` elements of packed fp32 inputs
// (`input_stride` floats each). `spec`: the sampler freedom of the specification check.
inline Comparison core_comparison(const std::string& function, const Options& options, const std::vector<float>& inputs, std::size_t count,
                                  std::size_t input_stride, const g::SamplerTolerance& spec) {
  // Nominal: the exact sampler. Low / high: every lookup at the end of what the spec allows.
  const g::Dictionary dictionary = configured(default_reference_dictionary(), options);
  const auto reference = reference_functions(dictionary).at(function);
  g::Dictionary low_dictionary = dictionary, high_dictionary = dictionary;
  low_dictionary.tolerance = high_dictionary.tolerance = &spec;
  low_dictionary.side = -1;
  high_dictionary.side = 1;
  const auto low_reference = reference_functions(low_dictionary).at(function);
  const auto high_reference = reference_functions(high_dictionary).at(function);
  // The reference with the footprint's log2 and the cell scale's exp2 at either end of the
  // spec's allowance (g::Dictionary::log2_side, exp2_side), for the transcendental term.
  std::vector<ReferenceFunction> transcendental_references;
  for (const int log2_side : {-1, 1}) {
    for (const int exp2_side : {-1, 1}) {
      g::Dictionary d = dictionary;
      d.log2_side = log2_side;
      d.exp2_side = exp2_side;
      transcendental_references.push_back(reference_functions(d).at(function));
    }
  }
  // And at either end of the spec's cos / sin allowance for every cell's rotation
  // (g::Dictionary::trig_side).
  std::vector<ReferenceFunction> trig_references;
  for (const int trig_side : {-1, 1}) {
    g::Dictionary d = dictionary;
    d.trig_side = trig_side;
    trig_references.push_back(reference_functions(d).at(function));
  }
  const auto largest_change = [](const std::vector<ReferenceFunction>& references, const std::vector<double>& x,
                                 const std::vector<double>& value) {
    std::vector<double> change(value.size(), 0.0);
    for (const ReferenceFunction& f : references) {
      Inputs in(x);
      const auto shifted = f(in);
      for (std::size_t m = 0; m < value.size(); ++m) change[m] = std::max(change[m], std::fabs(shifted[m] - value[m]));
    }
    return change;
  };
  Comparison result;
  std::mt19937_64 random(99);
  for (std::size_t e = 0; e < count; ++e) {
    const std::vector<double> x(inputs.begin() + e * input_stride, inputs.begin() + (e + 1) * input_stride);
    Inputs in(x), low_in(x), high_in(x);
    const auto nominal = reference(in);
    const auto low = low_reference(low_in), high = high_reference(high_in);
    const auto& value = nominal;
    std::vector<double> spread(value.size(), 0.0);
    for (int k = 0; k < 6; ++k) {
      std::vector<double> p = x;
      for (double& v : p) v *= 1.0 + ((random() & 1) ? 0x1.0p-21 : -0x1.0p-21);
      Inputs perturbed_in(p);
      const auto perturbed = reference(perturbed_in);
      for (std::size_t m = 0; m < value.size(); ++m) spread[m] = std::max(spread[m], std::fabs(perturbed[m] - value[m]));
    }
    const auto transcendental = largest_change(transcendental_references, x, value);
    const auto trig = largest_change(trig_references, x, value);
    for (std::size_t m = 0; m < value.size(); ++m) {
      const double fp32 = 3.0 * spread[m] + transcendental[m] + 4e-6 * std::fabs(value[m]) + 1e-12;
      const double lo = std::min(low[m], high[m]), hi = std::max(low[m], high[m]);
      result.outside += nominal[m] < lo - fp32 || nominal[m] > hi + fp32;
      push_interval(result.spec_expected, result.spec_bounds, lo, hi, fp32 + trig[m]);
      result.expected.push_back(value[m]);
      result.bounds.push_back(fp32);
    }
  }
  return result;
}

// The packed inputs of `function` for the first `count` scenarios.
inline std::vector<float> packed_inputs(const saagen::Function& function, std::size_t count) {
  std::vector<float> inputs;
  for (const Scenario& s : scenarios(count)) pack(function, s, inputs);
  return inputs;
}

// ---------------------------------------------------------------------------------------------
// The fragment wrappers: ddx/ddy taken in 2x2 quads, against the reference fed the same quad
// differences.

// Per-pixel inputs, a smooth function of the pixel centre (a curved, moving glinty surface),
// polynomials so that the device computes them to fp32 rounding (no cos / sin allowance);
// with ln density 19 the footprint's LOD is about 1.6 (two levels of cells are mixed).
struct PixelInputs {
  Vec3 i, o;
  Vec2 uv;
};

inline PixelInputs pixel_inputs(Vec2 p) {
  PixelInputs in;
  in.uv = {0.0123 + 2.3e-4 * p.x + 1e-6 * p.x * p.y, 0.0311 + 1.9e-4 * p.y};
  in.i = saagen::ref::normalize(Vec3{0.3 + 0.2 * (0.03 * p.x - 4e-4 * p.x * p.x), -0.2 + 0.15 * (1.0 - 5e-4 * p.y * p.y), 1.0});
  in.o = saagen::ref::normalize(Vec3{-0.25 + 0.1 * (1.0 - 3e-4 * p.x * p.y), 0.2 + 0.12 * (0.04 * p.y - 5e-4 * p.y * p.y), 1.0});
  return in;
}

constexpr const char* wrapper_body = R"(    real2 p = saagen_frag_coord;
    real2 uv = real2(0.0123 + 2.3e-4 * p.x + 1e-6 * p.x * p.y, 0.0311 + 1.9e-4 * p.y);
    real3 i = normalize(real3(0.3 + 0.2 * (0.03 * p.x - 4e-4 * p.x * p.x), -0.2 + 0.15 * (1.0 - 5e-4 * p.y * p.y), 1.0));
    real3 o = normalize(real3(-0.25 + 0.1 * (1.0 - 3e-4 * p.x * p.y), 0.2 + 0.12 * (0.04 * p.y - 5e-4 * p.y * p.y), 1.0));
    real3 roughness = real3(0.2, 0.15, 0.3);
    real2 mean_slope = real2(0.02, -0.01);
    SAAGEN_STORE(0, glint_brdf_filtered_fragment(i, o, mean_slope, uv, roughness, 19.0));
    SAAGEN_STORE(1, glint_brdf_filtered_slope_fragment(i, o, mean_slope, uv, roughness, 19.0));
)";

constexpr const char* baseline_wrapper_body = R"(    real2 p = saagen_frag_coord;
    real2 uv = real2(0.0123 + 2.3e-4 * p.x + 1e-6 * p.x * p.y, 0.0311 + 1.9e-4 * p.y);
    real3 i = normalize(real3(0.3 + 0.2 * (0.03 * p.x - 4e-4 * p.x * p.x), -0.2 + 0.15 * (1.0 - 5e-4 * p.y * p.y), 1.0));
    real3 o = normalize(real3(-0.25 + 0.1 * (1.0 - 3e-4 * p.x * p.y), 0.2 + 0.12 * (0.04 * p.y - 5e-4 * p.y * p.y), 1.0));
    SAAGEN_STORE(0, glint_brdf_fragment(i, o, real2(0.02, -0.01), uv, real3(0.2, 0.15, 0.3), 19.0));
)";

// The reference and bounds of the wrappers of the GGAA variant (`filtered`: two outputs per
// pixel, glint_brdf_filtered_fragment and glint_brdf_filtered_slope_fragment) or of the baseline
// (glint_brdf_fragment) over a width x height target, the plain ddx/ddy taken as `derivative`
// quad differences (fine: the pixel's own row and column of its quad; coarse: the quad's first
// row and column).
inline Comparison fragment_comparison(bool filtered, std::uint32_t width, std::uint32_t height, ref::Derivative derivative,
                                      const g::SamplerTolerance& spec) {
  const g::Dictionary dictionary = default_reference_dictionary();
  g::Dictionary low_dictionary = dictionary, high_dictionary = dictionary;
  low_dictionary.tolerance = high_dictionary.tolerance = &spec;
  low_dictionary.side = -1;
  high_dictionary.side = 1;
  std::vector<g::Dictionary> transcendental_dictionaries;
  for (const int log2_side : {-1, 1}) {
    for (const int exp2_side : {-1, 1}) {
      g::Dictionary d = dictionary;
      d.log2_side = log2_side;
      d.exp2_side = exp2_side;
      transcendental_dictionaries.push_back(d);
    }
  }
  for (const int trig_side : {-1, 1}) {
    g::Dictionary d = dictionary;
    d.trig_side = trig_side;
    transcendental_dictionaries.push_back(d);
  }
  const g::Roughness roughness{0.2, 0.15, 0.3};
  const Vec2 mean{0.02, -0.01};
  const bool coarse = derivative == ref::Derivative::coarse;
  Comparison result;
  std::mt19937_64 random(5);
  for (std::uint32_t y = 0; y < height; ++y) {
    for (std::uint32_t x = 0; x < width; ++x) {
      const auto at = [&](std::uint32_t px, std::uint32_t py) { return pixel_inputs({px + 0.5, py + 0.5}); };
      const PixelInputs self = at(x, y);
      const std::uint32_t x0 = x & ~1u, y0 = y & ~1u;
      const std::uint32_t row = coarse ? y0 : y, column = coarse ? x0 : x;
      const PixelInputs left = at(x0, row), right = at(x0 + 1, row), top = at(column, y0), bottom = at(column, y0 + 1);
      const auto projected = [](const PixelInputs& p) { return saagen::ref::normalize(p.i + p.o).xy(); };
      const auto slope = [](const PixelInputs& p) { return g::half_slope(p.i, p.o); };
      const Vec2 duv_dx = right.uv - left.uv, duv_dy = bottom.uv - top.uv;
      const auto evaluate = [&](int which, double jitter_scale, std::mt19937_64& rng, const g::Dictionary& dictionary) {
        // The device's fp32 rounding of the per-pixel values (relative 2^-21 on each input, as
        // for the core functions), of their differences (absolute, 2^-22 of the operands) and
        // of the internal log_density * 1 / (2 ln 2).
        const auto sign = [&] { return (rng() & 1) ? 1.0 : -1.0; };
        const auto relative = [&](double v) { return v * (1.0 + sign() * jitter_scale * 0x1.0p-21); };
        const auto rel2 = [&](Vec2 v) { return Vec2{relative(v.x), relative(v.y)}; };
        const auto rel3 = [&](Vec3 v) { return Vec3{relative(v.x), relative(v.y), relative(v.z)}; };
        const auto jitter = [&](Vec2 v, double magnitude) {
          return Vec2{v.x + sign() * jitter_scale * magnitude, v.y + sign() * jitter_scale * magnitude};
        };
        const Vec3 i = rel3(self.i), o = rel3(self.o);
        const Vec2 uv = rel2(self.uv);
        const double log_density = relative(19.0);
        const Vec2 dx = jitter(duv_dx, std::max(std::fabs(self.uv.x), std::fabs(self.uv.y)) * 0x1.0p-22);
        const Vec2 dy = jitter(duv_dy, std::max(std::fabs(self.uv.x), std::fabs(self.uv.y)) * 0x1.0p-22);
        if (which == 2) return g::brdf(dictionary, i, o, mean, uv, dx, dy, roughness, log_density);
        const Vec2 hdx = which == 0 ? projected(right) - projected(left) : slope(right) - slope(left);
        const Vec2 hdy = which == 0 ? projected(bottom) - projected(top) : slope(bottom) - slope(top);
        return g::brdf_filtered(dictionary, i, o, mean, jitter(hdx, 0x1.0p-22), jitter(hdy, 0x1.0p-22), uv, dx, dy, roughness, log_density);
      };
      for (int which : filtered ? std::vector<int>{0, 1} : std::vector<int>{2}) {
        const double value = evaluate(which, 0.0, random, dictionary);
        double spread = 0.0;
        for (int k = 0; k < 6; ++k) spread = std::max(spread, std::fabs(evaluate(which, 1.0, random, dictionary) - value));
        // The spec's log2 / exp2 allowances (the first four dictionaries), then its cos / sin
        // allowance (the last two).
        double transcendental = 0.0, trig = 0.0;
        for (std::size_t k = 0; k < transcendental_dictionaries.size(); ++k) {
          double& term = k < 4 ? transcendental : trig;
          term = std::max(term, std::fabs(evaluate(which, 0.0, random, transcendental_dictionaries[k]) - value));
        }
        const double fp32 = 3.0 * spread + transcendental + 4e-6 * std::fabs(value) + 1e-12;
        result.expected.push_back(value);
        result.bounds.push_back(fp32);
        push_interval(result.spec_expected, result.spec_bounds, evaluate(which, 0.0, random, low_dictionary),
                      evaluate(which, 0.0, random, high_dictionary), fp32 + trig);
      }
    }
  }
  return result;
}

}  // namespace glint

}  // namespace saagen::test
