// The trade's +taa rows (see trade.hpp, TradeConfig::taa, and trade_taa.hpp).
#include "trade_taa.hpp"

#include "trade_clips.hpp"

#include "saagen/measure/flip.hpp"
#include "saagen/measure/parallel.hpp"
#include "saagen/measure/taa.hpp"

#include <cmath>

namespace saagen::measure {

namespace {

// What one +taa configuration accumulates over the measured frames.
struct TaaAccumulator {
  TaaResolve resolve;
  TemporalStats stats, stats_display;
  TemporalDifference difference;
  Image previous_display;
  ClipRecorder clip;          // the verdict metrics (trade_clips.hpp) against each ground-truth seed
  ClipRecorder quarter_clip;  // the same against the quarter-sample ground truth (TradeRow::quarter_series)
  double rmse_linear = 0.0, rmse_tonemapped = 0.0, max_error = 0.0, flip_hdr = 0.0;
  std::size_t non_finite = 0;
  TaaAccumulator(int w, int h, const TaaOptions& options) : resolve(w, h, options), stats(w, h), stats_display(w, h) {}
};

Scene jittered_frame(const TradeConfig& config, SceneId id, int frame, Vec2 jitter) {
  const Scene scene = trade_animation_frame(config, id, frame);
  Camera camera = scene.camera();
  camera.jitter = jitter;
  return scene.with_camera(camera);
}

// One material's ground truths of a frame as the verdict metrics read them: every seed's, and the
// quarter-sample one's where the sanity suite runs (nullptr without); the previous frame's after
// the first frame (empty, nullptr at frame 0).
struct FrameTruths {
  std::span<const SeedReference> seeds, previous_seeds;
  const SeedReference* quarter = nullptr;
  const SeedReference* previous_quarter = nullptr;
};

std::span<const SeedReference> one_or_none(const SeedReference* reference) {
  return reference ? std::span(reference, 1) : std::span<const SeedReference>();
}

// Frame `frame` (>= 0) of a configuration after its resolve: the image metrics against the
// frame's ground truth and the temporal ones against the previous frame's.
// The verdict metrics read every seed's reference and the quarter-sample one's (`truths`); the
// older figures the first seed's.
void measure_frame(TaaAccumulator& a, const Image& out, const Image& reference, const FrameTruths& truths, bool last) {
  const Image& reference_display = truths.seeds[0].display;
  const Image* previous_reference_display = truths.previous_seeds.empty() ? nullptr : &truths.previous_seeds[0].display;
  Image display = display_image(out);
  const Image out_tonemapped = tonemapped(out);
  if (truths.quarter)
    a.quarter_clip.add_display(display, out_tonemapped, one_or_none(truths.quarter), one_or_none(truths.previous_quarter));
  a.clip.add_display(display, out_tonemapped, truths.seeds, truths.previous_seeds);
  const ImageError e = compare_images(out, reference);
  a.rmse_linear += e.rmse_linear;
  a.rmse_tonemapped += e.rmse_tonemapped;
  a.max_error = std::max(a.max_error, e.max_error);
  a.non_finite += e.non_finite;
  if (last) a.flip_hdr = hdr_flip_mean_grey(reference, out);
  a.stats.add(out);
  a.stats_display.add(out_tonemapped);
  if (previous_reference_display) a.difference.add_pair(a.previous_display, display, *previous_reference_display, reference_display);
  a.previous_display = std::move(display);
}

TradeRow finished_row(const TaaAccumulator& a, const TaaRowKey& key, SceneId id, const Material& material, int frames,
                      const TemporalStats& reference_stats, const TemporalStats& reference_display, bool quarter) {
  TradeRow row;
  finish_verdict_metrics(a.clip, row);
  if (quarter) row.quarter_series = a.quarter_clip.series;
  row.variant = key.variant;
  row.feed = key.feed;
  row.prefilter = key.prefilter;
  row.lobe = key.lobe;
  row.taa = true;
  row.scene = id;
  row.alpha = material.alpha;
  row.fresnel = material.fresnel;
  row.rmse_linear = a.rmse_linear / frames;
  row.rmse_tonemapped = a.rmse_tonemapped / frames;
  row.max_error = a.max_error;
  row.non_finite = a.non_finite;
  row.flip_ldr = row.flip_ldr_animation;  // the image series' mean (finish_verdict_metrics)
  row.flip_hdr = a.flip_hdr;
  const TemporalError temporal = a.difference.mean();
  row.tde = temporal.tde;
  row.tde_excess_flicker = temporal.excess_flicker;
  row.tde_lost_motion = temporal.lost_motion;
  row.flicker = flicker(a.stats, reference_stats);
  row.temporal_stddev = mean_temporal_stddev(a.stats);
  row.reference_temporal_stddev = mean_temporal_stddev(reference_stats);
  row.temporal_stddev_display = mean_temporal_stddev(a.stats_display);
  row.reference_temporal_stddev_display = mean_temporal_stddev(reference_display);
  row.flicker_display =
      row.reference_temporal_stddev_display > 0.0 ? row.temporal_stddev_display / row.reference_temporal_stddev_display : 0.0;
  return row;
}

// The ground truth's side of a TAA animation, per material: the references of every seed and of
// the quarter-sample truth for the current frame and the previous one, their clips for the video
// metric (empty without it) and their temporal statistics for the older figures.
struct TaaTruthState {
  std::size_t seeds = 1;
  bool quarter = false;
  std::vector<std::vector<ClipFrames>> clips;                    // [m][seed], the quarter's last
  std::vector<TemporalStats> stats, display;                     // [m]: the first seed's, linear and tonemapped
  std::vector<std::vector<SeedReference>> current, previous;     // [m][seed]
  std::vector<SeedReference> current_quarter, previous_quarter;  // [m]

