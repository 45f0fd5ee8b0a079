// The trade's verdict metrics on clips rendered elsewhere (`saagen score`): a clip in the display
// values `saagen bench --frames` writes (report/frames.hpp) against one or two ground-truth seeds'
// clips, measured by the same code the trade's rows are (trade_clips.hpp: the per-frame LDR-FLIP,
// the flicker error, the lag and ColorVideoVDP's JOD, each with its 95 % interval).
//
// The clips are 8-bit display values (measure::display_bytes()); LDR-FLIP reads their
// display-linear values, srgb_decode(byte / 255), where the trade reads tonemapped() of the
// unrounded radiance: the two differ by the 8-bit rounding only.
#pragma once

#include "saagen/measure/trade.hpp"

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace saagen::measure {

// A clip: `frames` frames of width x height 8-bit display values, frame after frame, rows top to bottom.
struct ByteClip {
  int width = 0, height = 0, frames = 0;
  std::vector<std::uint8_t> bytes;
};

// A clip's verdict metrics (as TradeRow's: image_error, flicker_error, video_error, lag) and the
// series the paired comparisons read (report/comparison.hpp).
struct ClipScore {
  AnimationSeries series;
  Interval image_error, flicker_error, video_error, lag;
};

// The ground truth's clips (one per seed, 1 or 2) with their metric references built once, so
// that every clip of a group is scored against the same references. Throws std::invalid_argument
// on clips of different sizes or frame counts, or without frames.
class ClipScorer {
 public:
  ClipScorer(std::span<const ByteClip> seeds, double frames_per_second);
  ~ClipScorer();
  // `clip` against the first `seeds` ground-truth seeds (the trade scores its rows against both,
  // its sanity results against the first). May be called from several threads at once.
  ClipScore score(const ByteClip& clip, std::size_t seeds) const;
  std::size_t seeds() const;

 private:
  struct State;
  std::unique_ptr<const State> state_;
};

}  // namespace saagen::measure
