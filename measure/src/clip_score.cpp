// The trade's verdict metrics on clips rendered elsewhere (see clip_score.hpp).
#include "saagen/measure/clip_score.hpp"

#include "trade_clips.hpp"

#include <stdexcept>

namespace saagen::measure {

namespace {

// Frame t of a clip as its display values (byte / 255).
Image display_frame(const ByteClip& clip, int t) {
  Image frame(clip.width, clip.height);
  const std::size_t offset = static_cast<std::size_t>(t) * frame.size();
  for (std::size_t i = 0; i < frame.size(); ++i) frame.pixels[i] = static_cast<float>(clip.bytes[offset + i] / 255.0);
  return frame;
}

// The display-linear values LDR-FLIP reads (what tonemapped() gives the trade), from display values.
Image display_linear(const Image& display) {
  Image out(display.width, display.height);
  for (std::size_t i = 0; i < display.size(); ++i) out.pixels[i] = static_cast<float>(srgb_decode(display.pixels[i]));
  return out;
}

void check_clip(const ByteClip& clip, const ByteClip& first) {
  if (clip.frames < 1 || clip.width < 1 || clip.height < 1) throw std::invalid_argument("a clip has no frames");
  if (clip.width != first.width || clip.height != first.height || clip.frames != first.frames)
    throw std::invalid_argument("a clip's size or frame count differs from the ground truth's");
  if (clip.bytes.size() != static_cast<std::size_t>(clip.width) * clip.height * clip.frames)
    throw std::invalid_argument("a clip's pixels do not fill its frames");
}

ClipFrames clip_frames(const ByteClip& clip) { return {clip.width, clip.height, clip.frames, clip.bytes}; }

}  // namespace

struct ClipScorer::State {
  std::vector<std::vector<SeedReference>> frames;  // [t][seed]
  std::vector<VideoVdpReference> video;            // [seed]
  ByteClip first;
};

ClipScorer::ClipScorer(std::span<const ByteClip> seeds, double frames_per_second) {
  if (seeds.empty() || seeds.size() > 2) throw std::invalid_argument("ClipScorer: one or two ground-truth seeds");
  auto state = std::make_unique<State>();
  state->first = {seeds[0].width, seeds[0].height, seeds[0].frames, {}};
  for (const ByteClip& seed : seeds) check_clip(seed, seeds[0]);
  state->frames.resize(static_cast<std::size_t>(seeds[0].frames));
  for (int t = 0; t < seeds[0].frames; ++t) {
    for (std::size_t s = 0; s < seeds.size(); ++s) {
      Image display = display_frame(seeds[s], t);
      const Image linear = display_linear(display);
      const SeedReference* previous = t > 0 ? &state->frames[static_cast<std::size_t>(t) - 1][s] : nullptr;
      state->frames[static_cast<std::size_t>(t)].push_back(seed_reference(std::move(display), linear, previous, true));
    }
  }
  for (const ByteClip& seed : seeds) state->video.emplace_back(clip_frames(seed).grey(), video_vdp_standard_fhd(), frames_per_second);
  state_ = std::move(state);
}

ClipScorer::~ClipScorer() = default;

std::size_t ClipScorer::seeds() const { return state_->video.size(); }

ClipScore ClipScorer::score(const ByteClip& clip, std::size_t seeds) const {
  check_clip(clip, state_->first);
  if (seeds < 1 || seeds > this->seeds()) throw std::invalid_argument("ClipScorer::score: no such ground-truth seed");
  ClipRecorder recorder;
  recorder.keep_frames = true;
  for (int t = 0; t < clip.frames; ++t) {
    Image display = display_frame(clip, t);
    const Image linear = display_linear(display);
    const std::span<const SeedReference> references = std::span(state_->frames[static_cast<std::size_t>(t)]).first(seeds);
    const std::span<const SeedReference> previous =
        t > 0 ? std::span(state_->frames[static_cast<std::size_t>(t) - 1]).first(seeds) : std::span<const SeedReference>();
    recorder.add_display(std::move(display), linear, references, previous);
  }
  recorder.finish_video(std::span(state_->video).first(seeds));
  TradeRow row;
  finish_verdict_metrics(recorder, row);
  return {row.series, row.image_error, row.flicker_error, row.video_error, row.lag};
}

}  // namespace saagen::measure