  TaaTruthState(const TradeConfig& config, const AnimationGroundTruths& truths, std::size_t materials)
      : seeds(truths.second.empty() ? 1 : 2),
        quarter(!truths.quarter.empty()),
        clips(config.video_metric ? materials : 0, std::vector<ClipFrames>(seeds + (quarter ? 1 : 0))),
        stats(materials, TemporalStats(config.flicker_width, config.flicker_height)),
        display(materials, TemporalStats(config.flicker_width, config.flicker_height)),
        previous(materials),
        previous_quarter(quarter ? materials : 0) {}

  // Frame `frame`'s references (none during the warm-up, frame < 0).
  void begin_frame(const TradeConfig& config, const AnimationGroundTruths& truths, int frame) {
    current.assign(previous.size(), std::vector<SeedReference>(seeds));
    current_quarter.assign(previous_quarter.size(), SeedReference{});
    if (frame < 0) return;
    const auto f = static_cast<std::size_t>(frame);
    for (std::size_t m = 0; m < previous.size(); ++m) {
      const Image& reference = truths.first[f][m];
      stats[m].add(reference);
      display[m].add(tonemapped(reference));
      for (std::size_t s = 0; s < seeds; ++s) {
        current[m][s] = seed_reference(s == 0 ? reference : truths.second[f][m], frame > 0 ? &previous[m][s] : nullptr, config.flip);
        if (!clips.empty()) clips[m][s].append(current[m][s].display);
      }
      if (!quarter) continue;
      current_quarter[m] = seed_reference(truths.quarter[f][m], frame > 0 ? &previous_quarter[m] : nullptr, config.flip);
      if (!clips.empty()) clips[m][seeds].append(current_quarter[m].display);
    }
  }

  // What material m's rows read at frame `frame` (>= 0).
  FrameTruths frame_truths(std::size_t m, int frame) const {
    FrameTruths truths{current[m], {}};
    if (frame > 0) truths.previous_seeds = previous[m];
    if (quarter) truths.quarter = &current_quarter[m], truths.previous_quarter = frame > 0 ? &previous_quarter[m] : nullptr;
    return truths;
  }

