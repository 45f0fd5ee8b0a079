// ColorVideoVDP (see video_vdp.hpp for the steps and their sources).
//
// Layout: planar double images. A clip's frames go through the display model once (a luminance
// plane per frame), then, frame by frame, the four temporal channels (each times its colour
// channel's DKL factor), their Gaussian pyramids and contrast bands. The reference clip's bands, sensitivities and
// masked-contrast inputs are kept per frame (VideoVdpReference::State); a comparison computes the
// test clip's bands and pools the masked differences frame by frame.
#include "saagen/measure/video_vdp.hpp"

#include "video_vdp_tables.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace saagen::measure {
namespace {

namespace data = video_vdp_data;

constexpr double kPi = 3.14159265358979323846;
// Channels in the model's order: sustained achromatic, red-green, yellow-violet (omega = 0 Hz),
// transient achromatic (5 Hz).
constexpr int kChannels = 4;

// ---- Planes ----------------------------------------------------------------------------------

struct Plane {
  int width = 0, height = 0;
  std::vector<double> v;
  Plane() = default;
  Plane(int w, int h, double fill = 0.0) : width(w), height(h), v(static_cast<std::size_t>(w) * h, fill) {}
  double& at(int x, int y) { return v[static_cast<std::size_t>(y) * width + x]; }
  double at(int x, int y) const { return v[static_cast<std::size_t>(y) * width + x]; }
  double* row(int y) { return v.data() + static_cast<std::size_t>(y) * width; }
  const double* row(int y) const { return v.data() + static_cast<std::size_t>(y) * width; }
  std::size_t size() const { return v.size(); }
};

using Channels = std::array<Plane, kChannels>;

// The reference implementation's power with an offset (video_vdp.hpp, step 8): differentiable at
// 0, and what the parameters were calibrated with: pow(x, e) = (x + 1e-5)^e - 1e-5^e. The
// exponents 2, 4, 1/2 and 1/4 (the pooling's) by products and square roots.
constexpr double kPowOffset = 1e-5;
class OffsetPow {
 public:
  explicit OffsetPow(double e) : e_(e), offset_(std::pow(kPowOffset, e)) {}
  double operator()(double x) const {
    const double y = x + kPowOffset;
    if (e_ == 2.0) return y * y - offset_;
    if (e_ == 4.0) return (y * y) * (y * y) - offset_;
    if (e_ == 0.5) return std::sqrt(y) - offset_;
    if (e_ == 0.25) return std::sqrt(std::sqrt(y)) - offset_;
    return static_cast<double>(std::pow(static_cast<float>(y), static_cast<float>(e_))) - offset_;
  }

