// Random numbers and the truncated Gaussian pixel filter (see sampling.hpp).
#include "saagen/measure/sampling.hpp"

#include <cmath>
#include <stdexcept>

namespace saagen::measure {

namespace {

// SplitMix64 finaliser (Stafford's "Mix13" variant constants, as used by SplitMix64).
std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

constexpr std::uint64_t kGoldenGamma = 0x9e3779b97f4a7c15ULL;
constexpr double kInvSqrt2 = 0.70710678118654752440;
constexpr double kInvSqrt2Pi = 0.39894228040143267794;
constexpr int kTableIntervals = 1 << 16;

}  // namespace

std::uint64_t Rng::next_u64() {
  state_ += kGoldenGamma;
  return mix64(state_);
}

double Rng::next_double() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }

std::uint64_t hash_words(std::initializer_list<std::uint64_t> words) {
  std::uint64_t h = 0x243f6a8885a308d3ULL;  // digits of pi: any fixed start will do
  for (std::uint64_t w : words) h = mix64(h ^ mix64(w + kGoldenGamma));
  return h;
}

std::uint64_t pixel_seed(std::uint64_t seed, int x, int y) {
  return hash_words(
      {seed, static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)), static_cast<std::uint64_t>(static_cast<std::uint32_t>(y))});
}

double standard_normal_pdf(double x) { return kInvSqrt2Pi * std::exp(-0.5 * x * x); }

// Phi(x) = erfc(-x / sqrt 2) / 2, accurate in both tails.
double standard_normal_cdf(double x) { return 0.5 * std::erfc(-x * kInvSqrt2); }

GaussianPixelFilter::GaussianPixelFilter(double variance, double truncation) : variance_(variance), truncation_(truncation) {
  if (!(variance > 0.0) || !(truncation > 0.0)) throw std::invalid_argument("pixel filter: variance and truncation must be positive");
  const double c = truncation;
  cdf_low_ = standard_normal_cdf(-c);
  cdf_range_ = standard_normal_cdf(c) - cdf_low_;
  // Variance of N(0, 1) truncated to [-c, c]: 1 - 2 c phi(c) / (Phi(c) - Phi(-c)).
  const double unit_variance = 1.0 - 2.0 * c * standard_normal_pdf(c) / cdf_range_;
  sigma0_ = std::sqrt(variance / unit_variance);

  // Table of the exact inverse CDF at u = k / N; consecutive entries are close, so each Newton
  // solve starts from the previous entry.
  table_.resize(kTableIntervals + 1);
  table_.front() = -radius();
  table_.back() = radius();
  double x = -radius();
  for (int k = 1; k < kTableIntervals; ++k) {
    const double u = static_cast<double>(k) / kTableIntervals;
    for (int it = 0; it < 50; ++it) {
      const double step = (cdf(x) - u) / pdf(x);
      x -= step;
      if (x < -radius()) x = -radius();
      if (x > radius()) x = radius();
      if (std::fabs(step) < 1e-15) break;
    }
    table_[k] = x;
  }
}

double GaussianPixelFilter::pdf(double x) const {
  if (std::fabs(x) > radius()) return 0.0;
  return standard_normal_pdf(x / sigma0_) / (sigma0_ * cdf_range_);
}

double GaussianPixelFilter::cdf(double x) const {
  if (x <= -radius()) return 0.0;
  if (x >= radius()) return 1.0;
  return (standard_normal_cdf(x / sigma0_) - cdf_low_) / cdf_range_;
}

double GaussianPixelFilter::inverse_cdf_exact(double u) const {
  if (u <= 0.0) return -radius();
  if (u >= 1.0) return radius();
  // Start from the table, then Newton (the CDF is smooth and strictly increasing).
  double x = sample(u);
  for (int it = 0; it < 50; ++it) {
    const double step = (cdf(x) - u) / pdf(x);
    x -= step;
    if (std::fabs(step) < 1e-15) break;
  }
  return x;
}

double GaussianPixelFilter::sample(double u) const {
  if (u <= 0.0) return table_.front();
  if (u >= 1.0) return table_.back();
  const double scaled = u * kTableIntervals;
  const int k = static_cast<int>(scaled);
  const double f = scaled - k;
  return table_[k] + f * (table_[k + 1] - table_[k]);
}

const GaussianPixelFilter& default_pixel_filter() {
  static const GaussianPixelFilter filter(0.25, 3.0);
  return filter;
}

void stratified_filter_offsets(const GaussianPixelFilter& filter, int strata, Rng& rng, std::vector<FilmOffset>& out) {
  out.clear();
  out.reserve(static_cast<std::size_t>(strata) * strata);
  const double inv = 1.0 / strata;
  for (int j = 0; j < strata; ++j) {
    for (int i = 0; i < strata; ++i) {
      const double u = (i + rng.next_double()) * inv;
      const double v = (j + rng.next_double()) * inv;
      out.push_back({filter.sample(u), filter.sample(v)});
    }
  }
}

}  // namespace saagen::measure
