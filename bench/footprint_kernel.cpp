// footprint_kernel: what the SAA kernel would be worth if it were the pixel footprint's own, on
// the medium preset's images and animation (docs/FILTERED_GGX.md, "The bump plane").
//
//   footprint_kernel [--cache DIR] [SCENE...]      (default: bump_plane; a scene's name or a .glb/.gltf asset)
//
// Per scene, alpha (the medium preset's six, no Fresnel) and configuration, the LDR-FLIP of
// frame 0 (128 px) against the 256-spp ground truth and the TDE of the 16-frame animation (64 px)
// against its 64-spp ground truths, as `saagen bench --preset medium` measures them (the ground
// truths come from the same cache; the trade's own renders otherwise):
//   none        the 1-spp image without SAA;
//   quad        forward-aniso-projected's kernel (coarse 2x2 quad derivatives of the projected
//               half vector) shaded with the exact filtered GGX (Lobe::exact);
//   stable      the kernel an oracle would give: 2 x the covariance of the half vector's slope
//               (h.xy / h.z in each sample's own tangent frame) over 8 x 8 sub-pixel rays placed
//               at the quantiles of the ground truth's Gaussian pixel filter (sigma 0.5 px, the
//               same pattern every frame), eigenvalues clamped to kappa, around the pixel
//               centre's half vector (exact filtered GGX);
//   bake        the same covariance around the footprint's mean slope instead of the centre's: the
//               filtered NDF a prefiltered normal field (LEAN's two moments at the footprint) gives;
//   band-limited  what a shader computes from one sample on procedural bumps (the trade's
//               forward-aniso-projected:geometric+lean rows, renderer.hpp PixelFields::
//               has_footprint_moments): the bump field's slope moments over the pixel filter's
//               footprint in closed form, the band-limited normal and 2 x their covariance plus the
//               geometric normal's kernel (exact filtered GGX). Scenes without procedural bumps
//               have no such moments: there it is the geometric-feed kernel alone.
// With each kernel, "kernel change": the mean over the animation's frame pairs and the pixels the
// ground truth lights in either frame (display value > 0.05) of |k_t - k_t-1| / max(k_t, k_t-1),
// k = tr(K) / 2: how much the kernel estimate itself moves from one frame to the next; for the
// quad kernel also the quantiles of its ratio to the stable kernel at those pixels.
// `stable` and `bake` cast 64 rays per pixel: they are measurements of what a temporally stable
// kernel and a bake could reach, not forms a shader evaluates from one sample.
#include "saagen/measure/flip.hpp"
#include "saagen/measure/gltf.hpp"
#include "saagen/measure/render.hpp"
#include "saagen/reference/brdf.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace {

namespace measure = saagen::measure;
namespace ref = saagen::ref;
using ref::Sym2;
using ref::Vec2;
using ref::Vec3;

constexpr int kMainSize = 128, kMainStrata = 16, kFlickerSize = 64, kFlickerStrata = 8, kFrames = 16;
constexpr int kFootprintRays = 8;  // per axis

// The medium preset's trade configuration (report::preset_config("medium"); the ground-truth cache
// keys depend on every one of these numbers).
measure::TradeConfig medium_config() {
  measure::TradeConfig config;
  config.width = config.height = kMainSize;
  config.strata = kMainStrata;
  config.flicker_width = config.flicker_height = kFlickerSize;
  config.flicker_strata = kFlickerStrata;
  config.frames = kFrames;
  config.rotation_degrees_per_frame = 0.5;
  config.alphas = {0.0025, 0.0064, 0.01, 0.05, 0.1, 0.3};
  config.fresnel_modes = {false};
  return config;
}

