// `saagen bench --frames DIR`: the animation clips behind every row, as the trade measured them,
// so that any external video metric can be run on exactly what the verdict read.
//
// DIR/index.json lists the clips: per scene and material, the ground truth's clip and each
// configuration's and sanity result's (measure::AnimationFrame::clip), with the frames' size and
// count. Each clip is one 8-bit greyscale PNG, its frames stacked top to bottom (frame t in rows
// t * height .. (t + 1) * height - 1), in display values (measure::display_image(): Reinhard's
// x / (1 + x), then the sRGB encoding, rounded to 8 bits): one image pixel per display pixel.
// Paths: SCENE/a<ALPHA>[-fresnel]/<CLIP>.png, the clip's name with '/', ':' and '+' as '_'.
#pragma once

#include "saagen/io/output.hpp"
#include "saagen/measure/trade.hpp"

#include <cstdint>
#include <map>
#include <regex>
#include <string>
#include <vector>

namespace saagen::report {

// The rate the clips are meant to be played at, which DIR/index.json states and the trade's video
// metric measures at (measure::TradeConfig::clip_frames_per_second): the animation has none of its own.
inline constexpr int kClipFramesPerSecond = 30;

class ClipWriter {
 public:
  // Clips whose name matches `keep` (and the ground truth's, always) are kept.
  ClipWriter(std::filesystem::path directory, std::regex keep);
  // A frame of a clip (measure::AnimationFrameFn); a clip is encoded when its last frame arrives.
  void add(const measure::AnimationFrame& frame, int frames);
  // The PNGs and DIR/index.json, for write_outputs.
  std::vector<OutputFile> outputs() const;

 private:
  struct Clip {
    std::string scene, name, path;
    double alpha = 0.0;
    bool fresnel = false;
    int width = 0, height = 0, frames = 0;
    std::vector<std::uint8_t> pixels;
    std::string png;
  };
  std::filesystem::path directory_;
  std::regex keep_;
  std::map<std::string, Clip> clips_;  // by path
};

}  // namespace saagen::report
