// The trade report: `saagen report` writes a self-contained report whose every image loads in a
// headless browser (Debian's chromium, installed by scripts/install-deps.sh; a missing browser
// fails this test, it never skips), and `saagen bench` prints and writes the trade table.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <tuple>

#include <sys/wait.h>

namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream stream(path, std::ios::binary);
  std::ostringstream text;
  text << stream.rdbuf();
  return text.str();
}

int run(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

class Report : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scratch_ = fs::temp_directory_path() / ("saagen-report-" + std::to_string(::getpid()));
    fs::remove_all(scratch_);
    fs::create_directories(scratch_);
    // A cost file in bench_shading's --json format, so the plot and the cost columns are drawn.
    nlohmann::json rows = nlohmann::json::array();
    const char* variants[] = {"forward-aniso-slope",
                              "forward-aniso-projected",
                              "forward-axis-slope",
                              "forward-axis-projected",
                              "deferred-previous",
                              "deferred-max",
                              "deferred-sum",
                              "deferred-avg",
                              "deferred-projected-space"};
    double ratio = 1.0;
    for (const char* variant : variants) {
      rows.push_back({{"target", "glsl"}, {"variant", variant}, {"cost_ratio", ratio += 0.01}, {"delta_spirv_instructions", 20}});
    }
    std::ofstream(scratch_ / "cost.json") << nlohmann::json{{"device", "test fixture"}, {"rows", rows}}.dump();
    const std::string command = std::string("'") + SAAGEN_CLI_PATH + "' report --preset quick --cost '" +
                                (scratch_ / "cost.json").string() + "' -o '" + (scratch_ / "report").string() + "' > '" +
                                (scratch_ / "report.log").string() + "' 2>&1";
    report_exit_ = run(command);
  }
  static void TearDownTestSuite() { fs::remove_all(scratch_); }

  static inline fs::path scratch_;
  static inline int report_exit_ = -1;
};

TEST_F(Report, WritesHtmlMarkdownSheetsAndPlot) {
  ASSERT_EQ(report_exit_, 0) << read_text(scratch_ / "report.log");
  const fs::path dir = scratch_ / "report";
  for (const char* file : {"index.html", "report.md", "trade_curved_forward.svg", "trade_curved_deferred.svg", "trade_bump_forward.svg"})
    EXPECT_TRUE(fs::exists(dir / file)) << file;
  int sheets = 0, strips = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".png") continue;
    const std::string name = entry.path().filename().string();
    sheets += name.rfind("sheet_", 0) == 0;
    strips += name.rfind("strip_", 0) == 0;
  }
  EXPECT_EQ(sheets, 8);  // quick preset: 4 scenes x 2 alphas, without Fresnel
  EXPECT_EQ(strips, 4);  // one per scene
  // The page opens with the verdict and the strips, before any table.
  const std::string html = read_text(dir / "index.html");
  const auto verdict = html.find("<h2>Verdict"), strip = html.find("strip_sphere.png"), first_table = html.find("<table>");
  ASSERT_NE(verdict, std::string::npos);
  ASSERT_NE(strip, std::string::npos);
  EXPECT_LT(verdict, strip);
  EXPECT_LT(strip, first_table);
  for (const char* text : {"deferred, curved: ", "forward, bump: ", "LDR-FLIP", "TDE", "Where the recommendation loses, per scene"})
    EXPECT_NE(html.find(text), std::string::npos) << text;
  // The run's log (stderr is a file here): one line per stage, no carriage-return frames.
  const std::string log = read_text(scratch_ / "report.log");
  EXPECT_EQ(log.find('\r'), std::string::npos);
  EXPECT_NE(log.find("[  0%] ground truth sphere\n"), std::string::npos) << log.substr(0, 300);
  EXPECT_NE(log.find("flicker bump_plane frame 4/4\n"), std::string::npos);
  const std::string markdown = read_text(dir / "report.md");
  EXPECT_NE(markdown.find("| deferred-avg |"), std::string::npos);
  EXPECT_NE(markdown.find("test fixture"), std::string::npos);
  // The trade of one content and path: no SAA's point, the engines as unlabelled orange
  // diamonds (6 engines + the legend's swatch), the frontier's labels in a column, none over
  // another (14 px apart at least).
  const std::string svg = read_text(dir / "trade_curved_forward.svg");
  EXPECT_NE(svg.find("forward, curved: image error against cost"), std::string::npos);
  EXPECT_NE(svg.find(">no SAA<"), std::string::npos);
  std::size_t orange = 0;
  for (std::size_t at = svg.find("#e67e22"); at != std::string::npos; at = svg.find("#e67e22", at + 1)) ++orange;
  EXPECT_EQ(orange, 7u);
  EXPECT_EQ(svg.find("engine-godot</text>"), std::string::npos);  // named in its tooltip only
  EXPECT_NE(svg.find("<title>engine-godot</title>"), std::string::npos);
  std::vector<double> label_y;
  for (std::size_t at = svg.find("<text x=\"442\" y=\""); at != std::string::npos; at = svg.find("<text x=\"442\" y=\"", at + 1))
    label_y.push_back(std::stod(svg.substr(at + 17)));
  std::sort(label_y.begin(), label_y.end());
  for (std::size_t i = 1; i < label_y.size(); ++i) EXPECT_GE(label_y[i] - label_y[i - 1], 14.0 - 1e-9);
  EXPECT_NE(markdown.find("## The trade per content and render path"), std::string::npos);
  EXPECT_NE(markdown.find("](trade_curved_forward.svg)"), std::string::npos);
  for (const char* section :
       {"## Recommended configuration", "## Switching from an engine's shipped form", "## Per scene:", "| engine-hdrp | curved |",
        "LDR-FLIP", "HDR-FLIP", "TDE", "excess flicker", "lost motion", "flicker tm ratio"})
    EXPECT_NE(markdown.find(section), std::string::npos) << section;
}

