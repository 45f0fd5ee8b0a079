// The TAA resolve (see taa.hpp).
#include "saagen/measure/taa.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace saagen::measure {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The current filter's support half-width per axis (px): 3 sigma of the default 0.25 px^2, the
// ground truth's truncation (sampling.hpp), and the reach of a 3 x 3 neighbourhood's jittered
// samples.
constexpr double kCurrentFilterReach = 1.5;

// Catmull-Rom weights of the four taps around a sample at fraction t in [0, 1) past tap 1
// (Catmull & Rom 1974; the cubic with tension 0.5 that Karis 2014 samples the history with).
std::array<double, 4> catmull_rom_weights(double t) {
  return {t * (-0.5 + t * (1.0 - 0.5 * t)), 1.0 + t * t * (-2.5 + 1.5 * t), t * (0.5 + t * (2.0 - 1.5 * t)), t * t * (-0.5 + 0.5 * t)};
}

bool inside_film(Vec2 p, int width, int height) { return p.x >= 0.0 && p.y >= 0.0 && p.x <= width && p.y <= height; }

}  // namespace

std::string_view history_filter_name(HistoryFilter filter) { return filter == HistoryFilter::catmull_rom ? "catmull-rom" : "bilinear"; }

void check_taa_options(const TaaOptions& options) {
  if (options.sequence_length < 1 || options.sequence_length > 256)
    throw std::invalid_argument("TAA sequence length " + std::to_string(options.sequence_length) + ": must be in [1, 256]");
  if (!(options.blend > 0.0 && options.blend <= 1.0))
    throw std::invalid_argument("TAA blend " + std::to_string(options.blend) + ": must be in (0, 1]");
  if (!(options.clip_gamma > 0.0)) throw std::invalid_argument("TAA clip gamma " + std::to_string(options.clip_gamma) + ": must be > 0");
  if (!(options.current_filter_variance >= 0.0) || std::isinf(options.current_filter_variance))
    throw std::invalid_argument("TAA current filter variance " + std::to_string(options.current_filter_variance) + ": must be >= 0");
}

double radical_inverse(int index, int base) {
  double result = 0.0, digit_weight = 1.0 / base;
  for (int i = index; i > 0; i /= base) {
    result += (i % base) * digit_weight;
    digit_weight /= base;
  }
  return result;
}

Vec2 taa_jitter(int frame, int sequence_length) {
  if (frame < 0 || sequence_length < 1) throw std::invalid_argument("taa_jitter: frame must be >= 0 and the sequence length >= 1");
  const int index = frame % sequence_length + 1;
  return {radical_inverse(index, 2) - 0.5, radical_inverse(index, 3) - 0.5};
}

std::vector<Vec2> reproject_history(const GBuffer& gbuffer, const Scene& current, const Scene& previous) {
  const int w = gbuffer.width, h = gbuffer.height;
  const Vec2 jitter = current.camera().jitter;
  Camera previous_camera = previous.camera();
  previous_camera.jitter = {};
  std::vector<Vec2> positions(gbuffer.pixels.size());
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const PixelFields& f = gbuffer.at(x, y);
      Vec2& out = positions[static_cast<std::size_t>(y) * w + x];
      if (!f.hit) {
        out = {x + 0.5, y + 0.5};
        continue;
      }
      // The rigid motion taken back: object space of this frame, then the previous frame's world.
      const Vec3 object_point = current.object_to_world().inverse_point(f.position);
      const Vec3 previous_point = previous.object_to_world().apply_point(object_point);
      const std::optional<Vec2> film = previous_camera.project(previous_point, w, h);
      out = film ? *film - jitter : Vec2{kNaN, kNaN};
      if (!inside_film(out, w, h)) out = {kNaN, kNaN};
    }
  }
  return positions;
}

TaaResolve::TaaResolve(int width, int height, const TaaOptions& options)
    : options_(options), width_(width), height_(height), history_(width, height), output_(width, height) {
  check_taa_options(options);
  if (width <= 0 || height <= 0) throw std::invalid_argument("TaaResolve: bad image size");
}

double TaaResolve::to_space(double radiance) const {
  if (!options_.luma_weighting) return radiance;
  return tonemap(radiance);
}

double TaaResolve::from_space(double value) const {
  if (!options_.luma_weighting) return value;
  value = std::clamp(value, 0.0, 1.0 - 1e-12);
  return value / (1.0 - value);
}

