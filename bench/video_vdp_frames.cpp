// saagen's ColorVideoVDP (measure/video_vdp.hpp) on the clips of a `saagen bench --frames DIR`
// folder: the JOD of every clip against its group's ground truth, written as the rows
// scripts/video_metric.py writes (scene, alpha, fresnel, configuration, clip, jod, seconds), so
// that scripts/video_vdp_match.py can compare the two (docs/COLORVIDEOVDP.md).
//
//   video_vdp_frames --frames DIR --out J.json [--filter REGEX] [--reference-clip NAME]
//                    [--fps F] [--threads N]
//   video_vdp_frames --write-synthetic DIR
//
// --filter keeps the rows whose 'scene/aALPHA/configuration' matches (ECMAScript, searched);
// --reference-clip compares with that clip of each group instead of the ground truth (which
// becomes a row named "ground-truth"), as video_metric.py does. Display standard_fhd; fps: --fps,
// else the index's "fps", else 30. "seconds" is the comparison's own time on one thread (the
// group's reference half, done once per group, is reported apart).
// --write-synthetic writes the synthetic clips of tests/support/video_vdp_clips.hpp as such a folder.
#include "support/video_vdp_clips.hpp"

#include "saagen/measure/parallel.hpp"
#include "saagen/measure/video_vdp.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using saagen::measure::GreyClip;
namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& message) {
  std::cerr << "video_vdp_frames: " << message << "\n";
  std::exit(2);
}

// A clip PNG: 8-bit grey (or the Rec. 709 luma of RGB), frames stacked top to bottom.
GreyClip load_clip(const fs::path& path, int frames) {
  int width = 0, height = 0, channels = 0;
  unsigned char* data = stbi_load(path.string().c_str(), &width, &height, &channels, 0);
  if (!data) fail(fmt::format("{}: cannot read the PNG ({})", path.string(), stbi_failure_reason()));
  if (frames <= 0 || height % frames != 0) {
    stbi_image_free(data);
    fail(fmt::format("{}: {} rows do not hold {} frames", path.string(), height, frames));
  }
  GreyClip clip{width, height / frames, frames, std::vector<float>(static_cast<std::size_t>(width) * height)};
  for (std::size_t i = 0; i < clip.pixels.size(); ++i) {
    const unsigned char* p = data + i * channels;
    const double v = channels >= 3 ? (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) / 255.0 : p[0] / 255.0;
    clip.pixels[i] = static_cast<float>(v);
  }
  stbi_image_free(data);
  return clip;
}

int write_synthetic(const fs::path& directory) {
  namespace test = saagen::test;
  fs::create_directories(directory);
  nlohmann::json groups = nlohmann::json::array();
  for (const test::SyntheticSize& size : test::kSyntheticSizes) {
    nlohmann::json group = {{"scene", std::string("synthetic-") + size.name},
                            {"alpha", 0.1},
                            {"fresnel", false},
                            {"width", size.width},
                            {"height", size.height},
                            {"frames", size.frames},
                            {"clips", nlohmann::json::array()}};
    fs::create_directories(directory / size.name);
    for (test::SyntheticVariant variant : test::kSyntheticVariants) {
      const std::vector<std::uint8_t> bytes = test::synthetic_clip(size, variant);
      const std::string file = fmt::format("{}/{}.png", size.name, test::synthetic_variant_name(variant));
      if (!stbi_write_png((directory / file).string().c_str(), size.width, size.height * size.frames, 1, bytes.data(), size.width))
        fail(fmt::format("cannot write {}", (directory / file).string()));
      if (variant == test::SyntheticVariant::reference) {
        group["reference"] = file;
        // The reference itself as a row too: the identical clip scores 10.
        group["clips"].push_back({{"configuration", "identical"}, {"file", file}});
      } else {
        group["clips"].push_back({{"configuration", test::synthetic_variant_name(variant)}, {"file", file}});
      }
    }
    groups.push_back(group);
  }
  const nlohmann::json index = {{"generator", "bench/video_vdp_frames --write-synthetic (tests/support/video_vdp_clips.hpp)"},
                                {"version", 1},
                                {"fps", 30},
                                {"groups", groups}};
  std::ofstream(directory / "index.json") << index.dump(1) << "\n";
  std::cout << fmt::format("wrote {} synthetic clip groups and {}/index.json\n", groups.size(), directory.string());
  return 0;
}

struct Arguments {
  std::string frames_dir, out_path, filter, reference_clip, synthetic;
  double fps = 0.0;
  int threads = 0;
};

