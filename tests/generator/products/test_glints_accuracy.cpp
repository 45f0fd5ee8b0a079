// Accuracy: the glinty BRDF at one sample per pixel with and without GGAA, and with LEAN
// (rho) / LEAN (rho = 0) / no LEAN, against a supersampled ground truth, in the issue-4 renderer's
// scenes (saagen::measure: analytic shapes, cameras, lights, the sigma^2 = 0.25 Gaussian pixel
// filter, the image metrics and the flicker metric).
//
// Ground truth of a pixel (2021 Eq. 9): the patch P is the pixel's footprint (uv and its screen
// derivatives at the pixel centre fix the LOD, the cells and their random transforms); the
// glinty BRDF of that patch, unfiltered (textureLod), is averaged over strata^2 rays distributed
// by the pixel filter, each with its own hit point, tangent frame, light and view directions
// (and, with a normal map, its own normal-map slope). GGAA approximates exactly this average
// by a convolution in slope space. The 1-spp images evaluate the same patch at the pixel centre
// with ddx/ddy taken as a GPU does (fine 2x2-quad differences; a partner pixel off the surface or
// on another tube contributes no difference, as in the renderer).
//
// Metrics (saagen::measure): RMSE of linear radiance relative to the RMS of the ground truth (in
// percent), the RMSE after Reinhard's tonemap, and the temporal flicker of an animation (the
// shape turns about the vertical axis; mean per-pixel temporal standard deviation of the 1-spp
// frames minus that of the ground-truth frames).
#include "support/glint_support.hpp"

#include "saagen/measure/render.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <functional>
#include <iostream>

namespace {

namespace g = saagen::ref::glints;
namespace r = saagen::measure;
using saagen::ref::Vec2;
using saagen::ref::Vec3;

// ---------------------------------------------------------------------------------------------
// Surface parameterisation (uv) of the renderer's shapes, consistent with their tangent frames.

Vec2 surface_uv(const r::Scene& scene, r::SceneId id, const r::SurfaceHit& hit) {
  const Vec3 p = scene.object_to_world().inverse_point(hit.position);
  if (id == r::SceneId::sphere) {
    // Stereographic coordinates from the pole -z: the conformal map whose x axis the
    // sphere's tangent field follows.
    return {p.x / (1.0 + p.z), p.y / (1.0 + p.z)};
  }
  // Tubes (9 tubes, radius 0.05, spacing 0.22; axes along object x): u along the axis, v the
  // arc length around it, each tube offset by 1 in v.
  const double axis_y = (hit.object - 4) * 0.22;
  return {p.x, 0.05 * std::atan2(p.z, p.y - axis_y) + hit.object};
}

struct Sample {
  bool hit = false;
  int object = 0;
  Vec2 uv;
  Vec3 light_ts, view_ts;
  double irradiance = 0.0;
};

Sample trace(const r::Scene& scene, r::SceneId id, double fx, double fy, int width, int height) {
  Sample s;
  const r::Ray ray = scene.camera().generate(fx, fy, width, height);
  r::SurfaceHit hit;
  if (!scene.intersect(ray, hit)) return s;
  s.hit = true;
  s.object = hit.object;
  s.uv = surface_uv(scene, id, hit);
  Vec3 to_light;
  scene.light().at(hit.position, to_light, s.irradiance);
  const Vec3 to_view = -ray.direction;
  const auto tangent_space = [&](Vec3 v) {
    return Vec3{saagen::ref::dot(v, hit.tangent), saagen::ref::dot(v, hit.bitangent), saagen::ref::dot(v, hit.normal)};
  };
  s.light_ts = tangent_space(to_light);
  s.view_ts = tangent_space(to_view);
  return s;
}

// ---------------------------------------------------------------------------------------------
// A normal map for LEAN: grooves (slopes along d = (cos 30 deg, sin 30 deg) in the tangent frame,
// a sin(2 pi d.uv / period)) stored as a texture over uv in [-1, 1]^2 with its moment MIP chain.

struct NormalMap {
  int size = 0;
  std::vector<saagen::glints::MomentLevel> levels;

