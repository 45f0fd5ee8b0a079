// saagen reference: the microfacet BRDFs of templates/30-brdf.saa, in double precision.
//
// Directions are unit vectors in tangent space (z = shading normal). A roughness matrix A is
// a Sym2 (A00, A01, A11) in the alpha^2 domain; (ax^2, ay^2) is a Vec2. BRDF values exclude
// the Fresnel factor. Same names, argument order, guards and clamps as the templates.
//
// Guards (templates/30-brdf.saa): the free functions compute saagen's default emission
// (guarded, fp32 guard constants). `Brdf{params}` has the same functions under an explicit
// Params: `params.guards = false` gives the unguarded paper form, `params.half_precision` the
// half constants. The guarded sites: the determinant floor max(tau, TINY_POSITIVE); the floor of
// the adjugate's quadratic form in the matrix NDFs (quadratic_form_floor: a near-singular A
// makes it cancel to any sign); the Beckmann matrix exponent taken as
// (h.xy^T adj h.xy / det) / h.z^2 (the slope h.xy / h.z overflows); the alpha^2 floor of the
// axis NDFs and the cos^4 floor of the Beckmann NDFs (TINY_POSITIVE); |w.z| >= LAMBDA_MIN_Z in
// every Lambda, and the GGX matrix Lambda's quadratic form >= 0; the BRDFs' cosines
// max(i.z, LAMBDA_MIN_Z) max(o.z, LAMBDA_MIN_Z), consistent with Lambda; safe_normalize(i + o)
// in the filtered wrappers.
#pragma once

#include "saagen/reference/math.hpp"
#include "saagen/reference/quad.hpp"
#include "saagen/reference/saa.hpp"

#include <array>

