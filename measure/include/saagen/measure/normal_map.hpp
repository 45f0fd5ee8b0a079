// saagen ground-truth renderer: tangent-space normal maps with a MIP chain, sampled as a GPU does.
//
// A normal map is what engines ship: level 0 holds unit tangent-space normals (z > 0), and every
// coarser level is the 2x2 box reduction of the level above. Per texel, three things are kept:
//
//   normal        what a MIP generator writes and a shader samples: the renormalised mean of the
//                 four child texels' stored normals (the usual "average and renormalise" chain);
//   mean_normal   the unnormalised mean of the level-0 unit normals under the texel. Its length
//                 |mean_normal| <= 1 is what Toksvig's prefiltering reads (Toksvig 2005, Eq. 2:
//                 a shorter mean normal means a wider spread of normals);
//   slope_mean,   the first and second moments of the level-0 normals' slopes s = -n.xy / n.z
//   slope_second  (LEAN mapping, Olano & Baker 2010, Sec. 3: E[s] and E[s s^T]); their
//                 covariance E[s s^T] - E[s] E[s]^T is the slope variance the texture adds to the
//                 NDF (Kaplanyan et al. 2016 Sec. 4, the texture-space half of SAA).
//
// Box reduction of means is exact for all three moments (the mean over 4 children, each the
// mean over its own 4^l level-0 texels). Sampling (texel, bilinear, trilinear, lod) is
// MipChain's (mip_chain.hpp): the Vulkan specification's rules.
#pragma once

#include "saagen/measure/mip_chain.hpp"
#include "saagen/reference/math.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace saagen::measure {

using ref::Sym2;
using ref::Vec2;
using ref::Vec3;

// One texel of one level (see the top of this file). Linear in every field, so that bilinear
// and trilinear filtering are plain weighted sums.
struct NormalTexel {
  Vec3 normal;        // stored (renormalised) normal: what a shader samples
  Vec3 mean_normal;   // unnormalised mean of the level-0 unit normals (Toksvig)
  Vec2 slope_mean;    // E[s], s = -n.xy / n.z (LEAN)
  Sym2 slope_second;  // E[s s^T] (LEAN)
};

NormalTexel operator*(double w, const NormalTexel& t);
NormalTexel operator+(const NormalTexel& a, const NormalTexel& b);

// The slope of a unit normal with z > 0: s = -(n.x, n.y) / n.z.
Vec2 normal_slope(Vec3 n);
// The covariance E[s s^T] - E[s] E[s]^T of a filtered texel (clamped to PSD up to rounding).
Sym2 slope_covariance(const NormalTexel& t);

class NormalMap : public MipChain<NormalTexel> {
 public:
  NormalMap() = default;
  // width and height: powers of two >= 1; normals: width * height unit vectors with z > 0,
  // row-major, row 0 at v = 0. Throws std::invalid_argument otherwise.
  NormalMap(int width, int height, const std::vector<Vec3>& normals);

  // Every number that defines the texture (for the ground-truth cache keys): size and a
  // 64-bit hash of level 0.
  std::string describe() const;

 private:
  NormalMap(std::uint64_t hash, int width, int height, const std::vector<Vec3>& normals);  // after the checks
  std::uint64_t hash_ = 0;
};

// A tangent-space normal map of the height field h(x, y) given by `height` on the unit square
// (periodic in both axes, sampled at texel centres): n = normalize(-dh/du, -dh/dv, 1), the
// derivatives taken analytically by the callback (dh/du, dh/dv in height units per texture
// unit). Pixel (x, y) samples uv ((x + 0.5) / size, (y + 0.5) / size).
template <class GradientFn>
std::vector<Vec3> normals_from_gradient(int size, GradientFn gradient) {
  std::vector<Vec3> normals(static_cast<std::size_t>(size) * size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const Vec2 g = gradient(Vec2{(x + 0.5) / size, (y + 0.5) / size});
      normals[static_cast<std::size_t>(y) * size + x] = ref::normalize(Vec3{-g.x, -g.y, 1.0});
    }
  return normals;
}

}  // namespace saagen::measure