 private:
  double e_, offset_;
};

// ---- Step 1: display model -------------------------------------------------------------------

// The sRGB decoding (IEC 61966-2-1), the display's EOTF (color_spaces.json: "EOTF": "sRGB").
double srgb_decode(double v) { return v > 0.04045 ? std::pow((v + 0.055) / 1.055, 2.4) : v / 12.92; }

struct Photometry {
  double peak = 0.0;       // L_peak
  double black = 0.0;      // L_black = L_peak / contrast
  double reflected = 0.0;  // L_refl = k_refl E_ambient / pi
};

Photometry photometry(const VideoVdpDisplay& display) {
  return {display.peak_luminance, display.peak_luminance / display.contrast, display.reflectivity * display.ambient_illuminance / kPi};
}

// L = (L_peak - L_black) EOTF(V) + L_black + L_refl, V clamped to [0, 1] (NaN: 0).
double emitted_luminance(float encoded, const Photometry& p) {
  const double v = std::isfinite(encoded) ? std::clamp(static_cast<double>(encoded), 0.0, 1.0) : 0.0;
  return (p.peak - p.black) * srgb_decode(v) + p.black + p.reflected;
}

// ---- Step 2: colour --------------------------------------------------------------------------

// CIE XYZ -> LMS cone responses (CIE 2006 cone fundamentals) and LMS -> DKL with a D65 white: the
// constants of ColorVideoVDP 0.5.4's display model (pycvvdp/display_model.py, XYZ_to_LMS2006 and
// LMS2006_to_DKLd65), numbers as published.
constexpr double kXyzToLms2006[3][3] = {{0.187596268556126, 0.585168649077728, -0.026384263306304},
                                        {-0.133397430663221, 0.405505777260049, 0.034502127690364},
                                        {0.000244379021663, -0.000542995890619, 0.019406849066323}};
constexpr double kLms2006ToDkl[3][3] = {{1.0, 1.0, 0.0}, {1.0, -2.311130179947035, 0.0}, {-1.0, -1.0, 50.977571328718781}};

// DKL (achromatic, red-green, yellow-violet) of linear RGB (1, 1, 1): a grey pixel of luminance L
// has L times these (the colour path of step 2 applied to R = G = B).
std::array<double, 3> grey_to_dkl() {
  double xyz[3], lms[3];
  std::array<double, 3> dkl{};
  for (int i = 0; i < 3; ++i) xyz[i] = data::kRgbToXyz[i][0] + data::kRgbToXyz[i][1] + data::kRgbToXyz[i][2];
  for (int i = 0; i < 3; ++i) lms[i] = kXyzToLms2006[i][0] * xyz[0] + kXyzToLms2006[i][1] * xyz[1] + kXyzToLms2006[i][2] * xyz[2];
  for (int i = 0; i < 3; ++i) dkl[i] = kLms2006ToDkl[i][0] * lms[0] + kLms2006ToDkl[i][1] * lms[1] + kLms2006ToDkl[i][2] * lms[2];
  return dkl;
}

// A clip's frames as emitted luminance planes (step 1). Their DKL channels (step 2) are these
// times grey_to_dkl(): the transform of a grey pixel is one factor per channel, applied by
// channels_of() after the temporal filter (linear, so the order does not matter).
std::vector<Plane> luminance_frames(const GreyClip& clip, const Photometry& p) {
  const std::size_t pixels = static_cast<std::size_t>(clip.width) * clip.height;
  std::vector<Plane> frames(static_cast<std::size_t>(clip.frames));
  for (int t = 0; t < clip.frames; ++t) {
    frames[t] = Plane(clip.width, clip.height);
    for (std::size_t i = 0; i < pixels; ++i) frames[t].v[i] = emitted_luminance(clip.pixels[static_cast<std::size_t>(t) * pixels + i], p);
  }
  return frames;
}

// ---- Step 3: temporal channels ---------------------------------------------------------------

// The taps of the four channels' filters at `fps` (step 3): N = 2 ceil(fps / 8) + 1 taps; the
// frequency response at (N + 1) / 2 frequencies spaced evenly over [0, fps / 2]; the taps its
// real inverse DFT of length N (odd: no Nyquist sample), centred.
std::array<std::vector<double>, kChannels> temporal_filters(double fps) {
  const data::VideoVdpParameters& P = data::kParameters;
  const int n = static_cast<int>(std::ceil(0.25 * fps / 2.0)) * 2 + 1;
  const int m = n / 2 + 1;
  std::array<std::vector<double>, kChannels> filters;
  for (int c = 0; c < kChannels; ++c) {
    std::vector<double> response(static_cast<std::size_t>(m));
    for (int k = 0; k < m; ++k) {
      const double omega = (fps / 2.0) * k / (m - 1);
      if (c < 3) {
        // Sustained: exp(-omega^beta / sigma)  [beta_tf, sigma_tf]
        response[k] = std::exp(-std::pow(omega, P.beta_tf[c]) / P.sigma_tf[c]);
      } else {
        // Transient, a band-pass peaking at 5 Hz: exp(-(omega^beta - 5^beta)^2 / sigma)
        const double d = std::pow(omega, P.beta_tf[3]) - std::pow(5.0, P.beta_tf[3]);
        response[k] = std::exp(-d * d / P.sigma_tf[3]);
      }
    }
    // r[j] = (R_0 + 2 sum_k R_k cos(2 pi k j / N)) / N, symmetric in j; tap i holds lag i - (N - 1) / 2.
    std::vector<double> taps(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      const int j = std::abs(i - (n - 1) / 2);
      double sum = response[0];
      for (int k = 1; k < m; ++k) sum += 2.0 * response[k] * std::cos(2.0 * kPi * k * j / n);
      taps[i] = sum / n;
    }
    filters[c] = std::move(taps);
  }
  return filters;
}

// Frame t of the four temporal channels: dkl_c sum_k F_c[k] L[max(t - k, 0)], L the luminance
// frames, dkl_c the DKL factor of the colour channel that feeds channel c (the achromatic one
// for the sustained and transient achromatic channels).
Channels temporal_channels(const std::vector<Plane>& frames, int t, const std::array<std::vector<double>, kChannels>& filters) {
  const std::array<double, 3> dkl = grey_to_dkl();
  Channels out;
  for (int c = 0; c < kChannels; ++c) {
    Plane& plane = out[c];
    plane = Plane(frames[0].width, frames[0].height);
    const std::vector<double>& taps = filters[c];
    for (std::size_t k = 0; k < taps.size(); ++k) {
      const Plane& x = frames[std::max(t - static_cast<int>(k), 0)];
      const double w = taps[k] * dkl[c == 3 ? 0 : c];
      for (std::size_t i = 0; i < plane.size(); ++i) plane.v[i] += w * x.v[i];
    }
  }
  return out;
}

// ---- Step 4: pyramid -------------------------------------------------------------------------

// The 5-tap Gaussian kernel [0.25 - a/2, 0.25, a, 0.25, 0.25 - a/2], a = 0.4.
constexpr double kPyramidA = 0.4;
constexpr double kKernel[5] = {0.25 - kPyramidA / 2.0, 0.25, kPyramidA, 0.25, 0.25 - kPyramidA / 2.0};

// Symmetric border: index -1 -> 0, -2 -> 1, n -> n - 1, n + 1 -> n - 2 (repeated for tiny n).
int symmetric_index(int i, int n) {
  while (i < 0 || i >= n) i = i < 0 ? -i - 1 : 2 * n - i - 1;
  return i;
}

// Filter with the kernel and keep every other sample: n -> ceil(n / 2), along x then y.
Plane reduce(const Plane& in) {
  const int w = (in.width + 1) / 2, h = (in.height + 1) / 2;
  Plane rows(w, in.height);
  std::vector<double> line(static_cast<std::size_t>(in.width) + 4);  // a row, two samples of border each side
  for (int y = 0; y < in.height; ++y) {
    for (int i = -2; i < in.width + 2; ++i) line[i + 2] = in.at(symmetric_index(i, in.width), y);
    for (int x = 0; x < w; ++x) {
      double sum = 0.0;
      for (int k = 0; k < 5; ++k) sum += kKernel[k] * line[2 * x + k];
      rows.at(x, y) = sum;
    }
    // The reference implementation (0.5.4) borders the last column as if the width had the
    // parity of the height: for an even width and an odd height its last sample reads
    // K3 x[n-1] + K4 x[n-2] past the edge instead of K4 x[n-1], for an odd width and an even
    // height K4 x[n-1] instead of K3 x[n-1] + K4 x[n-2]. Square clips are unaffected; kept so
    // that the others match it too (it moves a JOD by up to 0.1 on a 46 x 24 clip).
    const int n = in.width;
    const double* x = line.data() + 2;
    if (n % 2 == 0 && in.height % 2 == 1) rows.at(w - 1, y) += (kKernel[3] - kKernel[4]) * x[n - 1] + kKernel[4] * x[n - 2];
    if (n % 2 == 1 && in.height % 2 == 0) rows.at(w - 1, y) += (kKernel[4] - kKernel[3]) * x[n - 1] - kKernel[4] * x[n - 2];
  }
  Plane out(w, h);
  for (int y = 0; y < h; ++y) {
    double* o = out.row(y);
    for (int k = 0; k < 5; ++k) {
      const double* r = rows.row(symmetric_index(2 * y + k - 2, in.height));
      for (int x = 0; x < w; ++x) o[x] += kKernel[k] * r[x];
    }
  }
  return out;
}

// The expansion of a line of ceil(size / 2) samples to `size`: sample i at position 2 i, zeros
// between, the first sample repeated at position -2 and the last at the first even position
// past the end; filtered with twice the kernel. The input sample at position j, or -1 for a zero.
int expand_source(int j, int size, int inputs) {
  if (j == -2) return 0;
  if (j >= 0 && j < size) return j % 2 == 0 ? j / 2 : -1;
  if (j == (size % 2 == 0 ? size : size + 1)) return inputs - 1;
  return -1;
}

// The expansion of a pyramid level to width x height (the next finer level's size): along y, then x.
Plane expand(const Plane& in, int width, int height) {
  Plane cols(in.width, height);
  for (int y = 0; y < height; ++y) {
    double* o = cols.row(y);
    for (int k = 0; k < 5; ++k) {
      const int source = expand_source(y + k - 2, height, in.height);
      if (source < 0) continue;
      const double* r = in.row(source);
      for (int x = 0; x < in.width; ++x) o[x] += 2.0 * kKernel[k] * r[x];
    }
  }
  Plane out(width, height);
  std::vector<double> line(static_cast<std::size_t>(width) + 4);  // the upsampled row, position j at j + 2
  for (int y = 0; y < height; ++y) {
    for (int j = -2; j < width + 2; ++j) {
      const int source = expand_source(j, width, in.width);
      line[j + 2] = source < 0 ? 0.0 : cols.at(source, y);
    }
    double* o = out.row(y);
    for (int k = 0; k < 5; ++k) {
      const double weight = 2.0 * kKernel[k];
      const double* in = line.data() + k;
      for (int x = 0; x < width; ++x) o[x] += weight * in[x];
    }
  }
  return out;
}

// The pyramid's height (step 4): the bands are height + 1 (the last the base band).
int pyramid_height(int width, int height, double ppd) {
  const int smaller = std::min(width, height);
  int log2_floor = 0;
  while ((2 << log2_floor) <= smaller) ++log2_floor;
  const int max_levels = log2_floor - 1;
  // The first band whose frequency is at most 0.2 cpd among rho_0 = ppd / 2, rho_b = 0.3228
  // 2^-(b-1) ppd / 2 (b = 1 .. 14); max_levels when none is.
  int max_band = max_levels;
  for (int b = 0; b < 15; ++b) {
    const double rho = (b == 0 ? 1.0 : 0.3228 * std::ldexp(1.0, -(b - 1))) * ppd / 2.0;
    if (rho <= 0.2) {
      max_band = b;
      break;
    }
  }
  return std::max(0, std::min(max_band + 1, max_levels));
}

// The frequency of band b of a pyramid of `height` (step 4), the base band's 0.1 cpd.
double band_frequency(int b, int height, double ppd) {
  if (b == height) return 0.1;
  return (b == 0 ? 1.0 : 0.3228 * std::ldexp(1.0, -(b - 1))) * ppd / 2.0;
}

// ---- Step 5: contrast ------------------------------------------------------------------------

constexpr double kMinAdaptation = 0.01;  // cd/m^2, the least adaptation luminance
constexpr double kMaxContrast = 1000.0;

struct Band {
  Channels contrast;
  Plane adaptation;  // the local adaptation luminance (base band: one value, 1 x 1)
};

// The contrast bands of one frame of the first `count` temporal channels (step 5).
std::vector<Band> contrast_bands(const Channels& channels, int count, int pyramid_height) {
  std::vector<Channels> gaussian(static_cast<std::size_t>(pyramid_height) + 1);
  gaussian[0] = channels;
  for (int level = 1; level <= pyramid_height; ++level)
    for (int c = 0; c < count; ++c) gaussian[level][c] = reduce(gaussian[level - 1][c]);
  std::vector<Band> bands(gaussian.size());
  for (int b = 0; b <= pyramid_height; ++b) {
    Band& band = bands[b];
    const Channels& level = gaussian[b];
    if (b == pyramid_height) {
      // The base band: the level itself over the mean of its clamped achromatic luminance.
      double sum = 0.0;
      for (double l : level[0].v) sum += std::max(l, kMinAdaptation);
      const double adaptation = sum / static_cast<double>(level[0].size());
      band.adaptation = Plane(1, 1, adaptation);
      for (int c = 0; c < count; ++c) {
        band.contrast[c] = level[c];
        for (double& v : band.contrast[c].v) v = std::min(v / adaptation, kMaxContrast);
      }
      continue;
    }
    // Bands between the first and the base band are doubled (the reference's band scaling).
    const double scale = b == 0 ? 1.0 : 2.0;
    Channels expanded;
    for (int c = 0; c < count; ++c) expanded[c] = expand(gaussian[b + 1][c], level[c].width, level[c].height);
    band.adaptation = expanded[0];
    for (double& l : band.adaptation.v) l = std::max(l, kMinAdaptation);
    for (int c = 0; c < count; ++c) {
      band.contrast[c] = Plane(level[c].width, level[c].height);
      for (std::size_t i = 0; i < level[c].size(); ++i)
        band.contrast[c].v[i] = std::min((level[c].v[i] - expanded[c].v[i]) / band.adaptation.v[i], kMaxContrast) * scale;
    }
  }
  return bands;
}

// ---- Step 6: sensitivity ---------------------------------------------------------------------

// log10 S of one channel at one spatial frequency, at each of the table's luminances: linear in
// log10 rho between the table's two frequencies around it (the end segments extended beyond).
std::array<double, data::kCsfLuminances> csf_at_frequency(int channel, double rho) {
  const double x = std::log10(rho);
  int i = 0;  // the segment [i, i + 1]: the last whose left end is below x, or the first
  while (i + 2 < data::kCsfFrequencies && std::log10(data::kCsfRho[i + 1]) < x) ++i;
  const double x0 = std::log10(data::kCsfRho[i]), x1 = std::log10(data::kCsfRho[i + 1]);
  std::array<double, data::kCsfLuminances> out{};
  for (int l = 0; l < data::kCsfLuminances; ++l) {
    const double y0 = data::kCsfLogSensitivity[channel][l][i], y1 = data::kCsfLogSensitivity[channel][l][i + 1];
    out[l] = y0 + (y1 - y0) / (x1 - x0) * (x - x0);
  }
  return out;
}

// The sensitivity of one channel at one frequency for any adaptation luminance: the table's
// luminances are evenly spaced in log10; between them linear in log10 L, clamped at the ends.
class Sensitivity {
 public:
  Sensitivity(int channel, double rho)
      : log_s_(csf_at_frequency(channel, rho)), correction_(std::pow(10.0, data::kParameters.sensitivity_correction / 20.0)) {}
  double operator()(double adaptation) const {
    const double first = std::log10(data::kCsfLuminance[0]), last = std::log10(data::kCsfLuminance[data::kCsfLuminances - 1]);
    const double position =
        std::clamp((std::log10(adaptation) - first) / (last - first) * (data::kCsfLuminances - 1), 0.0, double(data::kCsfLuminances - 1));
    const int i = static_cast<int>(position);
    const double f = position - i;
    const int j = std::min(i + 1, data::kCsfLuminances - 1);
    return std::pow(10.0, log_s_[i] * (1.0 - f) + log_s_[j] * f) * correction_;
  }

