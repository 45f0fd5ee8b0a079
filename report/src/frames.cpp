// The animation clips behind the trade's rows (see frames.hpp).
#include "saagen/report/frames.hpp"

#include "saagen/report/png.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace saagen::report {

namespace {

std::string file_name(std::string clip) {
  std::replace_if(
      clip.begin(), clip.end(), [](char c) { return c == '/' || c == ':' || c == '+'; }, '_');
  return clip;
}

std::string clip_path(const measure::AnimationFrame& frame) {
  return fmt::format("{}/a{}{}/{}.png", measure::scene_name(frame.scene), frame.alpha, frame.fresnel ? "-fresnel" : "",
                     file_name(frame.clip));
}

}  // namespace

ClipWriter::ClipWriter(std::filesystem::path directory, std::regex keep) : directory_(std::move(directory)), keep_(std::move(keep)) {}

void ClipWriter::add(const measure::AnimationFrame& frame, int frames) {
  if (frame.clip != "ground-truth" && !std::regex_search(frame.clip, keep_)) return;
  const measure::Image& image = *frame.display;
  Clip& clip = clips_[clip_path(frame)];
  if (clip.pixels.empty() && clip.png.empty()) {
    clip = {std::string(measure::scene_name(frame.scene)),
            frame.clip,
            clip_path(frame),
            frame.alpha,
            frame.fresnel,
            image.width,
            image.height,
            frames,
            std::vector<std::uint8_t>(static_cast<std::size_t>(image.width) * image.height * frames, 0),
            {}};
  }
  const std::vector<std::uint8_t> bytes = measure::display_bytes(image);
  std::copy(bytes.begin(), bytes.end(), clip.pixels.begin() + static_cast<std::ptrdiff_t>(frame.frame * image.size()));
  if (frame.frame == frames - 1) {
    clip.png = encode_tagged_png(clip.width, clip.height * clip.frames, 1, clip.pixels, "bench --frames");
    clip.pixels.clear();
    clip.pixels.shrink_to_fit();
  }
}

std::vector<OutputFile> ClipWriter::outputs() const {
  std::vector<OutputFile> files;
  // One entry per (scene, material): its ground truth and the other clips.
  std::map<std::string, nlohmann::json> groups;
  for (const auto& [path, clip] : clips_) {
    const std::string key = path.substr(0, path.rfind('/'));
    nlohmann::json& group = groups[key];
    if (group.is_null())
      group = {{"scene", clip.scene},   {"alpha", clip.alpha},   {"fresnel", clip.fresnel},         {"width", clip.width},
               {"height", clip.height}, {"frames", clip.frames}, {"clips", nlohmann::json::array()}};
    if (clip.name == "ground-truth")
      group["reference"] = path;
    else
      group["clips"].push_back({{"configuration", clip.name}, {"file", path}});
    files.push_back({directory_ / path, clip.png});
  }
  nlohmann::json index = {{"generator", std::string(output_tag) + " saagen bench --frames"},
                          {"version", 1},
                          // The animation has no rate of its own; the rate the clips are meant to be played at
                          // (the verdict's metrics do not depend on it).
                          {"fps", kClipFramesPerSecond},
                          {"display",
                           "8-bit greyscale PNG, the clip's frames stacked top to bottom; display values: Reinhard x / (1 + x) of the "
                           "linear specular radiance, then the sRGB encoding; one image pixel per display pixel"},
                          {"groups", nlohmann::json::array()}};
  for (auto& [key, group] : groups) index["groups"].push_back(group);
  files.push_back({directory_ / "index.json", index.dump(1) + "\n"});
  return files;
}

}  // namespace saagen::report
