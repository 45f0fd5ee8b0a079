// Scoring clips rendered elsewhere with the trade's verdict metrics (see score.hpp).
#include "saagen/report/score.hpp"

#include "saagen/error.hpp"
#include "saagen/io/input.hpp"
#include "saagen/measure/parallel.hpp"
#include "saagen/report/frames.hpp"
#include "saagen/report/trade_json.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <optional>

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#include <stb/stb_image.h>

namespace saagen::report {

namespace {

namespace fs = std::filesystem;

// The largest clip read: 4096 pixels a side of a frame, 2^26 pixels in all (64 MiB of bytes).
constexpr long long kMaxClipSide = 4096, kMaxClipPixels = 1LL << 26;

const char* const kFormatHint = "write it as `saagen bench --frames` does (report/frames.hpp)";

[[noreturn]] void fail_index(const fs::path& index, const std::string& what) {
  throw Error(fmt::format("{}: {}; {}", index.string(), what, kFormatHint));
}

nlohmann::json parse_index(const fs::path& index) {
  const std::string text = read_input_file(index, table_size_limit, "the index.json `saagen bench --frames` writes");
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& error) {
    fail_index(index, fmt::format("not JSON ({})", error.what()));
  }
}

const char* type_name(nlohmann::json::value_t type) {
  switch (type) {
    case nlohmann::json::value_t::string:
      return "string";
    case nlohmann::json::value_t::boolean:
      return "boolean";
    case nlohmann::json::value_t::array:
      return "array";
    default:
      return "number";
  }
}

// object[key], which must be of `type` (number_float: any number).
const nlohmann::json& field(const nlohmann::json& object, const char* key, nlohmann::json::value_t type, const fs::path& index,
                            const std::string& where) {
  const auto found = object.find(key);
  const bool numeric = type == nlohmann::json::value_t::number_float;
  if (found == object.end() || (numeric ? !found->is_number() : found->type() != type))
    fail_index(index, fmt::format("{}: '{}' must be a {}", where, key, type_name(type)));
  return *found;
}

int positive_int(const nlohmann::json& object, const char* key, const fs::path& index, const std::string& where) {
  const auto found = object.find(key);
  if (found == object.end() || !found->is_number_integer() || found->get<long long>() < 1 || found->get<long long>() > kMaxClipPixels)
    fail_index(index, fmt::format("{}: '{}' must be a positive integer", where, key));
  return found->get<int>();
}

// A clip's file: a relative path inside the directory.
fs::path clip_path(const fs::path& directory, const std::string& file, const fs::path& index, const std::string& where) {
  const fs::path relative = fs::path(file).lexically_normal();
  if (file.empty() || relative.is_absolute() || relative.begin()->string() == "..")
    fail_index(index, fmt::format("{}: clip file '{}' must be a relative path inside {}", where, file, directory.string()));
  return directory / relative;
}

// An 8-bit greyscale PNG of width x (height * frames) pixels, as a clip.
measure::ByteClip read_clip(const fs::path& path, int width, int height, int frames) {
  const std::string bytes = read_input_file(path, image_size_limit, "a clip PNG `saagen bench --frames` writes");
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = static_cast<int>(bytes.size());
  int w = 0, h = 0, channels = 0;
  if (!stbi_info_from_memory(data, size, &w, &h, &channels))
    throw Error(fmt::format("{}: not a readable PNG ({}); write 8-bit greyscale PNGs", path.string(), stbi_failure_reason()));
  if (channels != 1 || stbi_is_16_bit_from_memory(data, size))
    throw Error(fmt::format("{}: {} channel(s){}; write the clip as an 8-bit greyscale PNG (display values, no alpha)", path.string(),
                            channels, stbi_is_16_bit_from_memory(data, size) ? " of 16 bits" : ""));
  if (w != width || static_cast<long long>(h) != static_cast<long long>(height) * frames)
    throw Error(
        fmt::format("{}: {} x {} pixels, not the group's {} x {} ({} frames of {} x {} stacked top to bottom); write the clip at the "
                    "group's size",
                    path.string(), w, h, width, static_cast<long long>(height) * frames, frames, width, height));
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load_from_memory(data, size, &w, &h, &channels, 1), stbi_image_free);
  if (!pixels) throw Error(fmt::format("{}: not a readable PNG ({}); write 8-bit greyscale PNGs", path.string(), stbi_failure_reason()));
  measure::ByteClip clip{width, height, frames, {}};
  clip.bytes.assign(pixels.get(), pixels.get() + static_cast<std::size_t>(w) * h);
  return clip;
}

