// prefilter_flicker: where a normal-map bake's temporal difference error (TDE) comes from, on the
// trade's animation of a normal-mapped scene (docs/PREFILTER.md, "The LOD bias").
//
//   prefilter_flicker [--preset full|medium] [--cache DIR] [--dump DIR] [SCENE]   (default: full, nmap-sphere)
//
// Per configuration: the main image's LDR-FLIP (frame 0) and the animation's TDE with its excess
// flicker and lost motion, means over the preset's six alphas without Fresnel, against the
// ground truths `saagen bench --preset P` caches (rendered when the cache lacks them). The bake is
// HDRP's (`+hdrp`) on forward-axis-projected:geometric/tail unless a line says otherwise; each
// experiment changes one thing in the G-buffer the bake's row shades:
//   bake of the texel roughness  HDRP's stored form: the per-texel bake filtered trilinearly,
//                                not the bake of the filtered mean normal's length;
//   bake level -1 / +1           the mean normal's length (L) read one level finer / coarser, the
//                                normal at the implicit LOD;
//   constant bake                every mapped pixel the frame's mean bake (no spatial variation);
//   footprint bake               L of the level-0 normals under the ground truth's Gaussian pixel
//                                filter (9 x 9 taps over +-2 sigma through the quad's uv
//                                derivatives): the bake's value where the pixel really looks;
//   half bake                    prefilter scale 0.5;
//   normal and bake +B           both sampled B levels coarser (TradeConfig::prefilter_lod_bias);
// and two references for the TDE: a frozen image (E|dR|, the TDE of an image that never changes)
// and the ground truth's own noise (E|R_a - R_b| of one frame rendered with two seeds).
// --dump DIR writes the first alpha's frames 10 and 11 of the ground truth and of every
// configuration (numbered as printed, from 00) as 8-bit PGM display images.
#include "saagen/measure/flip.hpp"
#include "saagen/measure/render.hpp"
#include "saagen/reference/prefilter.hpp"
#include "saagen/report/report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

using namespace saagen;
using namespace saagen::measure;

