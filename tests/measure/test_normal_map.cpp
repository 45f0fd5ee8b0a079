// Normal maps with a MIP chain (measure/normal_map.hpp): the box reduction's moments,
// Vulkan's bilinear / trilinear filtering and implicit LOD, checked on hand-made maps.
#include "saagen/measure/normal_map.hpp"
#include "saagen/measure/renderer.hpp"
#include "saagen/measure/scene.hpp"
#include "saagen/measure/trade.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace saagen::measure;
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

// Why the prefiltered rows sample the map one level coarser (TradeConfig::prefilter_lod_bias,
// docs/PREFILTER.md "The LOD bias"). An 8 x 8 map whose columns repeat (+theta, +theta, -theta,
// -theta): a period of 4 texels, i.e. 2 pixels where a pixel spans 2 texels (implicit LOD 1), the
// pixel grid's Nyquist frequency. At LOD 1 every level-1 texel holds one tilt (L = 1: the bake sees
// no spread) and the sampled normal swings from +theta to -theta as the pattern slides by half a
// pixel: the grid cannot show the pattern, and a 1-spp shader aliases it. One level coarser each
// texel spans a whole period: the sampled normal stays flat at every offset and the spread is in
// the bake, 1 - L^2 = sin^2 theta = E[n_x^2] - E[n_x]^2 (the variance the normal no longer shows).
// Tolerance 1e-15: at most four double additions and multiplications of values <= 1 per field,
// each within half an ulp (1.1e-16).
TEST(NormalMap, OneLevelCoarserMovesTheNyquistBandFromTheNormalIntoTheBake) {
  const double theta = 0.35;  // 20 degrees, the content map's largest tilt (scene.hpp)
  std::vector<Vec3> normals;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) normals.push_back({(x % 4 < 2 ? 1.0 : -1.0) * std::sin(theta), 0.0, std::cos(theta)});
  const NormalMap map(8, 8, normals);
  for (int step = 0; step < 8; ++step) {
    const double offset = step / 8.0;  // the pattern's motion, in pixels of 2 texels
    for (int pixel = 0; pixel < 4; ++pixel) {
      const Vec2 uv{(2.0 * pixel + 1.0 + 2.0 * offset) / 8.0, 0.5 / 8.0};
      // Implicit LOD 1: bilinear between texels of opposite tilt, x = +-sin(theta) (1 - 2 |offset'|).
      const NormalTexel fine = map.trilinear(uv, 1.0);
      const double to_centre = offset <= 0.5 ? offset : 1.0 - offset;  // distance to the nearest texel centre, pixels
      const double sign = ((pixel + (offset > 0.5 ? 1 : 0)) % 2 == 0) ? 1.0 : -1.0;
      EXPECT_NEAR(fine.mean_normal.x, sign * std::sin(theta) * (1.0 - 2.0 * to_centre), 1e-15) << step << " " << pixel;
      // One level coarser: flat, with the whole spread in the mean normal's length.
      const NormalTexel coarse = map.trilinear(uv, 2.0);
      EXPECT_NEAR(coarse.mean_normal.x, 0.0, 1e-15) << step << " " << pixel;
      EXPECT_NEAR(coarse.normal.x, 0.0, 1e-15) << step << " " << pixel;
      EXPECT_NEAR(1.0 - ref::dot(coarse.mean_normal, coarse.mean_normal), std::sin(theta) * std::sin(theta), 1e-15);
    }
    // At the texel centres the unbiased sample is a single tilt: no spread for a bake to see.
    if (step == 0) {
      EXPECT_NEAR(ref::length(map.trilinear({1.0 / 8.0, 0.5 / 8.0}, 1.0).mean_normal), 1.0, 1e-15);
    }
  }
}

// The trade's prefiltered rows shade a G-buffer whose normal map is sampled prefilter_lod_bias
// levels coarser (1 by default): on nmap-sphere at 64 x 64 px every mapped pixel's LOD is the
// implicit one plus 1 and its texel is the map's trilinear sample there, so the shading normal and
// the bake's moments both move (the derivatives, the geometric frame and the hit do not).
TEST(NormalMap, TheGBufferSamplesTheMapAtTheBiasedLod) {
  EXPECT_EQ(TradeConfig{}.prefilter_lod_bias, 1.0);
  const Scene scene = make_scene(SceneId::nmap_sphere);
  const GBuffer plain = render_gbuffer(scene, 64, 64, 1);
  const GBuffer biased = render_gbuffer(scene, 64, 64, 1, 1.0);
  const auto map = content_normal_map();
  int mapped = 0, turned = 0;
  for (std::size_t i = 0; i < plain.pixels.size(); ++i) {
    const PixelFields& a = plain.pixels[i];
    const PixelFields& b = biased.pixels[i];
    ASSERT_EQ(a.hit, b.hit);
    if (!a.has_normal_map) continue;
    ++mapped;
    EXPECT_EQ(b.lod, a.lod + 1.0);
    EXPECT_EQ(b.duv_dx.x, a.duv_dx.x);
    EXPECT_EQ(b.geometric_normal.z, a.geometric_normal.z);
    const NormalTexel expected = map->trilinear(b.uv, a.lod + 1.0);
    EXPECT_EQ(b.texel.mean_normal.x, expected.mean_normal.x);
    EXPECT_EQ(b.texel.mean_normal.z, expected.mean_normal.z);
    turned += b.normal.x != a.normal.x;
  }
  EXPECT_GT(mapped, 64 * 64 / 4);  // the sphere covers about half the frame
  EXPECT_GT(turned, mapped / 2);
}
