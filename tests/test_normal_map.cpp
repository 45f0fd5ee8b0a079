// Normal maps with a MIP chain (reference/render/normal_map.hpp): the box reduction's moments,
// Vulkan's bilinear / trilinear filtering and implicit LOD, checked on hand-made maps.
#include "saagen/reference/render/normal_map.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace saagen::render;
namespace ref = saagen::ref;

namespace {

// A 4 x 4 map whose columns alternate between two normals tilted by +-theta about the y axis.
NormalMap two_normal_map(double theta) {
  std::vector<Vec3> normals;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const double s = (x % 2 == 0 ? 1.0 : -1.0) * std::sin(theta);
      normals.push_back({s, 0.0, std::cos(theta)});
    }
  return NormalMap(4, 4, normals);
}

}  // namespace

TEST(NormalMap, ChainGoesDownToOneTexel) {
  const NormalMap map = two_normal_map(0.3);
  ASSERT_EQ(map.levels(), 3);
  EXPECT_EQ(map.width(2), 1);
  EXPECT_EQ(map.height(2), 1);
}

TEST(NormalMap, RejectsNonPowerOfTwoAndNonUnitNormals) {
  EXPECT_THROW(NormalMap(3, 4, std::vector<Vec3>(12, Vec3{0, 0, 1})), std::invalid_argument);
  EXPECT_THROW(NormalMap(2, 2, std::vector<Vec3>(4, Vec3{0, 0, 2})), std::invalid_argument);
  EXPECT_THROW(NormalMap(2, 2, std::vector<Vec3>(4, Vec3{0, 0, -1})), std::invalid_argument);
}

// Level 1 averages one +theta and one -theta column per texel: the mean normal is
// (0, 0, cos theta), of length cos theta (Toksvig's shortening), the stored normal is renormalised
// to (0, 0, 1), and the slope variance is tan^2 theta along x, 0 along y (exact moments).
TEST(NormalMap, BoxReductionKeepsExactMoments) {
  const double theta = 0.3;
  const NormalMap map = two_normal_map(theta);
  const NormalTexel& t = map.texel(1, 0, 0);
  EXPECT_NEAR(t.mean_normal.x, 0.0, 1e-15);
  EXPECT_NEAR(t.mean_normal.z, std::cos(theta), 1e-15);
  EXPECT_NEAR(t.normal.z, 1.0, 1e-15);
  const Sym2 c = slope_covariance(t);
  EXPECT_NEAR(c.xx, std::tan(theta) * std::tan(theta), 1e-15);
  EXPECT_NEAR(c.xy, 0.0, 1e-15);
  EXPECT_NEAR(c.yy, 0.0, 1e-15);
}

TEST(NormalMap, BilinearAtTexelCentreIsTheTexelAndHalfwayIsTheMean) {
  const NormalMap map = two_normal_map(0.3);
  const NormalTexel centre = map.bilinear(0, {0.5 / 4, 0.5 / 4});
  EXPECT_NEAR(centre.normal.x, std::sin(0.3), 1e-15);
  const NormalTexel half = map.bilinear(0, {1.0 / 4, 0.5 / 4});
  EXPECT_NEAR(half.normal.x, 0.0, 1e-15);
  // Repeat addressing: u and u + 1 give the same sample.
  const NormalTexel wrapped = map.bilinear(0, {1.0 + 0.5 / 4, -1.0 + 0.5 / 4});
  EXPECT_NEAR(wrapped.normal.x, centre.normal.x, 1e-15);
}

TEST(NormalMap, TrilinearInterpolatesBetweenLevelsAndClampsLod) {
  const NormalMap map = two_normal_map(0.3);
  const Vec2 uv{0.5 / 4, 0.5 / 4};
  const double c0 = slope_covariance(map.trilinear(uv, 0.0)).xx;
  const double c1 = slope_covariance(map.bilinear(1, uv)).xx;
  EXPECT_NEAR(slope_covariance(map.trilinear(uv, -3.0)).xx, c0, 1e-15);
  EXPECT_NEAR(map.trilinear(uv, 0.5).slope_second.xx, 0.5 * map.bilinear(0, uv).slope_second.xx + 0.5 * map.bilinear(1, uv).slope_second.xx,
              1e-15);
  EXPECT_NEAR(slope_covariance(map.trilinear(uv, 99.0)).xx, slope_covariance(map.texel(2, 0, 0)).xx, 1e-15);
  EXPECT_GT(c1, c0);
}

// Vulkan's implicit LOD: rho = the longer texel-space derivative, lambda = log2(rho).
TEST(NormalMap, LodIsLog2OfTheLongerTexelSpaceDerivative) {
  const NormalMap map = two_normal_map(0.3);                      // 4 x 4 texels
  EXPECT_NEAR(map.lod({1.0, 0.0}, {0.0, 0.25}), 2.0, 1e-15);      // 4 texels per pixel
  EXPECT_NEAR(map.lod({0.125, 0.0}, {0.0, 0.125}), -1.0, 1e-15);  // half a texel per pixel
  EXPECT_NEAR(map.lod({0.3, 0.4}, {0.0, 0.0}), std::log2(2.0), 1e-15);
}
