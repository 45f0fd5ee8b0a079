// `saagen bench --frames DIR`: the animation clips behind every row, as the trade measured them,
// so that any external video metric can be run on exactly what the verdict read.
//
// DIR/index.json lists the clips: per scene and material, the ground truth's clip and each
// configuration's and sanity result's (render::AnimationFrame::clip), with the frames' size and
// count. Each clip is one 8-bit greyscale PNG, its frames stacked top to bottom (frame t in rows
// t * height .. (t + 1) * height - 1), in display values (render::display_image(): Reinhard's
// x / (1 + x), then the sRGB encoding, rounded to 8 bits): one image pixel per display pixel.
// Paths: SCENE/a<ALPHA>[-fresnel]/<CLIP>.png, the clip's name with '/', ':' and '+' as '_'.
#pragma once

#include "saagen/io/output.hpp"
#include "saagen/reference/render/trade.hpp"

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <regex>
#include <string>
#include <tuple>
#include <vector>

namespace saagen::render {
class VideoVdpReference;
}

namespace saagen::report {

// The rate the clips are meant to be played at, which DIR/index.json states and `--jod` measures
// at: the animation has none of its own.
inline constexpr int kClipFramesPerSecond = 30;

// A frame's display values as the clips store them: round(255 v), v clamped to [0, 1] (NaN: 0).
std::vector<std::uint8_t> clip_bytes(const render::Image& display);

class ClipWriter {
 public:
  // Clips whose name matches `keep` (and the ground truth's, always) are kept.
  ClipWriter(std::filesystem::path directory, std::regex keep);
  // A frame of a clip (render::AnimationFrameFn); a clip is encoded when its last frame arrives.
  void add(const render::AnimationFrame& frame, int frames);
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

// `saagen bench --jod`: the ColorVideoVDP JOD (render/video_vdp.hpp; display standard_fhd,
// kClipFramesPerSecond) of every clip against its ground truth, computed on exactly the 8-bit
// clips ClipWriter writes. Frames arrive in the trade's order (render::AnimationFrameFn: a scene's
// every frame before the next scene's; within a frame the ground truth's before the rows'), so a
// scene's clips are complete when the next scene starts: they are compared then (on `threads`
// threads), and their 8-bit frames and references dropped.
class ClipJods {
 public:
  explicit ClipJods(int threads);
  ~ClipJods();
  void add(const render::AnimationFrame& frame, int frames);
  // Compares the clips still pending; call once the trade is measured.
  void finish();
  // Sets "jod" on each of trade_json's "cases" and "sanity" rows whose clip was measured; returns
  // how many.
  std::size_t annotate(nlohmann::json& table) const;
  std::size_t clips() const { return jods_.size(); }
  double compare_seconds() const { return compare_seconds_; }  // summed over the clips, one thread each

 private:
  using Group = std::tuple<std::string, double, bool>;  // scene, alpha, Fresnel
  struct Pending {
    Group group;
    std::string clip;
    int width = 0, height = 0;
    std::vector<std::uint8_t> bytes;  // frames x height x width
  };
  void flush();

  int threads_ = 0;
  std::optional<render::SceneId> scene_;
  std::map<std::pair<Group, std::string>, Pending> partial_;  // clips still receiving frames
  std::vector<Pending> complete_;                             // clips awaiting their comparison
  std::map<Group, std::shared_ptr<const render::VideoVdpReference>> references_;
  std::map<std::pair<Group, std::string>, double> jods_;
  double compare_seconds_ = 0.0;
};

}  // namespace saagen::report
