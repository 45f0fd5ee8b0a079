// `saagen score --frames DIR`: the inverse of `saagen bench --frames DIR` (frames.hpp). Clips in
// that format, rendered by anything (a browser, an engine), get the trade's verdict metrics
// (measure/clip_score.hpp: image error, video error, flicker error, lag, with 95 % intervals) and
// each result its paired comparison with each baseline (comparison.hpp: beats / ties / loses).
//
// DIR/index.json as frames.hpp describes it. Per group, the ground truth has two seeds: the
// group's "reference" and its clip named "sanity:other-seed" (as `bench --frames` writes them);
// every clip is a result. Clips named "sanity:NAME" are scored against the first seed only, as
// the trade scores its sanity results; the others against both. A group may name its material
// ("material"), which then names the group; else SCENE/aALPHA[-fresnel], as the clips' folders.
// Clips are 8-bit greyscale PNGs (no alpha), width x (height * frames).
#pragma once

#include "saagen/measure/clip_score.hpp"
#include "saagen/report/comparison.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace saagen::report {

// The name of the clip that holds a group's second ground-truth seed.
inline constexpr const char* kSecondSeedClip = "sanity:other-seed";

struct ClipGroupInput {
  std::string name;  // the group's material, else SCENE/aALPHA[-fresnel]
  std::string scene, material;
  double alpha = 0.0;
  bool fresnel = false;
  std::vector<measure::ByteClip> seeds;                            // the ground truth's two seeds
  std::vector<std::pair<std::string, measure::ByteClip>> results;  // every clip, in the index's order
};

struct ClipSetInput {
  double frames_per_second = 30.0;
  std::vector<ClipGroupInput> groups;
};

// DIR/index.json and its clips. Throws saagen::Error (naming the file and what to do) on anything
// it cannot read or that is not in the format.
ClipSetInput read_clip_set(const std::filesystem::path& directory);

struct ScoredResult {
  std::string configuration;
  bool sanity = false;  // a sanity result: scored against the first seed only
  measure::ClipScore score;
};

struct ScoredGroup {
  std::string name, scene, material;
  double alpha = 0.0;
  bool fresnel = false;
  int width = 0, height = 0, frames = 0;
  std::vector<ScoredResult> results;
  std::vector<PairedComparison> comparisons;  // every non-sanity result against each baseline but itself
};

struct ScoreTable {
  std::vector<std::string> baselines;
  std::vector<ScoredGroup> groups;
};

// Every group's results scored and compared with each baseline (a configuration every group has).
// Throws saagen::Error when a group lacks a baseline.
ScoreTable score_clip_set(const ClipSetInput& input, const std::vector<std::string>& baselines, int threads);

// The table as `saagen score` prints it, and as its --json writes it.
std::string format_score_table(const ScoreTable& table);
nlohmann::json score_json(const ScoreTable& table);

}  // namespace saagen::report
