// Images and error metrics (see image.hpp).
#include "saagen/measure/image.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace saagen::measure {

double tonemap(double x) {
  if (!(x > 0.0)) return 0.0;
  if (std::isinf(x)) return 1.0;
  return x / (1.0 + x);
}

double srgb_encode(double display_linear) {
  const double v = display_linear > 0.0 ? std::min(display_linear, 1.0) : 0.0;  // NaN -> 0
  if (v <= 0.0031308) return v * 12.92;
  return 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

double srgb_decode(double encoded) {
  const double v = encoded > 0.0 ? std::min(encoded, 1.0) : 0.0;  // NaN -> 0
  if (v <= 0.04045) return v / 12.92;
  return std::pow((v + 0.055) / 1.055, 2.4);
}

double display_value(double radiance) { return srgb_encode(tonemap(radiance)); }

Image tonemapped(const Image& radiance) {
  Image out(radiance.width, radiance.height);
  for (std::size_t i = 0; i < radiance.size(); ++i) out.pixels[i] = static_cast<float>(tonemap(radiance.pixels[i]));
  return out;
}

Image display_image(const Image& radiance) {
  Image out(radiance.width, radiance.height);
  for (std::size_t i = 0; i < radiance.size(); ++i) out.pixels[i] = static_cast<float>(display_value(radiance.pixels[i]));
  return out;
}

std::vector<std::uint8_t> display_bytes(const Image& display) {
  std::vector<std::uint8_t> bytes(display.size());
  for (std::size_t i = 0; i < display.size(); ++i) {
    const float v = display.pixels[i] >= 0.0f ? std::min(display.pixels[i], 1.0f) : 0.0f;  // NaN compares false: 0
    bytes[i] = static_cast<std::uint8_t>(std::lround(v * 255.0f));
  }
  return bytes;
}

ImageError compare_images(const Image& image, const Image& reference) {
  if (image.width != reference.width || image.height != reference.height) throw std::invalid_argument("compare_images: size mismatch");
  ImageError e;
  double sum_linear = 0.0, sum_tonemapped = 0.0;
  std::size_t counted = 0;
  for (std::size_t i = 0; i < image.size(); ++i) {
    const double a = image.pixels[i], r = reference.pixels[i];
    if (!std::isfinite(a)) {
      ++e.non_finite;
      continue;
    }
    const double d = a - r;
    const double dt = tonemap(a) - tonemap(r);
    sum_linear += d * d;
    sum_tonemapped += dt * dt;
    e.max_error = std::max(e.max_error, std::fabs(d));
    ++counted;
  }
  if (counted > 0) {
    e.rmse_linear = std::sqrt(sum_linear / counted);
    e.rmse_tonemapped = std::sqrt(sum_tonemapped / counted);
  }
  return e;
}

double rms(const Image& image) {
  double s = 0.0;
  for (float v : image.pixels) s += static_cast<double>(v) * v;
  return image.size() ? std::sqrt(s / image.size()) : 0.0;
}

TemporalStats::TemporalStats(int width, int height)
    : width_(width),
      height_(height),
      mean_(static_cast<std::size_t>(width) * height, 0.0),
      m2_(static_cast<std::size_t>(width) * height, 0.0) {}

void TemporalStats::add(const Image& frame) {
  if (frame.width != width_ || frame.height != height_) throw std::invalid_argument("TemporalStats: frame size mismatch");
  ++frames_;
  const double n = frames_;
  for (std::size_t i = 0; i < mean_.size(); ++i) {
    const double x = frame.pixels[i];
    const double delta = x - mean_[i];
    mean_[i] += delta / n;
    m2_[i] += delta * (x - mean_[i]);
  }
}

double TemporalStats::stddev(std::size_t i) const {
  if (frames_ == 0) return 0.0;
  return std::sqrt(std::max(0.0, m2_[i] / frames_));
}

double mean_temporal_stddev(const TemporalStats& stats) {
  if (stats.size() == 0) return 0.0;
  double s = 0.0;
  for (std::size_t i = 0; i < stats.size(); ++i) s += stats.stddev(i);
  return s / stats.size();
}

double flicker(const TemporalStats& image, const TemporalStats& reference) {
  if (image.size() != reference.size()) throw std::invalid_argument("flicker: size mismatch");
  if (image.size() == 0) return 0.0;
  double s = 0.0;
  for (std::size_t i = 0; i < image.size(); ++i) s += image.stddev(i) - reference.stddev(i);
  return s / image.size();
}

namespace {

void check_same_size(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height) throw std::invalid_argument("temporal difference error: frame size mismatch");
}

}  // namespace

void TemporalDifference::add_pair(const Image& previous, const Image& current, const Image& reference_previous,
                                  const Image& reference_current) {
  check_same_size(previous, current);
  check_same_size(previous, reference_previous);
  check_same_size(previous, reference_current);
  for (std::size_t i = 0; i < current.size(); ++i) {
    const double d_image = static_cast<double>(current.pixels[i]) - previous.pixels[i];
    const double d_reference = static_cast<double>(reference_current.pixels[i]) - reference_previous.pixels[i];
    const double excess = std::fabs(d_image) - std::fabs(d_reference);
    sum_tde_ += std::fabs(d_image - d_reference);
    sum_excess_ += std::max(0.0, excess);
    sum_lost_ += std::max(0.0, -excess);
  }
  samples_ += current.size();
  ++pairs_;
}

TemporalError TemporalDifference::mean() const {
  if (samples_ == 0) return {};
  const double n = static_cast<double>(samples_);
  return {sum_tde_ / n, sum_excess_ / n, sum_lost_ / n};
}

TemporalError temporal_difference_error(std::span<const Image> frames, std::span<const Image> reference) {
  if (frames.size() != reference.size()) throw std::invalid_argument("temporal difference error: frame count mismatch");
  TemporalDifference accumulated;
  for (std::size_t t = 1; t < frames.size(); ++t) accumulated.add_pair(frames[t - 1], frames[t], reference[t - 1], reference[t]);
  return accumulated.mean();
}

}  // namespace saagen::measure