namespace {

using Modify = std::function<void(GBuffer&, const NormalMap&)>;

struct Case {
  std::string label;
  Variant variant;
  NormalFeed feed;
  Prefilter prefilter;
  Lobe lobe;
  double scale = 1.0;
  Modify modify = {};  // changes the G-buffer the row shades; empty: the trade's own (bias 0)
  double bias = 0.0;
};

double hdrp_term(double length) { return ref::hdrp_texture_alpha2(0.0, length); }

// The mean-normal length whose HDRP term is v (hdrp_term decreases with L): bisection.
double length_of_hdrp_term(double v) {
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (hdrp_term(mid) > v ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

void set_length(PixelFields& f, double length) { f.texel.mean_normal = length * ref::normalize(f.texel.mean_normal); }

double bilinear_hdrp_term(const NormalMap& map, int level, Vec2 uv) {
  const double fx = uv.x * map.width(level) - 0.5, fy = uv.y * map.height(level) - 0.5;
  const double x0 = std::floor(fx), y0 = std::floor(fy), ax = fx - x0, ay = fy - y0;
  const int ix = static_cast<int>(x0), iy = static_cast<int>(y0);
  const auto v = [&](int x, int y) { return hdrp_term(ref::length(map.texel(level, x, y).mean_normal)); };
  return (1 - ax) * (1 - ay) * v(ix, iy) + ax * (1 - ay) * v(ix + 1, iy) + (1 - ax) * ay * v(ix, iy + 1) + ax * ay * v(ix + 1, iy + 1);
}

void texel_roughness_bake(GBuffer& g, const NormalMap& map) {
  for (PixelFields& f : g.pixels) {
    if (!f.has_normal_map) continue;
    const double lambda = std::clamp(f.lod, 0.0, static_cast<double>(map.levels() - 1));
    const int d = static_cast<int>(std::floor(lambda));
    const double t = lambda - d;
    double v = bilinear_hdrp_term(map, d, f.uv);
    if (t > 0.0 && d + 1 < map.levels()) v = (1.0 - t) * v + t * bilinear_hdrp_term(map, d + 1, f.uv);
    set_length(f, length_of_hdrp_term(v));
  }
}

Modify bake_level(double offset) {
  return [offset](GBuffer& g, const NormalMap& map) {
    for (PixelFields& f : g.pixels)
      if (f.has_normal_map) f.texel.mean_normal = map.trilinear(f.uv, f.lod + offset).mean_normal;
  };
}

void constant_bake(GBuffer& g, const NormalMap&) {
  double sum = 0.0;
  int count = 0;
  for (const PixelFields& f : g.pixels)
    if (f.has_normal_map) sum += hdrp_term(ref::length(f.texel.mean_normal)), ++count;
  if (count == 0) return;
  const double length = length_of_hdrp_term(sum / count);
  for (PixelFields& f : g.pixels)
    if (f.has_normal_map) set_length(f, length);
}

Vec3 level0_normal(const NormalMap& map, Vec2 uv) {
  const double fx = uv.x * map.width(0) - 0.5, fy = uv.y * map.height(0) - 0.5;
  const double x0 = std::floor(fx), y0 = std::floor(fy), ax = fx - x0, ay = fy - y0;
  const int ix = static_cast<int>(x0), iy = static_cast<int>(y0);
  return ref::normalize(((1 - ax) * (1 - ay)) * map.texel(0, ix, iy).normal + (ax * (1 - ay)) * map.texel(0, ix + 1, iy).normal +
                        ((1 - ax) * ay) * map.texel(0, ix, iy + 1).normal + (ax * ay) * map.texel(0, ix + 1, iy + 1).normal);
}

void footprint_bake(GBuffer& g, const NormalMap& map) {
  const double sigma = std::sqrt(default_pixel_filter().variance());
  for (PixelFields& f : g.pixels) {
    if (!f.has_normal_map) continue;
    Vec3 sum{0.0, 0.0, 0.0};
    double weights = 0.0;
    for (int i = -4; i <= 4; ++i)
      for (int j = -4; j <= 4; ++j) {
        const double w = std::exp(-0.5 * (i * i + j * j) / 4.0);  // taps sigma / 2 apart
        const Vec2 uv = f.uv + (0.5 * sigma * i) * f.duv_dx + (0.5 * sigma * j) * f.duv_dy;
        sum = sum + w * level0_normal(map, uv);
        weights += w;
      }
    f.texel.mean_normal = (1.0 / weights) * sum;
  }
}

std::vector<Case> cases() {
  const auto G = NormalFeed::geometric, S = NormalFeed::shading;
  const auto fap = Variant::forward_axis_projected;
  return {
      {"none", Variant::none, S, Prefilter::none, Lobe::papers},
      {"engine-hdrp", Variant::engine_hdrp, G, Prefilter::none, Lobe::papers},
      {"forward-axis-projected:geometric/tail (no bake)", fap, G, Prefilter::none, Lobe::tail},
      {"bake (+hdrp, bias 0)", fap, G, Prefilter::hdrp, Lobe::tail},
      {"bake of the texel roughness", fap, G, Prefilter::hdrp, Lobe::tail, 1.0, texel_roughness_bake},
      {"bake level -1", fap, G, Prefilter::hdrp, Lobe::tail, 1.0, bake_level(-1.0)},
      {"bake level +1", fap, G, Prefilter::hdrp, Lobe::tail, 1.0, bake_level(1.0)},
      {"constant bake", fap, G, Prefilter::hdrp, Lobe::tail, 1.0, constant_bake},
      {"footprint bake", fap, G, Prefilter::hdrp, Lobe::tail, 1.0, footprint_bake},
      {"half bake", fap, G, Prefilter::hdrp, Lobe::tail, 0.5},
      {"normal and bake +0.5", fap, G, Prefilter::hdrp, Lobe::tail, 1.0, {}, 0.5},
      {"normal and bake +1 (+hdrp, bias 1)", fap, G, Prefilter::hdrp, Lobe::tail, 1.0, {}, 1.0},
      {"deferred-sum:geometric+hdrp/tail, bias 1", Variant::deferred_sum, G, Prefilter::hdrp, Lobe::tail, 1.0, {}, 1.0},
      {"none+hdrp, bias 1", Variant::none, S, Prefilter::hdrp, Lobe::papers, 1.0, {}, 1.0},
  };
}

// The trade's own preset (the ground-truth cache keys depend on every number in it).
TradeConfig preset(const std::string& name) {
  if (name != "medium" && name != "full") throw std::invalid_argument("prefilter_flicker: --preset full or medium");
  return saagen::report::preset_config(name);
}

GBuffer case_buffer(const Case& c, const Scene& scene, int width, int height, const NormalMap& map) {
  GBuffer g = render_gbuffer(scene, width, height, 0, c.bias);
  if (c.modify) c.modify(g, map);
  return g;
}

// An 8-bit PGM of display values in [0, 1] (--dump: the first alpha's frames 10 and 11).
void write_pgm(const std::string& path, const Image& display) {
  std::ofstream out(path, std::ios::binary);
  out << "P5\n" << display.width << " " << display.height << "\n255\n";
  for (std::size_t i = 0; i < display.size(); ++i)
    out.put(static_cast<char>(std::lround(255.0 * std::clamp(static_cast<double>(display.pixels[i]), 0.0, 1.0))));
  if (!out) throw std::runtime_error("prefilter_flicker: cannot write " + path);
}

double mean_abs_difference(const Image& a, const Image& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += std::fabs(static_cast<double>(a.pixels[i]) - b.pixels[i]);
  return sum / static_cast<double>(a.size());
}

struct Options {
  std::string preset = "full", cache, scene = "nmap-sphere", dump;
};

Options parse_options(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--preset" && i + 1 < argc) {
      options.preset = argv[++i];
    } else if (arg == "--dump" && i + 1 < argc) {
      options.dump = argv[++i];
    } else if (arg == "--cache" && i + 1 < argc) {
      options.cache = argv[++i];
    } else {
      options.scene = arg;
    }
  }
  return options;
}

// What every pass measures: the scene at the preset's sizes, the materials without Fresnel (one
// per alpha) and the cases.
struct Run {
  Options options;
  SceneId id;
  TradeConfig config;
  std::vector<Material> materials;
  std::vector<std::size_t> measured;  // the materials without Fresnel
  std::shared_ptr<const NormalMap> map;
  std::vector<Case> all;

