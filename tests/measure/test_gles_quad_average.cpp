// GLSL ES 3.00 has no dFdxFine/dFdyFine, so the GLES target's quad-average normal (the
// deferred-previous and deferred-max wrappers, T&K 2019 Listing 3) takes plain dFdx/dFdy, which an
// implementation may evaluate fine or coarse (GLSL ES 3.00 section 8.9). This measures, on the
// trade scenes at the trade resolution (256 x 256) and alphas, what the coarse case changes in the
// filtered roughness alpha'^2 against the fine form the desktop targets emit, per scene, and
// checks the two properties that hold exactly: the forms agree at the top-left pixel of every
// quad (both take (n_tr + n_bl) / 2 there), and on a normal field linear in screen position.
// The figures are printed ([ quad-avg ] lines) and quoted in targets/gles.json's note.
#include "saagen/measure/renderer.hpp"
#include "saagen/measure/scene.hpp"
#include "saagen/reference/reference.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace {

namespace ref = saagen::ref;
namespace measure = saagen::measure;
using ref::Derivative;
using ref::Quad;
using ref::Vec2;
using ref::Vec3;

constexpr int kSize = 256;                        // TradeConfig's width and height
const double kAlphas[] = {0.01, 0.05, 0.1, 0.3};  // TradeConfig's alphas

struct Difference {
  double max = 0.0;
  double sum = 0.0;
  double sum_fine = 0.0;  // sum of alpha'^2 with the fine form, for a relative figure
  long count = 0;
  long changed = 0;  // pixels whose alpha'^2 moves by more than 1e-3 of its value
};

// alpha'^2 of a wrapper with the quad average taken fine or coarse; the wrapper's own plain
// derivatives are coarse in both, so only the average differs.
double filtered(bool previous, const ref::Params& p, double alpha2, const measure::QuadFields& q, Derivative average) {
  if (previous) {
    return ref::deferred_previous_fragment_quad(p, alpha2, q.normal, q.tangent, q.bitangent, q.frag_coord, q.pixel, Derivative::coarse,
                                                average);
  }
  return ref::deferred_max_fragment_quad(p, alpha2, q.normal, q.tangent, q.bitangent, q.frag_coord, q.pixel, Derivative::coarse, average);
}

TEST(GlesQuadAverage, CoarseAndFineAgreeOnLinearFieldsAndAtTopLeftPixels) {
  // A normal field linear in screen position (not unit: the average is not normalised).
  const auto field = [](double x, double y) { return Vec3{0.1 + 0.02 * x - 0.01 * y, -0.05 + 0.015 * y + 0.005 * x, 0.9}; };
  const Quad<Vec2> frag{{4.5, 6.5}, {5.5, 6.5}, {4.5, 7.5}, {5.5, 7.5}};
  const Quad<Vec3> normal{field(4.5, 6.5), field(5.5, 6.5), field(4.5, 7.5), field(5.5, 7.5)};
  for (int pixel = 0; pixel < 4; ++pixel) {
    const Vec3 fine = ref::quad_average_normal_quad(normal, frag, pixel, Derivative::fine);
    const Vec3 coarse = ref::quad_average_normal_quad(normal, frag, pixel, Derivative::coarse);
    EXPECT_NEAR(fine.x, coarse.x, 1e-15) << pixel;
    EXPECT_NEAR(fine.y, coarse.y, 1e-15) << pixel;
    EXPECT_NEAR(fine.z, coarse.z, 1e-15) << pixel;
  }
  // A curved field: the forms differ, except at the top-left pixel.
  const auto curved = [](double x, double y) { return Vec3{0.02 * x * x, 0.03 * y * x, 1.0}; };
  const Quad<Vec3> bent{curved(4.5, 6.5), curved(5.5, 6.5), curved(4.5, 7.5), curved(5.5, 7.5)};
  const Vec3 top_left_fine = ref::quad_average_normal_quad(bent, frag, 0, Derivative::fine);
  const Vec3 top_left_coarse = ref::quad_average_normal_quad(bent, frag, 0, Derivative::coarse);
  EXPECT_EQ(top_left_fine.x, top_left_coarse.x);
  EXPECT_EQ(top_left_fine.y, top_left_coarse.y);
  const Vec3 bottom_right_fine = ref::quad_average_normal_quad(bent, frag, 3, Derivative::fine);
  const Vec3 bottom_right_coarse = ref::quad_average_normal_quad(bent, frag, 3, Derivative::coarse);
  EXPECT_NE(bottom_right_fine.y, bottom_right_coarse.y);
}

TEST(GlesQuadAverage, CoarseSubstituteErrorOnTheTradeScenes) {
  const ref::Params p;
  std::vector<measure::SceneId> scenes(measure::all_scenes().begin(), measure::all_scenes().end());
  scenes.insert(scenes.end(), measure::content_scenes().begin(), measure::content_scenes().end());
  for (const measure::SceneId id : scenes) {
    const measure::GBuffer gbuffer = measure::render_gbuffer(measure::make_scene(id), kSize, kSize);
    for (const bool previous : {true, false}) {
      Difference d;
      for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
          if (!gbuffer.at(x, y).hit) continue;
          const measure::QuadFields q = measure::gather_quad(gbuffer, x, y);
          for (const double alpha : kAlphas) {
            const double fine = filtered(previous, p, alpha * alpha, q, Derivative::fine);
            const double coarse = filtered(previous, p, alpha * alpha, q, Derivative::coarse);
            ASSERT_TRUE(std::isfinite(fine) && std::isfinite(coarse));
            const double error = std::fabs(coarse - fine);
            d.max = std::max(d.max, error);
            d.sum += error;
            d.sum_fine += fine;
            ++d.count;
            if (error > 1e-3 * fine) ++d.changed;
          }
        }
      }
      ASSERT_GT(d.count, 0);
      std::cout << fmt::format(
          "[ quad-avg ] {:<17} {:<18} |coarse - fine| in alpha'^2: mean {:.2e} ({:.2f}% of mean alpha'^2), max {:.2e}; "
          "{:.1f}% of pixel-alphas move by > 0.1%\n",
          measure::scene_name(id), previous ? "deferred-previous" : "deferred-max", d.sum / d.count, 100.0 * d.sum / d.sum_fine, d.max,
          100.0 * d.changed / d.count);
      // Both forms add a kernel in [0, kappa] to the same alpha^2 (deferred_previous and
      // deferred_max clamp it by kappa before saturating), so they differ by at most kappa.
      EXPECT_LE(d.max, p.kappa);
    }
  }
}

}  // namespace