 private:
  std::array<double, data::kCsfLuminances> log_s_;
  double correction_;  // 10^(sensitivity_correction / 20)  [sensitivity_correction, in dB]
};

// ---- Step 7: masking, its channel gains and phase-uncertainty blur ---------------------------

constexpr double kChannelGain[kChannels] = {1.0, 1.45, 1.0, 1.0};  // the masking model's channel gains

// The phase-uncertainty blur (step 7): a normalised Gaussian of standard deviation pu_dilate,
// 4 pu_dilate + 1 taps, mirrored borders (-1 -> 1, n -> n - 2); only on planes larger than
// 2 pu_dilate in both directions.
class PhaseUncertainty {
 public:
  PhaseUncertainty() {
    const double sigma = data::kParameters.pu_dilate;
    const int taps = static_cast<int>(sigma * 4.0) + 1;
    radius_ = taps / 2;
    pad_ = static_cast<int>(sigma * 2.0);
    kernel_.resize(static_cast<std::size_t>(taps));
    double sum = 0.0;
    for (int k = 0; k < taps; ++k) {
      const double x = k - (taps - 1) * 0.5;
      kernel_[k] = std::exp(-0.5 * (x / sigma) * (x / sigma));
      sum += kernel_[k];
    }
    for (double& k : kernel_) k /= sum;
  }
  bool applies(const Plane& p) const { return pad_ > 0 && p.width > pad_ && p.height > pad_; }
  // In place, `scratch` a buffer of the plane's size.
  void blur(Plane& p, Plane& scratch) const {
    const int w = p.width, h = p.height, r = radius_;
    // Along x: each row mirrored into a padded line, then the kernel.
    std::vector<double> line(static_cast<std::size_t>(w + 2 * r));
    for (int y = 0; y < h; ++y) {
      for (int i = -r; i < w + r; ++i) line[i + r] = p.at(mirror(i, w), y);
      double* out = scratch.row(y);
      std::fill(out, out + w, 0.0);
      for (int k = 0; k <= 2 * r; ++k) {
        const double weight = kernel_[k];
        const double* in = line.data() + k;
        for (int x = 0; x < w; ++x) out[x] += weight * in[x];
      }
    }
    // Along y: whole rows, the mirrored row indices looked up once per output row.
    for (int y = 0; y < h; ++y) {
      double* out = p.row(y);
      std::fill(out, out + w, 0.0);
      for (int k = 0; k <= 2 * r; ++k) {
        const double* in = scratch.row(mirror(y + k - r, h));
        const double weight = kernel_[k];
        for (int x = 0; x < w; ++x) out[x] += weight * in[x];
      }
    }
  }