// The Gaussian-weighted mean of the 3 x 3 neighbourhood's samples at their jittered positions
// (x' + 0.5 + jitter), centred on pixel (x, y)'s centre.
double TaaResolve::current_at(const Image& space, Vec2 jitter, int x, int y) const {
  if (options_.current_filter_variance == 0.0) return space.at(x, y);
  const double inv_two_variance = 0.5 / options_.current_filter_variance;
  double sum = 0.0, weights = 0.0;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const int sx = x + dx, sy = y + dy;
      if (sx < 0 || sy < 0 || sx >= width_ || sy >= height_) continue;
      const double ox = dx + jitter.x, oy = dy + jitter.y;
      if (std::abs(ox) > kCurrentFilterReach || std::abs(oy) > kCurrentFilterReach) continue;
      const double weight = std::exp(-(ox * ox + oy * oy) * inv_two_variance);
      sum += weight * space.at(sx, sy);
      weights += weight;
    }
  }
  return weights > 0.0 ? sum / weights : space.at(x, y);
}

// The history at a film position, Catmull-Rom (clamped to its 16 taps' range, which removes
// the cubic's overshoot) or bilinear, the taps clamped to the image's edge.
double TaaResolve::history_at(Vec2 position) const {
  const double u = position.x - 0.5, v = position.y - 0.5;
  const int ix = static_cast<int>(std::floor(u)), iy = static_cast<int>(std::floor(v));
  const double tx = u - ix, ty = v - iy;
  auto tap = [&](int x, int y) { return static_cast<double>(history_.at(std::clamp(x, 0, width_ - 1), std::clamp(y, 0, height_ - 1))); };
  if (options_.history_filter == HistoryFilter::bilinear) {
    return (1.0 - ty) * ((1.0 - tx) * tap(ix, iy) + tx * tap(ix + 1, iy)) + ty * ((1.0 - tx) * tap(ix, iy + 1) + tx * tap(ix + 1, iy + 1));
  }
  const std::array<double, 4> wx = catmull_rom_weights(tx), wy = catmull_rom_weights(ty);
  double sum = 0.0, lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 4; ++i) {
      const double value = tap(ix - 1 + i, iy - 1 + j);
      sum += wx[i] * wy[j] * value;
      lowest = std::min(lowest, value);
      highest = std::max(highest, value);
    }
  }
  return std::clamp(sum, lowest, highest);
}

const Image& TaaResolve::resolve(const Image& samples, Vec2 jitter, const std::vector<Vec2>& history_positions) {
  if (samples.width != width_ || samples.height != height_) throw std::invalid_argument("TaaResolve: frame size differs from the history");
  if (has_history_ && history_positions.size() != samples.size())
    throw std::invalid_argument("TaaResolve: one history position per pixel expected");
  Image space(width_, height_);
  for (std::size_t i = 0; i < samples.size(); ++i) space.pixels[i] = static_cast<float>(to_space(samples.pixels[i]));
  Image next(width_, height_);
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const double current = current_at(space, jitter, x, y);
      double value = current;
      const Vec2 position = has_history_ ? history_positions[static_cast<std::size_t>(y) * width_ + x] : Vec2{kNaN, kNaN};
      if (!std::isnan(position.x)) {
        // Variance clipping (Salvi 2016) against the 3 x 3 current samples.
        double m1 = 0.0, m2 = 0.0;
        int n = 0;
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const int sx = x + dx, sy = y + dy;
            if (sx < 0 || sy < 0 || sx >= width_ || sy >= height_) continue;
            const double s = space.at(sx, sy);
            m1 += s;
            m2 += s * s;
            ++n;
          }
        }
        const double mean = m1 / n, sigma = std::sqrt(std::max(0.0, m2 / n - mean * mean));
        double history = history_at(position);
        if (!std::isinf(options_.clip_gamma))
          history = std::clamp(history, mean - options_.clip_gamma * sigma, mean + options_.clip_gamma * sigma);
        value = history + options_.blend * (current - history);
      }
      next.at(x, y) = static_cast<float>(value);
      output_.at(x, y) = static_cast<float>(from_space(value));
    }
  }
  history_ = std::move(next);
  has_history_ = true;
  return output_;
}

}  // namespace saagen::measure