std::string group_name(const ClipGroupInput& group) {
  if (!group.material.empty()) return group.scene + "/" + group.material;
  return fmt::format("{}/a{}{}", group.scene, group.alpha, group.fresnel ? "-fresnel" : "");
}

ClipGroupInput read_group(const fs::path& directory, const fs::path& index, const nlohmann::json& json, std::size_t number) {
  const std::string where = fmt::format("group {}", number + 1);
  if (!json.is_object()) fail_index(index, where + " is not an object");
  ClipGroupInput group;
  group.scene = field(json, "scene", nlohmann::json::value_t::string, index, where).get<std::string>();
  group.alpha = field(json, "alpha", nlohmann::json::value_t::number_float, index, where).get<double>();
  group.fresnel = field(json, "fresnel", nlohmann::json::value_t::boolean, index, where).get<bool>();
  if (json.contains("material")) group.material = field(json, "material", nlohmann::json::value_t::string, index, where).get<std::string>();
  group.name = group_name(group);
  const int width = positive_int(json, "width", index, where), height = positive_int(json, "height", index, where);
  const int frames = positive_int(json, "frames", index, where);
  if (width > kMaxClipSide || height > kMaxClipSide || static_cast<long long>(width) * height * frames > kMaxClipPixels)
    fail_index(index, fmt::format("{}: {} frames of {} x {} is larger than saagen scores (at most {} a side, {} pixels in all)", where,
                                  frames, width, height, kMaxClipSide, kMaxClipPixels));
  const std::string reference = field(json, "reference", nlohmann::json::value_t::string, index, where).get<std::string>();
  group.seeds.push_back(read_clip(clip_path(directory, reference, index, where), width, height, frames));
  const nlohmann::json& clips = field(json, "clips", nlohmann::json::value_t::array, index, where);
  for (const nlohmann::json& clip : clips) {
    if (!clip.is_object()) fail_index(index, where + ": a clip is not an object");
    const std::string name = field(clip, "configuration", nlohmann::json::value_t::string, index, where).get<std::string>();
    const std::string file = field(clip, "file", nlohmann::json::value_t::string, index, where).get<std::string>();
    const bool repeated = std::any_of(group.results.begin(), group.results.end(), [&](const auto& result) { return result.first == name; });
    if (repeated) fail_index(index, fmt::format("{}: two clips named '{}'", where, name));
    group.results.emplace_back(name, read_clip(clip_path(directory, file, index, where), width, height, frames));
    if (name == kSecondSeedClip) group.seeds.push_back(group.results.back().second);
  }
  if (group.seeds.size() != 2)
    fail_index(index, fmt::format("{} ({}) has no second ground-truth seed; add its clip, named '{}'", where, group.name, kSecondSeedClip));
  return group;
}

bool is_sanity(const std::string& configuration) { return configuration.starts_with("sanity:"); }

const ScoredResult* find_result(const ScoredGroup& group, const std::string& configuration) {
  const auto found =
      std::find_if(group.results.begin(), group.results.end(), [&](const ScoredResult& r) { return r.configuration == configuration; });
  return found == group.results.end() ? nullptr : &*found;
}

ScoredGroup score_group(const ClipGroupInput& input, double frames_per_second, int threads) {
  const measure::ClipScorer scorer(input.seeds, frames_per_second);
  ScoredGroup group{input.name,           input.scene,           input.material,        input.alpha, input.fresnel,
                    input.seeds[0].width, input.seeds[0].height, input.seeds[0].frames, {},          {}};
  group.results.resize(input.results.size());
  measure::parallel_rows(static_cast<int>(input.results.size()), threads, [&](int i) {
    const auto& [name, clip] = input.results[static_cast<std::size_t>(i)];
    const bool sanity = is_sanity(name);
    group.results[static_cast<std::size_t>(i)] = {name, sanity, scorer.score(clip, sanity ? 1 : scorer.seeds())};
  });
  return group;
}

void compare_with_baselines(ScoredGroup& group, const std::vector<std::string>& baselines) {
  for (const std::string& baseline : baselines) {
    const ScoredResult* base = find_result(group, baseline);
    for (const ScoredResult& result : group.results) {
      if (result.sanity || result.configuration == baseline) continue;
      const CellPair cell{&result.score.series, &base->score.series};
      group.comparisons.push_back(compare_cells(result.configuration, baseline, std::span(&cell, 1)));
    }
  }
}

std::string interval_text(const measure::Interval& interval, int digits) {
  return fmt::format("{:.{}f} [{:.{}f}, {:.{}f}]", interval.mean, digits, interval.low, digits, interval.high, digits);
}