 private:
  static int mirror(int i, int n) {
    while (i < 0 || i >= n) i = i < 0 ? -i : 2 * n - i - 2;
    return i;
  }
  std::vector<double> kernel_;
  int radius_ = 0, pad_ = 0;
};

// ---- Step 8: pooling ------------------------------------------------------------------------

class Pooling {
 public:
  explicit Pooling(int channels)
      : channels_(channels),
        pixel_power_(data::kParameters.beta),
        pixel_root_(1.0 / data::kParameters.beta),
        band_power_(data::kParameters.beta_sch),
        band_root_(1.0 / data::kParameters.beta_sch),
        channel_power_(data::kParameters.beta_tch),
        channel_root_(1.0 / data::kParameters.beta_tch),
        frame_power_(data::kParameters.beta_t),
        frame_root_(1.0 / data::kParameters.beta_t) {}

  // The p-mean of a band's differences over its pixels: pow(sum pow(D, beta) / n, 1 / beta).  [beta]
  double pixels(const std::vector<double>& d) const {
    double sum = 0.0;
    for (double v : d) sum += pixel_power_(v);
    return pixel_root_(sum / static_cast<double>(d.size()));
  }

  // The base band, not masked: D = S |T - R| per channel, pooled over the pixels.
  std::array<double, kChannels> base_band(const Channels& test, const Channels& reference, const Channels& sensitivity) const {
    std::array<double, kChannels> q{};
    for (int c = 0; c < channels_; ++c) {
      std::vector<double> d(test[c].size());
      for (std::size_t i = 0; i < d.size(); ++i) d[i] = std::abs(test[c].v[i] - reference[c].v[i]) * sensitivity[c].v[i];
      q[c] = pixels(d);
    }
    return q;
  }

