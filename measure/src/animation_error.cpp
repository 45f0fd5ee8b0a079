// The trade's verdict metrics on an animation and their intervals (see animation_error.hpp).
#include "saagen/measure/animation_error.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace saagen::measure {

namespace {

std::vector<double> gaussian_weights(double sigma) {
  const int radius = std::max(1, static_cast<int>(std::ceil(3.0 * sigma)));
  std::vector<double> weights(static_cast<std::size_t>(2 * radius + 1));
  for (int i = -radius; i <= radius; ++i) weights[static_cast<std::size_t>(i + radius)] = std::exp(-0.5 * (i * i) / (sigma * sigma));
  return weights;
}

// One pass of the separable convolution along x (step 1) or y (step width), renormalised at the
// border.
Image convolve_1d(const Image& image, const std::vector<double>& weights, bool along_x) {
  const int radius = static_cast<int>(weights.size() / 2);
  Image out(image.width, image.height);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      double sum = 0.0, weight = 0.0;
      for (int k = -radius; k <= radius; ++k) {
        const int sx = along_x ? x + k : x, sy = along_x ? y : y + k;
        if (sx < 0 || sy < 0 || sx >= image.width || sy >= image.height) continue;
        const double w = weights[static_cast<std::size_t>(k + radius)];
        sum += w * image.at(sx, sy);
        weight += w;
      }
      out.at(x, y) = static_cast<float>(sum / weight);
    }
  }
  return out;
}

void check_same_size(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height) throw std::invalid_argument("animation error: frames of different sizes");
}

}  // namespace

Image gaussian_pooled(const Image& image, double sigma) {
  if (!(sigma > 0.0)) return image;
  const std::vector<double> weights = gaussian_weights(sigma);
  return convolve_1d(convolve_1d(image, weights, true), weights, false);
}

Image pooled_change(const Image& previous, const Image& current, double sigma) {
  check_same_size(previous, current);
  Image change(current.width, current.height);
  for (std::size_t i = 0; i < current.size(); ++i) {
    const double d = static_cast<double>(current.pixels[i]) - previous.pixels[i];
    change.pixels[i] = std::isfinite(d) ? static_cast<float>(std::fabs(d)) : 1.0f;  // display values lie in [0, 1]
  }
  return gaussian_pooled(change, sigma);
}

double lag_error(const Image& result, const Image& reference, const Image& previous_reference) {
  check_same_size(result, reference);
  check_same_size(result, previous_reference);
  double sum = 0.0;
  for (std::size_t i = 0; i < result.size(); ++i) {
    const double on_time = static_cast<double>(result.pixels[i]) - reference.pixels[i];
    const double late = static_cast<double>(result.pixels[i]) - previous_reference.pixels[i];
    sum += on_time * on_time - late * late;
  }
  return result.size() ? sum / static_cast<double>(result.size()) : 0.0;
}

FlickerError flicker_error(const Image& pooled_change_result, const Image& pooled_change_reference) {
  check_same_size(pooled_change_result, pooled_change_reference);
  FlickerError e;
  const std::size_t n = pooled_change_result.size();
  if (n == 0) return e;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = static_cast<double>(pooled_change_result.pixels[i]) - pooled_change_reference.pixels[i];
    if (d > 0.0)
      e.excess += d;
    else
      e.missing -= d;
  }
  e.excess /= static_cast<double>(n);
  e.missing /= static_cast<double>(n);
  e.error = e.excess + e.missing;
  return e;
}

double student_t_975(int dof) {
  // t_{0.975} for 1 .. 30 degrees of freedom (any statistics table, e.g. NIST/SEMATECH
  // e-Handbook of Statistical Methods, 1.3.6.7.2); beyond, the Cornish-Fisher expansion in 1/dof
  // about the normal quantile 1.959964 (Abramowitz and Stegun 26.7.5), within 1e-4 there.
  static constexpr std::array<double, 30> kTable = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
                                                    2.201,  2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086,
                                                    2.080,  2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042};
  if (dof < 1) throw std::invalid_argument("student_t_975: dof < 1");
  if (dof <= 30) return kTable[static_cast<std::size_t>(dof - 1)];
  const double z = 1.959964, n = dof;
  const double g1 = (z * z * z + z) / 4.0;
  const double g2 = (5 * std::pow(z, 5) + 16 * z * z * z + 3 * z) / 96.0;
  return z + g1 / n + g2 / (n * n);
}

