// The inputs and the double-precision reference of every core function, shared by the suites
// that run emitted core functions on a device (test_gpu_core: Vulkan; test_webgl: WebGL2):
// 131072 inputs -- a structured grid over h_z, roughness, derivative magnitude and direction,
// then seeded random draws -- packed per function by parameter name, and per function the
// reference value and the magnitude scale S of its fp32 rounding bound.
//
// Error bound per output, |gpu - reference| <= 2e-5 * S + 1e-30, where S is a magnitude scale:
//  - filters (sums of products, min, saturate, sqrt of sums of squares, one division in the
//    projected-space form): S = max(|f(x)|, |f|(|x|)), the function evaluated on the absolute
//    values of its derivative inputs. Running error analysis bounds the rounding error of such
//    expressions by gamma_n * |f|(|x|) with gamma_n ~ n * 2^-24; n <= 12 here gives ~7e-7. The
//    bound allows 2e-5: Vulkan lets division be 2.5 ulp and sqrt inherit inversesqrt's 2 ulp.
//  - BRDFs: S = |f| * (1 + c) where c is the conditioning: the eigenvalue ratio of the
//    roughness matrix (the determinant and the adjugate's quadratic form cancel by up to that
//    factor; inputs keep it <= 100), plus the Beckmann exponent e (exp amplifies a relative
//    error of e by e). Smith Lambda is a difference (-0.5 + ..., or Walter's fit whose
//    numerator has roots near a = 1.55), so its scale is the sum of the magnitudes of its terms.
//  - deferred-aniso (templates/20-deferred.saa): reference_dispatch.hpp, deferred_aniso_reference.
#pragma once

#include "reference_dispatch.hpp"

#include "saagen/front/catalogue.hpp"
#include "saagen/reference/reference.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace saagen::test::core {

namespace ref = saagen::ref;
using ref::Sym2;
using ref::Vec2;
using ref::Vec3;
using saagen::Catalogue;

constexpr std::uint32_t element_count = 131072;  // >= 1e5, a multiple of the workgroup size
constexpr double rounding_bound = 2e-5;

// One input configuration; every parameter of every function is derived from it.
struct Scenario {
  Vec3 h;  // unit half vector / normal in tangent space
  double alpha_x = 0.1, alpha_y = 0.1;
  Vec3 dh_x, dh_y;          // derivatives of h along screen x and y, tangent to the sphere at h
  Vec3 i, o;                // unit light and view directions
  double anisotropy = 1.0;  // eigenvalue ratio of the BRDF roughness matrix, in [1, 100]
  double matrix_angle = 0.0;
  double tau_scale = 1.0;  // tau = det(A) * tau_scale: both sides of the clamp
};

inline Vec3 direction(double z, double azimuth) {
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {r * std::cos(azimuth), r * std::sin(azimuth), z};
}

// Derivative pair tangent to the sphere at h: magnitude m along angle psi, and a second one of
// relative size `ratio` rotated by 90 degrees plus a shear, so Sigma is full rank and rotated.
inline void set_derivatives(Scenario& s, double m, double psi, double ratio) {
  const ref::SphereBasis basis = ref::sphere_tangent_basis(s.h);
  const double c = std::cos(psi), sn = std::sin(psi);
  s.dh_x = m * (c * basis.e_theta + sn * basis.e_phi);
  s.dh_y = (m * ratio) * ((-sn + 0.3 * c) * basis.e_theta + (c + 0.3 * sn) * basis.e_phi);
}