  // One frame's value from q[channel][band]: the p-norm over the bands of q times the channel's
  // weight (and on the base band the baseband_weight), then over the channels.
  // [beta_sch, beta_tch, ch_chrom_w, ch_trans_w, baseband_weight]
  double frame(const std::array<std::vector<double>, kChannels>& q) const {
    const data::VideoVdpParameters& P = data::kParameters;
    const double channel_weight[kChannels] = {1.0, P.ch_chrom_w, P.ch_chrom_w, P.ch_trans_w};
    double channel_sum = 0.0;
    for (int c = 0; c < channels_; ++c) {
      double band_sum = 0.0;
      for (std::size_t b = 0; b < q[c].size(); ++b) {
        const double w = channel_weight[c] * (b + 1 == q[c].size() ? P.baseband_weight[c] : 1.0);
        band_sum += band_power_(q[c][b] * w);
      }
      channel_sum += channel_power_(band_root_(band_sum));
    }
    return channel_root_(channel_sum);
  }

  // The p-mean over the frames.  [beta_t]
  double frames(const std::vector<double>& frame_q) const {
    double sum = 0.0;
    for (double v : frame_q) sum += frame_power_(v);
    return frame_root_(sum / static_cast<double>(frame_q.size()));
  }

 private:
  int channels_;
  OffsetPow pixel_power_, pixel_root_, band_power_, band_root_, channel_power_, channel_root_, frame_power_, frame_root_;
};

// ---- Step 7: masking (the bands below the base band) -----------------------------------------

class Masking {
 public:
  Masking()
      : d_max_(std::pow(10.0, data::kParameters.d_max)),
        mask_scale_(std::pow(10.0, data::kParameters.mask_c)),
        difference_power_(data::kParameters.mask_p),
        masker_power_{OffsetPow(data::kParameters.mask_q[0]), OffsetPow(data::kParameters.mask_q[1]),
                      OffsetPow(data::kParameters.mask_q[2]), OffsetPow(data::kParameters.mask_q[3])} {
    for (int k = 0; k < kChannels; ++k)
      for (int c = 0; c < kChannels; ++c) cross_[k][c] = std::exp2(data::kParameters.xcm_weights[4 * k + c]);
  }