TEST_F(Report, EveryImageLoadsInHeadlessChromium) {
  ASSERT_EQ(report_exit_, 0) << read_text(scratch_ / "report.log");
  const fs::path dom = scratch_ / "dom.html";
  const std::string command =
      "chromium --headless --no-sandbox --disable-gpu --disable-background-networking --disable-component-update "
      "--disable-sync --no-first-run --user-data-dir='" +
      (scratch_ / "profile").string() + "' --virtual-time-budget=10000 --dump-dom 'file://" +
      (scratch_ / "report" / "index.html").string() + "' > '" + dom.string() + "' 2> /dev/null";
  ASSERT_EQ(run(command), 0) << "chromium did not run; scripts/install-deps.sh installs it";
  std::smatch match;
  const std::string page = read_text(dom);
  ASSERT_TRUE(std::regex_search(page, match, std::regex(R"(images loaded: (\d+)/(\d+))"))) << page.substr(0, 500);
  EXPECT_EQ(match[1].str(), match[2].str());
  EXPECT_EQ(match[2].str(), "16");  // 4 strips, 8 sheets and the trade plots (curved and bump, forward and deferred)
}

TEST_F(Report, BenchPrintsTheTableAndWritesJsonThePlannerReads) {
  const fs::path json = scratch_ / "trade.json";
  const std::string command = std::string("'") + SAAGEN_CLI_PATH + "' bench --preset quick --cost '" + (scratch_ / "cost.json").string() +
                              "' --json '" + json.string() + "' > '" + (scratch_ / "bench.txt").string() + "' 2> /dev/null";
  ASSERT_EQ(run(command), 0);
  const std::string table = read_text(scratch_ / "bench.txt");
  EXPECT_NE(table.find("RMSE tonemapped"), std::string::npos);
  EXPECT_NE(table.find("deferred-projected-space"), std::string::npos);
  // It ends with the verdict: one headline per path and content, LDR-FLIP and TDE against none and
  // the best engine, and where the recommendation loses (the quick preset has no normal maps).
  const auto verdict = table.rfind("Verdict: what to use");
  ASSERT_NE(verdict, std::string::npos);
  EXPECT_EQ(table.find("where it does not"), std::string::npos);  // the long loss lists are the report's
  for (const char* headline : {"\n  forward, curved: ", "\n  deferred, curved: ", "\n  forward, bump: ", "\n  deferred, bump: "})
    EXPECT_NE(table.find(headline, verdict), std::string::npos) << headline;
  EXPECT_NE(table.find("TDE ", verdict), std::string::npos);
  EXPECT_NE(table.find("(none ", verdict), std::string::npos);
  EXPECT_NE(table.find("best engine engine-", verdict), std::string::npos);
  const auto document = nlohmann::json::parse(read_text(json));
  // none + 11 variants + 6 engines, the 11 variants fed the geometric normal (the bump plane has
  // normal detail), the 7 lobe variants with the tail and mapped lobes on both feeds, and the bump
  // plane's band-limited rows: none+lean and the 6 prefiltered variants with LEAN's moments in
  // the papers', tail and mapped lobes.
  ASSERT_EQ(document["rows"].size(), 29u + 28u + 1u + 6u * 3u);
  for (const auto& row : document["rows"]) {
    EXPECT_TRUE(row["error"].is_number());
    // TDE and its parts: excess + lost <= TDE (image.hpp).
    ASSERT_TRUE(row["tde"].is_number()) << row.dump();
    EXPECT_GT(row["tde"].get<double>(), 0.0) << row["variant"];
    EXPECT_LE(row["tde_excess_flicker"].get<double>() + row["tde_lost_motion"].get<double>(), row["tde"].get<double>() * (1.0 + 1e-12));
  }
  for (const auto& row : document["by_content"]) EXPECT_TRUE(row["tde"].is_number());
  // A content row that beats no SAA names the content's scenes where it loses ("loses_on"): exactly
  // those whose per-scene comparison with no SAA is "loses" or "mixed".
  std::map<std::pair<std::string, std::string>, std::string> scene_outcome;
  for (const auto& c : document["comparisons"])
    if (c["scope"] == "scene") scene_outcome[{c["name"].get<std::string>(), c["configuration"].get<std::string>()}] = c["outcome"];
  std::map<std::string, std::string> content_of_scene;
  for (const auto& entry : document["decisions"]["per_scene"]) content_of_scene[entry["scene"]] = entry["content"];
  std::size_t beating = 0;
  for (const auto& row : document["by_content"]) {
    if (!row.contains("against_none")) continue;
    const auto& against = row["against_none"];
    const bool beats_mean = (against["image"]["high"].get<double>() < 0 || against["temporal"]["high"].get<double>() < 0) &&
                            against["image"]["low"].get<double>() <= 0 && against["temporal"]["low"].get<double>() <= 0;
    if (!beats_mean) continue;
    ++beating;
    std::set<std::string> expected;
    for (const auto& [key, outcome] : scene_outcome)
      if (key.second == row["configuration"] && content_of_scene[key.first] == row["content"] && (outcome == "loses" || outcome == "mixed"))
        expected.insert(key.first);
    const std::set<std::string> written = row.contains("loses_on") ? row["loses_on"].get<std::set<std::string>>() : std::set<std::string>{};
    EXPECT_EQ(written, expected) << row["content"] << " " << row["configuration"];
  }
  EXPECT_GT(beating, 0u);
  // A row's "not_worse_than" (the decision's ties) names only other rows of its content that could
  // be recommended as it could: beating no SAA and losing on none of the content's scenes.
  std::set<std::pair<std::string, std::string>> recommendable;
  for (const auto& row : document["by_content"])
    if (row.contains("against_none") && !row.contains("loses_on") && row["against_none"]["image"]["low"].get<double>() <= 0 &&
        row["against_none"]["temporal"]["low"].get<double>() <= 0 &&
        (row["against_none"]["image"]["high"].get<double>() < 0 || row["against_none"]["temporal"]["high"].get<double>() < 0))
      recommendable.emplace(row["content"].get<std::string>(), row["configuration"].get<std::string>());
  std::size_t paired = 0;
  for (const auto& row : document["by_content"]) {
    if (!row.contains("not_worse_than")) continue;
    const std::string content = row["content"], configuration = row["configuration"];
    EXPECT_TRUE(recommendable.contains({content, configuration})) << row.dump();
    for (const auto& other : row["not_worse_than"]) {
      EXPECT_NE(other.get<std::string>(), configuration);
      EXPECT_TRUE(recommendable.contains({content, other.get<std::string>()})) << configuration << " " << other;
      ++paired;
    }
  }
  EXPECT_GT(paired, 0u);
  // Per cell (one scene at one alpha), each configuration against no SAA: the difference of the two
  // cases' means, paired on that cell alone; a scene's comparison pools as many cells as it has.
  std::map<std::tuple<std::string, double, std::string>, double> case_image;
  for (const auto& c : document["cases"])
    if (!c["fresnel"].get<bool>()) case_image[{c["scene"], c["alpha"], c["configuration"]}] = c["image_error"]["mean"];
  std::map<std::pair<std::string, std::string>, int> cells_of_scene, scene_cells;
  for (const auto& c : document["comparisons"]) {
    const std::pair<std::string, std::string> key{c["name"], c["configuration"]};
    if (c["scope"] == "scene") scene_cells[key] = c["cells"];
    if (c["scope"] != "cell") continue;
    EXPECT_EQ(c["cells"], 1) << c.dump();
    ++cells_of_scene[key];
    const double alpha = c["alpha"];
    const auto with = case_image.find({key.first, alpha, key.second});
    const auto without = case_image.find({key.first, alpha, "none"});
    ASSERT_TRUE(with != case_image.end() && without != case_image.end()) << c.dump();
    EXPECT_NEAR(c["image_error"]["mean"].get<double>(), with->second - without->second, 1e-12) << c.dump();
    EXPECT_LE(c["image_error"]["low"].get<double>(), c["image_error"]["high"].get<double>());
  }
  EXPECT_FALSE(cells_of_scene.empty());
  EXPECT_EQ(cells_of_scene, scene_cells);
  // 3 scenes without normal detail x 2 alphas x (18 + 14 lobe) configurations + the bump plane's 2 x 76.
  EXPECT_EQ(document["cases"].size(), 3u * 2u * 32u + 2u * 76u);
}

TEST_F(Report, BadCostFileIsOneLineAndRendersNothing) {
  std::ofstream(scratch_ / "bad.json") << "{\"rows\": 3}";
  const std::string command = std::string("'") + SAAGEN_CLI_PATH + "' report --preset quick --cost '" + (scratch_ / "bad.json").string() +
                              "' -o '" + (scratch_ / "never").string() + "' 2> '" + (scratch_ / "err.txt").string() + "'";
  EXPECT_NE(run(command), 0);
  const std::string error = read_text(scratch_ / "err.txt");
  EXPECT_NE(error.find("no \"rows\" array"), std::string::npos) << error;
  EXPECT_EQ(std::count(error.begin(), error.end(), '\n'), 1) << error;
  EXPECT_FALSE(fs::exists(scratch_ / "never"));
}

}  // namespace