inline std::vector<Scenario> scenarios() {
  std::vector<Scenario> all;
  // h_z = 1 exactly has no tangent direction for the derivative construction; 0.9999 is 0.8 deg off.
  const double h_zs[] = {0.02, 0.05, 0.1, 0.2, 0.35, 0.5, 0.7, 0.85, 0.95, 0.9999};
  const double alphas[] = {0.001, 0.01, 0.05, 0.1, 0.3, 0.6, 1.0};
  const double magnitudes[] = {0.0, 1e-4, 1e-3, 1e-2, 0.05, 0.2, 1.0, 5.0};
  for (double h_z : h_zs)
    for (int azimuth = 0; azimuth < 4; ++azimuth)
      for (double alpha : alphas)
        for (double stretch : {1.0, 0.5})
          for (double m : magnitudes)
            for (int psi = 0; psi < 4; ++psi) {
              Scenario s;
              s.h = direction(h_z, 0.4 + azimuth * 1.5);
              s.alpha_x = alpha;
              s.alpha_y = alpha * stretch;
              set_derivatives(s, m, psi * 0.8, 0.25 + 0.25 * psi);
              s.i = direction(0.05 + 0.95 * (psi + 1) / 4.0, azimuth * 1.1);
              s.o = direction(std::max(0.05, h_z), 2.0 + azimuth);
              s.anisotropy = 1.0 + 99.0 * (psi / 3.0);
              s.matrix_angle = 0.7 * azimuth;
              s.tau_scale = stretch == 1.0 ? 0.5 : 1.5;
              all.push_back(s);
            }
  std::mt19937_64 random(20261123);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  while (all.size() < element_count) {
    Scenario s;
    s.h = direction(0.01 + 0.99 * unit(random), 6.283185307179586 * unit(random));
    s.alpha_x = std::pow(10.0, -3.0 * unit(random));
    s.alpha_y = std::pow(10.0, -3.0 * unit(random));
    set_derivatives(s, std::pow(10.0, -5.0 + 6.0 * unit(random)), 6.283185307179586 * unit(random), unit(random));
    s.i = direction(0.02 + 0.98 * unit(random), 6.283185307179586 * unit(random));
    s.o = direction(0.02 + 0.98 * unit(random), 6.283185307179586 * unit(random));
    s.anisotropy = 1.0 + 99.0 * unit(random);
    s.matrix_angle = 3.14159 * unit(random);
    s.tau_scale = 0.25 + 1.5 * unit(random);
    all.push_back(s);
  }
  return all;
}

// The BRDF roughness matrix: eigenvalues alpha_x^2 and alpha_x^2 * anisotropy, rotated.
inline Sym2 roughness_matrix(const Scenario& s) {
  const double l1 = s.alpha_x * s.alpha_x, l2 = l1 * s.anisotropy;
  const double c = std::cos(s.matrix_angle), sn = std::sin(s.matrix_angle);
  return {l1 * c * c + l2 * sn * sn, (l1 - l2) * c * sn, l1 * sn * sn + l2 * c * c};
}

inline void push(std::vector<float>& out, double v) { out.push_back(static_cast<float>(v)); }
inline void push(std::vector<float>& out, Vec2 v) { push(out, v.x), push(out, v.y); }
inline void push(std::vector<float>& out, Vec3 v) { push(out, v.x), push(out, v.y), push(out, v.z); }
inline void push(std::vector<float>& out, Sym2 m) { push(out, m.xx), push(out, m.xy), push(out, m.yy); }
inline void push(std::vector<float>& out, const ref::IsotropicLobe& lobe) {
  for (double v : lobe) push(out, v);
}

