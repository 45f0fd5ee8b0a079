// saagen ground-truth renderer: the quality trade table of the SAA variants.
//
// For every scene, GGX alpha, Fresnel switch and variant, the 1-spp image of the variant is
// compared with the ground truth of the same view (renderer.hpp):
//   rmse_linear      RMSE of linear specular radiance over all pixels;
//   rmse_tonemapped  RMSE after Reinhard's x / (1 + x) on both images (image.hpp);
//   max_error        the largest absolute linear error of a pixel;
//   flip_ldr         mean LDR-FLIP (Andersson et al. 2020) of the tonemapped images;
//   flip_hdr         mean HDR-FLIP (Andersson et al. 2021) of the linear images;
//   tde              temporal difference error (image.hpp, TemporalDifference): the animation
//                    below, in display values (display_image(): tonemap(), then the sRGB
//                    encoding LDR-FLIP takes); mean over pixels and consecutive frame pairs of
//                    |(I_t - I_{t-1}) - (R_t - R_{t-1})| of the 1-spp frames I against the
//                    ground-truth frames R (the pixel-level tLP of Chu et al. 2020, TecoGAN).
//                    0: the frames change as the converged animation does. Its parts:
//   tde_excess_flicker  mean max(0, |dI| - |dR|): change the ground truth does not make
//                    (aliasing: sub-pixel highlights popping from pixel to pixel);
//   tde_lost_motion  mean max(0, |dR| - |dI|): change the ground truth makes that is missing
//                    (a highlight blurred or clamped away, which a std ratio rewards);
//   flicker          per pixel, the temporal standard deviation of the variant's 1-spp frames
//                    minus that of the ground-truth frames, averaged over the pixels (linear
//                    values; image.hpp, flicker());
//   flicker_display  (secondary) the mean per-pixel temporal std of the tonemapped 1-spp frames
//                    divided by that of the tonemapped ground truth. A method that loses the
//                    moving highlight scores below 1 and looks "stable": the verdicts use tde.
//
// The animation (trade_animation_frame). Frame k of `frames`: the scene rotated about the
// vertical axis through its pivot by k times rotation_degrees_per_frame (make_scene), seen
// through the camera translated parallel to its film by (k - (frames - 1) / 2) times
// pan_pixels_per_frame (right, up), in pixels of the flicker resolution measured at the look-at
// distance (Camera::panned). The rotation alone moves little on screen (the torus turns under a
// highlight that stays nearly fixed, the sphere slides slowly about its off-centre pivot); the pan slides every sub-pixel highlight across
// the pixel grid by a fraction of a pixel per frame (0.11, 0.37 by default: the sub-pixel phase does not repeat within 32 frames), the
// motion at which 1-spp specular aliasing shimmers. It is mostly vertical, across the sideways slide of the sphere's off-centre rotation
// rather than against it, and centred on the unpanned view so that the shapes stay in frame.
//
// Flicker ground truth. 32 converged frames at the full resolution and 1024 spp would cost 32
// times the main ground truth, so the animation is rendered at flicker_width x flicker_height
// (default 128 x 128, half the main resolution) with flicker_strata^2 samples per pixel (default
// 16^2 = 256), and the 1-spp frames of the variants at that same resolution. Every frame uses
// the same per-pixel sample pattern (the pixel seeds do not depend on the frame), so the
// ground truth's residual Monte-Carlo error is correlated from frame to frame and changes only
// as the surface moves under the pattern: its temporal standard deviation measures mostly the
// motion of the converged image, not sampler noise. Measured at 128 x 128 over 8 frames of the
// rotation alone (before the pan), the mean temporal standard deviation of the ground truth at
// 256 spp is within 2 % of the 1024-spp value for every scene and alpha except the bump plane
// at alpha = 0.01 (0.84 at 256 spp, 0.69 at 1024, 1.19 at 64: its sub-pixel glints are not
// converged), so that case's flicker is biased low by ~0.15-0.25 (against 1-spp standard
// deviations of 0.5 - 2.3). Set flicker_strata = 32 for 1024 spp (4 x the cost).
//
// Ground-truth images can be cached on disk (cache_dir): one file per (scene, rotation, camera
// (hence the pan), size, samples, seed, filter, material list), named by a 64-bit FNV-1a hash of a text key holding
// every one of those numbers (and a format version); the key is stored in the file and
// compared on load, so a hash collision or a stale file only costs a re-render; so does a file
// whose pixels do not match the FNV-1a checksum stored with them (a corrupted file).
//
// A ground truth is checked before it is measured against: one holding a non-finite pixel, or
// black in every material (nothing of the scene lit in view: a camera scaled to nothing, an
// asset at one point), is a TradeError naming the scene, not a measurement in which every
// configuration errs by 0.
//
// Under TAA (TradeConfig::taa; taa.hpp). Each configuration (no SAA, every variant with its
// feeds, prefilters and lobes, every engine form) is also run through the TAA resolve as a row
// "CONFIGURATION+taa" ("forward-aniso-projected+taa/tail"): the animation at the flicker
// resolution, each 1-spp frame rendered with the Halton jitter (so the filters' derivatives come
// from the jittered quads), resolved with the history reprojected by the exact motion. A
// warm-up of taa_warmup_frames (default: one jitter cycle) before the animation's frame 0 fills
// the history; then, over the `frames` measured frames, the row's image metrics are means over
// the frames against each frame's ground truth (rmse_*, flip_ldr = flip_ldr_animation;
// max_error the largest; flip_hdr of the last frame) and its temporal ones are those of the
// resolved frames (tde and its parts, flicker), directly comparable with the rows without TAA.
// Every row without TAA gets the same flip_ldr_animation (mean LDR-FLIP of its 1-spp frames
// against the frames' ground truths), the figure to compare with a +taa row's flip_ldr (its own
// flip_ldr is frame 0's at the main resolution). The ground truths do not depend on the lobe.
#pragma once

