// Double-precision reference of templates/00-common.saa, 10-forward.saa and 20-deferred.saa.
// Each body follows its template statement by statement (same guards, clamps, saturates and
// order of operations where it matters for branches).
#include "saagen/reference/saa.hpp"

#include <algorithm>
#include <cmath>

namespace saagen::ref {

// ---------------------------------------------------------------------------------------------
// Helpers

// Kaplanyan et al. 2016 / Tokuyoshi & Kaplanyan 2019 Sec. 2.2: Delta^T Delta, Delta = [du; dv].
Sym2 sym2_from_derivative_rows(Vec2 du, Vec2 dv) {
  return {du.x * du.x + dv.x * dv.x, du.x * du.y + dv.x * dv.y, du.y * du.y + dv.y * dv.y};
}

// Largest eigenvalue of [m00 m01; m01 m11]: the larger root of
// lambda^2 - tr lambda + det = 0, i.e. tr/2 + sqrt((m00 - m11)^2/4 + m01^2).
double sym2_max_eigenvalue(Sym2 m) {
  const double half_trace = 0.5 * (m.xx + m.yy);
  const double half_difference = 0.5 * (m.xx - m.yy);
  return half_trace + std::sqrt(half_difference * half_difference + m.xy * m.xy);
}

double sym2_determinant(Sym2 m) { return m.xx * m.yy - m.xy * m.xy; }

double sym2_quadratic_form(Sym2 m, Vec2 v) { return m.xx * v.x * v.x + 2.0 * m.xy * v.x * v.y + m.yy * v.y * v.y; }

Vec3 to_tangent_space(Vec3 v, Vec3 t, Vec3 b, Vec3 n) { return {dot(v, t), dot(v, b), dot(v, n)}; }

// saagen guards (templates/00-common.saa): clamp(d, -DERIVATIVE_MAX, DERIVATIVE_MAX) per component.
Vec2 clamp_derivative2(const Params& p, Vec2 d) {
  const double m = p.guard_constants().derivative_max;
  return {std::clamp(d.x, -m, m), std::clamp(d.y, -m, m)};
}

Vec3 clamp_derivative3(const Params& p, Vec3 d) {
  const double m = p.guard_constants().derivative_max;
  return {std::clamp(d.x, -m, m), std::clamp(d.y, -m, m), std::clamp(d.z, -m, m)};
}

// v * rsqrt(max(dot(v, v), TINY_POSITIVE)), written as v / sqrt(...): bit-identical to
// normalize(v) whenever |v|^2 >= TINY_POSITIVE (the double reference's rounding is immaterial).
Vec3 safe_normalize(const Params& p, Vec3 v) { return v / std::sqrt(max(dot(v, v), p.guard_constants().tiny_positive)); }

Vec3 half_vector(const Params& p, Vec3 i, Vec3 o) {
  const Vec3 sum = i + o;
  if (!p.guards) return normalize(sum);
  return dot(sum, sum) >= p.guard_constants().divisor_min ? normalize(sum) : Vec3{0.0, 0.0, 1.0};
}

// Kaplanyan et al. 2016 (T&K 2019 Listing 1): slope h.xy / |h.z|; guarded: / max(|h.z|, SLOPE_MIN_Z).
Vec2 half_vector_slope_form(const Params& p, Vec3 half_ts) {
  const double z = std::fabs(half_ts.z);
  return half_ts.xy() / (p.guards ? max(z, p.guard_constants().slope_min_z) : z);
}

Vec2 half_vector_slope(Vec3 half_ts) { return half_vector_slope_form(Params{}, half_ts); }

// T&K 2019 Sec. 3.2: orthographic projection onto the hx-hy plane.
Vec2 half_vector_projected(Vec3 half_ts) { return half_ts.xy(); }

// T&K 2019 Sec. 2.2: A = diag(ax^2, ay^2) + 2 Sigma, Sigma = sigma^2 Delta^T Delta.
Sym2 filter_roughness_matrix(const Params& p, Vec2 alpha2, Vec2 du, Vec2 dv) {
  const Sym2 kernel = (2.0 * p.sigma2) * (p.guards ? sym2_from_derivative_rows(clamp_derivative2(p, du), clamp_derivative2(p, dv))
                                                   : sym2_from_derivative_rows(du, dv));
  return Sym2{alpha2.x, 0.0, alpha2.y} + kernel;
}

// Kaplanyan et al. 2016 axis-aligned rectangle: rect = |du| + |dv|,
// alpha^2 = saturate(alpha^2 + min(2 sigma^2 rect^2, kappa)) per axis.
Vec2 filter_roughness_rectangle(const Params& p, Vec2 alpha2, Vec2 du, Vec2 dv) {
  const Vec2 rectangle = abs(du) + abs(dv);
  const Vec2 kernel = min((2.0 * p.sigma2) * rectangle * rectangle, Vec2{p.kappa, p.kappa});
  return saturate(alpha2 + kernel);
}

// T&K 2019 Eqs. 2-3: tr(Sigma) = sigma^2 (|dn_u|^2 + |dn_v|^2).
double isotropic_kernel_sum(const Params& p, Vec3 dn_dx, Vec3 dn_dy) { return p.sigma2 * (dot(dn_dx, dn_dx) + dot(dn_dy, dn_dy)); }

// ---------------------------------------------------------------------------------------------
// Forward

// Kaplanyan et al. 2016; T&K 2019 Sec. 2.2.
Sym2 forward_aniso_slope(const Params& p, Vec2 alpha2, Vec2 dslope_dx, Vec2 dslope_dy) {
  return filter_roughness_matrix(p, alpha2, dslope_dx, dslope_dy);
}

// T&K 2019 Sec. 3.2 (projected-space Sigma) and Sec. 2.2 (A).
Sym2 forward_aniso_projected(const Params& p, Vec2 alpha2, Vec2 dproj_dx, Vec2 dproj_dy) {
  return filter_roughness_matrix(p, alpha2, dproj_dx, dproj_dy);
}

// Kaplanyan et al. 2016 rectangle; T&K 2019 Sec. 3.1.
Vec2 forward_axis_slope(const Params& p, Vec2 alpha2, Vec2 dslope_dx, Vec2 dslope_dy) {
  return filter_roughness_rectangle(p, alpha2, dslope_dx, dslope_dy);
}

// T&K 2019 Sec. 3.2 derivatives, Kaplanyan et al. 2016 rectangle.
Vec2 forward_axis_projected(const Params& p, Vec2 alpha2, Vec2 dproj_dx, Vec2 dproj_dy) {
  return filter_roughness_rectangle(p, alpha2, dproj_dx, dproj_dy);
}

// ---------------------------------------------------------------------------------------------
// Deferred

// Kaplanyan et al. 2016 rectangle maximum width (T&K 2019 Listing 3).
double deferred_previous(const Params& p, double alpha2, Vec2 dslope_dx, Vec2 dslope_dy) {
  const Vec2 rectangle = abs(dslope_dx) + abs(dslope_dy);
  const double width = max(rectangle.x, rectangle.y);
  return saturate(alpha2 + min(2.0 * p.sigma2 * width * width, p.kappa));
}

// T&K 2019 Eq. 1 with Sigma of Sec. 4.1.
double deferred_max(const Params& p, double alpha2, Vec2 dproj_dx, Vec2 dproj_dy) {
  const Vec2 du = p.guards ? clamp_derivative2(p, dproj_dx) : dproj_dx;
  const Vec2 dv = p.guards ? clamp_derivative2(p, dproj_dy) : dproj_dy;
  const double lambda_max = p.sigma2 * sym2_max_eigenvalue(sym2_from_derivative_rows(du, dv));
  return saturate(alpha2 + min(2.0 * lambda_max, p.kappa));
}

// T&K 2019 Eq. 1; Delta^T Delta and Delta Delta^T (the Gram matrix of the rows) share their
// eigenvalues, and the Gram matrix needs no frame.
double deferred_max_tangent_free(const Params& p, double alpha2, Vec3 dn_dx, Vec3 dn_dy) {
  const Vec3 dx = p.guards ? clamp_derivative3(p, dn_dx) : dn_dx;
  const Vec3 dy = p.guards ? clamp_derivative3(p, dn_dy) : dn_dy;
  const Sym2 gram{dot(dx, dx), dot(dx, dy), dot(dy, dy)};
  const double lambda_max = p.sigma2 * sym2_max_eigenvalue(gram);
  return saturate(alpha2 + min(2.0 * lambda_max, p.kappa));
}

// T&K 2019 Eq. 4.
double deferred_sum(const Params& p, double alpha2, Vec3 dn_dx, Vec3 dn_dy) {
  return saturate(alpha2 + min(2.0 * isotropic_kernel_sum(p, dn_dx, dn_dy), p.kappa));
}

// T&K 2019 Eq. 5.
double deferred_avg(const Params& p, double alpha2, Vec3 dn_dx, Vec3 dn_dy) {
  return saturate(alpha2 + min(isotropic_kernel_sum(p, dn_dx, dn_dy), p.kappa));
}

// Tokuyoshi & Kaplanyan 2021: p = a/(1-a), p' = p + k, a' = p'/(1+p'). Multiplying numerator
// and denominator by (1 - a): a' = (a + k(1-a)) / (1 + k(1-a)), defined at a = 1.
double deferred_projected_space(const Params& p, double alpha2, Vec3 dn_dx, Vec3 dn_dy) {
  const double a = saturate(alpha2);
  const double kernel = min(2.0 * isotropic_kernel_sum(p, dn_dx, dn_dy), p.kappa);
  const double kernel_scaled = kernel * (1.0 - a);
  return (a + kernel_scaled) / (1.0 + kernel_scaled);
}

// Duff et al. 2017 (JCGT 6(1)) Listing 3, with s = +1 at n.z = 0 as the template's n.z >= 0.
Vec3 normal_frame_tangent(Vec3 n) {
  const double s = n.z >= 0.0 ? 1.0 : -1.0;
  const double a = -1.0 / (s + n.z);
  return {1.0 + s * n.x * n.x * a, s * n.x * n.y * a, -s * n.x};
}

// Duff et al.'s b2 times s (the frame of template to_normal_frame): left-handed below n.z = 0.
Vec3 normal_frame_bitangent(Vec3 n) {
  const double s = n.z >= 0.0 ? 1.0 : -1.0;
  const double a = -1.0 / (s + n.z);
  return {s * n.x * n.y * a, 1.0 + s * n.y * n.y * a, -s * n.y};
}

// Dn^T Dn with the rows read in the frame built from n (template normal_variation_in_normal_frame).
Sym2 normal_variation_in_normal_frame(Vec3 dn_dx, Vec3 dn_dy, Vec3 n) {
  const Vec3 t = normal_frame_tangent(n), b = normal_frame_bitangent(n);
  return sym2_from_derivative_rows({dot(dn_dx, t), dot(dn_dx, b)}, {dot(dn_dy, t), dot(dn_dy, b)});
}

// M scaled by min(1, bound / tr(M)) (template sym2_trace_bounded): eigenvectors and eigenvalue
// ratio kept, the trace at most bound as T&K 2019 Eq. 4 bounds the same sum of squares.
Sym2 sym2_trace_bounded(Sym2 m, double bound) {
  const double half_trace = 0.5 * m.xx + 0.5 * m.yy;
  if (half_trace <= 0.5 * bound) return m;
  return ((0.5 * bound) / half_trace) * m;
}

// scale M min(1, bound / (scale tr(M))) = bound / max(bound / scale, tr(M)) M (template
// sym2_scaled_to_trace_bound): scale times the matrix sym2_trace_bounded gives for bound / scale,
// without its branch; the divisor is at least bound / scale.
Sym2 sym2_scaled_to_trace_bound(Sym2 m, double scale, double bound) { return (bound / std::max(bound / scale, m.xx + m.yy)) * m; }

// The normal matrix 2 sigma^2 Dn^T Dn (T&K 2019 Sec. 2.2) in the frame built from n.
Sym2 deferred_aniso(const Params& p, Vec3 dn_dx, Vec3 dn_dy, Vec3 normal_ws) {
  const Vec3 dx = p.guards ? clamp_derivative3(p, dn_dx) : dn_dx;
  const Vec3 dy = p.guards ? clamp_derivative3(p, dn_dy) : dn_dy;
  return (2.0 * p.sigma2) * sym2_trace_bounded(normal_variation_in_normal_frame(dx, dy, normal_ws), p.kappa / (2.0 * p.sigma2));
}

// deferred_aniso for the differences of vectors of length <= 1 (template
// deferred_aniso_from_bounded_derivatives): no clamp, the trace bound on Dn^T Dn itself.
Sym2 deferred_aniso_from_bounded_derivatives(const Params& p, Vec3 dn_dx, Vec3 dn_dy, Vec3 normal_ws) {
  return sym2_scaled_to_trace_bound(normal_variation_in_normal_frame(dn_dx, dn_dy, normal_ws), 2.0 * p.sigma2, p.kappa);
}

// ---------------------------------------------------------------------------------------------
// Fragment wrappers on a quad

// T&K 2019 Listing 3 (template helper quad_average_normal):
// w = 0.5 - 2 frac(floor(frag_coord) * 0.5) is +0.5 on even and -0.5 on odd pixel coordinates,
// so n + ddx_fine(n) w.x + ddy_fine(n) w.y moves half-way towards each edge neighbour.
Vec3 quad_average_normal_quad(const Quad<Vec3>& normal_ws, const Quad<Vec2>& frag_coord, int pixel, Derivative average) {
  const Vec2 neighbour_direction = Vec2{0.5, 0.5} - 2.0 * frac(floor(frag_coord[pixel]) * 0.5);
  return normal_ws[pixel] + ddx(normal_ws, pixel, average) * neighbour_direction.x + ddy(normal_ws, pixel, average) * neighbour_direction.y;
}

Sym2 forward_aniso_slope_fragment_quad(const Params& p, Vec2 alpha2, const Quad<Vec3>& half_ts, int pixel, Derivative mode) {
  const Quad<Vec2> slope = map(half_ts, [&](Vec3 h) { return half_vector_slope_form(p, h); });
  return forward_aniso_slope(p, alpha2, ddx(slope, pixel, mode), ddy(slope, pixel, mode));
}

Sym2 forward_aniso_projected_fragment_quad(const Params& p, Vec2 alpha2, const Quad<Vec3>& half_ts, int pixel, Derivative mode) {
  const Quad<Vec2> projected = map(half_ts, half_vector_projected);
  return forward_aniso_projected(p, alpha2, ddx(projected, pixel, mode), ddy(projected, pixel, mode));
}

Vec2 forward_axis_slope_fragment_quad(const Params& p, Vec2 alpha2, const Quad<Vec3>& half_ts, int pixel, Derivative mode) {
  const Quad<Vec2> slope = map(half_ts, [&](Vec3 h) { return half_vector_slope_form(p, h); });
  return forward_axis_slope(p, alpha2, ddx(slope, pixel, mode), ddy(slope, pixel, mode));
}

Vec2 forward_axis_projected_fragment_quad(const Params& p, Vec2 alpha2, const Quad<Vec3>& half_ts, int pixel, Derivative mode) {
  const Quad<Vec2> projected = map(half_ts, half_vector_projected);
  return forward_axis_projected(p, alpha2, ddx(projected, pixel, mode), ddy(projected, pixel, mode));
}

Vec2 transported_projected_derivative(Vec3 dh, Vec3 dn, double h_dot_n, Vec3 t, Vec3 b) {
  return {dot(dh, t) - dot(dn, t) * h_dot_n, dot(dh, b) - dot(dn, b) * h_dot_n};
}

namespace {

// The x and y derivatives of the projected half vector in the pixel's transported frame.
struct ProjectedDerivatives {
  Vec2 dx, dy;
};

ProjectedDerivatives transported_projected_derivatives(const Quad<Vec3>& half_ws, const Quad<Vec3>& normal_ws, const Quad<Vec3>& tangent_ws,
                                                       const Quad<Vec3>& bitangent_ws, int pixel, Derivative mode) {
  const double h_dot_n = dot(half_ws[pixel], normal_ws[pixel]);
  const Vec3 t = tangent_ws[pixel], b = bitangent_ws[pixel];
  return {transported_projected_derivative(ddx(half_ws, pixel, mode), ddx(normal_ws, pixel, mode), h_dot_n, t, b),
          transported_projected_derivative(ddy(half_ws, pixel, mode), ddy(normal_ws, pixel, mode), h_dot_n, t, b)};
}

}  // namespace

Sym2 forward_aniso_projected_transported_fragment_quad(const Params& p, Vec2 alpha2, const Quad<Vec3>& half_ws, const Quad<Vec3>& normal_ws,
                                                       const Quad<Vec3>& tangent_ws, const Quad<Vec3>& bitangent_ws, int pixel,
                                                       Derivative mode) {
  const ProjectedDerivatives d = transported_projected_derivatives(half_ws, normal_ws, tangent_ws, bitangent_ws, pixel, mode);
  return forward_aniso_projected(p, alpha2, d.dx, d.dy);
}

Vec2 forward_axis_projected_transported_fragment_quad(const Params& p, Vec2 alpha2, const Quad<Vec3>& half_ws, const Quad<Vec3>& normal_ws,
                                                      const Quad<Vec3>& tangent_ws, const Quad<Vec3>& bitangent_ws, int pixel,
                                                      Derivative mode) {
  const ProjectedDerivatives d = transported_projected_derivatives(half_ws, normal_ws, tangent_ws, bitangent_ws, pixel, mode);
  return forward_axis_projected(p, alpha2, d.dx, d.dy);
}

// Template deferred_previous_fragment: at every pixel q of the quad,
//   average_ts(q) = to_tangent_space(quad_average_normal(q), t(q), b(q), n(q)),
//   slope(q) = average_ts.xy / |average_ts.z| (guarded: / max(|average_ts.z|, SLOPE_MIN_Z));
// then ddx/ddy of slope at the requested pixel.
double deferred_previous_fragment_quad(const Params& p, double alpha2, const Quad<Vec3>& normal_ws, const Quad<Vec3>& tangent_ws,
                                       const Quad<Vec3>& bitangent_ws, const Quad<Vec2>& frag_coord, int pixel, Derivative mode,
                                       Derivative average) {
  const Quad<Vec2> slope = map_indexed(normal_ws, [&](Vec3 n, int q) {
    const Vec3 average_ts =
        to_tangent_space(quad_average_normal_quad(normal_ws, frag_coord, q, average), tangent_ws[q], bitangent_ws[q], n);
    const double z = std::fabs(average_ts.z);
    return average_ts.xy() / (p.guards ? max(z, p.guard_constants().slope_min_z) : z);
  });
  return deferred_previous(p, alpha2, ddx(slope, pixel, mode), ddy(slope, pixel, mode));
}

// Template deferred_max_fragment: at every pixel q,
//   projected(q) = to_tangent_space(normalize(quad_average_normal(q)), t(q), b(q), n(q)).xy
//   (guarded: safe_normalize);
// then ddx/ddy of projected at the requested pixel.
double deferred_max_fragment_quad(const Params& p, double alpha2, const Quad<Vec3>& normal_ws, const Quad<Vec3>& tangent_ws,
                                  const Quad<Vec3>& bitangent_ws, const Quad<Vec2>& frag_coord, int pixel, Derivative mode,
                                  Derivative average) {
  const Quad<Vec2> projected = map_indexed(normal_ws, [&](Vec3 n, int q) {
    const Vec3 sum = quad_average_normal_quad(normal_ws, frag_coord, q, average);
    const Vec3 average = p.guards ? safe_normalize(p, sum) : normalize(sum);
    return to_tangent_space(average, tangent_ws[q], bitangent_ws[q], n).xy();
  });
  return deferred_max(p, alpha2, ddx(projected, pixel, mode), ddy(projected, pixel, mode));
}

double deferred_max_tangent_free_fragment_quad(const Params& p, double alpha2, const Quad<Vec3>& normal_ws, int pixel, Derivative mode) {
  return deferred_max_tangent_free(p, alpha2, ddx(normal_ws, pixel, mode), ddy(normal_ws, pixel, mode));
}

double deferred_sum_fragment_quad(const Params& p, double alpha2, const Quad<Vec3>& normal_ws, int pixel, Derivative mode) {
  return deferred_sum(p, alpha2, ddx(normal_ws, pixel, mode), ddy(normal_ws, pixel, mode));
}

double deferred_avg_fragment_quad(const Params& p, double alpha2, const Quad<Vec3>& normal_ws, int pixel, Derivative mode) {
  return deferred_avg(p, alpha2, ddx(normal_ws, pixel, mode), ddy(normal_ws, pixel, mode));
}

double deferred_projected_space_fragment_quad(const Params& p, double alpha2, const Quad<Vec3>& normal_ws, int pixel, Derivative mode) {
  return deferred_projected_space(p, alpha2, ddx(normal_ws, pixel, mode), ddy(normal_ws, pixel, mode));
}

Sym2 deferred_aniso_fragment_quad(const Params& p, const Quad<Vec3>& normal_ws, int pixel, Derivative mode) {
  return deferred_aniso_from_bounded_derivatives(p, ddx(normal_ws, pixel, mode), ddy(normal_ws, pixel, mode), normal_ws[pixel]);
}

double alpha2_from_domain(RoughnessDomain domain, double value) {
  switch (domain) {
    case RoughnessDomain::alpha2:
      return value;
    case RoughnessDomain::alpha:
      return value * value;
    case RoughnessDomain::perceptual:
      return (value * value) * (value * value);  // alpha = r^2
    case RoughnessDomain::smoothness:
      return alpha2_from_domain(RoughnessDomain::perceptual, 1.0 - value);
  }
  return value;
}

double domain_from_alpha2(RoughnessDomain domain, double alpha2) {
  const auto ends = [&](double root) { return alpha2 >= 1.0 ? 1.0 : alpha2 <= 0.0 ? 0.0 : root; };
  switch (domain) {
    case RoughnessDomain::alpha2:
      return alpha2;
    case RoughnessDomain::alpha:
      return ends(std::sqrt(alpha2));
    case RoughnessDomain::perceptual:
      return ends(std::sqrt(std::sqrt(alpha2)));
    case RoughnessDomain::smoothness:
      return 1.0 - domain_from_alpha2(RoughnessDomain::perceptual, alpha2);
  }
  return alpha2;
}

}  // namespace saagen::ref