// Packs the inputs of `function` for one scenario, by parameter name (see templates/*.saa).
inline void pack_inputs(const saagen::Function& function, const Scenario& s, std::uint64_t index, const ref::Params& params,
                        std::vector<float>& out) {
  const Vec2 alpha2{s.alpha_x * s.alpha_x, s.alpha_y * s.alpha_y};
  const saagen::test::PrefilterInputs texel = saagen::test::prefilter_inputs(index);
  const Sym2 matrix = roughness_matrix(s);
  const Sym2 tensor = ref::deferred_aniso(params, s.dh_x, s.dh_y, s.h);  // deferred-aniso's geometry pass
  // The texture frame of deferred_aniso_covariance around normal_ws = h, mirrored every other index.
  const saagen::test::TextureFrame frame = saagen::test::texture_frame(s.h, s.matrix_angle, index % 2 == 0 ? 1.0 : -1.0);
  for (const saagen::Parameter& parameter : function.parameters) {
    const std::string& name = parameter.name;
    if (name == "alpha2")
      parameter.type == "real" ? push(out, alpha2.x) : push(out, alpha2);
    else if (name == "dslope_dx")
      push(out, ref::slope_differential(s.h, s.dh_x));
    else if (name == "dslope_dy")
      push(out, ref::slope_differential(s.h, s.dh_y));
    else if (name == "dproj_dx")
      push(out, ref::projected_differential(s.h, s.dh_x));
    else if (name == "dproj_dy")
      push(out, ref::projected_differential(s.h, s.dh_y));
    else if (name == "dn_dx")
      push(out, s.dh_x);
    else if (name == "dn_dy")
      push(out, s.dh_y);
    else if (name == "h")
      push(out, function.name.find("g2") != std::string::npos ? ref::normalize(s.i + s.o) : s.h);
    else if (name == "w" || name == "i")
      push(out, s.i);
    else if (name == "o")
      push(out, s.o);
    else if (name == "a")
      push(out, saagen::test::takes_unfiltered_alpha2(function) ? Sym2{alpha2.x, 0.0, alpha2.y} + matrix : matrix);
    else if (name == "filtered")
      parameter.type == "real" ? push(out, alpha2.x + matrix.xx) : push(out, alpha2 + Vec2{matrix.xx, matrix.yy});
    else if (name == "lobe")
      push(out, ref::ggx_filtered_lobe_isotropic(alpha2.x + matrix.xx, alpha2.x));
    else if (name == "kernel")
      push(out, matrix.xx);
    else if (name == "tau")
      push(out, ref::sym2_determinant(matrix) * s.tau_scale);
    else if (name == "normal_ws")
      push(out, s.h);
    else if (name == "light_ws")
      push(out, s.i);
    else if (name == "view_ws")
      push(out, s.o);
    else if (name == "tensor")
      push(out, tensor);
    else if (name == "tensor_lobe")
      push(out, ref::deferred_aniso_lobe(params, tensor, alpha2.x));
    else if (name == "mean_length")
      push(out, texel.mean_length);
    else if (name == "slope_mean")
      push(out, texel.slope_mean);
    else if (name == "slope_second")
      push(out, texel.slope_second);
    else if (name == "tangent_ws")
      push(out, frame.tangent);
    else if (name == "bitangent_ws")
      push(out, frame.bitangent);
    else if (name == "covariance")
      push(out, ref::deferred_aniso_covariance(params, texel.slope_mean, texel.slope_second, frame.tangent, frame.bitangent, s.h));
    else
      throw std::runtime_error("no input generator for parameter " + name + " of " + function.name);
  }
}

// Reads the packed fp32 inputs back as doubles, in parameter order.
using Inputs = saagen::test::FloatReader;

inline std::vector<double> outputs(double v) { return {v}; }
inline std::vector<double> outputs(Vec2 v) { return {v.x, v.y}; }
inline std::vector<double> outputs(Sym2 m) { return {m.xx, m.xy, m.yy}; }

struct ReferenceFunction {
  std::function<std::vector<double>(Inputs&)> value;
  // Magnitude scale per output for the rounding bound (see the file comment).
  std::function<std::vector<double>(Inputs&)> scale;
};

inline std::vector<double> brdf_scale(double value, Sym2 a, double exponent = 0.0) {
  const double mean = 0.5 * (a.xx + a.yy), spread = std::sqrt(0.25 * (a.xx - a.yy) * (a.xx - a.yy) + a.xy * a.xy);
  const double conditioning = (mean + spread) / std::max(mean - spread, 1e-30);
  return {std::fabs(value) * (1.0 + conditioning + exponent)};
}

inline double beckmann_exponent(Vec3 h, Sym2 a, double tau) {
  if (h.z <= 0.0) return 0.0;
  const double det = std::max(ref::sym2_determinant(a), tau);
  return ref::sym2_quadratic_form({a.yy, -a.xy, a.xx}, {h.x / h.z, h.y / h.z}) / det;
}