namespace saagen::ref {

// tau = ax^2 ay^2 for the determinant clamp (T&K 2019 supplemental Sec. 1, "Practical
// Implementation"): sqrt(det A) is kept >= the unfiltered ax ay.
double ndf_clamp_tau(Vec2 alpha2);

// ---------------------------------------------------------------------------------------------
// GGX

// Supplemental Sec. 1: D(h) = chi+(hz) / (pi sqrt(max(det A, tau)) (h.xy^T A^-1 h.xy + hz^2)^2),
// A^-1 = adj(A) / max(det A, tau).
double ggx_ndf_matrix(Vec3 h, Sym2 a, double tau);

// Supplemental Sec. 1: Lambda(w) = -1/2 + sqrt(w.xy^T A w.xy + wz^2) / (2 |wz|).
double ggx_lambda_matrix(Vec3 w, Sym2 a);

// Height-correlated G2 = chi+(i.h) chi+(o.h) / (1 + Lambda(i) + Lambda(o)) (Heitz 2014, as in
// the supplemental document Sec. 1).
double ggx_g2_matrix(Vec3 i, Vec3 o, Vec3 h, Sym2 a);

// T&K 2019 Sec. 2.2: f = G2 D / (4 |i.n| |o.n|) without F; 0 when i.z <= 0 or o.z <= 0.
double ggx_brdf_matrix(Vec3 i, Vec3 o, Sym2 a, double tau);

// Supplemental Sec. 1, axis-aligned: D(h) = chi+(hz) / (pi ax ay (hx^2/ax^2 + hy^2/ay^2 + hz^2)^2).
double ggx_ndf_axis(Vec3 h, Vec2 alpha2);

// Supplemental Sec. 1, axis-aligned: Lambda(w) = -1/2 + sqrt(ax^2 wx^2 + ay^2 wy^2 + wz^2) / (2|wz|).
double ggx_lambda_axis(Vec3 w, Vec2 alpha2);

// Axis-aligned GGX BRDF with height-correlated G2, without F.
double ggx_brdf_axis(Vec3 i, Vec3 o, Vec2 alpha2);

// ---------------------------------------------------------------------------------------------
// Beckmann

// Heitz 2014 with a roughness matrix: D(h) = chi+(hz) exp(-s^T A^-1 s) / (pi sqrt(max(det A, tau))
// hz^4), s = h.xy / hz, A^-1 = adj(A) / max(det A, tau).
double beckmann_ndf_matrix(Vec3 h, Sym2 a, double tau);

// Walter et al. 2007 rational fit: Lambda(a) = (1 - 1.259 a + 0.396 a^2) / (3.535 a + 2.181 a^2)
// for a < 1.6, else 0; a = 1 / (alpha_o tan theta_o).
double beckmann_lambda_from_a(double a_param);

// Exact Beckmann Smith Lambda (Heitz 2014 Eq. 81 form):
// Lambda(a) = (erf(a) - 1) / 2 + exp(-a^2) / (2 a sqrt(pi)). For testing the Walter fit.
double beckmann_lambda_exact(double a_param);

// Heitz 2014: Lambda(w) with a = |wz| / sqrt(w.xy^T A w.xy) and the Walter fit; 0 when
// w.xy^T A w.xy <= 0.
double beckmann_lambda_matrix(Vec3 w, Sym2 a);

// f = G2 D / (4 |i.n| |o.n|), matrix Beckmann NDF, without F.
double beckmann_brdf_matrix(Vec3 i, Vec3 o, Sym2 a, double tau);

// Beckmann 1963 axis-aligned: D(h) = chi+(hz) exp(-(sx^2/ax^2 + sy^2/ay^2)) / (pi ax ay hz^4).
double beckmann_ndf_axis(Vec3 h, Vec2 alpha2);

// Guard helper of the matrix NDFs: |v|^2 det_floor / (det max(tr A, TINY_POSITIVE)) with
// det_floor = max(det_a, min(det, DET_RELIABLE a00 a11)), a lower bound of v^T adj(A) v / det
// (lambda_min(A) >= det(A) / tr(A)) that treats a numerically singular A as det(A) >= tau.
double quadratic_form_floor(const Params& p, Sym2 a, double det_a, double det, Vec2 v);

// Axis-aligned Beckmann BRDF (Walter Lambda through the matrix form with A = diag(alpha2)).
double beckmann_brdf_axis(Vec3 i, Vec3 o, Vec2 alpha2);

// ---------------------------------------------------------------------------------------------
// Filtered GGX that keeps GGX's tails (saagen; docs/FILTERED_GGX.md)
//
// The papers add the kernel K = 2 Sigma to alpha^2: exact for Beckmann (Gaussian slopes, the
// variances add), not for GGX, whose slope distribution is a Student-t with 2 degrees of
// freedom: GGX(A0) convolved with N(0, Sigma) keeps GGX(A0)'s s^-4 tails, while GGX(A0 + K)
// scales them by det(A0 + K)^(3/2) / det(A0)^(3/2). The exact filtered distribution is the
// scale mixture integral_0^inf e^-w N(0, A0 / (2w) + Sigma) dw (GGX as a Gaussian scale mixture;
// filtered_ggx_slope_density below). saagen's closed form keeps the far tail exactly and puts
// the kernel into two Beckmann lobes (Gaussian slopes: there the variances add), a core and a
// shoulder four times wider (so that one exponential serves both: exp(-x) = exp(-x / 4)^4):
//   D = w GGX(lambda A0) + (1 - w) [(1 - f) Beckmann(A0 + c K) + f Beckmann(4 (A0 + c K))],
//   w = 1 / lambda,  lambda = 1 + 2 a r,  r = (K00 / ax^2 + K11 / ay^2) / 4  (k / alpha^2 when
//   isotropic),
// with c (the core's kernel factor) and f (the shoulder's share) quadratics in w, fitted
// (minimax over r in [1e-3, 2e5], scripts/fit_filtered_ggx.py) to the exact isotropic
// convolution: L1 <= 0.02, mass beyond 4 sqrt(k) within 8 % (test_filtered_ggx); GGX(A0)'s far
// tail is kept exactly in every direction (w lambda = 1), and c -> 1 as r -> inf (the kernel's
// own Gaussian). Every lobe is normalised, so the energy (integral of D cos) is 1.

// The shoulder lobe's matrix is this multiple of the core's.
inline constexpr double kFilteredShoulderScale = 4.0;

// The fitted functions of r.
struct FilteredGgxLobes {
  double tail_scale = 1.0;         // lambda
  double tail_weight = 1.0;        // w = 1 / lambda
  double shoulder_fraction = 0.0;  // f
  double core_kernel = 1.0;        // c
};
FilteredGgxLobes filtered_ggx_lobes(double ratio);
// c = 1 + w (1.3212 - 1.9936 w) from the tail lobe's weight w (template filtered_ggx_core_scale).
double filtered_ggx_core_kernel(double tail_weight);

// r = (K00 / ax^2 + K11 / ay^2) / 4 of a filtered matrix A = diag(alpha2) + K.
double filtered_ggx_ratio(Sym2 a, Vec2 alpha2);

// D of the mixture above for the filtered matrix A and the unfiltered (ax^2, ay^2).
double ggx_ndf_filtered_matrix(Vec3 h, Sym2 a, Vec2 alpha2);
// f = G2 D / (4 i.z o.z) with that D and the papers' G2 of A (masking of the filtered surface).
double ggx_brdf_filtered_matrix(Vec3 i, Vec3 o, Sym2 a, Vec2 alpha2);
// Axis-aligned forms: the filtered (ax'^2, ay'^2) and the unfiltered (ax^2, ay^2).
double ggx_ndf_filtered_axis(Vec3 h, Vec2 filtered, Vec2 alpha2);
double ggx_brdf_filtered_axis(Vec3 i, Vec3 o, Vec2 filtered, Vec2 alpha2);
// The isotropic form split where its work depends on the light: once per pixel the lobe's
// parameters of one filtered alpha^2 (the deferred forms' roughness), (alpha^2 lambda, w,
// 1 / (4 m), f / 2) with m = alpha^2 + c k the core lobe's (k = filtered - alpha^2), then per
// light the BRDF with them; ggx_brdf_filtered_lobe(i, o, f, a, ggx_filtered_lobe_isotropic(f, a))
// is ggx_brdf_filtered_axis(i, o, (f, f), (a, a)).
using IsotropicLobe = std::array<double, 4>;
IsotropicLobe ggx_filtered_lobe_isotropic(double filtered, double alpha2);
double ggx_brdf_filtered_lobe(Vec3 i, Vec3 o, double filtered, double alpha2, const IsotropicLobe& lobe);

// The exact filtered slope density of GGX(alpha2) convolved with an isotropic Gaussian of
// per-axis variance k, at slope radius rho (numerical quadrature of the scale mixture), and its
// mass beyond radius R. For tests and fits, not for shaders.
double filtered_ggx_slope_density(double rho, double alpha2, double k);
double filtered_ggx_mass_beyond(double radius, double alpha2, double k);

// The exact filtered GGX for any kernel: the slope density integral_0^inf e^-w N(s; A0 / (2w) +
// Sigma) dw at slope s (A0 = diag(alpha2), Sigma = K / 2, the covariance the forward variants'
// kernel K = 2 Sigma stands for), and as an NDF of the filtered matrix A = A0 + K, D(h) =
// P(-h.xy / h.z) / h.z^4, with the BRDF f = G2 D / (4 i.z o.z) (the papers' G2 of A, as
// ggx_brdf_filtered_matrix). Quadrature (trapezoid rule in ln w, step 0.25: the integrand is
// analytic in a strip of half-width pi / 2 about the real u axis, so the error is of order
// e^(-pi^2 / 0.25) relative). The renderer's Lobe::exact: the lobe a closed form should reach, a
// measuring instrument (about 180 exponentials per evaluation), not an emitted BRDF.
double filtered_ggx_slope_density_matrix(Vec2 slope, Vec2 alpha2, Sym2 sigma);
double ggx_ndf_filtered_exact(Vec3 h, Sym2 a, Vec2 alpha2);
double ggx_brdf_filtered_exact(Vec3 i, Vec3 o, Sym2 a, Vec2 alpha2);

// ---------------------------------------------------------------------------------------------
// The single GGX roughness that stands for the filtered lobe (saagen; docs/FILTERED_GGX.md):
// for engines that keep their own BRDF and only change alpha^2. Criterion: the GGX lobe whose
// mass within the kernel's core, radius 2 sqrt(k), equals the exact filtered lobe's (which, for
// a small kernel, matches the peak density). Fitted within 3.2 % over r in [1e-3, 2e5]:
//   alpha'^2 = alpha^2 + kernel g,  g = (p0 alpha^2 + p1 kernel / 2) / (2 alpha^2 + p2 kernel),
// kernel = 2 k the papers' alpha^2-domain kernel, p = (2.687, 0.782, 1.210). g -> 2.687 / 2 for
// a small kernel, 0.323 for a large one (the papers: 1).
double ggx_kernel_scale(double alpha2, double kernel);
double ggx_filtered_alpha2(double alpha2, double kernel);

// ---------------------------------------------------------------------------------------------
// The functions above under explicit Params (guards on/off, fp32 or half guard constants); only
// params.guards and params.half_precision matter. (A struct rather than overloads: the free
// functions must stay single functions, which callers pass around as values.)
struct Brdf {
  Params params;

