// saagen ground-truth renderer: periodic analytic height fields, the source of the procedural
// normal maps of the normal-mapped scenes (normal_map.hpp's normals_from_gradient).
//
// h(u, v) = sum_k a_k sin(2 pi (m_k u + n_k v) + phase_k) on the unit square with integer
// (m_k, n_k), so h repeats with period 1 in u and v (a tileable texture). The gradient is
// analytic: dh/du = sum_k 2 pi m_k a_k cos(.), dh/dv = sum_k 2 pi n_k a_k cos(.). Each wave's
// slope amplitude is a_k 2 pi |(m_k, n_k)|, so |grad h| <= sum_k a_k 2 pi |(m_k, n_k)| and the
// normal normalize(-dh/du, -dh/dv, 1) tilts by at most atan of that sum.
#pragma once

#include "saagen/reference/math.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace saagen::measure {

using ref::Vec2;

// One term a sin(2 pi (m u + n v) + phase).
struct PeriodicWave {
  int m = 0;
  int n = 0;
  double amplitude = 0.0;
  double phase = 0.0;
  double cycles() const;  // |(m, n)|: periods per unit length (wavelength 1 / cycles)
};

struct PeriodicHeightField {
  std::vector<PeriodicWave> waves;

  double height(Vec2 uv) const;
  Vec2 gradient(Vec2 uv) const;  // (dh/du, dh/dv)
  // sum_k a_k 2 pi |(m_k, n_k)|: an upper bound of |grad h| (the tangent of the largest tilt).
  double slope_bound() const;
  // Every number of the field (cache keys).
  std::string describe() const;

  // `count` waves with stratified random directions (wave k's angle uniform in
  // [k, k + 1) pi / count) and uniformly random phases from a fixed seed (SplitMix64,
  // sampling.hpp), cycles in cycles * [0.85, 1.15] (rounded to the integer lattice, distinct),
  // and equal slope amplitudes total_slope / count, so that slope_bound() == total_slope.
  static PeriodicHeightField random(std::uint64_t seed, int count, double cycles, double total_slope);
};

}  // namespace saagen::measure
