// The engines' shipped geometric SAA forms (measure/engines.hpp), the trade's baseline
// rows: hand-computed values, and the exact equivalences shared/REFERENCES.md states (HDRP and
// Filament are T&K 2019's Eq. 4 with their own sigma^2 and kappa).
#include "saagen/measure/engines.hpp"
#include "saagen/measure/renderer.hpp"
#include "saagen/measure/sampling.hpp"
#include "saagen/reference/saa.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace saagen::measure;
namespace ref = saagen::ref;
using ref::Vec3;

namespace {

// alpha = 0.1 (a = 0.01, r = sqrt(0.1)); |dn/dx|^2 = 0.01, |dn/dy|^2 = 0.04: S = 0.05,
// Smax = 0.04, largest component 0.2.
constexpr double kAlpha = 0.1;
constexpr Vec3 kDx{0.1, 0.0, 0.0};
constexpr Vec3 kDy{0.0, 0.2, 0.0};

double perceptual4(double r) { return r * r * r * r; }

}  // namespace

TEST(Engines, HandComputedValues) {
  // Exact binary fractions aside, each value is a handful of roundings from its formula.
  constexpr double eps = 1e-15;
  EXPECT_NEAR(hdrp_alpha2(kAlpha, kDx, kDy), 0.01 + 2 * 0.1 * 0.05, eps);       // 0.02
  EXPECT_NEAR(filament_alpha2(kAlpha, kDx, kDy), 0.01 + 2 * 0.15 * 0.05, eps);  // 0.025
  EXPECT_NEAR(godot_alpha2(kAlpha, kDx, kDy), 0.125 * 0.125, eps);              // alpha + 0.025
  const double curvature = std::pow(0.04, 0.333);                               // 0.34236
  EXPECT_NEAR(unreal_alpha2(kAlpha, kDx, kDy), perceptual4(curvature), eps);
  EXPECT_NEAR(babylon_alpha2(kAlpha, kDx, kDy), perceptual4(curvature), eps);
  EXPECT_NEAR(threejs_alpha2(kAlpha, kDx, kDy), perceptual4(std::sqrt(0.1) + 0.2), eps);
}

TEST(Engines, CapsAndFloors) {
  const Vec3 big{1.0, 0.0, 0.0};
  EXPECT_NEAR(hdrp_alpha2(kAlpha, big, big), 0.01 + 0.04, 1e-15);      // t^2 = 0.04
  EXPECT_NEAR(filament_alpha2(kAlpha, big, big), 0.01 + 0.04, 1e-15);  // T = 0.04
  EXPECT_NEAR(godot_alpha2(kAlpha, big, big), 0.28 * 0.28, 1e-15);     // alpha + limit 0.18
  // No cap in Unreal, three.js or Babylon.js: |dn| = 1 drives the surface to r = 1.
  EXPECT_EQ(unreal_alpha2(kAlpha, big, big), 1.0);
  EXPECT_EQ(threejs_alpha2(kAlpha, big, big), 1.0);
  EXPECT_EQ(babylon_alpha2(kAlpha, big, big), 1.0);
  // three.js floors perceptual roughness at 0.0525 even on a flat surface.
  EXPECT_NEAR(threejs_alpha2(0.0025, {}, {}), perceptual4(0.0525), 1e-18);
}

// REFERENCES.md: HDRP = deferred-sum with sigma^2 0.1, kappa 0.04; Filament = deferred-sum with
// 0.15, 0.04. Same operations in the same order up to the saturate: equal within a few ulps.
TEST(Engines, HdrpAndFilamentAreDeferredSumWithTheirConstants) {
  Rng rng(7);
  for (int i = 0; i < 10000; ++i) {
    const double alpha = rng.next_double();
    const Vec3 dx{rng.next_double() - 0.5, rng.next_double() - 0.5, rng.next_double() - 0.5};
    const Vec3 dy{rng.next_double() - 0.5, rng.next_double() - 0.5, rng.next_double() - 0.5};
    ref::Params hdrp{0.1, 0.04};
    ref::Params filament{0.15, 0.04};
    EXPECT_NEAR(hdrp_alpha2(alpha, dx, dy), ref::deferred_sum(hdrp, alpha * alpha, dx, dy), 4e-16);
    EXPECT_NEAR(filament_alpha2(alpha, dx, dy), ref::deferred_sum(filament, alpha * alpha, dx, dy), 4e-16);
  }
}

TEST(Engines, EachEngineReadsTheNormalItsSourceFilters) {
  EXPECT_EQ(engine_feed(Variant::engine_hdrp), NormalFeed::geometric);
  EXPECT_EQ(engine_feed(Variant::engine_filament), NormalFeed::geometric);
  EXPECT_EQ(engine_feed(Variant::engine_unreal), NormalFeed::geometric);
  EXPECT_EQ(engine_feed(Variant::engine_threejs), NormalFeed::geometric);
  EXPECT_EQ(engine_feed(Variant::engine_godot), NormalFeed::shading);
  EXPECT_EQ(engine_feed(Variant::engine_babylon), NormalFeed::shading);
  for (Variant engine : all_engines()) {
    EXPECT_TRUE(is_engine(engine));
    EXPECT_EQ(variant_from_id(variant_id(engine)), engine);
  }
}