  double ggx_ndf_matrix(Vec3 h, Sym2 a, double tau) const;
  double ggx_lambda_matrix(Vec3 w, Sym2 a) const;
  double ggx_g2_matrix(Vec3 i, Vec3 o, Vec3 h, Sym2 a) const;
  double ggx_brdf_matrix(Vec3 i, Vec3 o, Sym2 a, double tau) const;
  double ggx_ndf_axis(Vec3 h, Vec2 alpha2) const;
  double ggx_lambda_axis(Vec3 w, Vec2 alpha2) const;
  double ggx_brdf_axis(Vec3 i, Vec3 o, Vec2 alpha2) const;
  double beckmann_ndf_matrix(Vec3 h, Sym2 a, double tau) const;
  double beckmann_lambda_matrix(Vec3 w, Sym2 a) const;
  double beckmann_brdf_matrix(Vec3 i, Vec3 o, Sym2 a, double tau) const;
  double beckmann_ndf_axis(Vec3 h, Vec2 alpha2) const;
  double beckmann_brdf_axis(Vec3 i, Vec3 o, Vec2 alpha2) const;
  double filtered_ggx_ratio(Sym2 a, Vec2 alpha2) const;
  // Template filtered_ggx_mixture: w GGX(lambda A0) + (1 - w) ((1 - f) Beckmann(m) + f Beckmann(4 m)),
  // alpha2 the floored (ax^2, ay^2) of A0.
  double filtered_ggx_mixture(Sym2 m, Vec2 alpha2, double tail_scale, double w, double f, Vec3 h) const;
  double ggx_ndf_filtered_matrix(Vec3 h, Sym2 a, Vec2 alpha2) const;
  double ggx_brdf_filtered_matrix(Vec3 i, Vec3 o, Sym2 a, Vec2 alpha2) const;
  double ggx_brdf_filtered_axis(Vec3 i, Vec3 o, Vec2 filtered, Vec2 alpha2) const;
  IsotropicLobe ggx_filtered_lobe_isotropic(double filtered, double alpha2) const;
  double ggx_brdf_filtered_lobe(Vec3 i, Vec3 o, double filtered, double alpha2, const IsotropicLobe& lobe) const;
  // The isotropic material's matrix form split the same way (templates ggx_filtered_lobe_matrix and
  // ggx_brdf_filtered_lobe_matrix): once per pixel (alpha^2 lambda, w, 1 / sqrt(det 2 M), f / 2) of a
  // filtered A = alpha^2 I + K, then per light the BRDF with them; the pair is
  // ggx_brdf_filtered_matrix(i, o, a, (alpha2, alpha2)).
  IsotropicLobe ggx_filtered_lobe_matrix(Sym2 a, double alpha2) const;
  double ggx_brdf_filtered_lobe_matrix(Vec3 i, Vec3 o, Sym2 a, double alpha2, const IsotropicLobe& lobe) const;
  // The matrix the axis form's NDF sees: diag(filtered), the kernel floored at 0 per axis when
  // guarded (template ggx_ndf_filtered_diagonal).
  Sym2 diagonal_ndf_matrix(Vec2 filtered, Vec2 alpha2) const;
  double ggx_filtered_alpha2(double alpha2, double kernel) const;