// deferred-aniso's core and evaluate functions: the shared reference and its scale
// (reference_dispatch.hpp, deferred_aniso_reference).
inline void deferred_aniso_references(const ref::Params& p, std::map<std::string, ReferenceFunction>& table) {
  for (const char* name :
       {"deferred_aniso", "deferred_aniso_roughness", "deferred_aniso_brdf", "deferred_aniso_lobe", "deferred_aniso_brdf_lobe",
        "deferred_aniso_covariance", "deferred_aniso_roughness_with_covariance", "deferred_aniso_brdf_with_covariance"}) {
    const std::string function = name;
    table[function] = {[=](Inputs& in) { return *saagen::test::deferred_aniso_reference(function, p, in); },
                       [=](Inputs& in) { return *saagen::test::deferred_aniso_reference(function, p, in, true); }};
  }
}

inline std::map<std::string, ReferenceFunction> reference_functions(const ref::Params& p) {
  std::map<std::string, ReferenceFunction> table;
  // Filters: value on the inputs, scale on the absolute values of the derivative inputs (the
  // shared dispatch, reference_dispatch.hpp, by the templates' list).
  for (const std::string& name : saagen::test::filter_core_names()) {
    table[name] = {[=](Inputs& in) { return *saagen::test::filter_core_reference(name, p, in); },
                   [=](Inputs& in) { return *saagen::test::filter_core_reference(name, p, in, true); }};
  }

  table["ndf_clamp_tau"] = {[](Inputs& in) { return outputs(ref::ndf_clamp_tau(in.vec2())); },
                            [](Inputs& in) { return outputs(std::fabs(ref::ndf_clamp_tau(in.vec2()))); }};
  const auto ndf = [](auto function, bool beckmann) {
    const auto scale = [=](Inputs& in) {
      const Vec3 h = in.vec3();
      const Sym2 a = in.sym2();
      const double tau = in.real();
      return brdf_scale(function(h, a, tau), a, beckmann ? beckmann_exponent(h, a, tau) : 0.0);
    };
    return ReferenceFunction{[=](Inputs& in) {
                               const Vec3 h = in.vec3();
                               const Sym2 a = in.sym2();
                               return outputs(function(h, a, in.real()));
                             },
                             scale};
  };
  table["ggx_ndf_matrix"] = ndf(ref::ggx_ndf_matrix, false);
  table["beckmann_ndf_matrix"] = ndf(ref::beckmann_ndf_matrix, true);
  const auto lambda = [](auto function, auto term_magnitude) {
    return ReferenceFunction{[=](Inputs& in) {
                               const Vec3 w = in.vec3();
                               return outputs(function(w, in.sym2()));
                             },
                             [=](Inputs& in) {
                               const Vec3 w = in.vec3();
                               const Sym2 a = in.sym2();
                               return brdf_scale(term_magnitude(w, a), a);
                             }};
  };
  table["ggx_lambda_matrix"] = lambda(ref::ggx_lambda_matrix, [](Vec3 w, Sym2 a) { return 1.0 + ref::ggx_lambda_matrix(w, a); });
  table["beckmann_lambda_matrix"] = lambda(ref::beckmann_lambda_matrix, [](Vec3 w, Sym2 a) {
    const double q = ref::sym2_quadratic_form(a, w.xy());
    if (q <= 0.0) return 0.0;
    const double x = std::fabs(w.z) / std::sqrt(q);
    return (1.0 + 1.259 * x + 0.396 * x * x) / (3.535 * x + 2.181 * x * x);
  });
  table["ggx_g2_matrix"] = {[](Inputs& in) {
                              const Vec3 i = in.vec3(), o = in.vec3(), h = in.vec3();
                              return outputs(ref::ggx_g2_matrix(i, o, h, in.sym2()));
                            },
                            [](Inputs& in) {
                              const Vec3 i = in.vec3(), o = in.vec3(), h = in.vec3();
                              const Sym2 a = in.sym2();
                              return brdf_scale(ref::ggx_g2_matrix(i, o, h, a), a);
                            }};
  const auto brdf_matrix = [](auto function, bool beckmann) {
    return ReferenceFunction{[=](Inputs& in) {
                               const Vec3 i = in.vec3(), o = in.vec3();
                               const Sym2 a = in.sym2();
                               return outputs(function(i, o, a, in.real()));
                             },
                             [=](Inputs& in) {
                               const Vec3 i = in.vec3(), o = in.vec3();
                               const Sym2 a = in.sym2();
                               const double tau = in.real();
                               return brdf_scale(function(i, o, a, tau), a,
                                                 beckmann ? beckmann_exponent(ref::normalize(i + o), a, tau) : 0.0);
                             }};
  };
  table["ggx_brdf_matrix"] = brdf_matrix(ref::ggx_brdf_matrix, false);
  table["beckmann_brdf_matrix"] = brdf_matrix(ref::beckmann_brdf_matrix, true);
  const auto axis = [](auto function, bool beckmann) {
    return ReferenceFunction{[=](Inputs& in) {
                               const Vec3 h = in.vec3();
                               return outputs(function(h, in.vec2()));
                             },
                             [=](Inputs& in) {
                               const Vec3 h = in.vec3();
                               const Vec2 a2 = in.vec2();
                               const Sym2 a{a2.x, 0.0, a2.y};
                               return brdf_scale(function(h, a2), a, beckmann ? beckmann_exponent(h, a, a2.x * a2.y) : 0.0);
                             }};
  };
  table["ggx_ndf_axis"] = axis(ref::ggx_ndf_axis, false);
  table["ggx_lambda_axis"] = axis([](Vec3 w, Vec2 a2) { return 1.0 + ref::ggx_lambda_axis(w, a2); }, false);
  table["ggx_lambda_axis"].value = [](Inputs& in) {
    const Vec3 w = in.vec3();
    return outputs(ref::ggx_lambda_axis(w, in.vec2()));
  };
  table["beckmann_ndf_axis"] = axis(ref::beckmann_ndf_axis, true);
  const auto brdf_axis = [](auto function, bool beckmann) {
    return ReferenceFunction{[=](Inputs& in) {
                               const Vec3 i = in.vec3(), o = in.vec3();
                               return outputs(function(i, o, in.vec2()));
                             },
                             [=](Inputs& in) {
                               const Vec3 i = in.vec3(), o = in.vec3();
                               const Vec2 a2 = in.vec2();
                               const Sym2 a{a2.x, 0.0, a2.y};
                               return brdf_scale(function(i, o, a2), a,
                                                 beckmann ? beckmann_exponent(ref::normalize(i + o), a, a2.x * a2.y) : 0.0);
                             }};
  };
  table["ggx_brdf_axis"] = brdf_axis(ref::ggx_brdf_axis, false);
  table["beckmann_brdf_axis"] = brdf_axis(ref::beckmann_brdf_axis, true);
  // The tail-preserving filtered GGX and the single-roughness mapping: the shared reference and its scale.
  for (const char* name : {"ggx_ndf_filtered_matrix", "ggx_brdf_filtered_matrix", "ggx_brdf_filtered_axis", "ggx_filtered_lobe_isotropic",
                           "ggx_brdf_filtered_lobe", "ggx_filtered_alpha2"}) {
    const std::string function = name;
    table[function] = {[=](Inputs& in) { return *saagen::test::filtered_ggx_reference(function, p, in); },
                       [=](Inputs& in) { return *saagen::test::filtered_ggx_reference(function, p, in, true); }};
  }
  deferred_aniso_references(p, table);
  // Normal-map prefiltering (templates/40-prefilter.saa): the shared reference and its scale.
  for (const saagen::Function& function : Catalogue::builtin().functions()) {
    const std::string name = function.name;
    if (name.rfind("prefilter_", 0) != 0 && name != "toksvig_variance" && name != "lean_covariance") continue;
    table[name] = {[=](Inputs& in) { return *saagen::test::prefilter_reference(name, p, in); },
                   [=](Inputs& in) { return *saagen::test::prefilter_reference(name, p, in, true); }};
  }
  return table;
}

}  // namespace saagen::test::core
