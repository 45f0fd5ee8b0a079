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
  const std::size_t seeds = truths.second.empty() ? 1 : 2;
  const bool quarter = !truths.quarter.empty();
  std::vector<std::vector<ClipFrames>> reference_clips(config.video_metric ? materials.size() : 0,
                                                       std::vector<ClipFrames>(seeds + (quarter ? 1 : 0)));  // [m][seed], quarter
  std::vector<TemporalStats> reference_stats(materials.size(), TemporalStats(fw, fh));
  std::vector<TemporalStats> reference_display(materials.size(), TemporalStats(fw, fh));

  std::optional<Scene> previous;
  std::vector<std::vector<SeedReference>> previous_references(materials.size());  // [m][seed], of the previous frame
  std::vector<SeedReference> previous_quarter(quarter ? materials.size() : 0);    // [m], of the previous frame
  std::vector<ImageSet> last_frames(images ? materials.size() : 0);
  for (int frame = -warmup; frame < config.frames; ++frame) {
    // The jitter cycle starts with the warm-up; the animation's frame 0 follows it.
    const Vec2 jitter = taa_jitter(frame + warmup, config.taa_options.sequence_length);
    const Scene scene = jittered_frame(config, id, frame, jitter);
    const FrameBuffers buffers = frame_buffers(config, id, scene, fw, fh);
    const std::vector<Vec2> positions = previous ? reproject_history(buffers.plain, scene, *previous) : std::vector<Vec2>{};
    std::vector<std::vector<SeedReference>> references(materials.size(), std::vector<SeedReference>(seeds));
    std::vector<SeedReference> quarter_references(previous_quarter.size());
    if (frame >= 0) {
      const auto f = static_cast<std::size_t>(frame);
      for (std::size_t m = 0; m < materials.size(); ++m) {
        const Image& reference = truths.first[f][m];
        reference_stats[m].add(reference);
        reference_display[m].add(tonemapped(reference));
        for (std::size_t s = 0; s < seeds; ++s) {
          references[m][s] =
              seed_reference(s == 0 ? reference : truths.second[f][m], frame > 0 ? &previous_references[m][s] : nullptr, config.flip);
          if (!reference_clips.empty()) reference_clips[m][s].append(references[m][s].display);
        }
        if (!quarter) continue;
        quarter_references[m] = seed_reference(truths.quarter[f][m], frame > 0 ? &previous_quarter[m] : nullptr, config.flip);
        if (!reference_clips.empty()) reference_clips[m][seeds].append(quarter_references[m].display);
      }
    }
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
          if (frame >= 0) {
            FrameTruths frame_truths{references[m], {}};
            if (frame > 0) frame_truths.previous_seeds = previous_references[m];
            if (quarter)
              frame_truths.quarter = &quarter_references[m], frame_truths.previous_quarter = frame > 0 ? &previous_quarter[m] : nullptr;
            measure_frame(a, out, truths.first[static_cast<std::size_t>(frame)][m], frame_truths, last);
          }
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
    if (frame >= 0) previous_references = std::move(references), previous_quarter = std::move(quarter_references);
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
  if (!reference_clips.empty()) {
    const std::vector<std::vector<VideoVdpReference>> video = video_references(config, reference_clips);
    parallel_rows(static_cast<int>(accumulators.size()), config.threads, [&](int i) {
      const std::size_t r = static_cast<std::size_t>(i);
      const std::span<const VideoVdpReference> material(video[r / n_keys]);
      TaaAccumulator& a = accumulators[r];
      if (quarter) a.quarter_clip.series.video[0] = video_losses(material[seeds], a.clip.frames.grey());
      a.clip.finish_video(material.first(seeds));
    });
  }
  for (std::size_t m = 0; m < materials.size(); ++m)
    for (std::size_t k = 0; k < n_keys; ++k)
      rows.push_back(finished_row(accumulators[m * n_keys + k], keys[k], id, materials[m], config.frames, reference_stats[m],
                                  reference_display[m], quarter));
}

}  // namespace saagen::measure
