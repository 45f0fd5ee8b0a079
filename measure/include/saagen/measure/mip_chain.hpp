// saagen ground-truth renderer: a texture with a MIP chain, sampled as a GPU does, over any texel
// type that is linear (w * t and a + b), so that box reduction, bilinear and trilinear filtering
// are plain weighted sums: NormalMap's moments (normal_map.hpp) and ScalarMap's values
// (scalar_map.hpp) are two such textures.
//
// Level 0 holds the texels; every coarser level is the 2x2 box mean of the level above (a
// non-square map keeps halving its longer side alone), passed through the texture's `finish`
// (what its MIP generator stores: NormalMap renormalises its normal). Sampling follows the Vulkan
// specification's rules (Vulkan 1.3, "Texel Filtering" and "Scale Factor Operation, LOD Operation
// and Image Level(s) Selection"): repeat addressing, texel centres at (i + 0.5) / size, bilinear
// weights from u * size - 0.5; implicit LOD lambda = log2(rho) with rho = max(|d(uv size)/dx|,
// |d(uv size)/dy|) (the isotropic choice the spec allows), linear interpolation between the two
// levels around lambda (LINEAR_MIPMAP_LINEAR, "trilinear"), lambda clamped to [0, levels - 1].
#pragma once

#include "saagen/reference/math.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace saagen::measure {

using ref::Vec2;

// A texture's level-0 checks and cache-key hash.
namespace texture {

inline bool is_power_of_two(int v) { return v > 0 && (v & (v - 1)) == 0; }

// Throws std::invalid_argument "<texture>: ..." unless width and height are powers of two and
// `count` texels (`texels`: what they are called) fill width x height.
inline void check_level0(const std::string& texture, int width, int height, std::size_t count, const std::string& texels) {
  if (!is_power_of_two(width) || !is_power_of_two(height))
    throw std::invalid_argument(texture + ": width and height must be powers of two");
  if (count != static_cast<std::size_t>(width) * height) throw std::invalid_argument(texture + ": width * height " + texels + " expected");
}

// FNV-1a over a double's bytes, continuing `hash` (start with kFnvOffset): the textures' cache keys.
inline constexpr std::uint64_t kFnvOffset = 0xcbf29ce484222325ULL;
inline std::uint64_t fnv1a(std::uint64_t hash, double value) {
  unsigned char bytes[sizeof value];
  std::memcpy(bytes, &value, sizeof value);
  for (const unsigned char b : bytes) {
    hash ^= b;
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

}  // namespace texture

template <class Texel>
class MipChain {
 public:
  MipChain() = default;
  // width and height: powers of two >= 1 (the texture checks them); texels: width * height,
  // row-major, row 0 at v = 0. `finish(Texel&)` is applied to every texel of a coarser level.
  template <class Finish>
  MipChain(int width, int height, std::vector<Texel> texels, Finish finish) {
    levels_.push_back({width, height, std::move(texels)});
    while (levels_.back().width > 1 || levels_.back().height > 1) levels_.push_back(box_reduced(levels_.back(), finish));
  }

  int levels() const { return static_cast<int>(levels_.size()); }
  int width(int level) const { return levels_[level].width; }
  int height(int level) const { return levels_[level].height; }
  bool empty() const { return levels_.empty(); }

  // Texel (x, y) of a level, repeat addressing (any integer coordinates).
  const Texel& texel(int level, int x, int y) const {
    const Level& l = levels_[level];
    return l.texels[static_cast<std::size_t>(wrap(y, l.height)) * l.width + wrap(x, l.width)];
  }

  // Bilinear filtering of one level at uv (repeat addressing).
  Texel bilinear(int level, Vec2 uv) const {
    const Level& l = levels_[level];
    const double fx = uv.x * l.width - 0.5, fy = uv.y * l.height - 0.5;
    const double x0 = std::floor(fx), y0 = std::floor(fy);
    const double ax = fx - x0, ay = fy - y0;
    const int ix = static_cast<int>(x0), iy = static_cast<int>(y0);
    return ((1.0 - ax) * (1.0 - ay)) * texel(level, ix, iy) + (ax * (1.0 - ay)) * texel(level, ix + 1, iy) +
           ((1.0 - ax) * ay) * texel(level, ix, iy + 1) + (ax * ay) * texel(level, ix + 1, iy + 1);
  }

  // Linear interpolation between the bilinear samples of the levels around lod (clamped to
  // [0, levels - 1]): Vulkan's LINEAR_MIPMAP_LINEAR.
  Texel trilinear(Vec2 uv, double lod) const {
    const double top = static_cast<double>(levels() - 1);
    const double lambda = std::isnan(lod) ? 0.0 : ref::min(ref::max(lod, 0.0), top);
    const int d = static_cast<int>(std::floor(lambda));
    const double t = lambda - d;
    if (t == 0.0 || d + 1 > levels() - 1) return bilinear(d, uv);
    return (1.0 - t) * bilinear(d, uv) + t * bilinear(d + 1, uv);
  }

  // Implicit LOD from uv derivatives (isotropic: rho = the longer of the two texel-space
  // derivative vectors, lambda = log2(rho)); -inf for zero derivatives.
  double lod(Vec2 duv_dx, Vec2 duv_dy) const {
    const double w = levels_[0].width, h = levels_[0].height;
    const double rho_x = std::hypot(duv_dx.x * w, duv_dx.y * h);
    const double rho_y = std::hypot(duv_dy.x * w, duv_dy.y * h);
    return std::log2(ref::max(rho_x, rho_y));
  }

 private:
  struct Level {
    int width = 0;
    int height = 0;
    std::vector<Texel> texels;
  };

  static int wrap(int i, int size) {
    const int m = i % size;
    return m < 0 ? m + size : m;
  }

  template <class Finish>
  static Level box_reduced(const Level& fine, Finish finish) {
    Level coarse{std::max(1, fine.width / 2), std::max(1, fine.height / 2), {}};
    const int sx = fine.width / coarse.width, sy = fine.height / coarse.height;
    const double weight = 1.0 / (sx * sy);
    coarse.texels.resize(static_cast<std::size_t>(coarse.width) * coarse.height);
    for (int y = 0; y < coarse.height; ++y)
      for (int x = 0; x < coarse.width; ++x) {
        Texel sum{};
        for (int j = 0; j < sy; ++j)
          for (int i = 0; i < sx; ++i) sum = sum + fine.texels[static_cast<std::size_t>(y * sy + j) * fine.width + x * sx + i];
        Texel mean = weight * sum;
        finish(mean);
        coarse.texels[static_cast<std::size_t>(y) * coarse.width + x] = mean;
      }
    return coarse;
  }

  std::vector<Level> levels_;
};

}  // namespace saagen::measure
