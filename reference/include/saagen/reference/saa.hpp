// saagen reference: the filtering variants of templates/00-common.saa, 10-forward.saa and
// 20-deferred.saa, in double precision.
//
// Every function has the name and the argument order of its template function; the functions
// whose template body reads SIGMA2, KAPPA or a guard constant take a Params first (Params also
// selects the guarded or the unguarded paper form, and fp32 or half guard constants). Types: real -> double,
// real2 -> Vec2, real3 -> Vec3 (or Sym2 for a symmetric matrix (m00, m01, m11)).
// The bodies compute the same formulas as the templates, with the same guards, clamps and
// saturates, so that emitted fp32 code can be compared with them element-wise.
//
// Fragment wrappers (role: fragment, which call ddx/ddy on the GPU) have a *_quad reference
// taking the per-pixel inputs of a whole 2x2 quad (quad.hpp) and the index of the pixel whose
// result is wanted. Inputs that the wrapper does not differentiate (alpha2) are plain values:
// pass the value of that pixel.
#pragma once

#include "saagen/reference/math.hpp"
#include "saagen/reference/quad.hpp"

namespace saagen::ref {

// The guard constants of templates/00-common.saa: `value` in fp32 emissions, `half_value` in
// half-precision ones (GLSL fp16, HLSL min16).
struct GuardConstants {
  double slope_min_z = 0.0;         // SLOPE_MIN_Z: smallest |h_z| a slope divides by
  double derivative_max = 0.0;      // DERIVATIVE_MAX: derivative components clamped to +-this
  double tiny_positive = 0.0;       // TINY_POSITIVE: floor of determinants, squared lengths, cos products
  double lambda_min_z = 0.0;        // LAMBDA_MIN_Z: smallest |w_z| Smith Lambda (and the BRDF's cosines) use
  double det_reliable = 0.0;        // DET_RELIABLE: det(A) below this fraction of a00 a11 is rounding noise
  double slope_max = 0.0;           // SLOPE_MAX: slope moments clamped to +-this, second moments to this^2
  double exp_arg_max = 0.0;         // EXP_ARG_MAX (30-brdf.saa): exp(-x) = 0 for x >= this (rounds to 0 in fp32 anyway)
  double divisor_min = 0.0;         // DIVISOR_MIN (30-brdf.saa): 2^-126, Vulkan's x / y is bounded for |y| >= this
  double filtered_ratio_max = 0.0;  // FILTERED_RATIO_MAX (30-brdf.saa): r of the filtered GGX capped here
};
inline constexpr GuardConstants kGuardConstantsFp32{1e-4, 1e9, 1e-30, 1e-7, 1e-3, 1e4, 104.0, 1.1754943508222875e-38, 1e6};
inline constexpr GuardConstants kGuardConstantsHalf{1e-4, 100.0, 6.2e-5, 0.0078125, 0.1, 100.0, 17.5, 6.103515625e-5, 1e4};

// The emission-time constants of templates/00-common.saa, and the emission form.
struct Params {
  double sigma2 = 0.25;  // SIGMA2: variance of the Gaussian pixel filter, pixels^2 (sigma = 0.5)
  double kappa = 0.18;   // KAPPA: clamp of the kernel roughness, alpha^2 domain
  // The form of every guarded(safe, paper) site: true computes `safe` (saagen's default
  // emission), false the unguarded paper form (EmitOptions::guards = false).
  bool guards = true;
  // The guard constants' half_value (EmitOptions::precision fp16 / min16). Only the constants
  // change: the arithmetic stays double.
  bool half_precision = false;

