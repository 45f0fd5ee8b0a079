// saagen ground-truth renderer: a one-channel texture with a MIP chain, sampled as a GPU does.
//
// What a glTF material's packed roughness becomes (the G channel of metallicRoughnessTexture,
// linear, in [0, 1]). Level 0 holds the texels; every coarser level is the 2x2 box mean of the
// level above (exact for a mean, as for NormalMap's moments). Sampling (texel, bilinear,
// trilinear, lod) is MipChain's (mip_chain.hpp): the Vulkan rules NormalMap follows too.
#pragma once

#include "saagen/measure/mip_chain.hpp"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace saagen::measure {

class ScalarMap : public MipChain<double> {
 public:
  ScalarMap() = default;
  // width and height: powers of two >= 1; values: width * height finite numbers, row-major,
  // row 0 at v = 0. Throws std::invalid_argument otherwise.
  ScalarMap(int width, int height, std::vector<double> values);

  // Size and a 64-bit hash of level 0 (cache keys).
  std::string describe() const;
  // The smallest and the largest texel of level 0 (what every level's box means lie within).
  std::pair<double, double> value_range() const;

 private:
  ScalarMap(std::uint64_t hash, int width, int height, std::vector<double>&& values);  // after the checks
  std::uint64_t hash_ = 0;
};

}  // namespace saagen::measure