std::string difference_text(const MetricDifference& difference, int digits) {
  return fmt::format("{:+.{}f} [{:+.{}f}, {:+.{}f}] {}{}", difference.difference.mean, digits, difference.difference.low, digits,
                     difference.difference.high, digits, metric_outcome_name(outcome_of(difference)),
                     difference.ground_truth_limited ? " (ground truth limits)" : "");
}

}  // namespace

ClipSetInput read_clip_set(const fs::path& directory) {
  std::error_code error;
  if (!fs::is_directory(directory, error))
    throw Error(fmt::format("{}: not a directory; pass the directory `saagen bench --frames` wrote (its index.json and clip PNGs)",
                            directory.string()));
  const fs::path index = directory / "index.json";
  const nlohmann::json json = parse_index(index);
  if (!json.is_object()) fail_index(index, "not a JSON object");
  ClipSetInput input;
  input.frames_per_second = json.contains("fps")
                                ? field(json, "fps", nlohmann::json::value_t::number_float, index, "the index").get<double>()
                                : kClipFramesPerSecond;
  if (!(input.frames_per_second > 0.0)) fail_index(index, "'fps' must be above 0");
  const nlohmann::json& groups = field(json, "groups", nlohmann::json::value_t::array, index, "the index");
  if (groups.empty()) fail_index(index, "'groups' is empty");
  for (std::size_t g = 0; g < groups.size(); ++g) input.groups.push_back(read_group(directory, index, groups[g], g));
  return input;
}

ScoreTable score_clip_set(const ClipSetInput& input, const std::vector<std::string>& baselines, int threads) {
  for (const ClipGroupInput& group : input.groups)
    for (const std::string& baseline : baselines)
      if (std::none_of(group.results.begin(), group.results.end(), [&](const auto& r) { return r.first == baseline; }))
        throw Error(
            fmt::format("--baseline {}: group {} has no clip of that name; name a configuration every group has", baseline, group.name));
  ScoreTable table{baselines, {}};
  for (const ClipGroupInput& group : input.groups) {
    table.groups.push_back(score_group(group, input.frames_per_second, threads));
    compare_with_baselines(table.groups.back(), baselines);
  }
  return table;
}

std::string format_score_table(const ScoreTable& table) {
  std::string out;
  for (const ScoredGroup& group : table.groups) {
    out += fmt::format("{} ({} x {}, {} frames; 95 % intervals; sanity results against the first seed only)\n", group.name, group.width,
                       group.height, group.frames);
    out += fmt::format("  {:<34} {:<28} {:<28} {}\n", "clip", "image error (LDR-FLIP)", "video error (10 - JOD)", "lag");
    for (const ScoredResult& r : group.results)
      out += fmt::format("  {:<34} {:<28} {:<28} {}\n", r.configuration, interval_text(r.score.image_error, 4),
                         interval_text(r.score.video_error, 3), interval_text(r.score.lag, 4));
    for (const PairedComparison& c : group.comparisons) {
      out += fmt::format("  {:<34} vs {:<16} {:<6} image {}; video {}\n", c.configuration, c.baseline, comparison_outcome_name(c),
                         difference_text(c.image, 4), difference_text(temporal_metric(c), 3));
    }
    out += "\n";
  }
  return out;
}

nlohmann::json score_json(const ScoreTable& table) {
  nlohmann::json groups = nlohmann::json::array();
  for (const ScoredGroup& group : table.groups) {
    nlohmann::json results = nlohmann::json::array(), comparisons = nlohmann::json::array();
    for (const ScoredResult& r : group.results)
      results.push_back({{"configuration", r.configuration},
                         {"sanity", r.sanity},
                         {"image_error", interval_json(r.score.image_error)},
                         {"video_error", interval_json(r.score.video_error)},
                         {"flicker_error", interval_json(r.score.flicker_error)},
                         {"lag", interval_json(r.score.lag)}});
    for (const PairedComparison& c : group.comparisons) {
      comparisons.push_back({{"configuration", c.configuration},
                             {"baseline", c.baseline},
                             {"image_error", difference_json(c.image)},
                             {"flicker_error", difference_json(c.flicker)},
                             {"lag", difference_json(c.lag)},
                             {"outcome", std::string(comparison_outcome_name(c))}});
      if (c.video) comparisons.back()["video_error"] = difference_json(*c.video);
    }
    groups.push_back({{"name", group.name},
                      {"scene", group.scene},
                      {"material", group.material},
                      {"alpha", group.alpha},
                      {"fresnel", group.fresnel},
                      {"width", group.width},
                      {"height", group.height},
                      {"frames", group.frames},
                      {"results", results},
                      {"comparisons", comparisons}});
  }
  return {{"generator", std::string(output_tag) + " saagen score"}, {"baselines", table.baselines}, {"groups", groups}};
}

}  // namespace saagen::report
