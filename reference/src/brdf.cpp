// Double-precision reference of templates/30-brdf.saa. Each body follows its template
// statement by statement (same guards and clamps).
#include "saagen/reference/brdf.hpp"

#include "saagen/reference/prefilter.hpp"

#include <cmath>

namespace saagen::ref {

namespace {
constexpr double kSqrtPi = 1.7724538509055160273;  // sqrt(pi)

// adj(A) of a symmetric 2x2 matrix: (a11, -a01, a00).
constexpr Sym2 adjugate(Sym2 a) { return {a.yy, -a.xy, a.xx}; }
}  // namespace

// Supplemental Sec. 1, "Practical Implementation": tau = ax^2 ay^2.
double ndf_clamp_tau(Vec2 alpha2) { return alpha2.x * alpha2.y; }

// ---------------------------------------------------------------------------------------------
// GGX

// Supplemental Sec. 1 (clamped form):
// D(h) = chi+(hz) / (pi sqrt(max(det A, tau)) (h.xy^T A^-1 h.xy + hz^2)^2),
// A^-1 = adj(A) / max(det A, tau). Guarded: tau is floored at TINY_POSITIVE.
// Guarded: the adjugate's quadratic form is floored by quadratic_form_floor.
double Brdf::ggx_ndf_matrix(Vec3 h, Sym2 a, double tau) const {
  if (h.z <= 0.0) return 0.0;
  const double det_a = sym2_determinant(a);
  const double det = max(det_a, guarded(max(tau, tiny()), tau));
  const double spread = sym2_quadratic_form(adjugate(a), h.xy()) / det;
  const double q = guarded(max(spread, quadratic_form_floor(params, a, det_a, det, h.xy())), spread) + h.z * h.z;
  return 1.0 / (kPi * std::sqrt(det) * q * q);
}

// Supplemental Sec. 1: Lambda(w) = -1/2 + sqrt(w.xy^T A w.xy + wz^2) / (2 |wz|).
// Guarded: z = max(|wz|, LAMBDA_MIN_Z) in both places (so Lambda >= 0), the quadratic form >= 0.
double Brdf::ggx_lambda_matrix(Vec3 w, Sym2 a) const {
  const double z = guarded(max(std::fabs(w.z), params.guard_constants().lambda_min_z), std::fabs(w.z));
  const double spread = sym2_quadratic_form(a, w.xy());
  return -0.5 + std::sqrt(guarded(max(spread, 0.0), spread) + z * z) / (2.0 * z);
}

// Supplemental Sec. 1 / Heitz 2014: G2 = chi+(i.h) chi+(o.h) / (1 + Lambda(i) + Lambda(o)).
double Brdf::ggx_g2_matrix(Vec3 i, Vec3 o, Vec3 h, Sym2 a) const {
  if (dot(i, h) <= 0.0 || dot(o, h) <= 0.0) return 0.0;
  return 1.0 / (1.0 + ggx_lambda_matrix(i, a) + ggx_lambda_matrix(o, a));
}

// T&K 2019 Sec. 2.2: f = G2 D / (4 |i.n| |o.n|), Fresnel left to the caller.
// Guarded: the cosines floored at LAMBDA_MIN_Z, as in Lambda.
double Brdf::ggx_brdf_matrix(Vec3 i, Vec3 o, Sym2 a, double tau) const {
  if (i.z <= 0.0 || o.z <= 0.0) return 0.0;
  const Vec3 h = half_vector(params, i, o);
  return ggx_ndf_matrix(h, a, tau) * ggx_g2_matrix(i, o, h, a) / (4.0 * cosines(i, o));
}

// Supplemental Sec. 1: D(h) = chi+(hz) / (pi ax ay (hx^2/ax^2 + hy^2/ay^2 + hz^2)^2).
// Guarded: alpha^2 floored at TINY_POSITIVE per axis.
double Brdf::ggx_ndf_axis(Vec3 h, Vec2 alpha2) const {
  if (h.z <= 0.0) return 0.0;
  const Vec2 a2{guarded(max(alpha2.x, tiny()), alpha2.x), guarded(max(alpha2.y, tiny()), alpha2.y)};
  const double q = h.x * h.x / a2.x + h.y * h.y / a2.y + h.z * h.z;
  return 1.0 / (kPi * std::sqrt(a2.x * a2.y) * q * q);
}

// Supplemental Sec. 1: Lambda(w) = -1/2 + sqrt(ax^2 wx^2 + ay^2 wy^2 + wz^2) / (2 |wz|).
// Guarded: z = max(|wz|, LAMBDA_MIN_Z) in both places.
double Brdf::ggx_lambda_axis(Vec3 w, Vec2 alpha2) const {
  const double z = guarded(max(std::fabs(w.z), params.guard_constants().lambda_min_z), std::fabs(w.z));
  return -0.5 + std::sqrt(alpha2.x * w.x * w.x + alpha2.y * w.y * w.y + z * z) / (2.0 * z);
}

// T&K 2019 Sec. 2.2 with the axis-aligned GGX NDF and height-correlated G2.
double Brdf::ggx_brdf_axis(Vec3 i, Vec3 o, Vec2 alpha2) const {
  if (i.z <= 0.0 || o.z <= 0.0) return 0.0;
  const Vec3 h = half_vector(params, i, o);
  if (dot(i, h) <= 0.0 || dot(o, h) <= 0.0) return 0.0;
  const double g2 = 1.0 / (1.0 + ggx_lambda_axis(i, alpha2) + ggx_lambda_axis(o, alpha2));
  return ggx_ndf_axis(h, alpha2) * g2 / (4.0 * cosines(i, o));
}

// ---------------------------------------------------------------------------------------------
// Beckmann

// beckmann_falloff of the template: exp(-x), 0 for x >= EXP_ARG_MAX (guarded); the NDF's divisor
// floored at DIVISOR_MIN = 2^-126 (guarded). Vulkan spec, Appendix A, "Precision and Operation of
// SPIR-V Instructions": exp is bounded by 3 + 2|x| ULP, x / y only for |y| in [2^-126, 2^126],
// and denormals may flush to 0.
double Brdf::falloff(double x) const {
  if (!params.guards) return std::exp(-x);
  return x < params.guard_constants().exp_arg_max ? std::exp(-x) : 0.0;
}
double Brdf::divisor(double d) const { return guarded(max(d, params.guard_constants().divisor_min), d); }

// Supplemental Sec. 1 applied to Beckmann (Heitz 2014): the slope distribution
// exp(-s^T A^-1 s) / (pi sqrt(det A)), s = h.xy / hz, divided by hz^4 for the NDF.
// Guarded: tau and hz^4 floored at TINY_POSITIVE; the exponent computed as
// max(h.xy^T adj h.xy / det, quadratic_form_floor) / max(hz^2, TINY_POSITIVE).
double Brdf::beckmann_ndf_matrix(Vec3 h, Sym2 a, double tau) const {
  if (h.z <= 0.0) return 0.0;
  const double det_a = sym2_determinant(a);
  const double det = max(det_a, guarded(max(tau, tiny()), tau));
  const double cos2 = h.z * h.z;
  const double exponent =
      params.guards
          ? max(sym2_quadratic_form(adjugate(a), h.xy()) / det, quadratic_form_floor(params, a, det_a, det, h.xy())) / max(cos2, tiny())
          : sym2_quadratic_form(adjugate(a), h.xy() / h.z) / det;
  return falloff(exponent) / divisor(kPi * std::sqrt(det) * guarded(max(cos2 * cos2, tiny()), cos2 * cos2));
}

// Heitz 2014: a = |wz| / sqrt(w.xy^T A w.xy) (1 / (alpha_w tan theta_w)), Walter fit.
// Guarded: |wz| >= LAMBDA_MIN_Z.
double Brdf::beckmann_lambda_matrix(Vec3 w, Sym2 a) const {
  const double projected_roughness2 = sym2_quadratic_form(a, w.xy());
  if (projected_roughness2 <= 0.0) return 0.0;
  const double z = std::fabs(w.z);
  return beckmann_lambda_from_a(guarded(max(z, params.guard_constants().lambda_min_z), z) / std::sqrt(projected_roughness2));
}

// T&K 2019 Sec. 2.2 with the matrix Beckmann NDF. Guarded: the cosines floored.
double Brdf::beckmann_brdf_matrix(Vec3 i, Vec3 o, Sym2 a, double tau) const {
  if (i.z <= 0.0 || o.z <= 0.0) return 0.0;
  const Vec3 h = half_vector(params, i, o);
  if (dot(i, h) <= 0.0 || dot(o, h) <= 0.0) return 0.0;
  const double g2 = 1.0 / (1.0 + beckmann_lambda_matrix(i, a) + beckmann_lambda_matrix(o, a));
  return beckmann_ndf_matrix(h, a, tau) * g2 / (4.0 * cosines(i, o));
}

// Beckmann 1963, axis-aligned anisotropic. Guarded: alpha^2 and hz^4 floored.
double Brdf::beckmann_ndf_axis(Vec3 h, Vec2 alpha2) const {
  if (h.z <= 0.0) return 0.0;
  const Vec2 a2{guarded(max(alpha2.x, tiny()), alpha2.x), guarded(max(alpha2.y, tiny()), alpha2.y)};
  const Vec2 slope = h.xy() / h.z;
  const double cos2 = h.z * h.z;
  const double exponent = slope.x * slope.x / a2.x + slope.y * slope.y / a2.y;
  return falloff(exponent) / divisor(kPi * std::sqrt(a2.x * a2.y) * guarded(max(cos2 * cos2, tiny()), cos2 * cos2));
}

// T&K 2019 Sec. 2.2 with the axis-aligned Beckmann NDF (Walter et al. 2007 Lambda).
double Brdf::beckmann_brdf_axis(Vec3 i, Vec3 o, Vec2 alpha2) const {
  const Sym2 a{alpha2.x, 0.0, alpha2.y};
  if (i.z <= 0.0 || o.z <= 0.0) return 0.0;
  const Vec3 h = half_vector(params, i, o);
  if (dot(i, h) <= 0.0 || dot(o, h) <= 0.0) return 0.0;
  const double g2 = 1.0 / (1.0 + beckmann_lambda_matrix(i, a) + beckmann_lambda_matrix(o, a));
  return beckmann_ndf_axis(h, alpha2) * g2 / (4.0 * cosines(i, o));
}

// 4 i.z o.z of the BRDFs; guarded: max(i.z, LAMBDA_MIN_Z) max(o.z, LAMBDA_MIN_Z), the cosines
// Lambda uses (a floor of i.z o.z alone lets G2 / (i.z o.z) grow as 1 / i.z below LAMBDA_MIN_Z).
double Brdf::cosines(Vec3 i, Vec3 o) const {
  const double m = params.guard_constants().lambda_min_z;
  return guarded(max(i.z, m) * max(o.z, m), i.z * o.z);
}

// lambda_min(A) >= det(A) / tr(A); a determinant below DET_RELIABLE a00 a11 is rounding noise in
// fp32, and is then taken as det = max(det(A), tau) (filtered matrices have det(A) >= tau).
double quadratic_form_floor(const Params& p, Sym2 a, double det_a, double det, Vec2 v) {
  const GuardConstants& g = p.guard_constants();
  const double det_floor = max(det_a, min(det, g.det_reliable * a.xx * a.yy));
  return dot(v, v) * (det_floor / det) / max(a.xx + a.yy, g.tiny_positive);
}

// ---------------------------------------------------------------------------------------------
// The free functions: saagen's default emission (guarded, fp32 guard constants).

double ggx_ndf_matrix(Vec3 h, Sym2 a, double tau) { return Brdf{}.ggx_ndf_matrix(h, a, tau); }
double ggx_lambda_matrix(Vec3 w, Sym2 a) { return Brdf{}.ggx_lambda_matrix(w, a); }
double ggx_g2_matrix(Vec3 i, Vec3 o, Vec3 h, Sym2 a) { return Brdf{}.ggx_g2_matrix(i, o, h, a); }
double ggx_brdf_matrix(Vec3 i, Vec3 o, Sym2 a, double tau) { return Brdf{}.ggx_brdf_matrix(i, o, a, tau); }
double ggx_ndf_axis(Vec3 h, Vec2 alpha2) { return Brdf{}.ggx_ndf_axis(h, alpha2); }
double ggx_lambda_axis(Vec3 w, Vec2 alpha2) { return Brdf{}.ggx_lambda_axis(w, alpha2); }
double ggx_brdf_axis(Vec3 i, Vec3 o, Vec2 alpha2) { return Brdf{}.ggx_brdf_axis(i, o, alpha2); }
double beckmann_ndf_matrix(Vec3 h, Sym2 a, double tau) { return Brdf{}.beckmann_ndf_matrix(h, a, tau); }
double beckmann_lambda_matrix(Vec3 w, Sym2 a) { return Brdf{}.beckmann_lambda_matrix(w, a); }
double beckmann_brdf_matrix(Vec3 i, Vec3 o, Sym2 a, double tau) { return Brdf{}.beckmann_brdf_matrix(i, o, a, tau); }
double beckmann_ndf_axis(Vec3 h, Vec2 alpha2) { return Brdf{}.beckmann_ndf_axis(h, alpha2); }
double beckmann_brdf_axis(Vec3 i, Vec3 o, Vec2 alpha2) { return Brdf{}.beckmann_brdf_axis(i, o, alpha2); }

// Walter et al. 2007 rational approximation of the Beckmann Smith Lambda.
double beckmann_lambda_from_a(double a_param) {
  if (a_param >= 1.6) return 0.0;
  return (1.0 - 1.259 * a_param + 0.396 * a_param * a_param) / (3.535 * a_param + 2.181 * a_param * a_param);
}

// Heitz 2014 (Beckmann Lambda): (erf(a) - 1) / 2 + exp(-a^2) / (2 a sqrt(pi)).
double beckmann_lambda_exact(double a_param) {
  return 0.5 * (std::erf(a_param) - 1.0) + std::exp(-a_param * a_param) / (2.0 * a_param * kSqrtPi);
}

// ---------------------------------------------------------------------------------------------
// Filtered GGX that keeps GGX's tails (saagen's fit; brdf.hpp, docs/FILTERED_GGX.md)

// Coefficients fitted by minimax of the L1 distance to the exact isotropic convolution over
// r in [1e-3, 2e5], with the tail mass beyond 4 sqrt(k) held within 8 % (scripts/fit_filtered_ggx.py;
// tests/reference/test_filtered_ggx.cpp recomputes both); the tail lobe's weight 1 / lambda keeps GGX(A0)'s
// far tail exactly, and every parameter is a polynomial in that one reciprocal.
FilteredGgxLobes filtered_ggx_lobes(double ratio) {
  const double r = max(ratio, 0.0);
  FilteredGgxLobes lobes;
  lobes.tail_scale = 1.0 + 2.5072 * r;
  lobes.tail_weight = 1.0 / lobes.tail_scale;
  const double w = lobes.tail_weight;
  lobes.core_kernel = filtered_ggx_core_kernel(w);
  lobes.shoulder_fraction = w * (0.52867 - 0.40604 * w);
  return lobes;
}

double filtered_ggx_core_kernel(double tail_weight) { return 1.0 + tail_weight * (1.3212 - 1.9936 * tail_weight); }

// The template's floor of alpha^2 (TINY_POSITIVE) and cap of r (FILTERED_RATIO_MAX) hold in both
// forms (not guarded() sites): past the cap the tail lobe weighs < 1e-6 (fp16: 1e-4) and r's
// products would overflow.
double Brdf::filtered_ggx_ratio(Sym2 a, Vec2 alpha2) const {
  const double r = 0.25 * ((a.xx - alpha2.x) / max(alpha2.x, tiny()) + (a.yy - alpha2.y) / max(alpha2.y, tiny()));
  return min(max(r, 0.0), params.guard_constants().filtered_ratio_max);
}

// Template filtered_ggx_mixture: w GGX(lambda A0) + (1 - w) ((1 - f) Beckmann(M) + f Beckmann(4 M))
// for the core matrix M = A0 + c K and the floored (ax^2, ay^2). Guarded as the template: det(M)
// floored at det(A0) (det(A0 + c K) >= det(A0) for a PSD kernel; a numerically rank-1 kernel
// cancels det(M) to any sign) and TINY_POSITIVE, the Beckmann exponent's hxy^T M^-1 hxy at
// |hxy|^2 lambda_min(A0) / det(M) (lambda_max(M) <= det(M) / lambda_min(A0), as M >= A0), the
// shared divisor p hz^2 (p = hx^2 / ax^2 + hy^2 / ay^2 + lambda hz^2) at DIVISOR_MIN, exp(-x) as
// in beckmann_ndf_matrix and the Beckmann scale (before its 1 / pi) capped at 1 / DIVISOR_MIN. One reciprocal of
// p hz^2 gives 1 / hz^2 and 1 / p, and one exponential both Beckmann lobes, as in the template.
double Brdf::filtered_ggx_mixture(Sym2 m, Vec2 alpha2, double tail_scale, double w, double f, Vec3 h) const {
  const GuardConstants& g = params.guard_constants();
  const double det0 = alpha2.x * alpha2.y;
  const double det = max(sym2_determinant(m), guarded(max(det0, tiny()), det0));
  const double hx2 = h.x * h.x, hy2 = h.y * h.y, cos2 = h.z * h.z;
  const double spread = sym2_quadratic_form(adjugate(m), h.xy()) / det;
  const double projected = guarded(max(spread, (hx2 + hy2) * min(alpha2.x, alpha2.y) / det), spread);
  const double p = hx2 / alpha2.x + hy2 / alpha2.y + tail_scale * cos2;
  const double t = 1.0 / guarded(max(p * cos2, g.divisor_min), p * cos2);
  const double inverse_cos2 = p * t, inverse_p = cos2 * t;
  // w GGX(lambda A0) = 1 / (pi sqrt(det A0) p^2) in h (w lambda = 1); 1 / sqrt(det A0) per axis, and
  // 1 / pi applied once to the sum, as in the template.
  const double tail = inverse_p * inverse_p / (std::sqrt(alpha2.x) * std::sqrt(alpha2.y));
  const double scale = inverse_cos2 * inverse_cos2 / std::sqrt(det);
  const double shoulder = falloff(projected * inverse_cos2 / kFilteredShoulderScale);
  const double core = std::pow(shoulder, kFilteredShoulderScale);
  const double mixture = (1.0 - f) * core + f * shoulder / kFilteredShoulderScale;
  return (tail + (1.0 - w) * mixture * guarded(min(scale, 1.0 / g.divisor_min), scale)) / kPi;
}

double Brdf::ggx_ndf_filtered_matrix(Vec3 h, Sym2 a, Vec2 alpha2) const {
  if (h.z <= 0.0) return 0.0;
  const FilteredGgxLobes lobes = filtered_ggx_lobes(filtered_ggx_ratio(a, alpha2));
  const Sym2 unfiltered{alpha2.x, 0.0, alpha2.y};
  const Vec2 floored{max(alpha2.x, tiny()), max(alpha2.y, tiny())};
  const Sym2 core = unfiltered + lobes.core_kernel * (a - unfiltered);
  return filtered_ggx_mixture(core, floored, lobes.tail_scale, lobes.tail_weight, lobes.shoulder_fraction, h);
}

// Template ggx_brdf_filtered_matrix: D G2 / (4 i.z o.z) with the papers' G2 of A, written as
// D / (2 (o.z S(i) + i.z S(o))), S(v) = sqrt(v.xy^T A v.xy + v.z^2) (Lambda(v) = S(v) / (2 v.z) - 1/2),
// the cosines floored at LAMBDA_MIN_Z as in ggx_lambda_matrix and cosines().
double Brdf::ggx_brdf_filtered_matrix(Vec3 i, Vec3 o, Sym2 a, Vec2 alpha2) const { return filtered_brdf(i, o, a, a, alpha2); }

// Template ggx_brdf_filtered_axis: the matrix form of diag(filtered), whose NDF
// (ggx_ndf_filtered_diagonal) floors the kernel filtered - alpha^2 at 0 per axis when guarded; the
// G2 takes filtered as given.
double Brdf::ggx_brdf_filtered_axis(Vec3 i, Vec3 o, Vec2 filtered, Vec2 alpha2) const {
  return filtered_brdf(i, o, {filtered.x, 0.0, filtered.y}, diagonal_ndf_matrix(filtered, alpha2), alpha2);
}

// Template ggx_filtered_lobe_isotropic: r = k / (2 alpha^2) (the kernel k on both axes), capped at
// FILTERED_RATIO_MAX, and the core lobe's m = alpha^2 + c k floored at the floored alpha^2 (m >=
// alpha^2 for k >= 0); lambda multiplied through by alpha^2 as the template does.
IsotropicLobe Brdf::ggx_filtered_lobe_isotropic(double filtered, double alpha2) const {
  const double unfiltered = max(alpha2, tiny());
  const double kernel = guarded(max(filtered - alpha2, 0.0), filtered - alpha2);
  const double ratio = min(max(0.5 * kernel / unfiltered, 0.0), params.guard_constants().filtered_ratio_max);
  const FilteredGgxLobes lobes = filtered_ggx_lobes(ratio);
  const double core = max(alpha2 + lobes.core_kernel * kernel, unfiltered);
  return {unfiltered * lobes.tail_scale, lobes.tail_weight, 0.25 / core, 0.5 * lobes.shoulder_fraction};
}

// Template ggx_brdf_filtered_lobe: filtered_brdf of A = filtered I with the lobe's parameters
// given: M = m I makes hxy^T (4 M)^-1 hxy = |hxy|^2 / (4 m) and 1 / sqrt(det 2 M) = 2 / (4 m); p and
// the tail multiplied through by alpha^2 (p = |hxy|^2 + alpha^2 lambda hz^2, tail alpha^2 / p^2).
double Brdf::ggx_brdf_filtered_lobe(Vec3 i, Vec3 o, double filtered, double alpha2, const IsotropicLobe& lobe) const {
  if (i.z <= 0.0 || o.z <= 0.0) return 0.0;
  const Vec3 h = half_vector(params, i, o);
  if (dot(i, h) <= 0.0 || dot(o, h) <= 0.0) return 0.0;
  const GuardConstants& g = params.guard_constants();
  const auto [tail_scale, w, quarter_inverse_core, half_shoulder] = lobe;
  const double spread = h.x * h.x + h.y * h.y, cos2 = h.z * h.z;
  const double p = spread + tail_scale * cos2;
  const double t = 1.0 / guarded(max(p * cos2, g.divisor_min), p * cos2);
  const double inverse_cos2 = p * t, inverse_p = cos2 * t;
  const double tail = inverse_p * inverse_p * max(alpha2, tiny());
  const double scale = 2.0 * quarter_inverse_core * inverse_cos2 * inverse_cos2;
  const double shoulder = falloff(spread * quarter_inverse_core * inverse_cos2);
  const double mixture = half_shoulder * shoulder + (2.0 - 4.0 * half_shoulder) * std::pow(shoulder, kFilteredShoulderScale);
  const double ndf = (tail + (1.0 - w) * mixture * guarded(min(scale, 0.5 / g.divisor_min), scale)) / kPi;
  return 0.5 * ndf / filtered_g2_divisor(i, o, filtered * dot(i.xy(), i.xy()), filtered * dot(o.xy(), o.xy()));
}

// Template ggx_filtered_lobe_matrix: r of A = alpha^2 I + K (filtered_ggx_ratio), lambda multiplied
// through by the floored alpha^2, and 1 / sqrt(det 2 M) of the core lobe M = alpha^2 I + c K with
// det(M) floored as filtered_ggx_mixture floors it.
IsotropicLobe Brdf::ggx_filtered_lobe_matrix(Sym2 a, double alpha2) const {
  const double unfiltered = max(alpha2, tiny());
  const Sym2 a0{alpha2, 0.0, alpha2};
  const FilteredGgxLobes lobes = filtered_ggx_lobes(filtered_ggx_ratio(a, {alpha2, alpha2}));
  const Sym2 core = a0 + lobes.core_kernel * (a - a0);
  const double det0 = unfiltered * unfiltered;
  const double det = max(sym2_determinant(core), guarded(max(det0, tiny()), det0));
  return {unfiltered * lobes.tail_scale, lobes.tail_weight, 1.0 / std::sqrt(4.0 * det), 0.5 * lobes.shoulder_fraction};
}

// Template ggx_brdf_filtered_lobe_matrix: filtered_brdf of A with the lobe's lambda, w and f given
// and c again from w; filtered_ggx_mixture recomputes det(M) from the core lobe, which is the
// lobe's 1 / sqrt(det 2 M) in double.
double Brdf::ggx_brdf_filtered_lobe_matrix(Vec3 i, Vec3 o, Sym2 a, double alpha2, const IsotropicLobe& lobe) const {
  if (i.z <= 0.0 || o.z <= 0.0) return 0.0;
  const Vec3 h = half_vector(params, i, o);
  if (dot(i, h) <= 0.0 || dot(o, h) <= 0.0) return 0.0;
  const double unfiltered = max(alpha2, tiny()), w = lobe[1];
  const Sym2 a0{alpha2, 0.0, alpha2};
  const Sym2 core = a0 + filtered_ggx_core_kernel(w) * (a - a0);
  const double ndf = filtered_ggx_mixture(core, {unfiltered, unfiltered}, lobe[0] / unfiltered, w, 2.0 * lobe[3], h);
  return 0.5 * ndf / filtered_g2_divisor(i, o, sym2_quadratic_form(a, i.xy()), sym2_quadratic_form(a, o.xy()));
}

Sym2 Brdf::diagonal_ndf_matrix(Vec2 filtered, Vec2 alpha2) const {
  return {guarded(max(filtered.x, alpha2.x), filtered.x), 0.0, guarded(max(filtered.y, alpha2.y), filtered.y)};
}

double Brdf::filtered_brdf(Vec3 i, Vec3 o, Sym2 a, Sym2 ndf_matrix, Vec2 alpha2) const {
  if (i.z <= 0.0 || o.z <= 0.0) return 0.0;
  const Vec3 h = half_vector(params, i, o);
  if (dot(i, h) <= 0.0 || dot(o, h) <= 0.0) return 0.0;
  return 0.5 * ggx_ndf_filtered_matrix(h, ndf_matrix, alpha2) /
         filtered_g2_divisor(i, o, sym2_quadratic_form(a, i.xy()), sym2_quadratic_form(a, o.xy()));
}

double Brdf::filtered_g2_divisor(Vec3 i, Vec3 o, double spread_i, double spread_o) const {
  const double floor = params.guard_constants().lambda_min_z;
  const double zi = guarded(max(i.z, floor), i.z), zo = guarded(max(o.z, floor), o.z);
  const double length_i = std::sqrt(guarded(max(spread_i, 0.0), spread_i) + zi * zi);
  const double length_o = std::sqrt(guarded(max(spread_o, 0.0), spread_o) + zo * zo);
  return zo * length_i + zi * length_o;
}

namespace {
// The single-roughness mapping's kernel factor g (brdf.hpp), the divisor floored at `floor`.
double kernel_scale(double alpha2, double k, double floor) { return (2.687 * alpha2 + 0.391 * k) / max(2.0 * alpha2 + 1.210 * k, floor); }
}  // namespace

double Brdf::ggx_filtered_alpha2(double alpha2, double kernel) const {
  const double k = max(kernel, 0.0);
  return alpha2 + k * kernel_scale(alpha2, k, tiny());
}

double filtered_ggx_ratio(Sym2 a, Vec2 alpha2) { return Brdf{}.filtered_ggx_ratio(a, alpha2); }
double ggx_ndf_filtered_matrix(Vec3 h, Sym2 a, Vec2 alpha2) { return Brdf{}.ggx_ndf_filtered_matrix(h, a, alpha2); }
double ggx_brdf_filtered_matrix(Vec3 i, Vec3 o, Sym2 a, Vec2 alpha2) { return Brdf{}.ggx_brdf_filtered_matrix(i, o, a, alpha2); }
double ggx_ndf_filtered_axis(Vec3 h, Vec2 filtered, Vec2 alpha2) {
  const Brdf brdf{};
  return brdf.ggx_ndf_filtered_matrix(h, brdf.diagonal_ndf_matrix(filtered, alpha2), alpha2);
}
double ggx_brdf_filtered_axis(Vec3 i, Vec3 o, Vec2 filtered, Vec2 alpha2) { return Brdf{}.ggx_brdf_filtered_axis(i, o, filtered, alpha2); }
IsotropicLobe ggx_filtered_lobe_isotropic(double filtered, double alpha2) { return Brdf{}.ggx_filtered_lobe_isotropic(filtered, alpha2); }
double ggx_brdf_filtered_lobe(Vec3 i, Vec3 o, double filtered, double alpha2, const IsotropicLobe& lobe) {
  return Brdf{}.ggx_brdf_filtered_lobe(i, o, filtered, alpha2, lobe);
}

namespace {
// integral_0^inf e^-w f(w) dw by the trapezoid rule in u = ln w (the integrand is smooth and
// decays doubly exponentially at both ends in u, so the rule converges geometrically).
template <class F>
double exponential_mixture(F f) {
  constexpr double kStep = 0.02, kLow = -70.0, kHigh = 5.0;
  double sum = 0.0;
  for (double u = kLow; u < kHigh; u += kStep) {
    const double w = std::exp(u);
    sum += w * std::exp(-w) * f(w);
  }
  return sum * kStep;
}
}  // namespace

// GGX's slope distribution is a Gaussian scale mixture (a Student-t with 2 degrees of freedom):
// P(s) = integral_0^inf e^-w N(s; 0, alpha^2 / (2w) I) dw. Convolving with N(0, k I) adds k to
// every component's variance.
double filtered_ggx_slope_density(double rho, double alpha2, double k) {
  return exponential_mixture([&](double w) {
    const double variance = alpha2 / (2.0 * w) + k;
    return std::exp(-rho * rho / (2.0 * variance)) / (2.0 * kPi * variance);
  });
}

double filtered_ggx_mass_beyond(double radius, double alpha2, double k) {
  return exponential_mixture([&](double w) { return std::exp(-radius * radius / (2.0 * (alpha2 / (2.0 * w) + k))); });
}

double filtered_ggx_slope_density_matrix(Vec2 slope, Vec2 alpha2, Sym2 sigma) {
  constexpr double kStep = 0.25, kLow = -45.0, kHigh = 4.0;
  double sum = 0.0;
  for (double u = kLow; u < kHigh; u += kStep) {
    const double w = std::exp(u);
    const Sym2 c{alpha2.x / (2.0 * w) + sigma.xx, sigma.xy, alpha2.y / (2.0 * w) + sigma.yy};
    const double det = c.xx * c.yy - c.xy * c.xy;
    const double q = (c.yy * slope.x * slope.x - 2.0 * c.xy * slope.x * slope.y + c.xx * slope.y * slope.y) / det;
    sum += w * std::exp(-w - 0.5 * q) / (2.0 * kPi * std::sqrt(det));
  }
  return sum * kStep;
}

double ggx_ndf_filtered_exact(Vec3 h, Sym2 a, Vec2 alpha2) {
  if (h.z <= 0.0) return 0.0;
  const Sym2 sigma{0.5 * (a.xx - alpha2.x), 0.5 * a.xy, 0.5 * (a.yy - alpha2.y)};
  const double cos2 = h.z * h.z;
  return filtered_ggx_slope_density_matrix({h.x / h.z, h.y / h.z}, alpha2, sigma) / (cos2 * cos2);
}

double ggx_brdf_filtered_exact(Vec3 i, Vec3 o, Sym2 a, Vec2 alpha2) {
  if (i.z <= 0.0 || o.z <= 0.0) return 0.0;
  const Brdf brdf{};
  const Vec3 h = half_vector(brdf.params, i, o);
  const double floor = brdf.params.guard_constants().lambda_min_z;  // the cosines as Brdf::cosines guards them
  return ggx_ndf_filtered_exact(h, a, alpha2) * brdf.ggx_g2_matrix(i, o, h, a) / (4.0 * max(i.z, floor) * max(o.z, floor));
}

// ---------------------------------------------------------------------------------------------
// The single GGX roughness for the filtered lobe (brdf.hpp): fitted to the core-mass criterion.

double ggx_kernel_scale(double alpha2, double kernel) { return kernel_scale(alpha2, max(kernel, 0.0), kGuardConstantsFp32.tiny_positive); }

double ggx_filtered_alpha2(double alpha2, double kernel) { return Brdf{}.ggx_filtered_alpha2(alpha2, kernel); }

// ---------------------------------------------------------------------------------------------
// deferred-aniso's lighting pass (template deferred_aniso_roughness / deferred_aniso_brdf, and the
// pair deferred_aniso_lobe / deferred_aniso_brdf_lobe).
Sym2 deferred_aniso_roughness(const Params& p, Vec3 light_ws, Vec3 view_ws, Vec3 normal_ws, Sym2 tensor, double alpha2) {
  const double cosine = dot(normal_ws, half_vector(p, light_ws, view_ws));
  return Sym2{alpha2, 0.0, alpha2} + (cosine * cosine) * tensor;
}

Sym2 deferred_aniso_tail_roughness(Sym2 tensor, double alpha2) { return Sym2{alpha2, 0.0, alpha2} + tensor; }

namespace {
// A world-space direction in the frame the lighting pass rebuilds from the normal (to_normal_frame).
Vec3 in_normal_frame(Vec3 v, Vec3 normal_ws) {
  return to_tangent_space(v, normal_frame_tangent(normal_ws), normal_frame_bitangent(normal_ws), normal_ws);
}
}  // namespace

double deferred_aniso_brdf(const Params& p, Vec3 light_ws, Vec3 view_ws, Vec3 normal_ws, Sym2 tensor, double alpha2) {
  return Brdf{p}.ggx_brdf_filtered_matrix(in_normal_frame(light_ws, normal_ws), in_normal_frame(view_ws, normal_ws),
                                          deferred_aniso_tail_roughness(tensor, alpha2), {alpha2, alpha2});
}

IsotropicLobe deferred_aniso_lobe(const Params& p, Sym2 tensor, double alpha2) {
  return Brdf{p}.ggx_filtered_lobe_matrix(deferred_aniso_tail_roughness(tensor, alpha2), alpha2);
}

double deferred_aniso_brdf_lobe(const Params& p, Vec3 light_ws, Vec3 view_ws, Vec3 normal_ws, Sym2 tensor, double alpha2,
                                const IsotropicLobe& lobe) {
  return Brdf{p}.ggx_brdf_filtered_lobe_matrix(in_normal_frame(light_ws, normal_ws), in_normal_frame(view_ws, normal_ws),
                                               deferred_aniso_tail_roughness(tensor, alpha2), alpha2, lobe);
}

Sym2 deferred_aniso_covariance(const Params& p, Vec2 slope_mean, Sym2 slope_second, Vec3 tangent_ws, Vec3 bitangent_ws, Vec3 normal_ws) {
  const Sym2 sigma = 2.0 * lean_covariance(p, slope_mean, slope_second);
  const Vec3 tf = normal_frame_tangent(normal_ws), bf = normal_frame_bitangent(normal_ws);
  const double r00 = dot(tf, tangent_ws), r01 = dot(tf, bitangent_ws), r10 = dot(bf, tangent_ws), r11 = dot(bf, bitangent_ws);
  // Rows of R Sigma, then (R Sigma) R^T.
  const double a0 = r00 * sigma.xx + r01 * sigma.xy, b0 = r00 * sigma.xy + r01 * sigma.yy;
  const double a1 = r10 * sigma.xx + r11 * sigma.xy, b1 = r10 * sigma.xy + r11 * sigma.yy;
  const Sym2 rotated{a0 * r00 + b0 * r01, a0 * r10 + b0 * r11, a1 * r10 + b1 * r11};
  return p.guards ? sym2_clamp_psd(rotated) : rotated;
}

Sym2 deferred_aniso_roughness_with_covariance(const Params& p, Vec3 light_ws, Vec3 view_ws, Vec3 normal_ws, Sym2 tensor, Sym2 covariance,
                                              double alpha2) {
  return deferred_aniso_roughness(p, light_ws, view_ws, normal_ws, tensor, alpha2) + covariance;
}

double deferred_aniso_brdf_with_covariance(const Params& p, Vec3 light_ws, Vec3 view_ws, Vec3 normal_ws, Sym2 tensor, Sym2 covariance,
                                           double alpha2) {
  return deferred_aniso_brdf(p, light_ws, view_ws, normal_ws, tensor + covariance, alpha2);
}

// Fragment wrappers on a quad

namespace {
// The half vectors the filtered wrappers differentiate: normalize(i + o), guarded as in
// half_vector, which keeps i = -o (a zero sum) from putting NaN into the quad.
Quad<Vec3> filtered_half_vectors(const Params& p, const Quad<Vec3>& i, const Quad<Vec3>& o) {
  const auto half = [&](int q) { return half_vector(p, i[q], o[q]); };
  return {half(0), half(1), half(2), half(3)};
}
}  // namespace

// Template ggx_brdf_filtered_fragment: A = forward_aniso_projected_fragment(alpha2,
// normalize(i + o)) (T&K 2019 Sec. 3.2), then the matrix GGX BRDF with tau = ax^2 ay^2.
double ggx_brdf_filtered_fragment_quad(const Params& p, const Quad<Vec3>& i, const Quad<Vec3>& o, Vec2 alpha2, int pixel, Derivative mode) {
  const Quad<Vec3> half = filtered_half_vectors(p, i, o);
  const Sym2 a = forward_aniso_projected_fragment_quad(p, alpha2, half, pixel, mode);
  return Brdf{p}.ggx_brdf_matrix(i[pixel], o[pixel], a, ndf_clamp_tau(alpha2));
}

// Template ggx_brdf_tail_filtered_fragment: the same kernel, the tail-preserving filtered GGX.
double ggx_brdf_tail_filtered_fragment_quad(const Params& p, const Quad<Vec3>& i, const Quad<Vec3>& o, Vec2 alpha2, int pixel,
                                            Derivative mode) {
  const Quad<Vec3> half = filtered_half_vectors(p, i, o);
  const Sym2 a = forward_aniso_projected_fragment_quad(p, alpha2, half, pixel, mode);
  return Brdf{p}.ggx_brdf_filtered_matrix(i[pixel], o[pixel], a, alpha2);
}

// Template beckmann_brdf_filtered_fragment: as above with the matrix Beckmann BRDF.
double beckmann_brdf_filtered_fragment_quad(const Params& p, const Quad<Vec3>& i, const Quad<Vec3>& o, Vec2 alpha2, int pixel,
                                            Derivative mode) {
  const Quad<Vec3> half = filtered_half_vectors(p, i, o);
  const Sym2 a = forward_aniso_projected_fragment_quad(p, alpha2, half, pixel, mode);
  return Brdf{p}.beckmann_brdf_matrix(i[pixel], o[pixel], a, ndf_clamp_tau(alpha2));
}

}  // namespace saagen::ref