#include "saagen/reference/quad.hpp"
#include "saagen/reference/render/animation_error.hpp"
#include "saagen/reference/render/image.hpp"
#include "saagen/reference/render/renderer.hpp"
#include "saagen/reference/render/scene.hpp"
#include "saagen/reference/render/taa.hpp"
#include "saagen/reference/saa.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace saagen::render {

// A measurement that cannot be made (a degenerate ground truth): one line naming the scene.
class TradeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// saagen's variants, the no-SAA baseline and the engines' shipped forms.
std::vector<Variant> default_trade_variants();

// A scene measured at other sizes than the config's (TradeConfig::scene_sizes): the presets'
// glTF assets and CC0 normal-map scenes at fewer pixels, so that they fit the preset's time.
struct TradeSceneSize {
  SceneId scene = SceneId::sphere;
  int width = 0, height = 0, strata = 0;                          // main image and ground truth
  int flicker_width = 0, flicker_height = 0, flicker_strata = 0;  // animation
};

struct TradeConfig {
  int width = 256;
  int height = 256;
  int strata = 32;  // main ground truth: strata^2 = 1024 spp
  int flicker_width = 128;
  int flicker_height = 128;
  int flicker_strata = 16;  // flicker ground truth: 256 spp
  int frames = 32;          // 0 disables the temporal metrics (tde, flicker = 0)
  double rotation_degrees_per_frame = 0.25;
  // Camera translation per frame parallel to the film, (right, up) in flicker-resolution
  // pixels at the look-at distance (see the top of this file).
  Vec2 pan_pixels_per_frame{0.11, 0.37};
  std::vector<SceneId> scenes{SceneId::sphere, SceneId::torus, SceneId::tubes, SceneId::bump_plane};
  // Scenes with sizes of their own (the first entry of a scene counts); the others use the above.
  std::vector<TradeSceneSize> scene_sizes;
  std::vector<double> alphas{0.01, 0.05, 0.1, 0.3};
  std::vector<bool> fresnel_modes{false, true};
  std::vector<Variant> variants = default_trade_variants();
  // The normals the normal-based variants are fed (engines always read their own). The
  // geometric feed only adds rows on scenes with normal detail (normal maps, bump plane),
  // where it differs from the shading feed.
  std::vector<NormalFeed> feeds{NormalFeed::shading, NormalFeed::geometric};
  // On normal-mapped scenes: these variants fed the geometric normal (curvature) with the map's
  // detail prefiltered into roughness, the engines' recommended split; `none` with a
  // prefilter is texture prefiltering alone. Toksvig and LEAN, then the engines' bakes of the
  // mean-normal length (Unreal, Filament, HDRP; docs/PREFILTER.md compares them).
  std::vector<Prefilter> prefilters{Prefilter::toksvig, Prefilter::lean, Prefilter::unreal, Prefilter::filament_vmf, Prefilter::hdrp};
  std::vector<Variant> prefiltered_variants{
      Variant::none,         Variant::forward_aniso_projected,  Variant::forward_axis_projected, Variant::deferred_sum,
      Variant::deferred_avg, Variant::deferred_projected_space, Variant::deferred_aniso};
  double prefilter_scale = 1.0;  // multiplies the texture term (renderer.hpp)
  // The normal map's LOD bias of the prefiltered rows ("+FORM"): their normal and its bake (the
  // mean normal's length, LEAN's moments) are sampled this many levels coarser than the implicit
  // LOD; the other rows (no SAA, the engines, the filters without a bake) keep the implicit LOD.
  // 1: the level whose texels span two pixels, whose box has a zero at the pixel grid's Nyquist
  // frequency (0.5 cycles per pixel), so that the normal variation the grid cannot show goes into
  // the bake instead of aliasing under the widened lobe (docs/PREFILTER.md, "The LOD bias").
  double prefilter_lod_bias = 1.0;
  // The lobes the filters' roughness is evaluated with (renderer.hpp, Lobe): every variant in
  // `variants` and `prefiltered_variants` with the papers' GGX; those also in `lobe_variants`
  // once more with each further lobe here (rows "VARIANT/tail", "VARIANT/mapped").
  std::vector<Lobe> lobes{Lobe::tail, Lobe::mapped};
  std::vector<Variant> lobe_variants{Variant::forward_aniso_projected,
                                     Variant::forward_axis_projected,
                                     Variant::deferred_max,
                                     Variant::deferred_sum,
                                     Variant::deferred_avg,
                                     Variant::deferred_projected_space,
                                     Variant::deferred_aniso};
  ref::Params params{};
  ref::Derivative derivative = ref::Derivative::coarse;
  std::uint64_t seed = 0x5aa6e11ULL;
  int threads = 0;           // 0: hardware concurrency
  std::string cache_dir;     // empty: no ground-truth cache
  bool keep_images = false;  // fill TradeTable::images
  bool flip = true;          // compute the FLIP metrics (flip.hpp; ~80 ms per row at 256^2)
  // The +taa rows (see the top of this file); needs frames >= 2.
  bool taa = false;
  TaaOptions taa_options{};
  int taa_warmup_frames = 0;  // frames resolved before frame 0; 0: one jitter cycle
  // The animation's ground truth is rendered with this many seeds (1 or 2): with two, every
  // verdict metric is measured against each and averaged, and their spread is the ground truth's
  // Monte-Carlo error in every interval (animation_error.hpp, ground_truth_spread()).
  int ground_truth_seeds = 2;
  // The sanity suite (TradeTable::sanity; needs frames >= 2 and two ground-truth seeds).
  bool sanity = true;
  // The video metric (video_vdp.hpp): every clip's ColorVideoVDP JOD against each seed's ground
  // truth clip, on the 8-bit display values `saagen bench --frames` writes, played at this rate
  // (the animation has none of its own) on the display standard_fhd.
  bool video_metric = true;
  double clip_frames_per_second = 30.0;
};

