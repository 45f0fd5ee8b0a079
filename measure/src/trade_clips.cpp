// The clips behind the trade's verdict metrics (see trade_clips.hpp).
#include "trade_clips.hpp"

#include "saagen/measure/parallel.hpp"

namespace saagen::measure {

SeedReference seed_reference(const Image& linear, const SeedReference* previous, bool flip) {
  return seed_reference(display_image(linear), tonemapped(linear), previous, flip);
}

SeedReference seed_reference(Image display, const Image& tonemapped_frame, const SeedReference* previous, bool flip) {
  SeedReference r;
  if (flip) r.flip.emplace(tonemapped_frame, GreyFlipReference::Range::ldr);
  r.display = std::move(display);
  if (previous) r.change = pooled_change(previous->display, r.display);
  return r;
}

std::vector<double> video_losses(const VideoVdpReference& reference, const GreyClip& clip) {
  const VideoVdpResult result = reference.compare(clip);
  double frame_mean = 0.0;
  for (const double jod : result.frame_jod) frame_mean += jod / static_cast<double>(result.frame_jod.size());
  std::vector<double> losses;
  for (const double jod : result.frame_jod) losses.push_back((10.0 - jod) - (10.0 - frame_mean) + (10.0 - result.jod));
  return losses;
}

std::vector<std::vector<VideoVdpReference>> video_references(const TradeConfig& config,
                                                             const std::vector<std::vector<ClipFrames>>& reference_clips) {
  const std::size_t n_materials = reference_clips.size(), seeds = n_materials ? reference_clips[0].size() : 0;
  std::vector<std::optional<VideoVdpReference>> built(n_materials * seeds);
  parallel_rows(static_cast<int>(built.size()), config.threads, [&](int i) {
    const std::size_t m = static_cast<std::size_t>(i) / seeds, seed = static_cast<std::size_t>(i) % seeds;
    built[static_cast<std::size_t>(i)].emplace(reference_clips[m][seed].grey(), video_vdp_standard_fhd(), config.clip_frames_per_second);
  });
  std::vector<std::vector<VideoVdpReference>> references(n_materials);
  for (std::size_t i = 0; i < built.size(); ++i) references[i / seeds].push_back(std::move(*built[i]));
  return references;
}

void finish_verdict_metrics(const ClipRecorder& clip, TradeRow& row) {
  row.series = clip.series;
  row.image_error = series_interval(std::span<const SeedSeries>(&row.series.image, 1));
  row.flicker_error = series_interval(std::span<const SeedSeries>(&row.series.flicker, 1));
  if (!row.series.video[0].empty()) row.video_error = series_interval(std::span<const SeedSeries>(&row.series.video, 1));
  if (!row.series.lag[0].empty()) row.lag = series_interval(std::span<const SeedSeries>(&row.series.lag, 1));
  row.flip_ldr_animation = row.series.image[0].empty() ? 0.0 : mean_interval(row.series.image[0], 0.0).mean;
  if (clip.flicker_values > 0) {
    row.flicker_excess = clip.excess / clip.flicker_values;
    row.flicker_missing = clip.missing / clip.flicker_values;
  }
}

}  // namespace saagen::measure
