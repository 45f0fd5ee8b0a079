// saagen ground-truth renderer: the speed/accuracy trade's data (trade.hpp measures it): the
// configuration (TradeConfig), the rows it measures (TradeRow, with their per-frame series and the
// sanity suite's rows), the images behind them and the table; and the animation the temporal
// metrics measure, frame by frame. trade.cpp and its private parts (trade_clips, trade_taa) share
// these.
#pragma once

#include "saagen/measure/animation_error.hpp"
#include "saagen/measure/image.hpp"
#include "saagen/measure/renderer.hpp"
#include "saagen/measure/scene.hpp"
#include "saagen/measure/taa.hpp"
#include "saagen/reference/quad.hpp"
#include "saagen/reference/saa.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace saagen {
struct MeasuredTradeTable;  // saagen/scene/cost_tables.hpp
}

namespace saagen::measure {

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
  // The frame the forward filters difference their half vectors in (renderer.hpp, HalfVectorFrame):
  // the transported wrappers, which saagen's plans call (generator/data/advice.json).
  HalfVectorFrame half_vector_frame = HalfVectorFrame::transported;
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

// A trade row's scalar metrics (trade.hpp defines each): one measured row's (TradeRow), or their
// means over a set of rows (report::Metrics, whose max_error is the largest of the rows').
struct RowMetrics {
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
  // Secondary: the tonemapped temporal std over the ground truth's (TradeRow's
  // temporal_stddev_display / reference_temporal_stddev_display).
  double flicker_display = 0.0;
};

// The scalar metrics by name (the trade JSON's keys), in declaration order.
struct RowMetricField {
  std::string_view name;
  double RowMetrics::*value;
};
inline constexpr RowMetricField kRowMetricFields[] = {{"rmse_linear", &RowMetrics::rmse_linear},
                                                      {"rmse_tonemapped", &RowMetrics::rmse_tonemapped},
                                                      {"max_error", &RowMetrics::max_error},
                                                      {"flip_ldr", &RowMetrics::flip_ldr},
                                                      {"flip_hdr", &RowMetrics::flip_hdr},
                                                      {"tde", &RowMetrics::tde},
                                                      {"tde_excess_flicker", &RowMetrics::tde_excess_flicker},
                                                      {"tde_lost_motion", &RowMetrics::tde_lost_motion},
                                                      {"flicker", &RowMetrics::flicker},
                                                      {"flicker_display", &RowMetrics::flicker_display}};

// The metrics over a set of rows: add_over_rows() adds each row's to `over` (max_error keeps the
// largest), then means_over_rows() divides the sums by the number of rows (none: left at 0).
inline void add_over_rows(RowMetrics& over, const RowMetrics& row) {
  for (const RowMetricField& field : kRowMetricFields)
    over.*field.value =
        field.value == &RowMetrics::max_error ? std::max(over.*field.value, row.*field.value) : over.*field.value + row.*field.value;
}
inline void means_over_rows(RowMetrics& over, std::size_t rows) {
  if (rows == 0) return;
  for (const RowMetricField& field : kRowMetricFields)
    if (field.value != &RowMetrics::max_error) over.*field.value /= static_cast<double>(rows);
}

// The verdict's metrics (animation_error.hpp): image_error (LDR-FLIP per animation frame),
// flicker_error (pooled change) and video_error (10 - the ColorVideoVDP JOD of the clip,
// video_vdp.hpp; 0 without the video metric, TradeConfig). `Estimate` is Interval in a measured
// row (TradeRow) and double, the intervals' means, in a mean over rows (report::Metrics).
template <typename Estimate>
struct VerdictMetrics {
  Estimate image_error{};
  Estimate flicker_error{};
  Estimate video_error{};
};

// One measured row: its metrics (RowMetrics), and the verdict's metrics as means over the
// animation and over the ground-truth seeds, with 95 % intervals (over frame blocks, widened by
// the ground truth's seed-to-seed spread; the video error's, the ground truth's spread).
struct TradeRow : RowMetrics, VerdictMetrics<Interval> {
  Variant variant = Variant::none;
  NormalFeed feed = NormalFeed::shading;
  Prefilter prefilter = Prefilter::none;
  Lobe lobe = Lobe::papers;
  SceneId scene = SceneId::sphere;
  double alpha = 0.0;
  bool fresnel = false;
  double temporal_stddev = 0.0;            // mean per-pixel temporal std of the variant
  double reference_temporal_stddev = 0.0;  // the same for the ground truth
  // Display-referred flicker: the mean per-pixel temporal std of the tonemapped frames
  // (tonemap(), image.hpp), of the variant and of the ground truth, and their ratio flicker_display
  // (1: flickers as much as the converged animation; > 1: aliasing; < 1: overblurred motion).
  double temporal_stddev_display = 0.0;
  double reference_temporal_stddev_display = 0.0;
  std::size_t non_finite = 0;  // NaN/inf pixels of the frame-0 image (excluded)
  // The configuration resolved by TAA (configuration id "...+taa"; see the top of this file).
  bool taa = false;
  // Mean LDR-FLIP of the measured animation frames against their ground truths (flicker
  // resolution): the image_error against the config's seed alone.
  double flip_ldr_animation = 0.0;
  // The mean lag (animation_error.hpp, lag_error) over the frames and seeds, with its interval.
  Interval lag;
  double flicker_excess = 0.0;  // flicker_error's parts, means over pairs and seeds
  double flicker_missing = 0.0;
  AnimationSeries series;
  // The same clip against the sanity suite's quarter-sample ground truth alone ([0]; empty without
  // the suite): the suite's stable rule reads each verdict against it and against the first seed.
  AnimationSeries quarter_series;
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
  // A GPU's timings (bench_shading's table, `saagen bench --cost FILE`) that cost the verdict's
  // decisions where they were taken at the decided material's light count; null: the committed
  // ISA model costs them. The measurement does not read it.
  std::shared_ptr<const MeasuredTradeTable> decision_timing;

  const TradeRow* find(Variant variant, SceneId scene, double alpha, bool fresnel, NormalFeed feed = NormalFeed::shading,
                       Prefilter prefilter = Prefilter::none, Lobe lobe = Lobe::papers, bool taa = false) const;
};

// The configuration a row measures: the variant id, with ":geometric" appended when a saagen
// variant is fed the geometric normal, and "+toksvig" / "+lean" with a prefiltered normal map
// ("deferred-avg", "deferred-avg:geometric", "deferred-avg:geometric+lean", "none+toksvig",
// "engine-hdrp"), and "/tail" or "/mapped" for a lobe other than the papers'
// ("forward-aniso-projected/tail", "deferred-avg:geometric+lean/mapped"), and "+taa" before the
// lobe under TAA ("none+taa", "deferred-avg:geometric+lean+taa").
std::string configuration_id(Variant variant, NormalFeed feed, Prefilter prefilter = Prefilter::none, Lobe lobe = Lobe::papers,
                             bool taa = false);
std::string configuration_id(const TradeRow& row);

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

// Frame `frame` of the animation the temporal metrics measure (see the top of trade.hpp).
Scene trade_animation_frame(const TradeConfig& config, SceneId id, int frame);

}  // namespace saagen::measure