// The standard normal quantile by bisection of erfc (exact to double rounding; 64 calls per run).
double normal_quantile(double p) {
  double low = -9.0, high = 9.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (low + high);
    (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

struct Footprint {
  Vec2 mean;  // E[t], t = h.xy / h.z
  Sym2 covariance;
  int samples = 0;
};

// Per pixel, the moments of the half vector's slope over the filter-distributed sub-pixel rays.
std::vector<Footprint> footprints(const measure::Scene& scene, int size) {
  std::vector<Footprint> out(static_cast<std::size_t>(size) * size);
  std::vector<Sym2> second(out.size());
  for (int a = 0; a < kFootprintRays; ++a)
    for (int b = 0; b < kFootprintRays; ++b) {
      measure::Camera camera = scene.camera();
      camera.jitter = {0.5 * normal_quantile((a + 0.5) / kFootprintRays), 0.5 * normal_quantile((b + 0.5) / kFootprintRays)};
      const measure::Scene shifted = scene.with_camera(camera);
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
          const measure::PixelFields f = measure::pixel_fields(shifted, x, y, size, size);
          if (!f.hit || f.half_ts.z <= 0.0) continue;
          const std::size_t i = static_cast<std::size_t>(y) * size + x;
          const Vec2 t{f.half_ts.x / f.half_ts.z, f.half_ts.y / f.half_ts.z};
          out[i].mean = out[i].mean + t;
          second[i] = {second[i].xx + t.x * t.x, second[i].xy + t.x * t.y, second[i].yy + t.y * t.y};
          ++out[i].samples;
        }
    }
  for (std::size_t i = 0; i < out.size(); ++i) {
    Footprint& f = out[i];
    if (f.samples < 2) continue;
    const double n = f.samples;
    f.mean = f.mean / n;
    f.covariance = {second[i].xx / n - f.mean.x * f.mean.x, second[i].xy / n - f.mean.x * f.mean.y, second[i].yy / n - f.mean.y * f.mean.y};
  }
  return out;
}

// min(lambda, bound) on the eigenvalues of a symmetric 2x2 matrix (the forward forms' clamp).
Sym2 clamp_eigenvalues(Sym2 m, double bound) {
  const double half_trace = 0.5 * (m.xx + m.yy), half_difference = 0.5 * (m.xx - m.yy);
  const double spread = std::sqrt(half_difference * half_difference + m.xy * m.xy);
  const double large = half_trace + spread, small = half_trace - spread;
  if (large <= bound) return m;
  const double clamped_large = std::min(large, bound), clamped_small = std::min(std::max(small, 0.0), bound);
  if (spread <= 0.0) return {clamped_large, 0.0, clamped_large};
  // Projector onto the larger eigenvector: (M - small I) / (large - small).
  const Sym2 p{(m.xx - small) / (2.0 * spread), m.xy / (2.0 * spread), (m.yy - small) / (2.0 * spread)};
  return Sym2{clamped_small, 0.0, clamped_small} + (clamped_large - clamped_small) * p;
}

enum class Form { none, quad, stable, bake, band_limited };
constexpr Form kForms[] = {Form::none, Form::quad, Form::stable, Form::bake, Form::band_limited};

const char* form_name(Form form) {
  switch (form) {
    case Form::none:
      return "none";
    case Form::quad:
      return "quad kernel";
    case Form::stable:
      return "stable kernel";
    case Form::bake:
      return "bake";
    case Form::band_limited:
      return "band-limited";
  }
  return "?";
}

// The exact filtered GGX BRDF of the footprint kernel, centred on the pixel's half vector (stable)
// or on the footprint's mean slope (bake), with the centre's masking and cosines.
double footprint_brdf(const measure::PixelFields& f, const Footprint& footprint, double alpha2, double kappa, Form form) {
  const Sym2 kernel = clamp_eigenvalues(2.0 * footprint.covariance, kappa);
  const Sym2 a{alpha2 + kernel.xx, kernel.xy, alpha2 + kernel.yy};
  if (form == Form::stable) return ref::ggx_brdf_filtered_exact(f.light_ts, f.view_ts, a, {alpha2, alpha2});
  if (f.light_ts.z <= 0.0 || f.view_ts.z <= 0.0) return 0.0;
  const Vec2 t = footprint.mean;
  const double c = 1.0 / std::sqrt(1.0 + t.x * t.x + t.y * t.y);
  const double ndf = ref::ggx_ndf_filtered_exact({t.x * c, t.y * c, c}, a, {alpha2, alpha2});
  const Vec3 h = ref::normalize(f.light_ts + f.view_ts);
  return ndf * ref::ggx_g2_matrix(f.light_ts, f.view_ts, h, a) / (4.0 * f.light_ts.z * f.view_ts.z);
}

// The one-sample forms through the trade's own shading (exact filtered GGX): no SAA, the quad
// kernel on the shading normal, or the band-limited procedural bumps (geometric feed + LEAN).
measure::PixelShade one_sample_shade(const measure::GBuffer& gbuffer, int x, int y, const measure::Material& material, Form form) {
  const measure::Variant variant = form == Form::none ? measure::Variant::none : measure::Variant::forward_aniso_projected;
  const bool band_limited = form == Form::band_limited;
  return measure::shade_pixel(gbuffer, x, y, variant, material, ref::Params{}, ref::Derivative::coarse,
                              band_limited ? measure::NormalFeed::geometric : measure::NormalFeed::shading,
                              band_limited && gbuffer.at(x, y).has_footprint_moments ? measure::Prefilter::lean : measure::Prefilter::none,
                              1.0, measure::Lobe::exact);
}

measure::Image shade(const measure::GBuffer& gbuffer, const std::vector<Footprint>& footprint, const measure::Material& material,
                     Form form) {
  measure::Image image(gbuffer.width, gbuffer.height);
  const ref::Params params{};
  const double alpha2 = material.alpha * material.alpha;
  for (int y = 0; y < gbuffer.height; ++y)
    for (int x = 0; x < gbuffer.width; ++x) {
      const measure::PixelFields& f = gbuffer.at(x, y);
      if (!f.hit) continue;
      if (form == Form::none || form == Form::quad || form == Form::band_limited) {
        image.at(x, y) = static_cast<float>(one_sample_shade(gbuffer, x, y, material, form).radiance);
        continue;
      }
      const Footprint& fp = footprint[static_cast<std::size_t>(y) * gbuffer.width + x];
      if (fp.samples < 2) continue;
      const double brdf = footprint_brdf(f, fp, alpha2, params.kappa, form);
      image.at(x, y) =
          static_cast<float>(f.weight * measure::specular_radiance(brdf, f.light_ts, f.view_ts, f.irradiance, material.fresnel));
    }
  return image;
}

// tr(K) / 2 of a form's kernel at a pixel (-1: no kernel there).
double half_trace_kernel(const measure::GBuffer& gbuffer, const std::vector<Footprint>& footprint, const measure::Material& material, int x,
                         int y, Form form) {
  if (!gbuffer.at(x, y).hit) return -1.0;
  const ref::Params params{};
  const double alpha2 = material.alpha * material.alpha;
  if (form == Form::quad || form == Form::band_limited) {
    const Sym2 a = one_sample_shade(gbuffer, x, y, material, form).roughness;
    return 0.5 * (a.xx + a.yy) - alpha2;
  }
  const Footprint& fp = footprint[static_cast<std::size_t>(y) * gbuffer.width + x];
  if (fp.samples < 2) return -1.0;
  const Sym2 k = clamp_eigenvalues(2.0 * fp.covariance, params.kappa);
  return 0.5 * (k.xx + k.yy);
}

measure::SceneId scene_id(const std::string& name) {
  if (name.ends_with(".glb") || name.ends_with(".gltf")) return measure::register_gltf_scene(name);
  for (measure::SceneId id : measure::all_scenes())
    if (measure::scene_name(id) == name) return id;
  for (measure::SceneId id : measure::content_scenes())
    if (measure::scene_name(id) == name) return id;
  throw std::invalid_argument("unknown scene '" + name + "'");
}

// One scene's frame-0 inputs and animation inputs.
struct SceneInputs {
  measure::GroundTruth ground_truth;
  measure::GBuffer gbuffer;
  std::vector<Footprint> footprint;
  std::vector<measure::GroundTruth> frame_truths;
  std::vector<measure::GBuffer> frame_gbuffers;
  std::vector<std::vector<Footprint>> frame_footprints;
};

SceneInputs scene_inputs(const measure::TradeConfig& config, measure::SceneId id, const std::vector<measure::Material>& materials,
                         const std::string& cache) {
  measure::GroundTruthSettings main_settings;
  main_settings.width = main_settings.height = kMainSize;
  main_settings.strata = kMainStrata;
  main_settings.seed = config.seed;
  measure::GroundTruthSettings flicker_settings = main_settings;
  flicker_settings.width = flicker_settings.height = kFlickerSize;
  flicker_settings.strata = kFlickerStrata;
  SceneInputs in;
  const measure::Scene scene = measure::make_scene(id, 0.0);
  in.ground_truth = measure::cached_ground_truth(scene, main_settings, materials, cache);
  in.gbuffer = measure::render_gbuffer(scene, kMainSize, kMainSize, 0);
  in.footprint = footprints(scene, kMainSize);
  for (int frame = 0; frame < kFrames; ++frame) {
    const measure::Scene moved = measure::trade_animation_frame(config, id, frame);
    in.frame_truths.push_back(measure::cached_ground_truth(moved, flicker_settings, materials, cache));
    in.frame_gbuffers.push_back(measure::render_gbuffer(moved, kFlickerSize, kFlickerSize, 0));
    in.frame_footprints.push_back(footprints(moved, kFlickerSize));
  }
  return in;
}

// The kernel's mean relative change between consecutive frames at the pixels the ground truth lights.
double kernel_change(const SceneInputs& in, const measure::Material& material, const std::vector<measure::Image>& truths, Form form) {
  constexpr double kLit = 0.05;
  double sum = 0.0;
  std::size_t count = 0;
  std::vector<double> previous;
  for (int frame = 0; frame < kFrames; ++frame) {
    std::vector<double> current(static_cast<std::size_t>(kFlickerSize) * kFlickerSize);
    for (int y = 0; y < kFlickerSize; ++y)
      for (int x = 0; x < kFlickerSize; ++x)
        current[static_cast<std::size_t>(y) * kFlickerSize + x] =
            half_trace_kernel(in.frame_gbuffers[frame], in.frame_footprints[frame], material, x, y, form);
    for (std::size_t i = 0; frame > 0 && i < current.size(); ++i) {
      const double larger = std::max(current[i], previous[i]);
      const bool lit = std::max(truths[frame].pixels[i], truths[frame - 1].pixels[i]) > kLit;
      if (current[i] < 0.0 || previous[i] < 0.0 || larger <= 0.0 || !lit) continue;
      sum += std::fabs(current[i] - previous[i]) / larger;
      ++count;
    }
    previous = std::move(current);
  }
  return count ? sum / static_cast<double>(count) : 0.0;
}

// Quantiles (10, 50, 90, 99 %) of the quad kernel over the stable (footprint) kernel, tr(K) / 2,
// at the pixels the ground truth lights, over the animation's frames.
std::string kernel_ratio(const SceneInputs& in, const measure::Material& material, const std::vector<measure::Image>& truths) {
  constexpr double kLit = 0.05;
  std::vector<double> ratios;
  for (int frame = 0; frame < kFrames; ++frame)
    for (int y = 0; y < kFlickerSize; ++y)
      for (int x = 0; x < kFlickerSize; ++x) {
        if (truths[frame].pixels[static_cast<std::size_t>(y) * kFlickerSize + x] <= kLit) continue;
        const double quad = half_trace_kernel(in.frame_gbuffers[frame], in.frame_footprints[frame], material, x, y, Form::quad);
        const double stable = half_trace_kernel(in.frame_gbuffers[frame], in.frame_footprints[frame], material, x, y, Form::stable);
        if (quad < 0.0 || stable <= 0.0) continue;
        ratios.push_back(quad / stable);
      }
  if (ratios.empty()) return "-";
  std::sort(ratios.begin(), ratios.end());
  const auto at = [&](double q) { return ratios[static_cast<std::size_t>(q * static_cast<double>(ratios.size() - 1))]; };
  return fmt::format("{:.2f} / {:.2f} / {:.2f} / {:.2f} (n {})", at(0.1), at(0.5), at(0.9), at(0.99), ratios.size());
}

void measure_scene(const measure::TradeConfig& config, const std::string& name, const std::string& cache) {
  const std::vector<measure::Material> materials = measure::trade_materials(config);
  const SceneInputs in = scene_inputs(config, scene_id(name), materials, cache);
  fmt::print(
      "\n### {}\n\n| form | alpha | LDR-FLIP | TDE | excess flicker | lost motion | kernel change |\n|---|---:|---:|---:|---:|---:|---:|\n",
      name);
  for (Form form : kForms) {
    double flip_sum = 0.0, tde_sum = 0.0;
    for (std::size_t m = 0; m < materials.size(); ++m) {
      const double flip = measure::ldr_flip_mean_grey(tonemapped(in.ground_truth.images[m]),
                                                      tonemapped(shade(in.gbuffer, in.footprint, materials[m], form)));
      std::vector<measure::Image> frames, truths;
      for (int frame = 0; frame < kFrames; ++frame) {
        frames.push_back(measure::display_image(shade(in.frame_gbuffers[frame], in.frame_footprints[frame], materials[m], form)));
        truths.push_back(measure::display_image(in.frame_truths[frame].images[m]));
      }
      const measure::TemporalError temporal = measure::temporal_difference_error(frames, truths);
      std::string change = form == Form::none ? "" : fmt::format("{:.3f}", kernel_change(in, materials[m], truths, form));
      if (form == Form::quad) change += "; quad / stable " + kernel_ratio(in, materials[m], truths);
      fmt::print("| {} | {} | {:.4f} | {:.5f} | {:.5f} | {:.5f} | {} |\n", form_name(form), materials[m].alpha, flip, temporal.tde,
                 temporal.excess_flicker, temporal.lost_motion, change);
      flip_sum += flip;
      tde_sum += temporal.tde;
    }
    const double n = static_cast<double>(materials.size());
    fmt::print("| **{}** | mean | **{:.4f}** | **{:.5f}** | | |\n", form_name(form), flip_sum / n, tde_sum / n);
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::string cache;
    std::vector<std::string> scenes;
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      if (arg == "--cache" && i + 1 < argc) {
        cache = argv[++i];
      } else if (arg.rfind("--", 0) == 0) {
        throw std::invalid_argument("unknown option '" + arg + "'; usage: footprint_kernel [--cache DIR] [SCENE...]");
      } else {
        scenes.push_back(arg);
      }
    }
    if (scenes.empty()) scenes.push_back("bump_plane");
    const measure::TradeConfig config = medium_config();
    for (const std::string& name : scenes) measure_scene(config, name, cache);
    return 0;
  } catch (const std::exception& e) {
    fmt::print(stderr, "footprint_kernel: {}\n", e.what());
    return 1;
  }
}