 private:
  // guarded(safe, paper) of the templates.
  double guarded(double safe, double paper) const { return params.guards ? safe : paper; }
  double tiny() const { return params.guard_constants().tiny_positive; }
  double falloff(double x) const;        // exp(-x), 0 past EXP_ARG_MAX when guarded
  double divisor(double d) const;        // d, floored at DIVISOR_MIN when guarded
  double cosines(Vec3 i, Vec3 o) const;  // i.z o.z, guarded as the templates' BRDFs
  // D G2 / (4 i.z o.z) of the filtered GGX: G2 of a, D of ndf_matrix (a itself but in the axis form).
  double filtered_brdf(Vec3 i, Vec3 o, Sym2 a, Sym2 ndf_matrix, Vec2 alpha2) const;
  // o.z S(i) + i.z S(o), S(v) = sqrt(v.xy^T A v.xy + v.z^2) with the spreads v.xy^T A v.xy given
  // (template filtered_ggx_g2_divisor): G2 / (4 i.z o.z) of the filtered lobes is 1 / (2 this).
  double filtered_g2_divisor(Vec3 i, Vec3 o, double spread_i, double spread_o) const;
};

// ---------------------------------------------------------------------------------------------
// The lighting pass of deferred-aniso (templates/20-deferred.saa; docs/DEFERRED_KERNEL.md):
// world-space light, view and normal, the G-buffer tensor K of deferred_aniso.

// A = diag(alpha^2) + (n.h)^2 K, h = normalize(l + v) (guarded as half_vector), in the frame
// (normal_frame_tangent(n), normal_frame_bitangent(n), n).
Sym2 deferred_aniso_roughness(const Params& p, Vec3 light_ws, Vec3 view_ws, Vec3 normal_ws, Sym2 tensor, double alpha2);
// The tail-preserving lobe's A = diag(alpha^2) + K (the tilt at the highlight's peak, 1), the same
// for every light (template deferred_aniso_tail_roughness).
Sym2 deferred_aniso_tail_roughness(Sym2 tensor, double alpha2);
// The tail-preserving filtered GGX of that A, the light and view expressed in the same frame.
double deferred_aniso_brdf(const Params& p, Vec3 light_ws, Vec3 view_ws, Vec3 normal_ws, Sym2 tensor, double alpha2);
// The same BRDF split: its lobe once per pixel (Brdf::ggx_filtered_lobe_matrix of that A), then per
// light; deferred_aniso_brdf_lobe(p, l, v, n, K, a, deferred_aniso_lobe(p, K, a)) is
// deferred_aniso_brdf(p, l, v, n, K, a).
IsotropicLobe deferred_aniso_lobe(const Params& p, Sym2 tensor, double alpha2);
double deferred_aniso_brdf_lobe(const Params& p, Vec3 light_ws, Vec3 view_ws, Vec3 normal_ws, Sym2 tensor, double alpha2,
                                const IsotropicLobe& lobe);

// A texture covariance with deferred-aniso (docs/DEFERRED_KERNEL.md, "A texture covariance"). The
// geometry pass: C = R (2 Sigma_tex) R^T, Sigma_tex = lean_covariance(slope_mean, slope_second)
// in the texture's frame (tangent_ws, bitangent_ws), R = [t'.t t'.b; b'.t b'.b] the change of
// basis into (t', b') = (normal_frame_tangent(n), normal_frame_bitangent(n)); guarded: clamped to
// PSD (sym2_clamp_psd). Not clamped by kappa.
Sym2 deferred_aniso_covariance(const Params& p, Vec2 slope_mean, Sym2 slope_second, Vec3 tangent_ws, Vec3 bitangent_ws, Vec3 normal_ws);
// The lighting pass: A = diag(alpha^2) + (n.h)^2 K + C, and the tail-preserving filtered GGX of
// diag(alpha^2) + K + C.
Sym2 deferred_aniso_roughness_with_covariance(const Params& p, Vec3 light_ws, Vec3 view_ws, Vec3 normal_ws, Sym2 tensor, Sym2 covariance,
                                              double alpha2);
double deferred_aniso_brdf_with_covariance(const Params& p, Vec3 light_ws, Vec3 view_ws, Vec3 normal_ws, Sym2 tensor, Sym2 covariance,
                                           double alpha2);

// ---------------------------------------------------------------------------------------------
// Fragment wrappers on a 2x2 quad (quad.hpp): the template differentiates the projected half
// vector normalize(i + o) with plain ddx/ddy (forward_aniso_projected_fragment), then evaluates
// the matrix BRDF of this pixel with tau = ndf_clamp_tau(alpha2), both under p's guards.

double ggx_brdf_filtered_fragment_quad(const Params& p, const Quad<Vec3>& i, const Quad<Vec3>& o, Vec2 alpha2, int pixel,
                                       Derivative mode = Derivative::coarse);
// Template ggx_brdf_tail_filtered_fragment: the same kernel, saagen's tail-preserving filtered GGX.
double ggx_brdf_tail_filtered_fragment_quad(const Params& p, const Quad<Vec3>& i, const Quad<Vec3>& o, Vec2 alpha2, int pixel,
                                            Derivative mode = Derivative::coarse);
double beckmann_brdf_filtered_fragment_quad(const Params& p, const Quad<Vec3>& i, const Quad<Vec3>& o, Vec2 alpha2, int pixel,
                                            Derivative mode = Derivative::coarse);

}  // namespace saagen::ref
