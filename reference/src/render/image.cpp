// Images and error metrics (see image.hpp).
#include "saagen/reference/render/image.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace saagen::render {

double tonemap(double x) {
    if (!(x > 0.0)) return 0.0;
    if (std::isinf(x)) return 1.0;
    return x / (1.0 + x);
}

ImageError compare_images(const Image& image, const Image& reference) {
    if (image.width != reference.width || image.height != reference.height)
        throw std::invalid_argument("compare_images: size mismatch");
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
    if (frame.width != width_ || frame.height != height_)
        throw std::invalid_argument("TemporalStats: frame size mismatch");
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
    if (image.size() != reference.size())
        throw std::invalid_argument("flicker: size mismatch");
    if (image.size() == 0) return 0.0;
    double s = 0.0;
    for (std::size_t i = 0; i < image.size(); ++i) s += image.stddev(i) - reference.stddev(i);
    return s / image.size();
}

}  // namespace saagen::render