  std::size_t n() const { return measured.size(); }
  Image render(const Case& c, const GBuffer& g, std::size_t material) const {
    return render_variant(g, c.variant, materials[material], config.params, config.derivative, 0, c.feed, c.prefilter, c.scale, c.lobe);
  }
};

Run make_run(const Options& options) {
  const std::optional<SceneId> id = scene_from_name(options.scene);
  if (!id || (*id != SceneId::nmap_sphere && *id != SceneId::nmap_sphere_fine))
    throw std::invalid_argument("prefilter_flicker: " + options.scene + " is not nmap-sphere or nmap-sphere-fine");
  Run run{options, *id, sized_for_scene(preset(options.preset), *id), {}, {}, content_normal_map(), cases()};
  run.materials = trade_materials(run.config);
  for (std::size_t m = 0; m < run.materials.size(); ++m)
    if (!run.materials[m].fresnel) run.measured.push_back(m);
  return run;
}

// Each case's LDR-FLIP against the main ground truth, the mean over the materials.
std::vector<double> first_frame_flip(const Run& run) {
  const Scene scene = make_scene(run.id, 0.0);
  const GroundTruth main_gt = cached_ground_truth(scene, ground_truth_settings(run.config), run.materials, run.options.cache);
  std::vector<double> flip(run.all.size(), 0.0);
  for (std::size_t c = 0; c < run.all.size(); ++c) {
    const GBuffer g = case_buffer(run.all[c], scene, run.config.width, run.config.height, *run.map);
    for (std::size_t m : run.measured)
      flip[c] += ldr_flip_mean_grey(tonemapped(main_gt.images[m]), tonemapped(run.render(run.all[c], g, m))) / static_cast<double>(run.n());
  }
  return flip;
}

// The animation: each case's and material's frame-to-frame change against the ground truth's
// (row c * n + k), and the frozen image's mean |dR|.
struct Animation {
  std::vector<TemporalDifference> differences;
  double frozen = 0.0;
};

Animation animate(const Run& run) {
  const std::size_t n = run.n();
  const TradeConfig& config = run.config;
  const GroundTruthSettings flicker_settings = ground_truth_settings(config, true);
  Animation out{std::vector<TemporalDifference>(run.all.size() * n), 0.0};
  std::vector<Image> previous(run.all.size() * n), previous_reference(n);
  const bool dump = !run.options.dump.empty();
  for (int frame = 0; frame < config.frames; ++frame) {
    const Scene moved = trade_animation_frame(config, run.id, frame);
    const GroundTruth gt = cached_ground_truth(moved, flicker_settings, run.materials, run.options.cache);
    std::vector<Image> reference(n);
    for (std::size_t k = 0; k < n; ++k) {
      reference[k] = display_image(gt.images[run.measured[k]]);
      if (frame > 0) out.frozen += mean_abs_difference(reference[k], previous_reference[k]) / static_cast<double>(n * (config.frames - 1));
    }
    for (std::size_t c = 0; c < run.all.size(); ++c) {
      const GBuffer g = case_buffer(run.all[c], moved, config.flicker_width, config.flicker_height, *run.map);
      for (std::size_t k = 0; k < n; ++k) {
        const std::size_t r = c * n + k;
        Image image = display_image(run.render(run.all[c], g, run.measured[k]));
        if (frame > 0) out.differences[r].add_pair(previous[r], image, previous_reference[k], reference[k]);
        if (dump && k == 0 && (frame == 10 || frame == 11))
          write_pgm(fmt::format("{}/frame{}_case{:02}.pgm", run.options.dump, frame, c), image);
        previous[r] = std::move(image);
      }
    }
    if (dump && (frame == 10 || frame == 11)) write_pgm(fmt::format("{}/frame{}_ground_truth.pgm", run.options.dump, frame), reference[0]);
    previous_reference = std::move(reference);
  }
  return out;
}

// The ground truth's own noise: the middle frame rendered once more with another seed.
double ground_truth_noise(const Run& run) {
  const GroundTruthSettings flicker_settings = ground_truth_settings(run.config, true);
  const Scene middle = trade_animation_frame(run.config, run.id, run.config.frames / 2);
  const GroundTruth a = cached_ground_truth(middle, flicker_settings, run.materials, run.options.cache);
  GroundTruthSettings reseeded = flicker_settings;
  reseeded.seed = run.config.seed + 1;
  const GroundTruth b = render_ground_truth(middle, reseeded, run.materials);
  double noise = 0.0;
  for (std::size_t m : run.measured)
    noise += mean_abs_difference(display_image(a.images[m]), display_image(b.images[m])) / static_cast<double>(run.n());
  return noise;
}

void print_table(const Run& run, const std::vector<double>& flip, const Animation& animation, double noise) {
  const TradeConfig& config = run.config;
  const std::size_t n = run.n();
  fmt::print("{} {}: main {} px, animation {} frames at {} px ({} spp); means over {} alphas, no Fresnel\n", run.options.preset,
             run.options.scene, config.width, config.frames, config.flicker_width, config.flicker_strata * config.flicker_strata, n);
  fmt::print("{:<48} {:>8} {:>8} {:>8} {:>8}\n", "configuration", "LDR-FLIP", "TDE", "excess", "lost");
  for (std::size_t c = 0; c < run.all.size(); ++c) {
    TemporalError e;
    for (std::size_t k = 0; k < n; ++k) {
      const TemporalError one = animation.differences[c * n + k].mean();
      e.tde += one.tde / static_cast<double>(n);
      e.excess_flicker += one.excess_flicker / static_cast<double>(n);
      e.lost_motion += one.lost_motion / static_cast<double>(n);
    }
    fmt::print("{:<48} {:>8.4f} {:>8.5f} {:>8.5f} {:>8.5f}\n", run.all[c].label, flip[c], e.tde, e.excess_flicker, e.lost_motion);
  }
  fmt::print("{:<48} {:>8} {:>8.5f}\n", "frozen image (E|dR|)", "", animation.frozen);
  fmt::print("{:<48} {:>8} {:>8.5f}\n", "ground-truth noise (E|R_a - R_b|, one frame)", "", noise);
}

}  // namespace

int main(int argc, char** argv) try {
  const Run run = make_run(parse_options(argc, argv));
  const std::vector<double> flip = first_frame_flip(run);
  const Animation animation = animate(run);
  print_table(run, flip, animation, ground_truth_noise(run));
  return 0;
} catch (const std::exception& e) {
  fmt::print(stderr, "{}\n", e.what());
  return 1;
}
