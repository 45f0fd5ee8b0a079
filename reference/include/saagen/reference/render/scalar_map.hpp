// saagen ground-truth renderer: a one-channel texture with a MIP chain, sampled as a GPU does.
//
// What a glTF material's packed roughness becomes (the G channel of metallicRoughnessTexture,
// linear, in [0, 1]). Level 0 holds the texels; every coarser level is the 2x2 box mean of the
// level above (exact for a mean, as for NormalMap's moments). Sampling follows the same
// Vulkan rules as NormalMap (normal_map.hpp): repeat addressing, texel centres at
// (i + 0.5) / size, bilinear weights from u * size - 0.5, implicit LOD lambda = log2(rho) with
// rho the longer texel-space derivative vector, LINEAR_MIPMAP_LINEAR between the two levels
// around lambda clamped to [0, levels - 1].
#pragma once

#include "saagen/reference/math.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace saagen::render {

using ref::Vec2;

class ScalarMap {
 public:
  ScalarMap() = default;
  // width and height: powers of two >= 1; values: width * height finite numbers, row-major,
  // row 0 at v = 0. Throws std::invalid_argument otherwise.
  ScalarMap(int width, int height, std::vector<double> values);

  int levels() const { return static_cast<int>(levels_.size()); }
  int width(int level) const { return levels_[level].width; }
  int height(int level) const { return levels_[level].height; }

  // Texel (x, y) of a level, repeat addressing (any integer coordinates).
  double texel(int level, int x, int y) const;
  double bilinear(int level, Vec2 uv) const;
  double trilinear(Vec2 uv, double lod) const;
  // Implicit LOD from uv derivatives (isotropic), -inf for zero derivatives.
  double lod(Vec2 duv_dx, Vec2 duv_dy) const;
  // Size and a 64-bit hash of level 0 (cache keys).
  std::string describe() const;

 private:
  struct Level {
    int width = 0;
    int height = 0;
    std::vector<double> texels;
  };
  std::vector<Level> levels_;
  std::uint64_t hash_ = 0;
};

}  // namespace saagen::render