  // One band's pooled differences per channel: `test` the test's contrast (overwritten with T' = g S T),
  // `reference` the reference's R' = g S R, `sensitivity` S.
  std::array<double, kChannels> band(Channels& test, const Channels& reference, const Channels& sensitivity, int channels,
                                     const PhaseUncertainty& phase_uncertainty, const Pooling& pooling) const {
    const std::size_t pixels = test[0].size();
    // T' = g S T (in place); the mutual masker min(|T'|, |R'|), blurred, scaled by 10^mask_c, to
    // its channel's power q_k.  [mask_c, mask_q]
    Channels& test_p = test;
    Channels masker;
    Plane scratch(test[0].width, test[0].height);
    for (int c = 0; c < channels; ++c) {
      masker[c] = Plane(test[c].width, test[c].height);
      for (std::size_t i = 0; i < pixels; ++i) {
        test_p[c].v[i] *= kChannelGain[c] * sensitivity[c].v[i];
        masker[c].v[i] = std::min(std::abs(test_p[c].v[i]), std::abs(reference[c].v[i]));
      }
      if (phase_uncertainty.applies(masker[c])) phase_uncertainty.blur(masker[c], scratch);
      for (double& m : masker[c].v) m = masker_power_[c](std::abs(m * mask_scale_));
    }
    // An image has no transient channel: a masker of zeros in its place adds nothing.
    for (int c = channels; c < kChannels; ++c) masker[c] = Plane(test[0].width, test[0].height);
    std::array<double, kChannels> q{};
    std::vector<double> d(pixels);
    for (int c = 0; c < channels; ++c) {
      // pow(|T' - R'|, p) / (1 + M), soft-clamped to D_max, with the cross-channel masker M = sum
      // over the maskers k of 2^xcm[4k + c] M_k.  [mask_p, xcm_weights, d_max]
      for (std::size_t i = 0; i < pixels; ++i) d[i] = difference_power_(std::abs(test_p[c].v[i] - reference[c].v[i]));
      const double w0 = cross_[0][c], w1 = cross_[1][c], w2 = cross_[2][c], w3 = cross_[3][c];
      const double *m0 = masker[0].v.data(), *m1 = masker[1].v.data(), *m2 = masker[2].v.data(), *m3 = masker[3].v.data();
      for (std::size_t i = 0; i < pixels; ++i) {
        const double u = d[i] / (1.0 + (w0 * m0[i] + w1 * m1[i] + w2 * m2[i] + w3 * m3[i]));
        d[i] = d_max_ * u / (d_max_ + u);
      }
      q[c] = pooling.pixels(d);
    }
    return q;
  }