  // Texel coordinate of uv at level 0 (the texture covers [-1, 1]^2, repeated).
  double texels_per_uv() const { return size / 2.0; }

  // Bilinear moments at a level (repeat addressing).
  std::array<double, 5> bilinear(int level, Vec2 uv) const {
    const auto& l = levels[static_cast<std::size_t>(level)];
    const double x = (uv.x + 1.0) * 0.5 * l.width - 0.5, y = (uv.y + 1.0) * 0.5 * l.height - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    const double ax = x - fx, ay = y - fy;
    std::array<double, 5> result{};
    for (int dy = 0; dy < 2; ++dy) {
      for (int dx = 0; dx < 2; ++dx) {
        const int ix = ((static_cast<int>(fx) + dx) % l.width + l.width) % l.width;
        const int iy = ((static_cast<int>(fy) + dy) % l.height + l.height) % l.height;
        const double w = (dx ? ax : 1.0 - ax) * (dy ? ay : 1.0 - ay);
        for (int k = 0; k < 5; ++k) result[k] += w * l.moments[(static_cast<std::size_t>(iy) * l.width + ix) * 5 + k];
      }
    }
    return result;
  }
  // Trilinear moments for a footprint (isotropic LOD, as a GPU's trilinear filter).
  std::array<double, 5> filtered(Vec2 uv, Vec2 duv_dx, Vec2 duv_dy) const {
    const double rho = std::max(saagen::ref::length(duv_dx), saagen::ref::length(duv_dy)) * texels_per_uv();
    const double lod = std::clamp(std::log2(std::max(rho, 1e-30)), 0.0, levels.size() - 1.0);
    const int lo = static_cast<int>(std::floor(lod));
    const int hi = std::min(lo + 1, static_cast<int>(levels.size()) - 1);
    const double t = lod - lo;
    const auto a = bilinear(lo, uv), b = bilinear(hi, uv);
    std::array<double, 5> result{};
    for (int k = 0; k < 5; ++k) result[k] = (1.0 - t) * a[k] + t * b[k];
    return result;
  }
  // The unfiltered slope at a point (level 0, bilinear): what the ground truth sees.
  Vec2 slope(Vec2 uv) const {
    const auto m = bilinear(0, uv);
    return {m[0], m[1]};
  }
};

NormalMap make_normal_map(int size, double period_texels, double amplitude) {
  const double angle = 30.0 * M_PI / 180.0;
  const Vec2 d{std::cos(angle), std::sin(angle)};
  const double period = period_texels * 2.0 / size;
  saagen::glints::SlopeMap map{size, size, {}};
  map.slopes.reserve(static_cast<std::size_t>(size) * size * 2);
  for (int j = 0; j < size; ++j) {
    for (int i = 0; i < size; ++i) {
      const Vec2 uv{-1.0 + (i + 0.5) * 2.0 / size, -1.0 + (j + 0.5) * 2.0 / size};
      const double s = amplitude * std::sin(2.0 * M_PI * saagen::ref::dot(d, uv) / period);
      map.slopes.push_back(s * d.x);
      map.slopes.push_back(s * d.y);
    }
  }
  return {size, saagen::glints::lean_moments(map)};
}

// ---------------------------------------------------------------------------------------------
// Rendering

enum class Shading {
  lod,             // the 2020 model: textureLod, no GGAA
  ggaa_projected,  // GGAA, Eq. 21 (derivatives of h.xy)
  ggaa_slope,      // GGAA, Eq. 20 (derivatives of the half slope)
};

enum class Lean {
  none,      // no normal map
  naive,     // "no LEAN": the MIP-filtered mean slope only
  rho_zero,  // LEAN variances, correlation dropped
  full,      // LEAN with rho (Eq. 18)
};

struct Material {
  g::Roughness roughness{0.15, 0.15, 0.0};
  double log_density = 16.0;
};

struct View {
  const r::Scene* scene = nullptr;
  r::SceneId id = r::SceneId::sphere;
  int width = 128, height = 128;
};

struct Pixel {
  Sample centre;
  Vec2 duv_dx, duv_dy;  // fine quad differences
  Vec2 dproj_dx, dproj_dy;
  Vec2 dslope_dx, dslope_dy;
};

Vec3 half_ts(const Sample& s) { return saagen::ref::normalize(s.light_ts + s.view_ts); }

std::vector<Pixel> centre_pixels(const View& view) {
  std::vector<Sample> samples(static_cast<std::size_t>(view.width) * view.height);
  r::parallel_rows(view.height, 0, [&](int y) {
    for (int x = 0; x < view.width; ++x) {
      samples[static_cast<std::size_t>(y) * view.width + x] = trace(*view.scene, view.id, x + 0.5, y + 0.5, view.width, view.height);
    }
  });
  std::vector<Pixel> pixels(samples.size());
  for (int y = 0; y < view.height; ++y) {
    for (int x = 0; x < view.width; ++x) {
      Pixel& p = pixels[static_cast<std::size_t>(y) * view.width + x];
      p.centre = samples[static_cast<std::size_t>(y) * view.width + x];
      if (!p.centre.hit) continue;
      // Fine derivatives: the difference across the quad's row / column containing the pixel.
      const auto partner_difference = [&](int qx, int qy, bool along_x, Vec2& duv, Vec2& dproj, Vec2& dslope) {
        duv = dproj = dslope = {};
        if (qx >= view.width || qy >= view.height) return;
        const Sample& other = samples[static_cast<std::size_t>(qy) * view.width + qx];
        if (!other.hit || other.object != p.centre.object) return;
        const bool other_first = along_x ? qx < x : qy < y;
        const Sample& first = other_first ? other : p.centre;
        const Sample& second = other_first ? p.centre : other;
        duv = second.uv - first.uv;
        const Vec3 h1 = half_ts(first), h2 = half_ts(second);
        dproj = h2.xy() - h1.xy();
        dslope = g::half_slope(second.light_ts, second.view_ts) - g::half_slope(first.light_ts, first.view_ts);
      };
      partner_difference(x ^ 1, y, true, p.duv_dx, p.dproj_dx, p.dslope_dx);
      partner_difference(x, y ^ 1, false, p.duv_dy, p.dproj_dy, p.dslope_dy);
    }
  }
  return pixels;
}

// The roughness and mean slope a 1-spp pixel uses for a LEAN mode.
void lean_inputs(const NormalMap* map, Lean lean, const Material& material, const Pixel& p, g::Roughness& roughness, Vec2& mean) {
  roughness = material.roughness;
  mean = {};
  if (lean == Lean::none || !map) return;
  const auto m = map->filtered(p.centre.uv, p.duv_dx, p.duv_dy);
  mean = {m[0], m[1]};
  if (lean == Lean::naive) return;
  roughness = g::lean_roughness({material.roughness.alpha_x, material.roughness.alpha_y}, mean, {m[2], m[3], m[4]});
  if (lean == Lean::rho_zero) roughness.rho = 0.0;
}

r::Image render_one_spp(const View& view, const std::vector<Pixel>& pixels, const g::Dictionary& dictionary, const Material& material,
                        Shading shading, const NormalMap* map = nullptr, Lean lean = Lean::none) {
  r::Image image(view.width, view.height);
  r::parallel_rows(view.height, 0, [&](int y) {
    for (int x = 0; x < view.width; ++x) {
      const Pixel& p = pixels[static_cast<std::size_t>(y) * view.width + x];
      if (!p.centre.hit || p.centre.light_ts.z <= 0.0) continue;
      g::Roughness roughness;
      Vec2 mean;
      lean_inputs(map, lean, material, p, roughness, mean);
      const auto patch = g::make_patch(dictionary, p.centre.uv, p.duv_dx, p.duv_dy, material.log_density);
      const Sample& s = p.centre;
      double f = 0.0;
      if (shading == Shading::lod)
        f = g::patch_brdf(dictionary, patch, s.light_ts, s.view_ts, mean, roughness);
      else if (shading == Shading::ggaa_projected)
        f = g::patch_brdf_filtered(dictionary, patch, s.light_ts, s.view_ts, mean, p.dproj_dx, p.dproj_dy, roughness);
      else
        f = g::patch_brdf_filtered(dictionary, patch, s.light_ts, s.view_ts, mean, p.dslope_dx, p.dslope_dy, roughness);
      image.at(x, y) = static_cast<float>(f * s.light_ts.z * s.irradiance);
    }
  });
  return image;
}

// Ground truth: the pixel's patch, strata^2 filter-distributed rays.
r::Image render_ground_truth(const View& view, const std::vector<Pixel>& pixels, const g::Dictionary& dictionary, const Material& material,
                             int strata, const NormalMap* map = nullptr, std::uint64_t seed = 0x61177ULL) {
  r::Image image(view.width, view.height);
  const r::GaussianPixelFilter& filter = r::default_pixel_filter();
  r::parallel_rows(view.height, 0, [&](int y) {
    std::vector<r::FilmOffset> offsets;
    for (int x = 0; x < view.width; ++x) {
      const Pixel& p = pixels[static_cast<std::size_t>(y) * view.width + x];
      if (!p.centre.hit) continue;
      const auto patch = g::make_patch(dictionary, p.centre.uv, p.duv_dx, p.duv_dy, material.log_density);
      r::Rng rng(r::pixel_seed(seed, x, y));
      r::stratified_filter_offsets(filter, strata, rng, offsets);
      double sum = 0.0;
      for (const r::FilmOffset& off : offsets) {
        const Sample s = trace(*view.scene, view.id, x + 0.5 + off.dx, y + 0.5 + off.dy, view.width, view.height);
        if (!s.hit || s.light_ts.z <= 0.0) continue;
        const Vec2 mean = map ? map->slope(s.uv) : Vec2{};
        sum += g::patch_brdf(dictionary, patch, s.light_ts, s.view_ts, mean, material.roughness) * s.light_ts.z * s.irradiance;
      }
      image.at(x, y) = static_cast<float>(sum / offsets.size());
    }
  });
  return image;
}

struct Score {
  double rmse_percent = 0.0;     // RMSE / RMS(ground truth), linear radiance
  double rmse_tonemapped = 0.0;  // RMSE after x / (1 + x), in percent of the [0, 1) range
};

Score score(const r::Image& image, const r::Image& truth) {
  const r::ImageError error = r::compare_images(image, truth);
  return {100.0 * error.rmse_linear / r::rms(truth), 100.0 * error.rmse_tonemapped};
}

g::Dictionary dictionary_with_kernel(double kernel_scale) {
  g::Dictionary dictionary = saagen::test::default_reference_dictionary();
  dictionary.params.kernel_scale = kernel_scale;
  return dictionary;
}

// ---------------------------------------------------------------------------------------------
// GGAA: RMSE and flicker with and without, on curved glinty surfaces.

struct GgaaCase {
  r::SceneId scene;
  Material material;
};

TEST(GlintAccuracy, GgaaLowersRmseAndFlickerOnCurvedSurfaces) {
  const GgaaCase cases[] = {
      {r::SceneId::tubes, {{0.1, 0.1, 0.0}, 17.0}},
      {r::SceneId::sphere, {{0.1, 0.1, 0.0}, 16.0}},
  };
  for (const GgaaCase& c : cases) {
    const r::Scene scene = r::make_scene(c.scene, 0.0);
    const View view{&scene, c.scene, 128, 128};
    const auto pixels = centre_pixels(view);
    const auto truth = render_ground_truth(view, pixels, dictionary_with_kernel(0.5), c.material, 32);
    // Monte-Carlo noise of the truth: two independent 256-spp truths differ by sqrt(2) times
    // the noise of one; a 1024-spp truth has half of it.
    const double noise = 0.5 / std::sqrt(2.0) *
                         score(render_ground_truth(view, pixels, dictionary_with_kernel(0.5), c.material, 16, nullptr, 1),
                               render_ground_truth(view, pixels, dictionary_with_kernel(0.5), c.material, 16, nullptr, 2))
                             .rmse_percent;
    const Score lod = score(render_one_spp(view, pixels, dictionary_with_kernel(0.5), c.material, Shading::lod), truth);
    const Score projected = score(render_one_spp(view, pixels, dictionary_with_kernel(0.5), c.material, Shading::ggaa_projected), truth);
    const Score slope = score(render_one_spp(view, pixels, dictionary_with_kernel(0.5), c.material, Shading::ggaa_slope), truth);
    const Score projected_wide =
        score(render_one_spp(view, pixels, dictionary_with_kernel(1.0), c.material, Shading::ggaa_projected), truth);
    const Score slope_wide = score(render_one_spp(view, pixels, dictionary_with_kernel(1.0), c.material, Shading::ggaa_slope), truth);

    // Flicker: 16 frames at 64 x 64, 0.25 degrees per frame; ground truth 8^2 spp per frame.
    const int frames = 16;
    r::TemporalStats truth_stats(64, 64), lod_stats(64, 64), projected_stats(64, 64), slope_stats(64, 64), wide_stats(64, 64);
    for (int frame = 0; frame < frames; ++frame) {
      const r::Scene moving = r::make_scene(c.scene, frame * 0.25 * M_PI / 180.0);
      const View small{&moving, c.scene, 64, 64};
      const auto frame_pixels = centre_pixels(small);
      truth_stats.add(render_ground_truth(small, frame_pixels, dictionary_with_kernel(0.5), c.material, 8));
      lod_stats.add(render_one_spp(small, frame_pixels, dictionary_with_kernel(0.5), c.material, Shading::lod));
      projected_stats.add(render_one_spp(small, frame_pixels, dictionary_with_kernel(0.5), c.material, Shading::ggaa_projected));
      slope_stats.add(render_one_spp(small, frame_pixels, dictionary_with_kernel(0.5), c.material, Shading::ggaa_slope));
      wide_stats.add(render_one_spp(small, frame_pixels, dictionary_with_kernel(1.0), c.material, Shading::ggaa_projected));
    }
    const double rms_truth = r::rms(truth);
    std::cout << fmt::format(
        "[ ggaa     ] {} (alpha {}, ln density {}), 128x128, ground truth 1024 spp (its noise ~{:.2f} %); RMSE % of RMS(truth) (tonemapped RMSE %):\n"
        "[ ggaa     ]   no GGAA {:.2f} ({:.3f}); GGAA Eq. 21 s_K 0.5 {:.2f} ({:.3f}), s_K 1 {:.2f} ({:.3f}); Eq. 20 s_K 0.5 {:.2f} ({:.3f}), s_K 1 {:.2f} ({:.3f})\n"
        "[ ggaa     ]   flicker (64x64, 16 frames, truth 64 spp; mean temporal std minus the truth's, x 1e3, truth's own {:.3f}e-3; RMS(truth) {:.3f}): no GGAA {:.3f}, Eq. 21 {:.3f} (s_K 1: {:.3f}), Eq. 20 {:.3f}\n",
        r::scene_name(c.scene), c.material.roughness.alpha_x, c.material.log_density, noise, lod.rmse_percent, lod.rmse_tonemapped,
        projected.rmse_percent, projected.rmse_tonemapped, projected_wide.rmse_percent, projected_wide.rmse_tonemapped, slope.rmse_percent,
        slope.rmse_tonemapped, slope_wide.rmse_percent, slope_wide.rmse_tonemapped, 1e3 * r::mean_temporal_stddev(truth_stats), rms_truth,
        1e3 * r::flicker(lod_stats, truth_stats), 1e3 * r::flicker(projected_stats, truth_stats), 1e3 * r::flicker(wide_stats, truth_stats),
        1e3 * r::flicker(slope_stats, truth_stats));
    // The paper's ordering (Chermain et al. 2021 Fig. 8, 9): GGAA below the baseline.
    EXPECT_LT(projected.rmse_percent, lod.rmse_percent) << r::scene_name(c.scene);
    EXPECT_LT(slope.rmse_percent, lod.rmse_percent) << r::scene_name(c.scene);
    EXPECT_LT(r::flicker(projected_stats, truth_stats), r::flicker(lod_stats, truth_stats)) << r::scene_name(c.scene);
  }
}

// ---------------------------------------------------------------------------------------------
// Level-coherent seeds (Chermain et al. 2020 Eq. 8) under a slow zoom, two ways over 32 frames:
//   - zoom: the texture scale grows by 2^(1/64) per frame about the screen centre (uv and its
//     derivatives scaled): the glints move and the footprint's LOD crosses level boundaries;
//   - LOD sweep: only the footprint grows (uv fixed): what changes is the LOD alone, i.e. the
//     transitions that coherent seeds are meant to steady.
// With coherent seeds a cell shares its distributions, rotation and LOD offset with its corner
// child; without (the seed mixes the level in) every transition blends unrelated glints.
// Measured: the mean per-pixel temporal standard deviation of the 1-spp frames (the motion and
// the shading are the same in both runs), and the flicker as in the trade report (that minus the
// ground truth's, 16 spp per frame, the truth carrying the same seeds).

std::vector<Pixel> scaled(std::vector<Pixel> pixels, double uv_scale, double footprint_scale) {
  for (Pixel& p : pixels) {
    p.centre.uv = p.centre.uv * uv_scale;
    p.duv_dx = p.duv_dx * footprint_scale;
    p.duv_dy = p.duv_dy * footprint_scale;
  }
  return pixels;
}

TEST(GlintAccuracy, LevelCoherentSeedsUnderASlowZoom) {
  const r::Scene scene = r::make_scene(r::SceneId::sphere, 0.0);
  const View view{&scene, r::SceneId::sphere, 64, 64};
  const auto pixels = centre_pixels(view);
  const Material material{{0.1, 0.1, 0.0}, 16.0};
  double temporal[2][2][2] = {};  // [sweep][coherent][GGAA]
  double flicker[2][2][2] = {};
  for (const bool sweep : {false, true}) {
    for (const bool coherent : {true, false}) {
      g::Dictionary dictionary = dictionary_with_kernel(0.5);
      dictionary.params.coherent_seeds = coherent;
      r::TemporalStats lod_stats(64, 64), ggaa_stats(64, 64), truth_stats(64, 64);
      for (int frame = 0; frame < 32; ++frame) {
        const double zoom = std::exp2(frame / 64.0);
        const auto frame_pixels = scaled(pixels, sweep ? 1.0 : zoom, zoom);
        lod_stats.add(render_one_spp(view, frame_pixels, dictionary, material, Shading::lod));
        ggaa_stats.add(render_one_spp(view, frame_pixels, dictionary, material, Shading::ggaa_projected));
        // The truth evaluates each pixel's (scaled) patch over 16 filter-distributed rays.
        truth_stats.add(render_ground_truth(view, frame_pixels, dictionary, material, 4));
      }
      temporal[sweep][coherent][0] = r::mean_temporal_stddev(lod_stats);
      temporal[sweep][coherent][1] = r::mean_temporal_stddev(ggaa_stats);
      flicker[sweep][coherent][0] = r::flicker(lod_stats, truth_stats);
      flicker[sweep][coherent][1] = r::flicker(ggaa_stats, truth_stats);
    }
    std::cout << fmt::format(
        "[ zoom     ] sphere 64x64, alpha 0.1, ln density 16, 32 frames of 2^(1/64), {}; mean temporal std x 1e3: "
        "coherent seeds: no GGAA {:.3f}, GGAA Eq. 21 {:.3f}; level mixed into the seed: no GGAA {:.3f}, GGAA {:.3f}\n",
        sweep ? "LOD sweep (footprint only)" : "zoom (uv and footprint)", 1e3 * temporal[sweep][1][0], 1e3 * temporal[sweep][1][1],
        1e3 * temporal[sweep][0][0], 1e3 * temporal[sweep][0][1]);
    std::cout << fmt::format(
        "[ zoom     ]   flicker (minus the 16-spp truth's, x 1e3): coherent: no GGAA {:.3f}, GGAA {:.3f}; level mixed in: no GGAA {:.3f}, "
        "GGAA {:.3f}\n",
        1e3 * flicker[sweep][1][0], 1e3 * flicker[sweep][1][1], 1e3 * flicker[sweep][0][0], 1e3 * flicker[sweep][0][1]);
  }
  // Where only the LOD changes, coherent seeds change the image less.
  EXPECT_LT(temporal[1][1][0], temporal[1][0][0]);
  EXPECT_LT(temporal[1][1][1], temporal[1][0][1]);
}

// ---------------------------------------------------------------------------------------------
// LEAN: a glinty sphere with an anisotropic normal map (grooves at 30 degrees to the tangent).

TEST(GlintAccuracy, LeanWithRhoBeatsRhoZeroAndNoLean) {
  const r::Scene scene = r::make_scene(r::SceneId::sphere, 0.0);
  const View view{&scene, r::SceneId::sphere, 128, 128};
  const NormalMap map = make_normal_map(1024, 4.0, 0.25);
  const Material material{{0.06, 0.06, 0.0}, 18.0};
  const auto pixels = centre_pixels(view);
  const auto dictionary = dictionary_with_kernel(0.5);
  const auto truth = render_ground_truth(view, pixels, dictionary, material, 32, &map);
  const double noise = 0.5 / std::sqrt(2.0) *
                       score(render_ground_truth(view, pixels, dictionary, material, 16, &map, 1),
                             render_ground_truth(view, pixels, dictionary, material, 16, &map, 2))
                           .rmse_percent;
  const Score full_wide =
      score(render_one_spp(view, pixels, dictionary_with_kernel(1.0), material, Shading::ggaa_projected, &map, Lean::full), truth);
  const Score none = score(render_one_spp(view, pixels, dictionary, material, Shading::ggaa_projected, &map, Lean::naive), truth);
  const Score rho_zero = score(render_one_spp(view, pixels, dictionary, material, Shading::ggaa_projected, &map, Lean::rho_zero), truth);
  const Score full = score(render_one_spp(view, pixels, dictionary, material, Shading::ggaa_projected, &map, Lean::full), truth);
  const Score full_lod = score(render_one_spp(view, pixels, dictionary, material, Shading::lod, &map, Lean::full), truth);
  std::cout << fmt::format(
      "[ lean     ] sphere, grooves at 30 deg (slope amplitude 0.25, period 4 texels of 1024), alpha {}, ln density {}, GGAA Eq. 21;\n"
      "[ lean     ]   RMSE % of RMS(truth) (tonemapped RMSE %): no LEAN {:.2f} ({:.3f}), LEAN rho = 0 {:.2f} ({:.3f}), LEAN with rho {:.2f} ({:.3f}); "
      "LEAN with rho without GGAA {:.2f} ({:.3f}), with GGAA s_K 1 {:.2f} ({:.3f}); truth 1024 spp, its noise ~{:.2f} %\n",
      material.roughness.alpha_x, material.log_density, none.rmse_percent, none.rmse_tonemapped, rho_zero.rmse_percent,
      rho_zero.rmse_tonemapped, full.rmse_percent, full.rmse_tonemapped, full_lod.rmse_percent, full_lod.rmse_tonemapped,
      full_wide.rmse_percent, full_wide.rmse_tonemapped, noise);
  // The paper's ordering (Chermain et al. 2021 Fig. 7): LEAN with rho is the closest.
  EXPECT_LT(full.rmse_percent, rho_zero.rmse_percent);
  EXPECT_LT(full.rmse_percent, none.rmse_percent);
}

}  // namespace