Arguments parse_arguments(int argc, char** argv) {
  Arguments a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) fail(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--frames")
      a.frames_dir = value();
    else if (arg == "--out")
      a.out_path = value();
    else if (arg == "--filter")
      a.filter = value();
    else if (arg == "--reference-clip")
      a.reference_clip = value();
    else if (arg == "--fps")
      a.fps = std::stod(value());
    else if (arg == "--threads")
      a.threads = std::stoi(value());
    else if (arg == "--write-synthetic")
      a.synthetic = value();
    else
      fail("unknown argument " + arg + " (see the comment at the top of bench/video_vdp_frames.cpp)");
  }
  return a;
}

// Totals over the groups: the comparisons' and the references' own times.
struct Timing {
  double compare_seconds = 0.0, reference_seconds = 0.0;
  std::size_t compared = 0, references = 0;
};

// The rows of one group of the index: each clip the filter keeps against the group's reference
// (or --reference-clip, the ground truth then being a row "ground-truth").
void score_group(const nlohmann::json& group, const Arguments& a, double fps, const std::regex& pattern,
                 const saagen::measure::VideoVdpDisplay& display, nlohmann::json& rows, Timing& timing) {
  const std::string scene = group.at("scene");
  const double alpha = group.at("alpha");
  const bool fresnel = group.value("fresnel", false);
  const int frames = group.at("frames");
  struct Row {
    std::string configuration, file;
    double jod = 0.0, seconds = 0.0;
  };
  std::string reference = group.at("reference");
  std::vector<Row> todo;
  for (const nlohmann::json& clip : group.at("clips")) todo.push_back({clip.at("configuration"), clip.at("file")});
  if (!a.reference_clip.empty()) {
    const auto swap = std::find_if(todo.begin(), todo.end(), [&](const Row& r) { return r.configuration == a.reference_clip; });
    if (swap == todo.end()) return;
    const std::string ground_truth = reference;
    reference = swap->file;
    todo.erase(swap);
    todo.insert(todo.begin(), Row{"ground-truth", ground_truth});
  }
  std::erase_if(todo, [&](const Row& r) { return !std::regex_search(fmt::format("{}/a{:g}/{}", scene, alpha, r.configuration), pattern); });
  if (todo.empty()) return;
  const auto t0 = std::chrono::steady_clock::now();
  const saagen::measure::VideoVdpReference vdp(load_clip(fs::path(a.frames_dir) / reference, frames), display, fps);
  timing.reference_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++timing.references;
  saagen::measure::parallel_rows(static_cast<int>(todo.size()), a.threads, [&](int i) {
    const GreyClip test = load_clip(fs::path(a.frames_dir) / todo[i].file, frames);
    const auto start = std::chrono::steady_clock::now();
    todo[i].jod = vdp.compare(test).jod;
    todo[i].seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  });
  for (const Row& r : todo) {
    rows.push_back({{"scene", scene},
                    {"alpha", alpha},
                    {"fresnel", fresnel},
                    {"configuration", r.configuration},
                    {"clip", r.file},
                    {"jod", r.jod},
                    {"seconds", r.seconds}});
    timing.compare_seconds += r.seconds;
    ++timing.compared;
  }
}

}  // namespace

int main(int argc, char** argv) {
  const Arguments a = parse_arguments(argc, argv);
  if (!a.synthetic.empty()) return write_synthetic(a.synthetic);
  if (a.frames_dir.empty() || a.out_path.empty()) fail("--frames DIR and --out FILE are required");
  std::ifstream index_file(fs::path(a.frames_dir) / "index.json");
  if (!index_file) fail(a.frames_dir + ": no index.json (written by saagen bench --frames DIR)");
  const nlohmann::json index = nlohmann::json::parse(index_file);
  const double fps = a.fps > 0.0 ? a.fps : index.value("fps", 30.0);
  const std::regex pattern(a.filter.empty() ? "." : a.filter, std::regex::ECMAScript);
  const saagen::measure::VideoVdpDisplay display = saagen::measure::video_vdp_standard_fhd();

  nlohmann::json rows = nlohmann::json::array();
  Timing timing;
  const auto started = std::chrono::steady_clock::now();
  for (const nlohmann::json& group : index.at("groups")) score_group(group, a, fps, pattern, display, rows, timing);
  const nlohmann::json result = {{"metric", "ColorVideoVDP (saagen C++, saagen/measure/video_vdp.hpp)"},
                                 {"display", display.name},
                                 {"fps", fps},
                                 {"frames", fs::absolute(a.frames_dir).string()},
                                 {"filter", a.filter},
                                 {"reference_clip", a.reference_clip.empty() ? "ground-truth" : a.reference_clip},
                                 {"rows", rows}};
  std::ofstream(a.out_path) << result.dump(1) << "\n";
  std::cerr << fmt::format("{} rows: {:.4f} s per comparison, {:.4f} s per reference (one thread each), {:.1f} s in all -> {}\n",
                           timing.compared, timing.compared ? timing.compare_seconds / timing.compared : 0.0,
                           timing.references ? timing.reference_seconds / timing.references : 0.0,
                           std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), a.out_path);
  return 0;
}
