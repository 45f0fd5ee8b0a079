// The engines' shipped geometric SAA forms (see engines.hpp for sources and constants).
#include "saagen/measure/engines.hpp"

#include <cmath>

namespace saagen::measure {

using ref::dot;
using ref::max;
using ref::min;
using ref::saturate;
using ref::Vec3;

namespace {

double sum_of_squares(Vec3 dndx, Vec3 dndy) { return dot(dndx, dndx) + dot(dndy, dndy); }
double max_of_squares(Vec3 dndx, Vec3 dndy) { return max(dot(dndx, dndx), dot(dndy, dndy)); }

double alpha2_from_perceptual(double r) { return r * r * r * r; }  // alpha = r^2, a = alpha^2

// a' = sat(a + min(2 variance S, cap)): the HDRP / Filament form (T&K 2019 Eq. 4 with their
// constants).
double sum_form(double alpha, double variance, double cap, Vec3 dndx, Vec3 dndy) {
  return saturate(alpha * alpha + min(2.0 * variance * sum_of_squares(dndx, dndy), cap));
}

}  // namespace

double hdrp_alpha2(double alpha, Vec3 dndx, Vec3 dndy) { return sum_form(alpha, 0.1, 0.2 * 0.2, dndx, dndy); }

double filament_alpha2(double alpha, Vec3 dndx, Vec3 dndy) { return sum_form(alpha, 0.15, 0.04, dndx, dndy); }

double godot_alpha2(double alpha, Vec3 dndx, Vec3 dndy) {
  const double filtered = min(1.0, alpha + min(2.0 * 0.25 * sum_of_squares(dndx, dndy), 0.18));
  return filtered * filtered;
}

double unreal_alpha2(double alpha, Vec3 dndx, Vec3 dndy) {
  const double r = std::sqrt(alpha);
  const double curvature = saturate(1.0 * std::pow(max_of_squares(dndx, dndy), 0.333) + 0.0);
  return alpha2_from_perceptual(max(r, curvature));
}

double threejs_alpha2(double alpha, Vec3 dndx, Vec3 dndy) {
  const Vec3 d{max(std::fabs(dndx.x), std::fabs(dndy.x)), max(std::fabs(dndx.y), std::fabs(dndy.y)),
               max(std::fabs(dndx.z), std::fabs(dndy.z))};
  const double geometry_roughness = max(max(d.x, d.y), d.z);
  const double r = min(max(std::sqrt(alpha), 0.0525) + geometry_roughness, 1.0);
  return alpha2_from_perceptual(r);
}

double babylon_alpha2(double alpha, Vec3 dndx, Vec3 dndy) {
  const double r = std::sqrt(alpha);
  return alpha2_from_perceptual(max(r, std::pow(saturate(max_of_squares(dndx, dndy)), 0.333)));
}

}  // namespace saagen::measure