// The per-frame values behind a row's verdict metrics, against each ground-truth seed ([0]: the
// config's seed, [1]: the second seed; empty without it): the image error of every frame and the
// flicker error of every frame pair (animation_error.hpp). Comparisons pair them frame by frame.
struct AnimationSeries {
  SeedSeries image;
  SeedSeries flicker;
  // The video metric's loss, 10 - JOD (ColorVideoVDP; lower is better, 0 = no visible
  // difference): one value per seed for the whole clip, empty without the video metric.
  SeedSeries video;
  // The lag of every frame after the first (animation_error.hpp, lag_error): > 0 where the frame
  // is closer to the ground truth's previous frame than to its own.
  SeedSeries lag;
};

// The results of the sanity suite, whose ranking is known before any metric is computed: the
// converged animation with another seed and with a quarter of its samples must rank best; the
// others are degenerate and must rank clearly worse (the ground truth moves) and never win.
enum class SanityResult { other_seed, quarter_samples, delayed, blurred, frozen, no_highlight };
inline constexpr std::array<SanityResult, 6> kSanityResults = {SanityResult::other_seed, SanityResult::quarter_samples,
                                                               SanityResult::delayed,    SanityResult::blurred,
                                                               SanityResult::frozen,     SanityResult::no_highlight};
std::string_view sanity_name(SanityResult result);  // "other-seed", ...
// The 1 px Gaussian of the blurred result (standard deviation in pixels of the animation).
inline constexpr double kSanityBlurSigma = 1.0;

// One sanity result on one (scene, material), against the config's ground-truth seed only (the
// results are made from the second seed's frames, or a third seed's, never from the reference's).
struct SanityRow {
  SceneId scene = SceneId::sphere;
  double alpha = 0.0;
  bool fresnel = false;
  SanityResult result = SanityResult::other_seed;
  double image_error = 0.0;
  double flicker_error = 0.0;
  double video_error = 0.0;  // 10 - JOD
  double lag = 0.0;          // mean lag (animation_error.hpp)
  AnimationSeries series;    // [0] only
};