 private:
  double d_max_, mask_scale_;
  OffsetPow difference_power_;
  std::array<OffsetPow, kChannels> masker_power_;
  double cross_[kChannels][kChannels];  // [masker][masked]
};

// ---- Step 9: JOD ------------------------------------------------------------------------------

// Q -> JOD (step 9).
double jod_of(double q) {
  const data::VideoVdpParameters& P = data::kParameters;
  constexpr double q_t = 0.1;
  if (q <= q_t) return 10.0 - P.jod_a * std::pow(q_t, P.jod_exp - 1.0) * q;
  return 10.0 - P.jod_a * std::pow(q, P.jod_exp);
}

void check_clip(const GreyClip& clip, const char* what) {
  if (clip.width <= 0 || clip.height <= 0 || clip.frames <= 0)
    throw std::invalid_argument(std::string("ColorVideoVDP: the ") + what + " clip is empty");
  if (clip.pixels.size() != static_cast<std::size_t>(clip.width) * clip.height * clip.frames)
    throw std::invalid_argument(
        std::string("ColorVideoVDP: the ") + what + " clip holds " + std::to_string(clip.pixels.size()) +
        " values, not width x height x frames = " + std::to_string(static_cast<std::size_t>(clip.width) * clip.height * clip.frames));
}

}  // namespace

VideoVdpDisplay video_vdp_standard_fhd() {
  const data::DisplayData& d = data::kStandardFhd;
  return {"standard_fhd",
          d.resolution_width,
          d.resolution_height,
          d.viewing_distance_meters,
          d.diagonal_size_inches,
          d.max_luminance,
          d.contrast,
          d.e_ambient,
          d.k_refl};
}

double video_vdp_pixels_per_degree(const VideoVdpDisplay& display) {
  const double aspect = static_cast<double>(display.resolution_width) / display.resolution_height;
  const double height_m = std::sqrt(std::pow(display.diagonal_inches * 0.0254, 2.0) / (1.0 + aspect * aspect));
  const double width_m = aspect * height_m;
  const double pixel_degrees = 2.0 * std::atan(0.5 * width_m / display.resolution_width / display.viewing_distance_m) * 180.0 / kPi;
  return 1.0 / pixel_degrees;
}

struct VideoVdpReference::State {
  int width = 0, height = 0, frames = 0;
  int pyramid_height = 0;
  int channels = kChannels;  // 3 for an image (no transient channel)
  Photometry display;
  std::array<std::vector<double>, kChannels> filters;
  // Per frame, per band: the reference's masked-contrast input R' = g S R (the base band: R) and
  // its sensitivity S, per channel.
  struct FrameBand {
    Channels reference;
    Channels sensitivity;
  };
  std::vector<std::vector<FrameBand>> bands;  // [frame][band]
  PhaseUncertainty phase_uncertainty;

  Channels channels_of(const std::vector<Plane>& luminance, int t) const {
    if (frames > 1) return temporal_channels(luminance, t, filters);
    // An image: the three colour channels unfiltered.
    const std::array<double, 3> dkl = grey_to_dkl();
    Channels out;
    for (int c = 0; c < 3; ++c) {
      out[c] = luminance[t];
      for (double& v : out[c].v) v *= dkl[c];
    }
    return out;
  }
};

