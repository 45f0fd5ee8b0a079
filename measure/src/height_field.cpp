// Periodic analytic height fields (see height_field.hpp).
#include "saagen/measure/height_field.hpp"

#include "saagen/measure/sampling.hpp"

#include <cmath>
#include <sstream>

namespace saagen::measure {

using ref::kPi;

double PeriodicWave::cycles() const { return std::hypot(static_cast<double>(m), static_cast<double>(n)); }

double PeriodicHeightField::height(Vec2 uv) const {
  double h = 0.0;
  for (const PeriodicWave& w : waves) h += w.amplitude * std::sin(2.0 * kPi * (w.m * uv.x + w.n * uv.y) + w.phase);
  return h;
}

Vec2 PeriodicHeightField::gradient(Vec2 uv) const {
  Vec2 g{};
  for (const PeriodicWave& w : waves) {
    // d/du a sin(2 pi (m u + n v) + phase) = 2 pi m a cos(.), likewise for v.
    const double c = 2.0 * kPi * w.amplitude * std::cos(2.0 * kPi * (w.m * uv.x + w.n * uv.y) + w.phase);
    g = g + c * Vec2{static_cast<double>(w.m), static_cast<double>(w.n)};
  }
  return g;
}

double PeriodicHeightField::slope_bound() const {
  double s = 0.0;
  for (const PeriodicWave& w : waves) s += std::fabs(w.amplitude) * 2.0 * kPi * w.cycles();
  return s;
}

std::string PeriodicHeightField::describe() const {
  std::ostringstream s;
  s.precision(17);
  s << "height_field(";
  for (const PeriodicWave& w : waves) s << "wave(" << w.m << "," << w.n << "," << w.amplitude << "," << w.phase << ")";
  s << ")";
  return s.str();
}

PeriodicHeightField PeriodicHeightField::random(std::uint64_t seed, int count, double cycles, double total_slope) {
  Rng rng(seed);
  PeriodicHeightField field;
  while (static_cast<int>(field.waves.size()) < count) {
    // Stratified directions: wave k's angle uniform in [k, k + 1) pi / count (a wave and its
    // opposite are the same up to phase, so half a turn covers every direction).
    const double angle = kPi * (static_cast<double>(field.waves.size()) + rng.next_double()) / count;
    const double c = cycles * (0.85 + 0.3 * rng.next_double());
    PeriodicWave w;
    w.m = static_cast<int>(std::lround(c * std::cos(angle)));
    w.n = static_cast<int>(std::lround(c * std::sin(angle)));
    w.phase = 2.0 * kPi * rng.next_double();
    bool duplicate = w.m == 0 && w.n == 0;
    for (const PeriodicWave& o : field.waves) duplicate = duplicate || (o.m == w.m && o.n == w.n) || (o.m == -w.m && o.n == -w.n);
    if (duplicate) continue;
    // Slope amplitude a 2 pi |(m, n)| = total_slope / count.
    w.amplitude = total_slope / count / (2.0 * kPi * w.cycles());
    field.waves.push_back(w);
  }
  return field;
}

}  // namespace saagen::measure
