// saagen score --frames DIR: clips in the format `saagen bench --frames` writes get the trade's
// verdict metrics. On the bench's own clips of a tiny scene it gives the bench's figures for
// those rows (the video metric exactly; the image error and lag up to the clips' 8-bit rounding);
// its sanity results rank as they must; a result identical to the baseline ties at 0; bad input
// is one line naming the file and what to do, a non-zero exit and no output.
#include "support/cli_support.hpp"

#include "saagen/report/report.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

namespace {

using saagen::test::read_text;

nlohmann::json read_json(const std::filesystem::path& path) { return nlohmann::json::parse(read_text(path)); }

void write_text(const std::filesystem::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

class ScoreCli : public saagen::test::CliTest {
 protected:
  // The bench's clips and table of one tiny scene (the quick preset's two alphas, 8 x 8 pixels,
  // 4 frames), once per test.
  void bench_frames() {
    const auto run =
        saagen({"bench", "--scene", "sphere", "--preset", "quick", "--resolution", "16", "--json", table(), "--frames", frames()});
    ASSERT_EQ(run.exit_code, 0) << run.err;
  }
  std::string table() const { return (scratch_ / "t.json").string(); }
  std::string frames() const { return (scratch_ / "frames").string(); }
  std::filesystem::path index_path() const { return scratch_ / "frames" / "index.json"; }

  nlohmann::json score_json(const std::vector<std::string>& extra = {}) {
    std::vector<std::string> arguments{"score", "--frames", frames(), "--json", (scratch_ / "s.json").string(), "--force"};
    arguments.insert(arguments.end(), extra.begin(), extra.end());
    const auto run = saagen(arguments);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return read_json(scratch_ / "s.json");
  }

  // A bad input: exit 1, one line on stderr that names `names`, nothing on stdout, no --json file.
  void expect_refused(const std::vector<std::string>& extra, const std::string& names) {
    const std::filesystem::path json = scratch_ / "refused.json";
    std::vector<std::string> arguments{"score", "--frames", frames(), "--json", json.string()};
    arguments.insert(arguments.end(), extra.begin(), extra.end());
    const auto run = saagen(arguments);
    EXPECT_NE(run.exit_code, 0);
    EXPECT_TRUE(run.out.empty()) << run.out;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_NE(run.err.find(names), std::string::npos) << run.err;
    EXPECT_FALSE(std::filesystem::exists(json));
  }
};

const nlohmann::json& result_of(const nlohmann::json& group, const std::string& configuration) {
  for (const nlohmann::json& result : group["results"])
    if (result["configuration"] == configuration) return result;
  throw std::runtime_error("no result " + configuration);
}

TEST_F(ScoreCli, ReproducesTheBenchsFiguresForItsOwnClips) {
  bench_frames();
  const nlohmann::json bench = read_json(table());
  const nlohmann::json scored = score_json();
  ASSERT_EQ(scored["groups"].size(), 2u);
  int cases = 0, sanity = 0;
  for (const nlohmann::json& group : scored["groups"]) {
    for (const nlohmann::json& result : group["results"]) {
      const std::string configuration = result["configuration"];
      const bool is_sanity = result["sanity"].get<bool>();
      EXPECT_EQ(is_sanity, configuration.starts_with("sanity:")) << configuration;
      const nlohmann::json& rows = bench[is_sanity ? "sanity" : "cases"];
      const auto row = std::find_if(rows.begin(), rows.end(), [&](const nlohmann::json& r) {
        const std::string name = is_sanity ? "sanity:" + r["result"].get<std::string>() : r["configuration"].get<std::string>();
        return r["alpha"] == group["alpha"] && r["fresnel"] == group["fresnel"] && name == configuration;
      });
      ASSERT_NE(row, rows.end()) << group["name"] << " " << configuration;
      // The bench's case rows carry intervals (against both seeds), its sanity rows means (against the first).
      const auto mean = [&](const char* metric) { return is_sanity ? (*row)[metric].get<double>() : (*row)[metric]["mean"].get<double>(); };
      // The video metric reads the same 8-bit frames: the same figure.
      EXPECT_NEAR(result["video_error"]["mean"].get<double>(), mean("video_error"), 1e-9) << configuration;
      // LDR-FLIP and the lag read the frames' 8-bit rounding here, the unrounded values in the bench.
      EXPECT_NEAR(result["image_error"]["mean"].get<double>(), mean("image_error"), 2e-3) << configuration;
      EXPECT_NEAR(result["lag"]["mean"].get<double>(), mean("lag"), 1e-4) << configuration;
      if (!is_sanity) {
        EXPECT_NEAR(result["video_error"]["low"].get<double>(), (*row)["video_error"]["low"].get<double>(), 1e-9) << configuration;
        EXPECT_NEAR(result["video_error"]["high"].get<double>(), (*row)["video_error"]["high"].get<double>(), 1e-9) << configuration;
        EXPECT_NEAR(result["image_error"]["low"].get<double>(), (*row)["image_error"]["low"].get<double>(), 3e-3) << configuration;
        EXPECT_NEAR(result["image_error"]["high"].get<double>(), (*row)["image_error"]["high"].get<double>(), 3e-3) << configuration;
      }
      ++(is_sanity ? sanity : cases);
    }
    // The known ranking: a frozen clip is worse than another seed of the ground truth.
    EXPECT_GT(result_of(group, "sanity:frozen")["image_error"]["mean"].get<double>(),
              result_of(group, "sanity:other-seed")["image_error"]["mean"].get<double>() + 0.02);
    // Every non-sanity result is compared with the baseline: none against itself, the others once.
    int compared = 0;
    for (const nlohmann::json& c : group["comparisons"]) {
      EXPECT_EQ(c["baseline"], "none");
      EXPECT_NE(c["configuration"], "none");
      EXPECT_TRUE(c["outcome"] == "beats" || c["outcome"] == "ties" || c["outcome"] == "loses" || c["outcome"] == "mixed") << c;
      ++compared;
    }
    EXPECT_EQ(compared, static_cast<int>(group["results"].size()) - 1 - 6);  // less none and the 6 sanity results
  }
  EXPECT_EQ(cases, static_cast<int>(bench["cases"].size()));
  EXPECT_EQ(sanity, static_cast<int>(bench["sanity"].size()));
}

// With --taa the bench writes the +taa rows' resolved clips too (beside the sanity clips, which
// give the score its second ground-truth seed), and scoring them gives the video error the bench
// measured under TAA (its taa_cases rows: the mean against both seeds).
TEST_F(ScoreCli, TheTaaRowsClipsGiveTheBenchsFiguresUnderTaa) {
  const auto run = saagen({"bench", "--scene", "sphere", "--preset", "quick", "--resolution", "16", "--taa", "--json", table(), "--frames",
                           frames(), "--frames-filter", "^(none|none\\+taa|deferred-avg\\+taa/tail|sanity:.*)$"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json bench = read_json(table());
  const nlohmann::json scored = score_json();
  int taa_results = 0;
  for (const nlohmann::json& group : scored["groups"])
    for (const nlohmann::json& result : group["results"]) {
      const std::string configuration = result["configuration"];
      if (configuration.find("+taa") == std::string::npos) continue;
      ++taa_results;
      const auto& rows = bench["taa_cases"];
      const auto row = std::find_if(rows.begin(), rows.end(), [&](const nlohmann::json& r) {
        return r["alpha"] == group["alpha"] && r["configuration"] == configuration && r["taa"].get<bool>();
      });
      ASSERT_NE(row, rows.end()) << configuration;
      EXPECT_NEAR(result["video_error"]["mean"].get<double>(), (*row)["video_error"].get<double>(), 1e-9) << configuration;
      EXPECT_NEAR(result["image_error"]["mean"].get<double>(), (*row)["image_error"].get<double>(), 2e-3) << configuration;
    }
  EXPECT_EQ(taa_results, 4);  // none+taa and deferred-avg+taa/tail at the quick preset's two alphas
}

TEST_F(ScoreCli, AClipEqualToTheGroundTruthScoresZeroAndTheBaselineTiesWithItself) {
  bench_frames();
  nlohmann::json index = read_json(index_path());
  nlohmann::json& group = index["groups"][0];
  // The first seed's clip, as a sanity result (scored against the first seed only), and the
  // baseline's clip under a second name.
  const std::string none_file = [&] {
    for (const nlohmann::json& clip : group["clips"])
      if (clip["configuration"] == "none") return clip["file"].get<std::string>();
    return std::string();
  }();
  group["clips"].push_back({{"configuration", "sanity:same"}, {"file", group["reference"]}});
  group["clips"].push_back({{"configuration", "none-again"}, {"file", none_file}});
  write_text(index_path(), index.dump(1));
  const nlohmann::json scored = score_json();
  const nlohmann::json& scored_group = scored["groups"][0];
  EXPECT_NEAR(result_of(scored_group, "sanity:same")["image_error"]["mean"].get<double>(), 0.0, 1e-12);
  EXPECT_NEAR(result_of(scored_group, "sanity:same")["video_error"]["mean"].get<double>(), 0.0, 1e-6);
  bool found = false;
  for (const nlohmann::json& c : scored_group["comparisons"]) {
    if (c["configuration"] != "none-again") continue;
    found = true;
    EXPECT_EQ(c["outcome"], "ties");
    EXPECT_EQ(c["image_error"]["mean"].get<double>(), 0.0);
    EXPECT_EQ(c["video_error"]["mean"].get<double>(), 0.0);
  }
  EXPECT_TRUE(found);
}

TEST_F(ScoreCli, TwoBaselinesGiveEachResultTwoComparisons) {
  bench_frames();
  const nlohmann::json scored = score_json({"--baseline", "none", "--baseline", "engine-threejs"});
  const nlohmann::json& group = scored["groups"][0];
  int against_none = 0, against_threejs = 0;
  for (const nlohmann::json& c : group["comparisons"]) ++(c["baseline"] == "none" ? against_none : against_threejs);
  EXPECT_EQ(against_none, against_threejs);
  EXPECT_GT(against_none, 10);
}

TEST_F(ScoreCli, RefusesBadInputInOneLineWithoutOutput) {
  expect_refused({}, "not a directory");  // no clips yet
  bench_frames();
  expect_refused({"--baseline", "no-such-configuration"}, "--baseline no-such-configuration");
  const std::string original = read_text(index_path());
  write_text(index_path(), "{ not json");
  expect_refused({}, "index.json: not JSON");
  nlohmann::json index = nlohmann::json::parse(original);
  // No second seed: the sanity:other-seed clip left out.
  nlohmann::json without_seed = index;
  nlohmann::json& clips = without_seed["groups"][0]["clips"];
  clips.erase(std::remove_if(clips.begin(), clips.end(), [](const nlohmann::json& c) { return c["configuration"] == "sanity:other-seed"; }),
              clips.end());
  write_text(index_path(), without_seed.dump());
  expect_refused({}, "no second ground-truth seed");
  // A size the clips do not have.
  nlohmann::json wrong_size = index;
  wrong_size["groups"][0]["width"] = 4;
  write_text(index_path(), wrong_size.dump());
  expect_refused({}, "not the group's");
  // A clip outside the directory.
  nlohmann::json outside = index;
  outside["groups"][0]["reference"] = "../t.json";
  write_text(index_path(), outside.dump());
  expect_refused({}, "must be a relative path inside");
  // An RGB clip.
  const std::string rgb_file = index["groups"][0]["reference"];
  const int width = index["groups"][0]["width"], height = index["groups"][0]["height"], frames = index["groups"][0]["frames"];
  write_text(
      scratch_ / "frames" / rgb_file,
      saagen::report::encode_tagged_png(width, height * frames, 3, std::vector<std::uint8_t>(3u * width * height * frames, 128), "test"));
  write_text(index_path(), original);
  expect_refused({}, "8-bit greyscale PNG");
}

}  // namespace
