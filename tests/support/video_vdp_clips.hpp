// Deterministic synthetic grey clips for the ColorVideoVDP model (tests/measure/test_video_vdp.cpp), in
// the 8-bit display values `saagen bench --frames` writes, so that the reference implementation
// can be run on exactly them: `bench/video_vdp_frames --write-synthetic DIR` writes them as a
// --frames folder (DIR/index.json and one PNG per clip, frames stacked), which
// scripts/video_metric.py reads.
//
// The scene: a horizontal ramp of linear radiance with a faint vertical ripple, and a Gaussian
// highlight (standard deviation 2.5 pixels, peak 6) that moves 0.7 px right and 0.35 px down per
// frame; display values as the bench's: Reinhard x / (1 + x), the sRGB encoding, rounded to 8 bits.
// The variants, each from those frames: the reference itself, delayed by one frame, frozen at its
// first frame, blurred by a 1 px Gaussian (of the linear frames, borders clamped), with uniform
// noise (two seeds), and without the highlight.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace saagen::test {

enum class SyntheticVariant { reference, delayed, frozen, blurred, noise_a, noise_b, no_highlight };

inline const char* synthetic_variant_name(SyntheticVariant v) {
  switch (v) {
    case SyntheticVariant::reference:
      return "reference";
    case SyntheticVariant::delayed:
      return "delayed";
    case SyntheticVariant::frozen:
      return "frozen";
    case SyntheticVariant::blurred:
      return "blurred";
    case SyntheticVariant::noise_a:
      return "noise-a";
    case SyntheticVariant::noise_b:
      return "noise-b";
    case SyntheticVariant::no_highlight:
      return "no-highlight";
  }
  return "?";
}

inline constexpr SyntheticVariant kSyntheticVariants[] = {
    SyntheticVariant::reference, SyntheticVariant::delayed, SyntheticVariant::frozen,      SyntheticVariant::blurred,
    SyntheticVariant::noise_a,   SyntheticVariant::noise_b, SyntheticVariant::no_highlight};

// The clips' sizes: the bench's 64 x 64 x 16 and 32 x 32 x 16, a clip shorter than the 9-tap
// temporal filter (32 x 32 x 5), a small one with three pyramid bands (8 x 8 x 16), an image
// (64 x 64 x 1), odd sizes at every pyramid level but the last (27 x 27 x 12: 27, 14, 7, 4), a
// wide one (48 x 32 x 8) and two where a level's width and height differ in parity (46 x 24 x 8:
// 23 x 12; 24 x 46 x 8: 12 x 23), where the reference implementation's pyramid borders the last
// column by the height's parity.
struct SyntheticSize {
  const char* name;
  int width, height, frames;
};
inline constexpr SyntheticSize kSyntheticSizes[] = {{"s64", 64, 64, 16}, {"s32", 32, 32, 16},   {"short", 32, 32, 5},
                                                    {"tiny", 8, 8, 16},  {"image", 64, 64, 1},  {"odd", 27, 27, 12},
                                                    {"wide", 48, 32, 8}, {"uneven", 46, 24, 8}, {"uneven-tall", 24, 46, 8}};

// splitmix64 of (seed, t, x, y): a uniform value in [0, 1), the same on every platform.
inline double synthetic_uniform(std::uint64_t seed, int t, int x, int y) {
  std::uint64_t z = seed * 0x9e3779b97f4a7c15ULL + (static_cast<std::uint64_t>(t) << 40) + (static_cast<std::uint64_t>(y) << 20) +
                    static_cast<std::uint64_t>(x);
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

// Linear radiance of frame t at pixel (x, y) of a width x height clip.
inline double synthetic_radiance(int width, int height, int t, int x, int y, bool highlight) {
  const double u = (x + 0.5) / width, v = (y + 0.5) / height;
  double r = 0.05 + 0.6 * u + 0.03 * std::sin(2.0 * 3.14159265358979323846 * 3.0 * v);
  if (highlight) {
    const double cx = 0.3 * width + 0.7 * t, cy = 0.35 * height + 0.35 * t, s = 2.5;
    const double dx = x + 0.5 - cx, dy = y + 0.5 - cy;
    r += 6.0 * std::exp(-(dx * dx + dy * dy) / (2.0 * s * s));
  }
  return r;
}

// The bench's display value of a radiance, as a byte: round(255 sRGB(x / (1 + x))).
inline std::uint8_t synthetic_display_byte(double radiance) {
  const double x = std::max(radiance, 0.0);
  const double l = x / (1.0 + x);
  const double e = l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
  return static_cast<std::uint8_t>(std::lround(std::clamp(e, 0.0, 1.0) * 255.0));
}

// The frames of one variant: frames * height * width bytes, frame-major then row-major.
inline std::vector<std::uint8_t> synthetic_clip(const SyntheticSize& size, SyntheticVariant variant) {
  const int w = size.width, h = size.height;
  std::vector<std::uint8_t> out(static_cast<std::size_t>(w) * h * size.frames);
  std::vector<double> frame(static_cast<std::size_t>(w) * h), blurred(frame.size());
  for (int t = 0; t < size.frames; ++t) {
    const int source = variant == SyntheticVariant::frozen ? 0 : variant == SyntheticVariant::delayed ? std::max(t - 1, 0) : t;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        frame[static_cast<std::size_t>(y) * w + x] = synthetic_radiance(w, h, source, x, y, variant != SyntheticVariant::no_highlight);
    if (variant == SyntheticVariant::blurred) {
      // A Gaussian of standard deviation 1 px, radius 3, normalised, borders clamped; x then y.
      double k[7], sum = 0.0;
      for (int i = -3; i <= 3; ++i) sum += k[i + 3] = std::exp(-0.5 * i * i);
      for (double& v : k) v /= sum;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          double s = 0.0;
          for (int i = -3; i <= 3; ++i) s += k[i + 3] * frame[static_cast<std::size_t>(y) * w + std::clamp(x + i, 0, w - 1)];
          blurred[static_cast<std::size_t>(y) * w + x] = s;
        }
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          double s = 0.0;
          for (int i = -3; i <= 3; ++i) s += k[i + 3] * blurred[static_cast<std::size_t>(std::clamp(y + i, 0, h - 1)) * w + x];
          frame[static_cast<std::size_t>(y) * w + x] = s;
        }
    }
    if (variant == SyntheticVariant::noise_a || variant == SyntheticVariant::noise_b) {
      const std::uint64_t seed = variant == SyntheticVariant::noise_a ? 1 : 2;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) frame[static_cast<std::size_t>(y) * w + x] += 0.2 * (synthetic_uniform(seed, t, x, y) - 0.5);
    }
    for (std::size_t i = 0; i < frame.size(); ++i) out[static_cast<std::size_t>(t) * frame.size() + i] = synthetic_display_byte(frame[i]);
  }
  return out;
}

}  // namespace saagen::test