struct TradeRow {
  Variant variant = Variant::none;
  NormalFeed feed = NormalFeed::shading;
  Prefilter prefilter = Prefilter::none;
  Lobe lobe = Lobe::papers;
  SceneId scene = SceneId::sphere;
  double alpha = 0.0;
  bool fresnel = false;
  double rmse_linear = 0.0;
  double rmse_tonemapped = 0.0;
  double max_error = 0.0;
  // FLIP (flip.hpp): LDR-FLIP of the tonemapped images (tonemap(), then the sRGB encoding FLIP
  // expects) and HDR-FLIP of the linear images; means of the per-pixel error maps.
  double flip_ldr = 0.0;
  double flip_hdr = 0.0;
  // Temporal difference error of the display-value animation and its two parts (image.hpp,
  // TemporalError): the motion criterion.
  double tde = 0.0;
  double tde_excess_flicker = 0.0;
  double tde_lost_motion = 0.0;
  double flicker = 0.0;
  double temporal_stddev = 0.0;            // mean per-pixel temporal std of the variant
  double reference_temporal_stddev = 0.0;  // the same for the ground truth
  // Display-referred flicker: the mean per-pixel temporal std of the tonemapped frames
  // (tonemap(), image.hpp), of the variant and of the ground truth, and their ratio
  // (1: flickers as much as the converged animation; > 1: aliasing; < 1: overblurred motion).
  double temporal_stddev_display = 0.0;
  double reference_temporal_stddev_display = 0.0;
  double flicker_display = 0.0;  // temporal_stddev_display / reference's
  std::size_t non_finite = 0;    // NaN/inf pixels of the frame-0 image (excluded)
  // The configuration resolved by TAA (configuration id "...+taa"; see the top of this file).
  bool taa = false;
  // Mean LDR-FLIP of the measured animation frames against their ground truths (flicker
  // resolution): the image_error against the config's seed alone.
  double flip_ldr_animation = 0.0;
  // The verdict's metrics (animation_error.hpp), means over the animation and over the
  // ground-truth seeds, with 95 % intervals (over frame blocks, widened by the ground truth's
  // seed-to-seed spread): image_error (LDR-FLIP per frame) and flicker_error (pooled change).
  Interval image_error;
  Interval flicker_error;
  // The video metric: 10 - the ColorVideoVDP JOD of the clip (video_vdp.hpp), mean over the
  // seeds with its interval (the ground truth's spread); all 0 without it (TradeConfig).
  Interval video_error;
  // The mean lag (animation_error.hpp, lag_error) over the frames and seeds, with its interval.
  Interval lag;
  double flicker_excess = 0.0;  // flicker_error's parts, means over pairs and seeds
  double flicker_missing = 0.0;
  AnimationSeries series;
};

// The images behind the rows of one (scene, material): frame 0 at the main resolution.
struct ImageSet {
  SceneId scene = SceneId::sphere;
  Material material;
  Image reference;  // ground truth
  Image coverage;   // fraction of the ground-truth samples that hit the shape
  struct Rendered {
    Variant variant;
    NormalFeed feed;
    Prefilter prefilter;
    Lobe lobe;
    Image image;
  };
  std::vector<Rendered> variants;  // 1-spp images, in row order
};

struct TradeTable {
  TradeConfig config;
  std::vector<TradeRow> rows;              // scene-major, then alpha, Fresnel, variant (config order)
  std::vector<ImageSet> images;            // when config.keep_images
  double ground_truth_seconds = 0.0;       // wall time spent rendering ground truths
  std::uint64_t ground_truth_samples = 0;  // samples rendered (cache hits excluded)
  int cache_hits = 0;
  int cache_misses = 0;
  // When config.keep_images and config.taa: per (scene, material), the animation's last frame at
  // the flicker resolution: its ground truth and every +taa row's resolved image, in row order.
  std::vector<ImageSet> taa_images;
  // The sanity suite's rows (TradeConfig::sanity): per scene and material, each SanityResult.
  std::vector<SanityRow> sanity;

  const TradeRow* find(Variant variant, SceneId scene, double alpha, bool fresnel, NormalFeed feed = NormalFeed::shading,
                       Prefilter prefilter = Prefilter::none, Lobe lobe = Lobe::papers, bool taa = false) const;
};

