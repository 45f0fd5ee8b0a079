#include "saagen/reference/prefilter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace saagen::ref {

namespace {

double clamp(double v, double low, double high) { return min(max(v, low), high); }

double guarded(const Params& p, double safe, double paper) { return p.guards ? safe : paper; }

// 2 sigma^2 (|dn_dx|^2 + |dn_dy|^2) clamped by kappa: the Eq. 4 kernel, the only clamped term.
double clamped_kernel(const Params& p, Vec3 dn_dx, Vec3 dn_dy) { return min(2.0 * isotropic_kernel_sum(p, dn_dx, dn_dy), p.kappa); }

}  // namespace

// Toksvig 2005: |N_a| = 1 / (1 + sigma^2).
double toksvig_variance(const Params& p, double mean_length) {
  const double l = guarded(p, max(mean_length, p.guard_constants().tiny_positive), mean_length);
  return max((1.0 - l) / l, 0.0);
}

Sym2 sym2_clamp_psd(Sym2 m) {
  const double d0 = max(m.xx, 0.0), d1 = max(m.yy, 0.0);
  const double limit = std::sqrt(d0) * std::sqrt(d1);
  return {d0, clamp(m.xy, -limit, limit), d1};
}

// Olano & Baker 2010 Sec. 3.
Sym2 lean_covariance(const Params& p, Vec2 slope_mean, Sym2 slope_second) {
  Vec2 m = slope_mean;
  Sym2 e = slope_second;
  if (p.guards) {
    const double s = p.guard_constants().slope_max, bound = s * s;
    m = {clamp(m.x, -s, s), clamp(m.y, -s, s)};
    e = {clamp(e.xx, 0.0, bound), clamp(e.xy, -bound, bound), clamp(e.yy, 0.0, bound)};
  }
  const Sym2 covariance = e - Sym2{m.x * m.x, m.x * m.y, m.y * m.y};
  return p.guards ? sym2_clamp_psd(covariance) : covariance;
}

// Tokuyoshi & Kaplanyan 2021, written without a division by 1 - a.
double projected_space_add(double alpha2, double k) {
  const double a = saturate(alpha2);
  const double scaled = k * (1.0 - a);
  return (a + scaled) / (1.0 + scaled);
}

double prefilter_toksvig(const Params& p, double alpha2, double mean_length) {
  return saturate(alpha2 + 2.0 * toksvig_variance(p, mean_length));
}

double prefilter_toksvig_sum(const Params& p, double alpha2, double mean_length, Vec3 dn_dx, Vec3 dn_dy) {
  const double texture_term = 2.0 * toksvig_variance(p, mean_length);
  return saturate(alpha2 + texture_term + clamped_kernel(p, dn_dx, dn_dy));
}

double prefilter_toksvig_projected(const Params& p, double alpha2, double mean_length, Vec3 dn_dx, Vec3 dn_dy) {
  const double texture_term = 2.0 * toksvig_variance(p, mean_length);
  return projected_space_add(alpha2, texture_term + clamped_kernel(p, dn_dx, dn_dy));
}

double vmf_kappa(double mean_length) {
  if (!(mean_length < 1.0)) return std::numeric_limits<double>::infinity();
  const double l = max(mean_length, 0.0), l2 = l * l;
  return (3.0 * l - l * l2) / (1.0 - l2);
}

double unreal_composite_alpha2(double alpha2, double mean_length, double power) {
  const double l = std::min(mean_length, 1.0);
  if (!(l > 0.0)) return 1.0;  // no mean direction: (1 - L) / L is infinite, a' -> 1
  const double variance = power * max((1.0 - l) / l - 4e-5, 0.0);
  const double a = saturate(alpha2);
  const double b = 2.0 * variance * (a - 1.0);
  return (b - a) / (b - 1.0);
}

double filament_vmf_alpha2(double alpha2, double mean_length) { return saturate(alpha2 + 2.0 / vmf_kappa(mean_length)); }

double hdrp_texture_alpha2(double alpha2, double mean_length, double threshold) {
  const double variance = min(0.25 / vmf_kappa(mean_length), 0.03125);
  return saturate(alpha2 + min(2.0 * variance, threshold * threshold));
}

// T&K 2019 Sec. 2.2 with the texture's covariance.
Sym2 prefilter_lean(const Params& p, Vec2 alpha2, Vec2 slope_mean, Sym2 slope_second) {
  return Sym2{alpha2.x, 0.0, alpha2.y} + 2.0 * lean_covariance(p, slope_mean, slope_second);
}

Sym2 prefilter_lean_aniso_slope(const Params& p, Vec2 alpha2, Vec2 slope_mean, Sym2 slope_second, Vec2 dslope_dx, Vec2 dslope_dy) {
  return filter_roughness_matrix(p, alpha2, dslope_dx, dslope_dy) + 2.0 * lean_covariance(p, slope_mean, slope_second);
}

double prefilter_lean_sum(const Params& p, double alpha2, Vec2 slope_mean, Sym2 slope_second, Vec3 dn_dx, Vec3 dn_dy) {
  const double texture_term = trace(lean_covariance(p, slope_mean, slope_second));
  return saturate(alpha2 + texture_term + clamped_kernel(p, dn_dx, dn_dy));
}

double prefilter_lean_projected(const Params& p, double alpha2, Vec2 slope_mean, Sym2 slope_second, Vec3 dn_dx, Vec3 dn_dy) {
  const double texture_term = trace(lean_covariance(p, slope_mean, slope_second));
  return projected_space_add(alpha2, texture_term + clamped_kernel(p, dn_dx, dn_dy));
}

}  // namespace saagen::ref
