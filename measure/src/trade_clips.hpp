// The clips behind the trade's verdict metrics (trade.hpp, AnimationSeries): each ground-truth
// seed's frame as the metrics read it, and a clip's recorder over the frames (image error, flicker
// error, lag, and the frames the video metric reads). Shared by the trade's rows and its +taa rows.
#pragma once

#include "saagen/measure/animation_error.hpp"
#include "saagen/measure/flip.hpp"
#include "saagen/measure/trade_table.hpp"
#include "saagen/measure/video_vdp.hpp"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace saagen::measure {

// One ground-truth seed's frame of one material, as the verdict metrics read it.
struct SeedReference {
  std::optional<GreyFlipReference> flip;  // LDR-FLIP's reference half (TradeConfig::flip)
  Image display;                          // display values
  Image change;                           // G * |R_t - R_{t-1}| (frames after the first)
};

SeedReference seed_reference(const Image& linear, const SeedReference* previous, bool flip);
// The same from a frame already in display values and their display-linear (tonemapped) values:
// a frame rendered elsewhere (clip_score.hpp).
SeedReference seed_reference(Image display, const Image& tonemapped, const SeedReference* previous, bool flip);

// A clip's frames as the video metric reads them: the 8-bit display values that `saagen bench
// --frames` writes (display_bytes()), kept as bytes until compared.
struct ClipFrames {
  int width = 0, height = 0, frames = 0;
  std::vector<std::uint8_t> bytes;

  void append(const Image& display) {
    if (frames == 0) width = display.width, height = display.height;
    const std::vector<std::uint8_t> frame = display_bytes(display);
    bytes.insert(bytes.end(), frame.begin(), frame.end());
    ++frames;
  }
  GreyClip grey() const {
    GreyClip clip{width, height, frames, std::vector<float>(bytes.size())};
    std::transform(bytes.begin(), bytes.end(), clip.pixels.begin(), [](std::uint8_t b) { return static_cast<float>(b) / 255.0f; });
    return clip;
  }
};

// The video metric's per-frame losses of a clip against one reference (ClipRecorder::finish_video).
std::vector<double> video_losses(const VideoVdpReference& reference, const GreyClip& clip);

// A clip's state across frames: its previous display frame, its per-seed series, the sums of
// the flicker error's parts and, for the video metric, its frames.
struct ClipRecorder {
  AnimationSeries series;
  Image previous_display;
  double excess = 0.0, missing = 0.0;
  int flicker_values = 0;
  ClipFrames frames;  // kept only with the video metric
  bool keep_frames = false;

  // Frame t of the clip (linear radiance) against each seed's reference of that frame and, after
  // the first frame, of the previous one (`previous`, the same seeds).
  void add(const Image& linear, std::span<const SeedReference> references, std::span<const SeedReference> previous) {
    add_display(display_image(linear), tonemapped(linear), references, previous);
  }
  // The same from the frame's display values and their display-linear (tonemapped) values.
  void add_display(Image display, const Image& tonemapped_frame, std::span<const SeedReference> references,
                   std::span<const SeedReference> previous) {
    const bool has_previous = previous_display.size() == display.size() && previous_display.size() > 0;
    const Image change = has_previous ? pooled_change(previous_display, display) : Image();
    for (std::size_t s = 0; s < references.size(); ++s) {
      const SeedReference& reference = references[s];
      if (reference.flip) series.image[s].push_back(reference.flip->mean_error(tonemapped_frame));
      if (s < previous.size()) series.lag[s].push_back(lag_error(display, reference.display, previous[s].display));
      if (!has_previous) continue;
      const FlickerError e = flicker_error(change, reference.change);
      series.flicker[s].push_back(e.error);
      excess += e.excess;
      missing += e.missing;
      ++flicker_values;
    }
    if (keep_frames) frames.append(display);
    previous_display = std::move(display);
  }

  // The video metric against each seed's ground-truth clip; the frames are dropped. The series
  // is per frame, so that its interval sees the variation over the frames (animation_error.hpp):
  // the frames' losses (10 - VideoVdpResult::frame_jod) shifted so that their mean is the clip's
  // loss, 10 - JOD.
  void finish_video(std::span<const VideoVdpReference> references) {
    const GreyClip clip = frames.grey();
    for (std::size_t s = 0; s < references.size(); ++s) series.video[s] = video_losses(references[s], clip);
    frames = ClipFrames();
  }
};

// Each material's reference half of the video metric, once per seed ([m][seed], from
// reference_clips[m][seed]), on the configured threads.
std::vector<std::vector<VideoVdpReference>> video_references(const TradeConfig& config,
                                                             const std::vector<std::vector<ClipFrames>>& reference_clips);

// A row's verdict metrics from its recorder (trade.hpp).
void finish_verdict_metrics(const ClipRecorder& clip, TradeRow& row);

}  // namespace saagen::measure
