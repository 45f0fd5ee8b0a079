// saagen ground-truth renderer: single-channel float images and the error metrics.
//
// Images hold linear specular radiance (one channel: the specular term is grey), row-major,
// row 0 at the top (pixel (x, y) at pixels[y * width + x]), ready for a report writer (PNG,
// false-colour difference maps).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace saagen::measure {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<float> pixels;

  Image() = default;
  Image(int w, int h, float fill = 0.0f) : width(w), height(h), pixels(static_cast<std::size_t>(w) * h, fill) {}

  float& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
  float at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * width + x]; }
  std::size_t size() const { return pixels.size(); }
};

// Reinhard's global operator x / (1 + x) (Reinhard et al. 2002, Eq. 3 with L_white -> inf):
// maps radiance [0, inf) to [0, 1) monotonically, compressing the very bright 1-spp outliers
// of low-roughness highlights so that the tonemapped RMSE measures what a viewer sees rather
// than a handful of pixels. Negative values (never produced) are clamped to 0.
double tonemap(double x);
// tonemap() of every pixel: display-linear values, the input of ldr_flip_mean_grey.
Image tonemapped(const Image& radiance);

// The sRGB encoding (IEC 61966-2-1 OETF: 12.92 v for v <= 0.0031308, else 1.055 v^(1/2.4) -
// 0.055) of a display-linear value, clamped to [0, 1] first (NaN -> 0): the signal LDR-FLIP
// takes and a PNG stores.
double srgb_encode(double display_linear);
// Its inverse (IEC 61966-2-1 EOTF: v / 12.92 for v <= 0.04045, else ((v + 0.055) / 1.055)^2.4),
// clamped to [0, 1] first: the display-linear value of an encoded one (e.g. a clip's byte / 255).
double srgb_decode(double encoded);

// What a viewer's display receives for a radiance: srgb_encode(tonemap(radiance)), in [0, 1].
// The values LDR-FLIP compares and the temporal difference error is measured in.
double display_value(double radiance);
Image display_image(const Image& radiance);
// A display image (display_image()) as the 8-bit values a display receives, round(255 v), v
// clamped to [0, 1] and NaN as 0: the clips the video metric reads and `saagen bench --frames`
// writes.
std::vector<std::uint8_t> display_bytes(const Image& display);

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

// Temporal difference error (TDE) of an animation I against the ground-truth animation R: the
// pixel-level form of the tLP of Chu et al. 2020 ("Learning temporal coherence via
// self-supervision for GAN-based video generation", TecoGAN, Sec. 4), which compares the
// frame-to-frame changes of a result with those of the reference instead of the frames alone:
//   tde            = mean over pixels and consecutive frame pairs of |dI - dR|,
//                    dI = I_t - I_{t-1}, dR = R_t - R_{t-1};
//   excess_flicker = mean of max(0, |dI| - |dR|)  (changes the reference does not make: aliasing);
//   lost_motion    = mean of max(0, |dR| - |dI|)  (changes the reference makes that are missing:
//                    a highlight blurred or clamped away).
// A temporal standard deviation ratio rewards lost highlights (a blurred animation has a small
// std); TDE penalises both. excess_flicker + lost_motion = mean ||dI| - |dR|| <= tde; the rest
// is change of the wrong sign (|dI - dR| > ||dI| - |dR|| only where dI and dR have opposite
// signs). Meant for display values (display_image()), single-channel images of one size.
struct TemporalError {
  double tde = 0.0;
  double excess_flicker = 0.0;
  double lost_motion = 0.0;
};

// Accumulates TemporalError over frame pairs, one pair at a time (an animation need not be kept
// in memory): add_pair(I_{t-1}, I_t, R_{t-1}, R_t) for t = 1 .. frames - 1.
class TemporalDifference {
 public:
  void add_pair(const Image& previous, const Image& current, const Image& reference_previous, const Image& reference_current);
  int pairs() const { return pairs_; }
  // Means over every pixel of every pair added; zeros before the first pair.
  TemporalError mean() const;

 private:
  int pairs_ = 0;
  std::size_t samples_ = 0;
  double sum_tde_ = 0.0;
  double sum_excess_ = 0.0;
  double sum_lost_ = 0.0;
};

// TemporalError of a whole animation (frames and reference of the same length, >= 2 frames for
// a non-zero result).
TemporalError temporal_difference_error(std::span<const Image> frames, std::span<const Image> reference);

}  // namespace saagen::measure