VideoVdpReference::VideoVdpReference(const GreyClip& reference, const VideoVdpDisplay& display, double frames_per_second) {
  check_clip(reference, "reference");
  if (!(display.resolution_width > 0 && display.resolution_height > 0 && display.viewing_distance_m > 0.0 &&
        display.diagonal_inches > 0.0 && display.peak_luminance > 0.0 && display.contrast > 0.0 && display.ambient_illuminance >= 0.0 &&
        display.reflectivity >= 0.0))
    throw std::invalid_argument("ColorVideoVDP: the display '" + display.name + "' needs a positive size, distance, peak and contrast");
  if (reference.frames > 1 && !(frames_per_second > 0.0 && std::isfinite(frames_per_second)))
    throw std::invalid_argument("ColorVideoVDP: a clip of " + std::to_string(reference.frames) + " frames needs frames per second > 0");
  auto state = std::make_shared<State>();
  state->width = reference.width;
  state->height = reference.height;
  state->frames = reference.frames;
  state->display = photometry(display);
  const double ppd = video_vdp_pixels_per_degree(display);
  state->pyramid_height = pyramid_height(reference.width, reference.height, ppd);
  state->channels = reference.frames > 1 ? kChannels : 3;
  if (reference.frames > 1) state->filters = temporal_filters(frames_per_second);

  // The sensitivity functions of every band and channel (step 6).
  std::vector<std::vector<Sensitivity>> csf;
  for (int b = 0; b <= state->pyramid_height; ++b) {
    csf.emplace_back();
    // The transient channel reads the 5 Hz table, the others the 0 Hz ones.
    for (int c = 0; c < state->channels; ++c) csf.back().emplace_back(c, band_frequency(b, state->pyramid_height, ppd));
  }
  const std::vector<Plane> luminance = luminance_frames(reference, state->display);
  state->bands.resize(static_cast<std::size_t>(reference.frames));
  for (int t = 0; t < reference.frames; ++t) {
    const std::vector<Band> bands = contrast_bands(state->channels_of(luminance, t), state->channels, state->pyramid_height);
    std::vector<State::FrameBand>& out = state->bands[t];
    out.resize(bands.size());
    for (int b = 0; b <= state->pyramid_height; ++b) {
      const bool base = b == state->pyramid_height;
      const Band& band = bands[b];
      for (int c = 0; c < state->channels; ++c) {
        Plane& s = out[b].sensitivity[c];
        s = Plane(band.contrast[c].width, band.contrast[c].height);
        for (std::size_t i = 0; i < s.size(); ++i) s.v[i] = csf[b][c](band.adaptation.v[base ? 0 : i]);
        Plane& r = out[b].reference[c];
        r = band.contrast[c];
        if (!base)
          for (std::size_t i = 0; i < r.size(); ++i) r.v[i] *= kChannelGain[c] * s.v[i];
      }
    }
  }
  state_ = std::move(state);
}

int VideoVdpReference::bands() const { return state_->pyramid_height + 1; }

VideoVdpResult VideoVdpReference::compare(const GreyClip& test) const {
  const State& s = *state_;
  check_clip(test, "test");
  if (test.width != s.width || test.height != s.height || test.frames != s.frames)
    throw std::invalid_argument("ColorVideoVDP: the test clip is " + std::to_string(test.width) + " x " + std::to_string(test.height) +
                                " x " + std::to_string(test.frames) + ", the reference " + std::to_string(s.width) + " x " +
                                std::to_string(s.height) + " x " + std::to_string(s.frames));
  const Masking masking;
  const Pooling pooling(s.channels);
  const std::vector<Plane> luminance = luminance_frames(test, s.display);
  std::vector<double> frame_q(static_cast<std::size_t>(s.frames));
  for (int t = 0; t < s.frames; ++t) {
    std::vector<Band> bands = contrast_bands(s.channels_of(luminance, t), s.channels, s.pyramid_height);
    // q[c][b]: the p-mean over the pixels of the band's differences (step 8).
    std::array<std::vector<double>, kChannels> q;
    for (int b = 0; b <= s.pyramid_height; ++b) {
      const State::FrameBand& ref = s.bands[t][b];
      const std::array<double, kChannels> band_q =
          b == s.pyramid_height ? pooling.base_band(bands[b].contrast, ref.reference, ref.sensitivity)
                                : masking.band(bands[b].contrast, ref.reference, ref.sensitivity, s.channels, s.phase_uncertainty, pooling);
      for (int c = 0; c < s.channels; ++c) q[c].push_back(band_q[c]);
    }
    frame_q[t] = pooling.frame(q);
  }
  VideoVdpResult result;
  result.quality = s.frames == 1 ? frame_q[0] * data::kParameters.image_int : pooling.frames(frame_q);
  result.jod = jod_of(result.quality);
  for (const double q : frame_q) result.frame_jod.push_back(jod_of(q));
  return result;
}

VideoVdpResult video_vdp(const GreyClip& test, const GreyClip& reference, const VideoVdpDisplay& display, double frames_per_second) {
  return VideoVdpReference(reference, display, frames_per_second).compare(test);
}

}  // namespace saagen::measure
