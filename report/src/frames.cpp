// The animation clips behind the trade's rows (see frames.hpp).
#include "saagen/report/frames.hpp"

#include "saagen/reference/render/parallel.hpp"
#include "saagen/reference/render/video_vdp.hpp"
#include "saagen/report/report.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace saagen::report {

namespace {

std::string file_name(std::string clip) {
  std::replace_if(
      clip.begin(), clip.end(), [](char c) { return c == '/' || c == ':' || c == '+'; }, '_');
  return clip;
}

std::string clip_path(const render::AnimationFrame& frame) {
  return fmt::format("{}/a{}{}/{}.png", render::scene_name(frame.scene), frame.alpha, frame.fresnel ? "-fresnel" : "",
                     file_name(frame.clip));
}

std::uint8_t to_byte(float display) {
  const double v = std::isfinite(display) ? std::clamp(static_cast<double>(display), 0.0, 1.0) : 0.0;
  return static_cast<std::uint8_t>(std::lround(v * 255.0));
}

}  // namespace

std::vector<std::uint8_t> clip_bytes(const render::Image& display) {
  std::vector<std::uint8_t> bytes(display.size());
  for (std::size_t i = 0; i < display.size(); ++i) bytes[i] = to_byte(display.pixels[i]);
  return bytes;
}

ClipWriter::ClipWriter(std::filesystem::path directory, std::regex keep) : directory_(std::move(directory)), keep_(std::move(keep)) {}

void ClipWriter::add(const render::AnimationFrame& frame, int frames) {
  if (frame.clip != "ground-truth" && !std::regex_search(frame.clip, keep_)) return;
  const render::Image& image = *frame.display;
  Clip& clip = clips_[clip_path(frame)];
  if (clip.pixels.empty() && clip.png.empty()) {
    clip = {std::string(render::scene_name(frame.scene)),
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
  const std::vector<std::uint8_t> bytes = clip_bytes(image);
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

ClipJods::ClipJods(int threads) : threads_(threads) {}
ClipJods::~ClipJods() = default;

void ClipJods::add(const render::AnimationFrame& frame, int frames) {
  // A new scene: every clip of the previous one is complete.
  if (scene_ && *scene_ != frame.scene) flush();
  scene_ = frame.scene;
  const render::Image& image = *frame.display;
  const Group group{std::string(render::scene_name(frame.scene)), frame.alpha, frame.fresnel};
  Pending& clip = partial_[{group, frame.clip}];
  if (clip.bytes.empty()) clip = {group, frame.clip, image.width, image.height, std::vector<std::uint8_t>(image.size() * frames)};
  const std::vector<std::uint8_t> bytes = clip_bytes(image);
  std::copy(bytes.begin(), bytes.end(), clip.bytes.begin() + static_cast<std::ptrdiff_t>(frame.frame * image.size()));
  if (frame.frame != frames - 1) return;
  Pending done = std::move(clip);
  partial_.erase({group, frame.clip});
  if (done.clip != "ground-truth") {
    complete_.push_back(std::move(done));
    return;
  }
  render::GreyClip reference{done.width, done.height, frames, std::vector<float>(done.bytes.size())};
  for (std::size_t i = 0; i < done.bytes.size(); ++i) reference.pixels[i] = done.bytes[i] / 255.0f;
  references_[group] = std::make_shared<const render::VideoVdpReference>(reference, render::video_vdp_standard_fhd(), kClipFramesPerSecond);
}

void ClipJods::flush() {
  std::vector<double> jods(complete_.size()), seconds(complete_.size());
  std::vector<char> measured(complete_.size(), 0);  // not vector<bool>: written from several threads
  render::parallel_rows(static_cast<int>(complete_.size()), threads_, [&](int i) {
    const Pending& clip = complete_[static_cast<std::size_t>(i)];
    const auto reference = references_.find(clip.group);
    if (reference == references_.end()) return;  // no ground truth of its group: no JOD
    const int frames = static_cast<int>(clip.bytes.size() / (static_cast<std::size_t>(clip.width) * clip.height));
    render::GreyClip test{clip.width, clip.height, frames, std::vector<float>(clip.bytes.size())};
    for (std::size_t p = 0; p < clip.bytes.size(); ++p) test.pixels[p] = clip.bytes[p] / 255.0f;
    const auto start = std::chrono::steady_clock::now();
    jods[i] = reference->second->compare(test).jod;
    seconds[i] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    measured[i] = 1;
  });
  for (std::size_t i = 0; i < complete_.size(); ++i) {
    if (!measured[i]) continue;
    jods_[{complete_[i].group, complete_[i].clip}] = jods[i];
    compare_seconds_ += seconds[i];
  }
  complete_.clear();
  partial_.clear();
  references_.clear();
}

void ClipJods::finish() { flush(); }

std::size_t ClipJods::annotate(nlohmann::json& table) const {
  std::size_t count = 0;
  const auto set = [&](nlohmann::json& row, const std::string& clip) {
    const auto it = jods_.find({{row.at("scene").get<std::string>(), row.at("alpha").get<double>(), row.at("fresnel").get<bool>()}, clip});
    if (it == jods_.end()) return;
    row["jod"] = it->second;
    ++count;
  };
  if (table.contains("cases"))
    for (nlohmann::json& row : table["cases"]) set(row, row.at("configuration").get<std::string>());
  if (table.contains("sanity"))
    for (nlohmann::json& row : table["sanity"]) set(row, "sanity:" + row.at("result").get<std::string>());
  return count;
}

}  // namespace saagen::report
