// saagen ground-truth renderer: random numbers and the pixel filter.
//
// The ground truth of a pixel is the image of the scene convolved with the pixel filter that
// geometric SAA assumes: a Gaussian of variance sigma^2 = 0.25 px^2 per screen axis (sigma =
// 0.5 px; Params::sigma2 in saa.hpp, Tokuyoshi & Kaplanyan 2019 Sec. 2.2). SAA maps this filter
// to the space of half-vector slopes through the screen-space derivatives: Sigma = sigma^2
// Delta^T Delta is exactly the covariance of the filter pushed through the linearised map
// (pixel offset -> slope), so the quantity SAA is built on is the filter's second moment. The
// renderer therefore uses a filter whose variance is exactly sigma^2:
//
//   * a separable Gaussian N(0, s0^2) per axis, truncated at |x| <= 3 s0 (the support is the
//     square [-3 s0, 3 s0]^2; 1 - 0.9973^2 = 0.54 % of an untruncated Gaussian lies outside);
//   * truncation removes the tails and lowers the variance to s0^2 (1 - 2 c phi(c) / (2 Phi(c)
//     - 1)) with c = 3 (-2.67 %); s0 is chosen so that this is exactly sigma^2:
//     s0 = sigma / sqrt(1 - 2 c phi(c) / (2 Phi(c) - 1)) = 0.50680 px for sigma = 0.5
//     (support +-1.5204 px).
//
// The filter is importance-sampled: stratified (jittered) points u in [0,1)^2 are mapped
// through the inverse CDF of the truncated Gaussian on each axis, so each sample carries the
// same weight and the pixel estimate is the plain mean of the radiance at the sample positions.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <vector>

namespace saagen::measure {

// SplitMix64 (Steele, Lea & Flood 2014): a 64-bit counter passed through an invertible mixer.
// Small, fast and statistically adequate for jitter; seeded per pixel so that a pixel's samples
// depend only on (seed, pixel), never on the thread that renders it.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(seed) {}

  std::uint64_t next_u64();
  // Uniform double in [0, 1) with 53 random bits.
  double next_double();

 private:
  std::uint64_t state_;
};

// Mixes several 64-bit words into one seed (each word through the SplitMix64 finaliser).
std::uint64_t hash_words(std::initializer_list<std::uint64_t> words);

// The seed of pixel (x, y) for a render seed: independent of resolution tiling and threads.
std::uint64_t pixel_seed(std::uint64_t seed, int x, int y);

// Standard normal density phi(x) and distribution Phi(x).
double standard_normal_pdf(double x);
double standard_normal_cdf(double x);

// The truncated Gaussian pixel filter described at the top of this file.
class GaussianPixelFilter {
 public:
  // variance: the variance the truncated filter must have (sigma^2, px^2).
  // truncation: c, the half-width of the support in units of the underlying Gaussian's s0.
  explicit GaussianPixelFilter(double variance = 0.25, double truncation = 3.0);

  double variance() const { return variance_; }
  double truncation() const { return truncation_; }
  // s0, the standard deviation of the underlying (untruncated) Gaussian.
  double underlying_sigma() const { return sigma0_; }
  // Half-width of the support, c * s0 (px).
  double radius() const { return truncation_ * sigma0_; }

  // Density of the 1D truncated filter (integrates to 1 over [-radius, radius]).
  double pdf(double x) const;
  // Its distribution function.
  double cdf(double x) const;
  // Inverse CDF, exact to ~1e-14 px (Newton iterations on cdf).
  double inverse_cdf_exact(double u) const;
  // Inverse CDF from a table of 2^16 + 1 exact values with linear interpolation: the sampler
  // used by the renderer. Interpolation error: h^2/8 max|x''(u)| with h = 2^-16 is below
  // 3e-6 px over the whole support (x''(u) = x / (s0^2 pdf(x)^2) peaks at the support's end).
  double sample(double u) const;

 private:
  double variance_;
  double truncation_;
  double sigma0_;
  double cdf_low_;    // Phi(-c)
  double cdf_range_;  // Phi(c) - Phi(-c)
  std::vector<double> table_;
};

// The filter with sigma^2 = 0.25 and 3-sigma truncation, built once (thread-safe).
const GaussianPixelFilter& default_pixel_filter();

// A jittered stratified pattern of strata x strata points in [0,1)^2, in row-major stratum
// order, drawn from rng: point (i, j) = ((i + xi1) / strata, (j + xi2) / strata).
struct FilmOffset {
  double dx = 0.0;  // pixel-space offset from the pixel centre, +x right
  double dy = 0.0;  // +y down
};

// strata^2 filter-distributed offsets for one pixel: the stratified points above mapped
// through filter.sample on each axis.
void stratified_filter_offsets(const GaussianPixelFilter& filter, int strata, Rng& rng, std::vector<FilmOffset>& out);

}  // namespace saagen::measure