struct TradeProgress {
  std::string stage;       // e.g. "ground truth sphere", "flicker torus frame 3/32"
  std::uint64_t done = 0;  // work units: ground-truth samples + 1-spp pixel shadings
  std::uint64_t total = 0;
};

// Called on the calling thread, at most about every 100 ms and at each stage change.
using TradeProgressFn = std::function<void(const TradeProgress&)>;

// One clip of the animation, as the trade measured it (display values, display_image()), handed
// to an observer frame by frame: the ground truth's ("ground-truth"), every row's (its
// configuration id) and every sanity result's ("sanity:NAME"). Called on the calling thread.
struct AnimationFrame {
  SceneId scene = SceneId::sphere;
  double alpha = 0.0;
  bool fresnel = false;
  std::string clip;  // "ground-truth", a configuration id, or "sanity:NAME"
  int frame = 0;
  const Image* display = nullptr;
};
using AnimationFrameFn = std::function<void(const AnimationFrame&)>;

TradeTable compute_trade_table(const TradeConfig& config, const TradeProgressFn& progress = {}, const AnimationFrameFn& frames = {});
// The config with a scene's own sizes (TradeConfig::scene_sizes) in width ... flicker_strata.
TradeConfig sized_for_scene(const TradeConfig& config, SceneId id);
// The ground truth a sized config (sized_for_scene) renders: its main image's settings, or with
// `animation` its animation frames' (flicker_width, flicker_height, flicker_strata).
GroundTruthSettings ground_truth_settings(const TradeConfig& sized, bool animation = false);

// Frame `frame` of the animation the temporal metrics measure (see the top of this file).
Scene trade_animation_frame(const TradeConfig& config, SceneId id, int frame);

// The materials of a configuration in table order: for each alpha, for each Fresnel mode.
std::vector<Material> trade_materials(const TradeConfig& config);

// Ground truth through the disk cache (render_ground_truth when cache_dir is empty or the
// entry is missing or stale). *cache_hit (when given) tells which happened.
GroundTruth cached_ground_truth(const Scene& scene, const GroundTruthSettings& settings, std::span<const Material> materials,
                                const std::string& cache_dir, const SampleProgress& progress = {}, bool* cache_hit = nullptr);

// How a ground-truth cache file is written: (path, bytes), failures ignored (the cache is an
// optimisation). By default a temporary beside the path, renamed over it; a program with an
// output layer passes its own (the CLI's removes the temporary on a signal that ends the
// process). An empty writer restores the default.
using CacheFileWriter = std::function<void(const std::filesystem::path& path, const std::string& bytes)>;
void set_ground_truth_cache_writer(CacheFileWriter writer);

// The cache key text and its file name ("gt-<16 hex digits>.bin").
std::string ground_truth_cache_key(const Scene& scene, const GroundTruthSettings& settings, std::span<const Material> materials);
std::string ground_truth_cache_file(const std::string& key);

// The configuration a row measures: the variant id, with ":geometric" appended when a saagen
// variant is fed the geometric normal, and "+toksvig" / "+lean" with a prefiltered normal map
// ("deferred-avg", "deferred-avg:geometric", "deferred-avg:geometric+lean", "none+toksvig",
// "engine-hdrp"), and "/tail" or "/mapped" for a lobe other than the papers'
// ("forward-aniso-projected/tail", "deferred-avg:geometric+lean/mapped"), and "+taa" before the
// lobe under TAA ("none+taa", "deferred-avg:geometric+lean+taa").
std::string configuration_id(Variant variant, NormalFeed feed, Prefilter prefilter = Prefilter::none, Lobe lobe = Lobe::papers,
                             bool taa = false);
std::string configuration_id(const TradeRow& row);

// Whether a scene has normal detail beyond its geometry (normal map or bump shading), i.e.
// whether the geometric and the shading normal differ.
bool scene_has_normal_detail(SceneId id);
// Whether that detail comes from a normal map texture (which prefiltering needs).
bool scene_has_normal_map(SceneId id);
// Whether that detail is procedural with closed-form footprint moments (Shape::
// footprint_slope_moments: the bump plane's sum of sines). Such a scene gets the prefiltered rows
// of config.prefiltered_variants with LEAN only (renderer.hpp, Prefilter), if config.prefilters
// lists it: the procedural shader band-limited to its footprint, LEAN's moments in closed form.
bool scene_has_procedural_normals(SceneId id);

// Fixed-width text table and CSV of the rows.
std::string format_trade_table(const TradeTable& table);
std::string trade_table_csv(const TradeTable& table);

}  // namespace saagen::render