  const GuardConstants& guard_constants() const { return half_precision ? kGuardConstantsHalf : kGuardConstantsFp32; }
};

// ---------------------------------------------------------------------------------------------
// Helpers (templates/00-common.saa)

// Delta^T Delta for the 2x2 matrix Delta with rows du and dv
// (Kaplanyan et al. 2016; Tokuyoshi & Kaplanyan 2019 Sec. 2.2).
Sym2 sym2_from_derivative_rows(Vec2 du, Vec2 dv);

// Largest eigenvalue of a symmetric 2x2 matrix: (m00 + m11)/2 + sqrt(((m00 - m11)/2)^2 + m01^2).
double sym2_max_eigenvalue(Sym2 m);

// Determinant m00 m11 - m01^2.
double sym2_determinant(Sym2 m);

// v^T M v = m00 vx^2 + 2 m01 vx vy + m11 vy^2.
double sym2_quadratic_form(Sym2 m, Vec2 v);

// (v.t, v.b, v.n): v expressed in the frame (t, b, n), written with dot products.
Vec3 to_tangent_space(Vec3 v, Vec3 t, Vec3 b, Vec3 n);

// Guard helpers (saagen's, not the papers'): each derivative component clamped to
// +-DERIVATIVE_MAX so that products of derivatives stay finite.
Vec2 clamp_derivative2(const Params& p, Vec2 d);
Vec3 clamp_derivative3(const Params& p, Vec3 d);

// Guard helper: v * rsqrt(max(dot(v, v), TINY_POSITIVE)); a zero vector stays zero.
Vec3 safe_normalize(const Params& p, Vec3 v);
// Template brdf_half_vector: normalize(i + o); guarded: (0, 0, 1) where |i + o|^2 is below
// DIVISOR_MIN (there the device's rsqrt may see 0 or a flushed denormal).
Vec3 half_vector(const Params& p, Vec3 i, Vec3 o);

// Slope-space half vector h.xy / |h.z| (Kaplanyan et al. 2016; T&K 2019 Listing 1). The paper's
// slope (supplemental Eq. 5) is -h.xy / h.z; Sigma is quadratic in it, so the sign is immaterial.
// Guarded: h.xy / max(|h.z|, SLOPE_MIN_Z). half_vector_slope is the default emission (guarded,
// Params{}); half_vector_slope_form takes the form from p (a separate name, not an overload, so
// that half_vector_slope stays a single function that callers can pass to map()).
Vec2 half_vector_slope(Vec3 half_ts);
Vec2 half_vector_slope_form(const Params& p, Vec3 half_ts);

// Orthographic projection of h onto the hx-hy plane: h.xy (T&K 2019 Sec. 3.2).
Vec2 half_vector_projected(Vec3 half_ts);

// Roughness matrix A = diag(ax^2, ay^2) + 2 Sigma, Sigma = sigma^2 Delta^T Delta
// (T&K 2019 Sec. 2.2). Not clamped. Guarded: du and dv pass through clamp_derivative2.
Sym2 filter_roughness_matrix(const Params& p, Vec2 alpha2, Vec2 du, Vec2 dv);

// Kaplanyan et al. 2016 biased axis-aligned kernel: rect = |du| + |dv|,
// alpha^2 = saturate(alpha^2 + min(2 sigma^2 rect^2, kappa)) per axis.
Vec2 filter_roughness_rectangle(const Params& p, Vec2 alpha2, Vec2 du, Vec2 dv);

// tr(Sigma) = sigma^2 (|dn_dx|^2 + |dn_dy|^2) (T&K 2019 Eqs. 2-3).
double isotropic_kernel_sum(const Params& p, Vec3 dn_dx, Vec3 dn_dy);

// ---------------------------------------------------------------------------------------------
// Forward variants (templates/10-forward.saa)

// Kaplanyan et al. 2016 / T&K 2019 Sec. 2.2: A from slope-space derivatives (not clamped).
Sym2 forward_aniso_slope(const Params& p, Vec2 alpha2, Vec2 dslope_dx, Vec2 dslope_dy);

// T&K 2019 Sec. 3.2: A from derivatives of the projected half vector h.xy (not clamped).
Sym2 forward_aniso_projected(const Params& p, Vec2 alpha2, Vec2 dproj_dx, Vec2 dproj_dy);

// Kaplanyan et al. 2016 rectangle, slope-space derivatives (T&K 2019 Sec. 3.1); saturated.
Vec2 forward_axis_slope(const Params& p, Vec2 alpha2, Vec2 dslope_dx, Vec2 dslope_dy);

// T&K 2019 Sec. 3.2 derivatives with the Kaplanyan et al. 2016 rectangle; saturated.
Vec2 forward_axis_projected(const Params& p, Vec2 alpha2, Vec2 dproj_dx, Vec2 dproj_dy);

// ---------------------------------------------------------------------------------------------
// Deferred (normal-based isotropic) variants (templates/20-deferred.saa); alpha^2 domain.

// Kaplanyan et al. 2016 rectangle maximum width (T&K 2019 Listing 3):
// saturate(alpha^2 + min(2 sigma^2 max(rect.x, rect.y)^2, kappa)), rect = |dx| + |dy|.
double deferred_previous(const Params& p, double alpha2, Vec2 dslope_dx, Vec2 dslope_dy);

// T&K 2019 Eq. 1: saturate(alpha^2 + min(2 lambda_max(Sigma), kappa)), Sigma from the
// derivatives of the projected average normal (Sec. 4.1). Guarded: derivatives clamped.
double deferred_max(const Params& p, double alpha2, Vec2 dproj_dx, Vec2 dproj_dy);

// T&K 2019 Eq. 1 with lambda_max taken from the Gram matrix of the world-space normal
// derivatives (same nonzero eigenvalues as Delta^T Delta when the rows lie in one plane).
// Guarded: derivatives clamped (clamp_derivative3).
double deferred_max_tangent_free(const Params& p, double alpha2, Vec3 dn_dx, Vec3 dn_dy);

// T&K 2019 Eq. 4: saturate(alpha^2 + min(2 sigma^2 (|dn_dx|^2 + |dn_dy|^2), kappa)).
double deferred_sum(const Params& p, double alpha2, Vec3 dn_dx, Vec3 dn_dy);

// Roughness domains engines store (templates/05-domains.saa, templates/engines.json): alpha^2,
// alpha, perceptual r (alpha = r^2) and Unity smoothness s = 1 - r. The conversions to alpha^2
// and back; from alpha^2 they give exactly 0 and 1 at the ends of [0, 1].
enum class RoughnessDomain { alpha2, alpha, perceptual, smoothness };
double alpha2_from_domain(RoughnessDomain domain, double value);
double domain_from_alpha2(RoughnessDomain domain, double alpha2);

// T&K 2019 Eq. 5: saturate(alpha^2 + min(sigma^2 (|dn_dx|^2 + |dn_dy|^2), kappa)).
double deferred_avg(const Params& p, double alpha2, Vec3 dn_dx, Vec3 dn_dy);

// Tokuyoshi & Kaplanyan 2021 (projected space): p = a/(1-a), p' = p + k, a' = p'/(1+p'),
// written as (a + k(1-a)) / (1 + k(1-a)) with a = saturate(alpha2),
// k = min(2 sigma^2 (|dn_dx|^2 + |dn_dy|^2), kappa).
double deferred_projected_space(const Params& p, double alpha2, Vec3 dn_dx, Vec3 dn_dy);

// Anisotropic deferred filtering (deferred-aniso; docs/DEFERRED_KERNEL.md).

// The orthonormal frame (t, b, n) built from n alone (Duff et al. 2017, JCGT 6(1), Listing 3,
// with their b2 times s): s = sign(n.z) (+1 at n.z = 0), a = -1 / (s + n.z),
// t = (1 + s n.x^2 a, s n.x n.y a, -s n.x), b = (s n.x n.y a, 1 + s n.y^2 a, -s n.y);
// right-handed for n.z >= 0, left-handed below (no symmetric matrix read in it can tell).
Vec3 normal_frame_tangent(Vec3 n);
Vec3 normal_frame_bitangent(Vec3 n);

// Dn^T Dn, Dn the rows (dn_dx, dn_dy) read in the frame normal_frame_tangent / _bitangent(n).
Sym2 normal_variation_in_normal_frame(Vec3 dn_dx, Vec3 dn_dy, Vec3 n);
// M = Delta^T Delta scaled by min(1, bound / tr(M)): unchanged when its trace is <= bound, else
// its eigenvectors and eigenvalue ratio kept with the trace = bound (T&K 2019 Eq. 4's clamp of the
// same sum of squares); the trace halved first, as the template does, so that it cannot overflow.
Sym2 sym2_trace_bounded(Sym2 m, double bound);
// scale M with the same bound, for a matrix M whose trace cannot overflow:
// bound / max(bound / scale, tr(M)) M, its trace at most bound.
Sym2 sym2_scaled_to_trace_bound(Sym2 m, double scale, double bound);

// The G-buffer tensor K = 2 sigma^2 Dn^T Dn, Dn the rows (dn_dx, dn_dy) in the frame of
// normal_frame_tangent / normal_frame_bitangent(normal_ws), scaled so that its trace is at most
// kappa (the bound on Dn^T Dn is kappa / (2 sigma^2), then the scale). Guarded:
// derivatives clamped (clamp_derivative3).
Sym2 deferred_aniso(const Params& p, Vec3 dn_dx, Vec3 dn_dy, Vec3 normal_ws);
// The same tensor for derivatives of a vector of length <= 1 (|dn| <= 2), as the fragment wrapper
// takes them: no clamp, and the trace bound on Dn^T Dn itself (sym2_scaled_to_trace_bound).
Sym2 deferred_aniso_from_bounded_derivatives(const Params& p, Vec3 dn_dx, Vec3 dn_dy, Vec3 normal_ws);

// ---------------------------------------------------------------------------------------------
// Fragment wrappers on a 2x2 quad. `pixel` is the quad index 0..3 (quad.hpp); `mode` says how
// the wrapper's plain ddx/ddy are evaluated (the template's explicit ddx_fine/ddy_fine are
// always fine).

// Listing 3's neighbour-weighted normal at one pixel (template helper quad_average_normal):
// n + ddx_fine(n) w.x + ddy_fine(n) w.y, w = 0.5 - 2 frac(floor(frag_coord) / 2). Not normalised.
// Note: for the top-left pixel this is (n_tr + n_bl) / 2, for the top-right (n_tl + n_br) / 2:
// each pixel gets the mean of its two edge neighbours.
// `average` is the derivative the average takes: fine in GLSL and HLSL; GLSL ES 3.00 has only
// the plain dFdx/dFdy, fine or coarse as the implementation chooses.
Vec3 quad_average_normal_quad(const Quad<Vec3>& normal_ws, const Quad<Vec2>& frag_coord, int pixel, Derivative average = Derivative::fine);

Sym2 forward_aniso_slope_fragment_quad(const Params& p, Vec2 alpha2, const Quad<Vec3>& half_ts, int pixel,
                                       Derivative mode = Derivative::coarse);
Sym2 forward_aniso_projected_fragment_quad(const Params& p, Vec2 alpha2, const Quad<Vec3>& half_ts, int pixel,
                                           Derivative mode = Derivative::coarse);
Vec2 forward_axis_slope_fragment_quad(const Params& p, Vec2 alpha2, const Quad<Vec3>& half_ts, int pixel,
                                      Derivative mode = Derivative::coarse);
Vec2 forward_axis_projected_fragment_quad(const Params& p, Vec2 alpha2, const Quad<Vec3>& half_ts, int pixel,
                                          Derivative mode = Derivative::coarse);

// The projected forms' wrappers in transported frames (templates *_transported_fragment,
// docs/FORWARD_DERIVATIVES.md): the screen derivatives of the world-space half vector h and normal
// n, read in the pixel's own frame (t, b) with the frame's first-order change along the normal
// removed: d(h.t) = dh.t - (dn.t)(h.n), d(h.b) = dh.b - (dn.b)(h.n) (transported_projected_derivative).
Vec2 transported_projected_derivative(Vec3 dh, Vec3 dn, double h_dot_n, Vec3 t, Vec3 b);
Sym2 forward_aniso_projected_transported_fragment_quad(const Params& p, Vec2 alpha2, const Quad<Vec3>& half_ws, const Quad<Vec3>& normal_ws,
                                                       const Quad<Vec3>& tangent_ws, const Quad<Vec3>& bitangent_ws, int pixel,
                                                       Derivative mode = Derivative::coarse);
Vec2 forward_axis_projected_transported_fragment_quad(const Params& p, Vec2 alpha2, const Quad<Vec3>& half_ws, const Quad<Vec3>& normal_ws,
                                                      const Quad<Vec3>& tangent_ws, const Quad<Vec3>& bitangent_ws, int pixel,
                                                      Derivative mode = Derivative::coarse);

// Two levels of derivatives, as in the template: ddx_fine/ddy_fine form each pixel's
// neighbour-weighted normal, which is expressed in that pixel's own frame (t, b, n); the outer
// plain ddx/ddy (mode) then differentiate the per-pixel slope (previous) or projected unit
// vector (max). Guarded: the slope divides by max(|z|, SLOPE_MIN_Z) (previous), the average
// normal is normalised by safe_normalize (max).
double deferred_previous_fragment_quad(const Params& p, double alpha2, const Quad<Vec3>& normal_ws, const Quad<Vec3>& tangent_ws,
                                       const Quad<Vec3>& bitangent_ws, const Quad<Vec2>& frag_coord, int pixel,
                                       Derivative mode = Derivative::coarse, Derivative average = Derivative::fine);
double deferred_max_fragment_quad(const Params& p, double alpha2, const Quad<Vec3>& normal_ws, const Quad<Vec3>& tangent_ws,
                                  const Quad<Vec3>& bitangent_ws, const Quad<Vec2>& frag_coord, int pixel,
                                  Derivative mode = Derivative::coarse, Derivative average = Derivative::fine);

double deferred_max_tangent_free_fragment_quad(const Params& p, double alpha2, const Quad<Vec3>& normal_ws, int pixel,
                                               Derivative mode = Derivative::coarse);
double deferred_sum_fragment_quad(const Params& p, double alpha2, const Quad<Vec3>& normal_ws, int pixel,
                                  Derivative mode = Derivative::coarse);
double deferred_avg_fragment_quad(const Params& p, double alpha2, const Quad<Vec3>& normal_ws, int pixel,
                                  Derivative mode = Derivative::coarse);
double deferred_projected_space_fragment_quad(const Params& p, double alpha2, const Quad<Vec3>& normal_ws, int pixel,
                                              Derivative mode = Derivative::coarse);
// deferred_aniso_from_bounded_derivatives on the plain ddx/ddy (mode) of the normal, with this pixel's normal.
Sym2 deferred_aniso_fragment_quad(const Params& p, const Quad<Vec3>& normal_ws, int pixel, Derivative mode = Derivative::coarse);

}  // namespace saagen::ref
