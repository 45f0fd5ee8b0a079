// The temporal difference error (image.hpp, TemporalDifference) on hand-made sequences whose
// values are worked out in the comments, the display values it is measured in, and the trade's
// animation (trade.hpp): the camera pan moves content by exactly the pixels asked for, and the
// ground-truth cache key sees the pan.
#include "saagen/measure/render.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

using namespace saagen::measure;
using saagen::ref::Vec3;

namespace {

// A sequence of 1 x n frames.
std::vector<Image> frames(const std::vector<std::vector<float>>& values) {
  std::vector<Image> out;
  for (const auto& frame : values) {
    Image image(static_cast<int>(frame.size()), 1);
    image.pixels = frame;
    out.push_back(image);
  }
  return out;
}

constexpr double kFloat = 1e-7;  // the inputs are floats

TEST(TemporalDifference, IdenticalSequencesScoreZero) {
  const auto sequence = frames({{0.1f, 0.9f, 0.3f}, {0.7f, 0.2f, 0.3f}, {0.0f, 1.0f, 0.5f}});
  const TemporalError e = temporal_difference_error(sequence, sequence);
  EXPECT_EQ(e.tde, 0.0);
  EXPECT_EQ(e.excess_flicker, 0.0);
  EXPECT_EQ(e.lost_motion, 0.0);
}

// A variant that stays constant where the reference moves (a highlight blurred away): every
// change of the reference is lost. dR over the two pairs: (0.4, 0) and (-0.5, 0.4), so
// mean |dR| = (0.4 + 0 + 0.5 + 0.4) / 4 = 0.325 = TDE = lost motion; no excess flicker.
TEST(TemporalDifference, ConstantVariantLosesAllOfTheReferenceMotion) {
  const auto reference = frames({{0.2f, 0.5f}, {0.6f, 0.5f}, {0.1f, 0.9f}});
  const auto constant = frames({{0.3f, 0.3f}, {0.3f, 0.3f}, {0.3f, 0.3f}});
  const TemporalError e = temporal_difference_error(constant, reference);
  EXPECT_NEAR(e.tde, 0.325, kFloat);
  EXPECT_NEAR(e.lost_motion, 0.325, kFloat);
  EXPECT_EQ(e.excess_flicker, 0.0);
}

// A variant that flickers on a static reference: every change is excess. |dI| over the two
// pairs: (0.3, 0) and (0, 0.7), mean 0.25 = TDE = excess flicker; no lost motion.
TEST(TemporalDifference, FlickerOnAStaticReferenceIsAllExcess) {
  const auto reference = frames({{0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, 0.5f}});
  const auto flickering = frames({{0.1f, 0.2f}, {0.4f, 0.2f}, {0.4f, 0.9f}});
  const TemporalError e = temporal_difference_error(flickering, reference);
  EXPECT_NEAR(e.tde, 0.25, kFloat);
  EXPECT_NEAR(e.excess_flicker, 0.25, kFloat);
  EXPECT_EQ(e.lost_motion, 0.0);
}

// One pixel, three frames. I = 0, 0.5, 0.2: dI = 0.5, -0.3. R = 0, 0.2, 0.6: dR = 0.2, 0.4.
// |dI - dR| = 0.3, 0.7 -> TDE 0.5. Excess: max(0, 0.5 - 0.2) = 0.3 and max(0, 0.3 - 0.4) = 0
// -> 0.15. Lost: 0 and 0.1 -> 0.05. The second pair changes the wrong way (-0.3 against +0.4),
// which TDE counts in full (0.7) and the two parts only as the difference of magnitudes (0.1),
// so excess + lost = 0.2 < TDE.
TEST(TemporalDifference, HandComputedExample) {
  const auto image = frames({{0.0f}, {0.5f}, {0.2f}});
  const auto reference = frames({{0.0f}, {0.2f}, {0.6f}});
  const TemporalError e = temporal_difference_error(image, reference);
  EXPECT_NEAR(e.tde, 0.5, kFloat);
  EXPECT_NEAR(e.excess_flicker, 0.15, kFloat);
  EXPECT_NEAR(e.lost_motion, 0.05, kFloat);
}

// A static variant is not "stable" against a moving truth: blurring the motion away costs as
// much as flickering by the same amount (a temporal std ratio would score the first 0, the
// second 2: the old flicker error |ratio - 1| = 1 for both, while TDE tells them apart).
TEST(TemporalDifference, LostMotionAndExcessFlickerAreSymmetric) {
  const auto moving = frames({{0.0f}, {0.4f}, {0.0f}, {0.4f}});
  const auto still = frames({{0.2f}, {0.2f}, {0.2f}, {0.2f}});
  const TemporalError blurred = temporal_difference_error(still, moving);
  const TemporalError aliased = temporal_difference_error(moving, still);
  EXPECT_NEAR(blurred.tde, 0.4, kFloat);
  EXPECT_NEAR(aliased.tde, 0.4, kFloat);
  EXPECT_NEAR(blurred.lost_motion, 0.4, kFloat);
  EXPECT_NEAR(aliased.excess_flicker, 0.4, kFloat);
}

// Pair by pair accumulation is the mean over pixels and pairs, not a mean of per-pair means
// weighted otherwise; fewer than two frames give zeros.
TEST(TemporalDifference, AccumulatesPairsAndRefusesMismatches) {
  TemporalDifference d;
  EXPECT_EQ(d.mean().tde, 0.0);
  const auto a = frames({{0.0f, 0.0f}, {1.0f, 0.0f}});
  const auto r = frames({{0.0f, 0.0f}, {0.0f, 0.0f}});
  d.add_pair(a[0], a[1], r[0], r[1]);  // |dI - dR| = 1, 0
  d.add_pair(a[1], a[1], r[1], r[1]);  // 0, 0
  EXPECT_EQ(d.pairs(), 2);
  EXPECT_DOUBLE_EQ(d.mean().tde, 0.25);
  EXPECT_EQ(temporal_difference_error(std::vector<Image>{a[0]}, std::vector<Image>{r[0]}).tde, 0.0);
  EXPECT_THROW(temporal_difference_error(a, std::vector<Image>{r[0]}), std::invalid_argument);
  EXPECT_THROW(d.add_pair(a[0], Image(3, 1), r[0], r[1]), std::invalid_argument);
}

// Display values: Reinhard, then the sRGB encoding (IEC 61966-2-1) that LDR-FLIP takes.
TEST(DisplayValues, TonemapThenSrgbEncode) {
  EXPECT_NEAR(display_value(1.0), 0.7353569830524495, 1e-15);  // sRGB(0.5)
  EXPECT_NEAR(display_value(3.0), 0.8808250210902997, 1e-15);  // sRGB(0.75)
  EXPECT_NEAR(srgb_encode(0.002), 0.02584, 1e-15);             // the linear segment
  EXPECT_DOUBLE_EQ(srgb_encode(2.0), 1.0);                     // clamped: 1.055 - 0.055
  EXPECT_EQ(srgb_encode(std::numeric_limits<double>::quiet_NaN()), 0.0);
  EXPECT_DOUBLE_EQ(display_value(std::numeric_limits<double>::infinity()), 1.0);
  Image radiance(2, 1);
  radiance.pixels = {1.0f, 0.0f};
  const Image display = display_image(radiance);
  EXPECT_NEAR(display.pixels[0], 0.7353569830524495, 1e-7);
  EXPECT_EQ(display.pixels[1], 0.0f);
}

// Where a ray meets the plane through the camera's look-at point facing it.
Vec3 on_look_at_plane(const Camera& camera, const Camera& ray_camera, double fx, double fy, int size) {
  const Vec3 forward = saagen::ref::normalize(camera.look_at - camera.position);
  const Ray ray = ray_camera.generate(fx, fy, size, size);
  const double t = saagen::ref::dot(camera.look_at - ray.origin, forward) / saagen::ref::dot(ray.direction, forward);
  return ray.origin + t * ray.direction;
}

// Panning by (2, -3) pixels of a 128-pixel image: the point of the look-at plane seen at
// (40.5, 70.5) is seen at (40.5 - 2, 70.5 - 3) afterwards.
TEST(Animation, PanMovesTheLookAtPlaneByThePixelsAsked) {
  const Camera camera = make_scene(SceneId::torus).camera();
  const Camera moved = camera.panned(2.0, -3.0, 128);
  const Vec3 before = on_look_at_plane(camera, camera, 40.5, 70.5, 128);
  const Vec3 after = on_look_at_plane(camera, moved, 38.5, 67.5, 128);
  EXPECT_NEAR(saagen::ref::length(before - after), 0.0, 1e-12);
  // The pixel footprint at the look-at distance 4.2: 2 * 4.2 * tan(18 deg) / 128.
  const double pixel = 2.0 * 4.2 * std::tan(18.0 * 3.14159265358979323846 / 180.0) / 128.0;
  EXPECT_NEAR(saagen::ref::length(moved.position - camera.position), pixel * std::sqrt(13.0), 1e-12);
}

// The animation is centred on the unpanned view (frame 2 of 5 is make_scene's camera), the pan
// alone moves the camera, and the ground-truth cache key tells the frames apart.
TEST(Animation, FramesAreCentredAndTheCacheKeySeesThePan) {
  TradeConfig config;
  config.frames = 5;
  config.rotation_degrees_per_frame = 0.0;
  config.pan_pixels_per_frame = {0.25, 0.5};
  const Scene centre = trade_animation_frame(config, SceneId::sphere, 2);
  EXPECT_EQ(centre.describe(), make_scene(SceneId::sphere).describe());
  const Scene first = trade_animation_frame(config, SceneId::sphere, 0);
  const Scene last = trade_animation_frame(config, SceneId::sphere, 4);
  // 4 frames of (0.25, 0.5) px at 128 px: sqrt(1 + 4) pixels of 2 * 4 * tan(17 deg) / 128.
  const double pixel = 2.0 * 4.0 * std::tan(17.0 * 3.14159265358979323846 / 180.0) / 128.0;
  EXPECT_NEAR(saagen::ref::length(last.camera().position - first.camera().position), std::sqrt(5.0) * pixel, 1e-12);
  GroundTruthSettings settings;
  const std::vector<Material> materials{{0.1, false}};
  EXPECT_NE(ground_truth_cache_key(first, settings, materials), ground_truth_cache_key(last, settings, materials));
}

}  // namespace