std::vector<double> block_means(std::span<const double> series) {
  const std::size_t n = series.size();
  const std::size_t block = static_cast<std::size_t>(kFramesPerBlock);
  if (n < 2 * block) return {series.begin(), series.end()};
  const std::size_t blocks = n / block;
  std::vector<double> means;
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t begin = b * block, end = b + 1 == blocks ? n : begin + block;
    means.push_back(
        std::accumulate(series.begin() + static_cast<std::ptrdiff_t>(begin), series.begin() + static_cast<std::ptrdiff_t>(end), 0.0) /
        static_cast<double>(end - begin));
  }
  return means;
}

Interval mean_interval(std::span<const double> units, double ground_truth_sd) {
  Interval interval;
  if (units.empty()) return interval;
  const double n = static_cast<double>(units.size());
  interval.mean = std::accumulate(units.begin(), units.end(), 0.0) / n;
  double sampling = 0.0;
  if (units.size() > 1) {
    double ss = 0.0;
    for (double u : units) ss += (u - interval.mean) * (u - interval.mean);
    sampling = student_t_975(static_cast<int>(units.size()) - 1) * std::sqrt(ss / (n - 1.0) / n);
  }
  const double truth = 1.959964 * ground_truth_sd;
  const double half = std::sqrt(sampling * sampling + truth * truth);
  interval.low = interval.mean - half;
  interval.high = interval.mean + half;
  return interval;
}

double ground_truth_spread(std::span<const double> estimate_a, std::span<const double> estimate_b) {
  if (estimate_a.size() != estimate_b.size()) throw std::invalid_argument("ground_truth_spread: size mismatch");
  if (estimate_a.empty()) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < estimate_a.size(); ++i) {
    const double half_difference = 0.5 * (estimate_a[i] - estimate_b[i]);
    sum += half_difference * half_difference;
  }
  return std::sqrt(sum) / static_cast<double>(estimate_a.size());
}

namespace {

double mean_of(const std::vector<double>& values) {
  return values.empty() ? 0.0 : std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

bool has_second_seed(std::span<const SeedSeries> cells) {
  return !cells.empty() && std::all_of(cells.begin(), cells.end(), [](const SeedSeries& s) { return !s[1].empty(); });
}

}  // namespace

double series_ground_truth_sd(std::span<const SeedSeries> cells) {
  if (!has_second_seed(cells)) return 0.0;
  std::vector<double> a, b;
  for (const SeedSeries& cell : cells) {
    a.push_back(mean_of(cell[0]));
    b.push_back(mean_of(cell[1]));
  }
  return ground_truth_spread(a, b);
}

Interval series_interval(std::span<const SeedSeries> cells) {
  const bool two_seeds = has_second_seed(cells);
  std::vector<double> units;
  for (const SeedSeries& cell : cells) {
    std::vector<double> averaged = cell[0];
    if (two_seeds)
      for (std::size_t i = 0; i < averaged.size() && i < cell[1].size(); ++i) averaged[i] = 0.5 * (averaged[i] + cell[1][i]);
    const std::vector<double> blocks = block_means(averaged);
    units.insert(units.end(), blocks.begin(), blocks.end());
  }
  return mean_interval(units, series_ground_truth_sd(cells));
}

SeedSeries paired_difference(const SeedSeries& a, const SeedSeries& b) {
  SeedSeries d;
  for (std::size_t s = 0; s < d.size(); ++s) {
    if (a[s].size() != b[s].size()) throw std::invalid_argument("paired_difference: series of different lengths");
    d[s].resize(a[s].size());
    for (std::size_t i = 0; i < a[s].size(); ++i) d[s][i] = a[s][i] - b[s][i];
  }
  return d;
}

}  // namespace saagen::measure
