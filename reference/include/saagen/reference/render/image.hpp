// saagen ground-truth renderer: single-channel float images and the error metrics.
//
// Images hold linear specular radiance (one channel: the specular term is grey), row-major,
// row 0 at the top (pixel (x, y) at pixels[y * width + x]), ready for a report writer (PNG,
// false-colour difference maps).
#pragma once

#include <cstddef>
#include <vector>

namespace saagen::render {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<float> pixels;

    Image() = default;
    Image(int w, int h, float fill = 0.0f)
        : width(w), height(h), pixels(static_cast<std::size_t>(w) * h, fill) {}

    float& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
    float at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * width + x]; }
    std::size_t size() const { return pixels.size(); }
};

// Reinhard's global operator x / (1 + x) (Reinhard et al. 2002, Eq. 3 with L_white -> inf):
// maps radiance [0, inf) to [0, 1) monotonically, compressing the very bright 1-spp outliers
// of low-roughness highlights so that the tonemapped RMSE measures what a viewer sees rather
// than a handful of pixels. Negative values (never produced) are clamped to 0.
double tonemap(double x);

// Error metrics of an image against a reference of the same size, over all pixels (background
// pixels included; both images are 0 there unless a silhouette pixel is partially covered).
struct ImageError {
    double rmse_linear = 0.0;      // sqrt(mean((a - r)^2)) on linear radiance
    double rmse_tonemapped = 0.0;  // the same after tonemap() on both
    double max_error = 0.0;        // max |a - r| on linear radiance
    std::size_t non_finite = 0;    // pixels of `image` that are NaN or infinite (excluded above)
};

ImageError compare_images(const Image& image, const Image& reference);

// Root mean square of an image's values (for relative error bounds).
double rms(const Image& image);

// Per-pixel running mean and variance over the frames of an animation (Welford's update, in
// double precision). Identical frames give a variance of exactly 0.
class TemporalStats {
public:
    TemporalStats() = default;
    TemporalStats(int width, int height);

    void add(const Image& frame);
    int frames() const { return frames_; }
    // Population standard deviation (divide by the number of frames) of pixel i.
    double stddev(std::size_t i) const;
    std::size_t size() const { return mean_.size(); }

private:
    int width_ = 0;
    int height_ = 0;
    int frames_ = 0;
    std::vector<double> mean_;
    std::vector<double> m2_;
};

// Temporal flicker of a 1-spp animation against the ground-truth animation: the per-pixel
// temporal standard deviation of the 1-spp frames minus that of the ground-truth frames,
// averaged over all pixels. Positive: the variant flickers more than the converged image
// (aliasing); negative: it is temporally smoother (overfiltering).
double flicker(const TemporalStats& image, const TemporalStats& reference);

// Mean over pixels of the temporal standard deviation (the two terms of flicker()).
double mean_temporal_stddev(const TemporalStats& stats);

}  // namespace saagen::render