  void end_frame(int frame) {
    if (frame >= 0) previous = std::move(current), previous_quarter = std::move(current_quarter);
  }
};

// Each row's video error against every seed's clip (and the quarter-sample clip's), once the
// animation is over.
void finish_video(const TradeConfig& config, const TaaTruthState& truth, std::size_t n_keys, std::vector<TaaAccumulator>& accumulators) {
  if (truth.clips.empty()) return;
  const std::vector<std::vector<VideoVdpReference>> video = video_references(config, truth.clips);
  parallel_rows(static_cast<int>(accumulators.size()), config.threads, [&](int i) {
    const std::size_t r = static_cast<std::size_t>(i);
    const std::span<const VideoVdpReference> material(video[r / n_keys]);
    TaaAccumulator& a = accumulators[r];
    if (truth.quarter) a.quarter_clip.series.video[0] = video_losses(material[truth.seeds], a.clip.frames.grey());
    a.clip.finish_video(material.first(truth.seeds));
  });
}

}  // namespace

int taa_warmup(const TradeConfig& config) {
  return config.taa_warmup_frames > 0 ? config.taa_warmup_frames : config.taa_options.sequence_length;
}

void append_taa_rows(const TradeConfig& config, SceneId id, std::span<const Material> materials, std::span<const TaaRowKey> keys,
                     const AnimationGroundTruths& truths, std::vector<TradeRow>& rows,
                     const std::function<void(std::uint64_t pixels)>& shaded, std::vector<ImageSet>* images,
                     const AnimationFrameFn& on_frame) {
  const int fw = config.flicker_width, fh = config.flicker_height, warmup = taa_warmup(config);
  const std::size_t n_keys = keys.size();
  std::vector<TaaAccumulator> accumulators;
  accumulators.reserve(materials.size() * n_keys);
  for (std::size_t r = 0; r < materials.size() * n_keys; ++r) {
    accumulators.emplace_back(fw, fh, config.taa_options);
    accumulators.back().clip.keep_frames = config.video_metric;
  }
  TaaTruthState truth(config, truths, materials.size());
  std::optional<Scene> previous;
  std::vector<ImageSet> last_frames(images ? materials.size() : 0);
  for (int frame = -warmup; frame < config.frames; ++frame) {
    // The jitter cycle starts with the warm-up; the animation's frame 0 follows it.
    const Vec2 jitter = taa_jitter(frame + warmup, config.taa_options.sequence_length);
    const Scene scene = jittered_frame(config, id, frame, jitter);
    const FrameBuffers buffers = frame_buffers(config, id, scene, fw, fh);
    const std::vector<Vec2> positions = previous ? reproject_history(buffers.plain, scene, *previous) : std::vector<Vec2>{};
    truth.begin_frame(config, truths, frame);
    const bool last = frame + 1 == config.frames;
    std::vector<Image> last_outputs(images && last ? accumulators.size() : 0);
    // The rows of a frame in parallel, each on one thread (as the trade's other rows).
    int reported = 0;
    parallel_rows(
        static_cast<int>(accumulators.size()), config.threads,
        [&](int row) {
          const std::size_t r = static_cast<std::size_t>(row), m = r / n_keys;
          const TaaRowKey& key = keys[r % n_keys];
          TaaAccumulator& a = accumulators[r];
          const Image samples = render_variant(buffers.for_prefilter(key.prefilter), key.variant, materials[m], config.params,
                                               config.derivative, 1, key.feed, key.prefilter, config.prefilter_scale, key.lobe);
          const Image& out = a.resolve.resolve(samples, jitter, positions);
          if (frame >= 0) measure_frame(a, out, truths.first[static_cast<std::size_t>(frame)][m], truth.frame_truths(m, frame), last);
          if (!last_outputs.empty()) last_outputs[r] = out;
        },
        [&](int done) {
          if (shaded && done > reported) shaded(static_cast<std::uint64_t>(done - reported) * fw * fh);
          reported = done;
        });
    if (frame >= 0 && on_frame)
      for (std::size_t r = 0; r < accumulators.size(); ++r) {
        const TaaRowKey& key = keys[r % n_keys];
        const Material& material = materials[r / n_keys];
        on_frame({id, material.alpha, material.fresnel, configuration_id(key.variant, key.feed, key.prefilter, key.lobe, true), frame,
                  &accumulators[r].clip.previous_display});
      }
    truth.end_frame(frame);
    for (std::size_t r = 0; r < last_outputs.size(); ++r) {
      const TaaRowKey& key = keys[r % n_keys];
      last_frames[r / n_keys].variants.push_back({key.variant, key.feed, key.prefilter, key.lobe, std::move(last_outputs[r])});
    }
    previous = scene;
  }
  for (std::size_t m = 0; m < last_frames.size(); ++m) {
    last_frames[m].scene = id;
    last_frames[m].material = materials[m];
    last_frames[m].reference = truths.first.back()[m];
    images->push_back(std::move(last_frames[m]));
  }
  finish_video(config, truth, n_keys, accumulators);
  for (std::size_t m = 0; m < materials.size(); ++m)
    for (std::size_t k = 0; k < n_keys; ++k)
      rows.push_back(finished_row(accumulators[m * n_keys + k], keys[k], id, materials[m], config.frames, truth.stats[m], truth.display[m],
                                  truth.quarter));
}

}  // namespace saagen::measure
