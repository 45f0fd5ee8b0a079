// The TAA resolve of the reference renderer (taa.hpp): the Halton (2, 3) jitter, the camera's
// jitter and projection, the exact reprojection of the scene's rigid motion, convergence to the
// ground truth on a static scene as the jitter covers the pixel, and variance clipping rejecting
// the history of a disoccluded highlight.
#include "support/cli_support.hpp"

#include "saagen/measure/render.hpp"
#include "saagen/measure/taa.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <vector>

using namespace saagen::measure;

namespace {

// Mean |tonemap(a) - tonemap(b)| over the pixels: the display-referred error of a resolve.
double mean_tonemapped_error(const Image& a, const Image& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += std::abs(tonemap(a.pixels[i]) - tonemap(b.pixels[i]));
  return sum / static_cast<double>(a.size());
}

std::vector<Vec2> pixel_centres(int width, int height) {
  std::vector<Vec2> out;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) out.push_back({x + 0.5, y + 0.5});
  return out;
}

Scene with_jitter(const Scene& scene, Vec2 jitter) {
  Camera camera = scene.camera();
  camera.jitter = jitter;
  return scene.with_camera(camera);
}

}  // namespace

// Halton (1964): the radical inverse mirrors the digits about the radix point; base 2 of 1, 2,
// 3 = 0.1, 0.01, 0.11 (binary); base 3 of 1, 2, 3 = 0.1, 0.2, 0.01 (ternary).
TEST(TaaJitter, HaltonTwoThreeSequence) {
  EXPECT_EQ(radical_inverse(1, 2), 0.5);
  EXPECT_EQ(radical_inverse(2, 2), 0.25);
  EXPECT_EQ(radical_inverse(3, 2), 0.75);
  EXPECT_DOUBLE_EQ(radical_inverse(1, 3), 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(radical_inverse(2, 3), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(radical_inverse(3, 3), 1.0 / 9.0);
  // Frame 0 is index 1, (0.5, 1/3) - 0.5; the sequence repeats after its length.
  EXPECT_DOUBLE_EQ(taa_jitter(0, 8).x, 0.0);
  EXPECT_DOUBLE_EQ(taa_jitter(0, 8).y, 1.0 / 3.0 - 0.5);
  for (int frame = 0; frame < 16; ++frame) {
    const Vec2 j = taa_jitter(frame, 8), again = taa_jitter(frame + 8, 8);
    EXPECT_EQ(j.x, again.x);
    EXPECT_EQ(j.y, again.y);
    EXPECT_GE(j.x, -0.5);
    EXPECT_LT(j.x, 0.5);
    EXPECT_GE(j.y, -0.5);
    EXPECT_LT(j.y, 0.5);
  }
}

TEST(TaaJitter, OptionsOutOfRangeAreRefused) {
  TaaOptions options;
  options.blend = 0.0;
  EXPECT_THROW(check_taa_options(options), std::invalid_argument);
  options = {};
  options.sequence_length = 0;
  EXPECT_THROW(check_taa_options(options), std::invalid_argument);
  options = {};
  options.clip_gamma = -1.0;
  EXPECT_THROW(check_taa_options(options), std::invalid_argument);
  options = {};
  options.current_filter_variance = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(check_taa_options(options), std::invalid_argument);
  EXPECT_NO_THROW(check_taa_options(TaaOptions{}));
}

// A jittered camera's rays are the unjittered camera's rays at the film position plus the
// jitter, and project() inverts generate() (both in double precision: 1e-9 px).
TEST(TaaJitter, JitteredCameraProjectsBackToTheFilmPosition) {
  const Camera camera = make_scene(SceneId::torus).camera();
  Camera jittered = camera;
  jittered.jitter = {0.25, -0.375};
  for (const Vec2 film : {Vec2{3.5, 7.5}, Vec2{31.25, 0.125}, Vec2{16.0, 16.0}}) {
    const Ray a = jittered.generate(film.x, film.y, 32, 32), b = camera.generate(film.x + 0.25, film.y - 0.375, 32, 32);
    EXPECT_NEAR(a.direction.x, b.direction.x, 1e-15);
    EXPECT_NEAR(a.direction.y, b.direction.y, 1e-15);
    const std::optional<Vec2> back = jittered.project(a.origin + 3.0 * a.direction, 32, 32);
    ASSERT_TRUE(back.has_value());
    EXPECT_NEAR(back->x, film.x, 1e-9);
    EXPECT_NEAR(back->y, film.y, 1e-9);
  }
  EXPECT_FALSE(camera.project(camera.position - (camera.look_at - camera.position), 32, 32).has_value());
}

// The reprojection is the scene's exact motion: the previous frame's (unjittered) ray through a
// pixel's history position plus the current jitter meets the same surface point, moved back by
// the previous frame's rigid transform (the trade's animation: rotation and camera pan).
TEST(TaaReprojection, HistoryPositionSeesTheSamePointInThePreviousFrame) {
  TradeConfig config;
  config.frames = 16;
  config.flicker_width = config.flicker_height = 24;
  const Scene previous = trade_animation_frame(config, SceneId::torus, 4);
  const Vec2 jitter = taa_jitter(5, 8);
  const Scene current = with_jitter(trade_animation_frame(config, SceneId::torus, 5), jitter);
  const GBuffer gbuffer = render_gbuffer(current, 24, 24, 1);
  const std::vector<Vec2> positions = reproject_history(gbuffer, current, previous);
  int checked = 0;
  for (int y = 0; y < 24; ++y) {
    for (int x = 0; x < 24; ++x) {
      const PixelFields& f = gbuffer.at(x, y);
      const Vec2 p = positions[static_cast<std::size_t>(y) * 24 + x];
      if (!f.hit) {
        EXPECT_EQ(p.x, x + 0.5);
        EXPECT_EQ(p.y, y + 0.5);
        continue;
      }
      if (std::isnan(p.x)) continue;
      const Ray ray = previous.camera().generate(p.x + jitter.x, p.y + jitter.y, 24, 24);
      SurfaceHit hit;
      if (!previous.intersect(ray, hit)) continue;  // occluded in the previous frame
      const Vec3 expected = previous.object_to_world().apply_point(current.object_to_world().inverse_point(f.position));
      if (saagen::ref::length(hit.position - expected) > 1e-3) continue;  // another surface in front
      EXPECT_NEAR(hit.position.x, expected.x, 1e-9);
      EXPECT_NEAR(hit.position.y, expected.y, 1e-9);
      EXPECT_NEAR(hit.position.z, expected.z, 1e-9);
      ++checked;
    }
  }
  EXPECT_GT(checked, 24 * 24 / 4);
}

// On a constant image with identity motion the resolve is the identity at every frame: the
// current filter's weights are normalised and the clip box of a constant neighbourhood is the
// value itself (float storage: 1e-6 relative).
TEST(TaaResolveTest, ConstantImageStaysConstant) {
  TaaResolve taa(8, 8, TaaOptions{});
  const Image image(8, 8, 2.5f);
  const std::vector<Vec2> identity = pixel_centres(8, 8);
  for (int frame = 0; frame < 10; ++frame) {
    const Image& out = taa.resolve(image, taa_jitter(frame, 8), identity);
    for (float v : out.pixels) EXPECT_NEAR(v, 2.5, 2.5e-6);
  }
}

// A static scene converges towards its ground truth as the jitter sequence covers the pixel:
// the sphere at 32 x 32 px (its highlight about a pixel wide at alpha 0.05), 8 Halton
// positions, the default resolve without luma weighting (which converges to the 1 / (1 + x)
// weighted mean, biased low on a sub-pixel highlight by design: Karis 2014 trades that energy
// for stability). The mean tonemapped error against the 1024-spp ground truth after one frame
// (one jittered sample per pixel, filtered over the 3 x 3 neighbourhood; measured 2.8e-4) halves
// after a full cycle (1.4e-4) and falls again by four cycles (8.3e-5), where the EMA has
// forgotten the first frames (0.9^32 = 3 %). Without jitter coverage (a sequence of 1: one
// fixed position) it stays at the 1-spp level (2.7e-4 after 64 frames).
TEST(TaaResolveTest, StaticSceneConvergesToTheGroundTruth) {
  constexpr int kSize = 32;
  const Scene scene = make_scene(SceneId::sphere);
  GroundTruthSettings settings;
  settings.width = settings.height = kSize;
  settings.threads = 1;
  const Material material{0.05, false};
  const Image truth = render_ground_truth(scene, settings, std::span<const Material>(&material, 1)).images[0];
  const std::vector<Vec2> identity = pixel_centres(kSize, kSize);

  auto errors_after = [&](int sequence_length, std::vector<int> checkpoints) {
    TaaOptions options;
    options.sequence_length = sequence_length;
    options.luma_weighting = false;
    TaaResolve taa(kSize, kSize, options);
    std::vector<double> errors;
    for (int frame = 0; frame < checkpoints.back(); ++frame) {
      const Vec2 jitter = taa_jitter(frame, sequence_length);
      const GBuffer gbuffer = render_gbuffer(with_jitter(scene, jitter), kSize, kSize, 1);
      const Image& out =
          taa.resolve(render_variant(gbuffer, Variant::none, material, {}, saagen::ref::Derivative::coarse, 1), jitter, identity);
      for (int checkpoint : checkpoints)
        if (frame + 1 == checkpoint) errors.push_back(mean_tonemapped_error(out, truth));
    }
    return errors;
  };
  const std::vector<double> jittered = errors_after(8, {1, 8, 32, 64});
  const std::vector<double> fixed = errors_after(1, {1, 64});
  EXPECT_LT(jittered[1], 0.6 * jittered[0]);
  EXPECT_LT(jittered[2], 0.7 * jittered[1]);
  EXPECT_LT(jittered[3], 0.35 * jittered[0]);
  EXPECT_GT(fixed[1], 0.9 * fixed[0]);
}

// Variance clipping rejects the history of a disoccluded highlight (Salvi 2016): a converged
// bright block (radiance 4) whose surface leaves, uncovering the black background. The
// background's history position is its own pixel (it lies at infinity), so the history still
// holds the block; the current 3 x 3 neighbourhood is all black (mean 0, sigma 0), so the clip
// box is {0} and the history is rejected in one frame: exactly 0. Without the clip (gamma
// infinite) the block ghosts: (1 - blend) of its tonemapped value 0.8 stays, 0.72 -> 2.57.
TEST(TaaResolveTest, ClampRejectsHistoryOnADisocclusion) {
  constexpr int kSize = 16;
  Image block(kSize, kSize);
  for (int y = 4; y < 12; ++y)
    for (int x = 4; x < 12; ++x) block.at(x, y) = 4.0f;
  const Image background(kSize, kSize);
  const std::vector<Vec2> identity = pixel_centres(kSize, kSize);
  auto after_disocclusion = [&](double gamma) {
    TaaOptions options;
    options.clip_gamma = gamma;
    TaaResolve taa(kSize, kSize, options);
    for (int frame = 0; frame < 16; ++frame) taa.resolve(block, taa_jitter(frame, 8), identity);
    return taa.resolve(background, taa_jitter(16, 8), identity);
  };
  const Image clipped = after_disocclusion(1.0);
  const Image ghost = after_disocclusion(std::numeric_limits<double>::infinity());
  // Pixels whose whole 3 x 3 neighbourhood was inside the block: a converged 4 before.
  for (int y = 5; y < 11; ++y) {
    for (int x = 5; x < 11; ++x) {
      EXPECT_EQ(clipped.at(x, y), 0.0f);
      EXPECT_NEAR(ghost.at(x, y), 0.72 / 0.28, 1e-4);
    }
  }
}

// The trade's +taa rows (trade.hpp, TradeConfig::taa) on a tiny configuration: every
// configuration once more under TAA, after its rows without; their LDR-FLIP is the animation's
// (flip_ldr == flip_ldr_animation), every row without TAA carries the animation's LDR-FLIP too,
// and the temporal figures are those of the resolved frames (|dI - dR| >= ||dI| - |dR||, so TDE
// bounds excess flicker + lost motion from above, image.hpp).
TEST(TaaTrade, EveryConfigurationOnceMoreUnderTaa) {
  TradeConfig config;
  config.width = config.height = 16;
  config.strata = 2;
  config.flicker_width = config.flicker_height = 12;
  config.flicker_strata = 2;
  config.frames = 3;
  config.scenes = {SceneId::sphere};
  config.alphas = {0.1};
  config.fresnel_modes = {false};
  config.variants = {Variant::none, Variant::deferred_avg, Variant::engine_filament};
  config.lobes = {};
  config.threads = 1;
  config.flip = true;
  config.taa = true;
  const TradeTable table = compute_trade_table(config);
  ASSERT_EQ(table.rows.size(), 6u);
  for (std::size_t i = 0; i < 3; ++i) {
    const TradeRow& plain = table.rows[i];
    const TradeRow& taa = table.rows[i + 3];
    EXPECT_FALSE(plain.taa);
    EXPECT_TRUE(taa.taa);
    EXPECT_EQ(configuration_id(taa), configuration_id(plain) + "+taa");
    EXPECT_EQ(table.find(plain.variant, SceneId::sphere, 0.1, false, plain.feed, plain.prefilter, Lobe::papers, true), &taa);
    EXPECT_GT(plain.flip_ldr_animation, 0.0);
    EXPECT_EQ(taa.flip_ldr, taa.flip_ldr_animation);
    EXPECT_GT(taa.flip_ldr, 0.0);
    EXPECT_GT(taa.tde, 0.0);
    EXPECT_GE(taa.tde + 1e-12, taa.tde_excess_flicker + taa.tde_lost_motion);
    // The verdict's metrics, against both ground-truth seeds as the rows without TAA.
    for (std::size_t seed = 0; seed < 2; ++seed) {
      EXPECT_EQ(taa.series.image[seed].size(), 3u);
      EXPECT_EQ(taa.series.video[seed].size(), 3u);
      EXPECT_EQ(taa.series.lag[seed].size(), 2u);
    }
    EXPECT_NEAR(taa.flip_ldr_animation, mean_interval(taa.series.image[0], 0.0).mean, 1e-9);
    // And against the sanity suite's quarter-sample ground truth, as the rows without TAA, so that
    // the verdict under TAA judges the ground truth's sample bias too (report/comparison.hpp).
    EXPECT_EQ(taa.quarter_series.image[0].size(), 3u);
    EXPECT_EQ(taa.quarter_series.video[0].size(), 3u);
    EXPECT_EQ(taa.quarter_series.flicker[0].size(), 2u);
    EXPECT_EQ(taa.quarter_series.lag[0].size(), 2u);
    EXPECT_NE(taa.quarter_series.image[0], taa.series.image[0]);  // another ground truth
    EXPECT_EQ(plain.quarter_series.image[0].size(), 3u);
    EXPECT_GT(taa.image_error.mean, 0.0);
    EXPECT_GT(taa.video_error.mean, 0.0);
    EXPECT_LE(taa.video_error.low, taa.video_error.mean);
  }
  EXPECT_EQ(configuration_id(Variant::deferred_avg, NormalFeed::geometric, Prefilter::lean, Lobe::tail, true),
            "deferred-avg:geometric+lean+taa/tail");
  config.frames = 1;
  EXPECT_THROW(compute_trade_table(config), std::invalid_argument);
}

// The +taa rows of the lobes and the bakes: on a normal-mapped sphere, the tail-preserving and
// mapped lobes of a variant and of its engine bake (HDRP's, on the geometric normal) each run
// under TAA ("deferred-avg:geometric+hdrp+taa/tail"), and the image kept for the report is the
// resolve of that lobe's 1-spp frames: a resolve run here over the same jittered frames gives the
// same last frame to the bit, and it differs from the papers' lobe's.
TEST(TaaTrade, LobesAndBakesRunThroughTheResolve) {
  TradeConfig config;
  config.width = config.height = 8;
  config.strata = 2;
  config.flicker_width = config.flicker_height = 12;
  config.flicker_strata = 2;
  config.frames = 3;
  config.scenes = {SceneId::nmap_sphere};
  config.alphas = {0.05};
  config.fresnel_modes = {false};
  config.variants = {Variant::none, Variant::deferred_avg};
  config.feeds = {NormalFeed::shading};
  config.prefilters = {Prefilter::hdrp};
  config.prefiltered_variants = {Variant::deferred_avg};
  config.lobes = {Lobe::tail, Lobe::mapped};
  config.lobe_variants = {Variant::deferred_avg};
  config.threads = 1;
  config.flip = false;
  config.taa = true;
  config.keep_images = true;
  const TradeTable table = compute_trade_table(config);
  // none, deferred-avg (papers, tail, mapped), its HDRP bake (papers, tail, mapped); then each +taa.
  ASSERT_EQ(table.rows.size(), 14u);
  const TradeRow* bake_tail =
      table.find(Variant::deferred_avg, SceneId::nmap_sphere, 0.05, false, NormalFeed::geometric, Prefilter::hdrp, Lobe::tail, true);
  ASSERT_NE(bake_tail, nullptr);
  EXPECT_EQ(configuration_id(*bake_tail), "deferred-avg:geometric+hdrp+taa/tail");
  ASSERT_NE(table.find(Variant::deferred_avg, SceneId::nmap_sphere, 0.05, false, NormalFeed::shading, Prefilter::none, Lobe::mapped, true),
            nullptr);
  EXPECT_GT(bake_tail->tde, 0.0);
  EXPECT_GT(bake_tail->rmse_tonemapped, 0.0);
  EXPECT_EQ(bake_tail->flip_ldr_animation, 0.0);  // config.flip = false: no FLIP, as in the rows without TAA

  ASSERT_EQ(table.taa_images.size(), 1u);
  const ImageSet& last = table.taa_images.front();
  ASSERT_EQ(last.variants.size(), 7u);
  const auto kept = [&](Prefilter prefilter, Lobe lobe) -> const Image& {
    for (const auto& rendered : last.variants)
      if (rendered.variant == Variant::deferred_avg && rendered.prefilter == prefilter && rendered.lobe == lobe) return rendered.image;
    ADD_FAILURE() << "no kept image";
    return last.reference;
  };
  const Material material = trade_materials(config).front();
  const int warmup = config.taa_options.sequence_length;
  TaaResolve resolve(config.flicker_width, config.flicker_height, config.taa_options);
  std::optional<Scene> previous;
  for (int frame = -warmup; frame < config.frames; ++frame) {
    const Vec2 jitter = taa_jitter(frame + warmup, config.taa_options.sequence_length);
    const Scene scene = with_jitter(trade_animation_frame(config, SceneId::nmap_sphere, frame), jitter);
    const GBuffer gbuffer = render_gbuffer(scene, config.flicker_width, config.flicker_height, 1);
    const std::vector<Vec2> positions = previous ? reproject_history(gbuffer, scene, *previous) : std::vector<Vec2>{};
    // The bake's rows sample the map TradeConfig::prefilter_lod_bias levels coarser.
    const GBuffer prefiltered = render_gbuffer(scene, config.flicker_width, config.flicker_height, 1, config.prefilter_lod_bias);
    resolve.resolve(render_variant(prefiltered, Variant::deferred_avg, material, config.params, config.derivative, 1, NormalFeed::geometric,
                                   Prefilter::hdrp, config.prefilter_scale, Lobe::tail),
                    jitter, positions);
    previous = scene;
  }
  EXPECT_EQ(kept(Prefilter::hdrp, Lobe::tail).pixels, resolve.output().pixels);
  EXPECT_NE(kept(Prefilter::hdrp, Lobe::tail).pixels, kept(Prefilter::hdrp, Lobe::papers).pixels);
}

// saagen bench --taa on a tiny run: the per-scene TAA table after the summaries, the +taa rows in
// the JSON's taa_cases (and not in its summary rows); the resolve's options without --taa, and a
// --pan without two numbers, are one line and a non-zero exit.
class TaaCli : public saagen::test::CliTest {};

TEST_F(TaaCli, BenchTaaPrintsTheTaaTable) {
  const std::string json = (scratch_ / "trade.json").string();
  const auto run =
      saagen({"bench", "--scene", "sphere", "--preset", "quick", "--resolution", "8", "--taa", "--pan", "0.2,0.5", "--json", json});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("With TAA"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("none+taa"), std::string::npos) << run.out;
  const std::string text = saagen::test::read_text(json);
  EXPECT_NE(text.find("\"taa_cases\""), std::string::npos);
  EXPECT_NE(text.find("\"configuration\": \"engine-hdrp+taa\""), std::string::npos);
  EXPECT_EQ(text.find("\"variant\": \"none+taa\""), std::string::npos);

  const auto blend = saagen({"bench", "--preset", "quick", "--taa-blend", "0.2"});
  EXPECT_NE(blend.exit_code, 0);
  EXPECT_NE(blend.err.find("add --taa"), std::string::npos) << blend.err;
  EXPECT_EQ(std::count(blend.err.begin(), blend.err.end(), '\n'), 1) << blend.err;
  const auto pan = saagen({"bench", "--preset", "quick", "--pan", "1"});
  EXPECT_NE(pan.exit_code, 0);
}

// saagen report --taa: a "With TAA" section in index.html and report.md (after the strips), with
// the per-scene verdict and comparison and one image per scene (taa_<scene>.png: a crop of the last
// frame of the ground truth, none+taa, the configuration the verdict takes under TAA where one
// beats none+taa, and the best engine form under TAA).
TEST_F(TaaCli, ReportTaaHasTheWithTaaSection) {
  const std::filesystem::path dir = scratch_ / "report";
  const auto run = saagen({"report", "--scene", "sphere", "--preset", "quick", "--resolution", "8", "--taa", "-o", dir.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "taa_sphere.png"));
  const std::string markdown = saagen::test::read_text(dir / "report.md");
  const auto section = markdown.find("## With TAA"), image = markdown.find("](taa_sphere.png)");
  ASSERT_NE(section, std::string::npos);
  ASSERT_NE(image, std::string::npos);
  EXPECT_LT(markdown.find("](strip_sphere.png)"), section);
  EXPECT_LT(section, image);
  for (const char* text : {"- sphere: ", "| sphere | TAA | none+taa |", "| sphere | engine | engine-hdrp+taa |", "ground truth, none+taa ",
                           ", best engine: engine-"})
    EXPECT_NE(markdown.find(text), std::string::npos) << text;
  const std::string html = saagen::test::read_text(dir / "index.html");
  EXPECT_NE(html.find("<h2>With TAA"), std::string::npos);
  EXPECT_NE(html.find("<img src=\"taa_sphere.png\""), std::string::npos);
}

// The planner under TAA: `taa = true` (or `plan --taa`) plans sigma2 = 0.0625 with the measured
// reason unless the manifest sets sigma2 (or a preset does); a non-boolean `taa` is one line at
// its key.
TEST_F(TaaCli, PlanUnderTaaPlansTheSmallerKernel) {
  const std::string base = "name = \"s\"\ntargets = [\"glsl\"]\n";
  const std::string material = "[[material]]\nname = \"m\"\npath = \"forward\"\n";
  auto write = [&](const std::string& file, const std::string& text) {
    std::ofstream((scratch_ / file).string()) << text;
    return (scratch_ / file).string();
  };
  const auto keyed = saagen({"plan", write("taa.toml", base + "taa = true\n" + material), "--no-cost"});
  ASSERT_EQ(keyed.exit_code, 0) << keyed.err;
  EXPECT_NE(keyed.out.find("sigma2 = 0.0625 (taa = true;"), std::string::npos) << keyed.out;
  const auto flag = saagen({"plan", write("plain.toml", base + material), "--no-cost", "--taa"});
  ASSERT_EQ(flag.exit_code, 0) << flag.err;
  EXPECT_NE(flag.out.find("sigma2 = 0.0625 (taa = true;"), std::string::npos) << flag.out;
  const auto set = saagen({"plan", write("set.toml", base + "taa = true\nsigma2 = 0.25\n" + material), "--no-cost"});
  ASSERT_EQ(set.exit_code, 0) << set.err;
  EXPECT_NE(set.out.find("sigma2 = 0.25"), std::string::npos) << set.out;
  EXPECT_EQ(set.out.find("taa = true;"), std::string::npos) << set.out;
  const auto bad = saagen({"plan", write("bad.toml", base + "taa = \"yes\"\n" + material), "--no-cost"});
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("bad.toml:3:7: key 'taa': must be a boolean"), std::string::npos) << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
}
