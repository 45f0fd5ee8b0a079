// The saagen command line: what it writes, what it prints, and how it refuses bad input (one
// line on stderr, a non-zero exit, nothing written).
#include "support/cli_support.hpp"
#include "support/material_combinations.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <sys/wait.h>

namespace {

namespace fs = std::filesystem;

using saagen::test::CliRun;
using saagen::test::read_text;

class Cli : public saagen::test::CliTest {
 protected:
  // Asserts a refusal: non-zero exit, exactly one line on stderr containing `expected`.
  void expect_one_line_error(const CliRun& run, const std::string& expected) const {
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.err.find(expected), std::string::npos) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  }

  std::set<std::string> files_in(const fs::path& directory) const {
    std::set<std::string> names;
    if (!fs::exists(directory)) return names;
    for (const auto& entry : fs::directory_iterator(directory)) names.insert(entry.path().filename().string());
    return names;
  }
};

TEST_F(Cli, ListJsonIsTheContract) {
  const CliRun run = saagen({"list", "--json", "--prefix", "eng_"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["prefix"], "eng_");
  EXPECT_EQ(json["core_only_macro"], "ENG_CORE_ONLY");
  ASSERT_EQ(json["variants"].size(), 16u);  // 14 SAA variants, glints, glints-ggaa
  for (const auto& variant : json["variants"]) {
    for (const char* key : {"id", "summary", "paper", "equation", "render_path", "needs_tangents", "domain", "functions"}) {
      EXPECT_TRUE(variant.contains(key)) << key;
    }
    for (const auto& function : variant["functions"]) {
      EXPECT_EQ(function["emitted_name"].get<std::string>(), "eng_" + function["name"].get<std::string>());
      for (const auto& parameter : function["parameters"]) {
        EXPECT_FALSE(parameter["meaning"].get<std::string>().empty());
        EXPECT_TRUE(parameter["target_types"].contains("glsl"));
        EXPECT_TRUE(parameter["target_types"].contains("hlsl"));
      }
    }
  }
  const auto& sum = json["variants"][6];
  EXPECT_EQ(sum["id"], "deferred-sum");
  EXPECT_EQ(sum["needs_tangents"], false);
  EXPECT_EQ(sum["functions"][0]["parameters"][1]["target_types"]["hlsl"], "float3");
  // GLSL ES declarations carry their precision.
  EXPECT_EQ(sum["functions"][0]["parameters"][1]["target_types"]["gles"], "highp vec3");
  EXPECT_EQ(json["options"][0]["name"], "sigma2");
  EXPECT_EQ(json["options"][0]["default"], 0.25);
}

// The trade's numeric options refuse NaN and infinities (CLI::Range alone lets NaN through, and a
// NaN sigma^2 rendered every row alike with exit 0), in one line, before any rendering.
TEST_F(Cli, BenchRefusesNonFiniteNumbers) {
  for (const std::string command : {"bench", "report"}) {
    expect_one_line_error(saagen({command, "--preset", "quick", "--sigma2", "nan"}), "--sigma2: not a finite number in [1e-06, 16]");
    expect_one_line_error(saagen({command, "--preset", "quick", "--kappa", "nan"}), "--kappa: not a finite number in [1e-06, 1]");
    expect_one_line_error(saagen({command, "--preset", "quick", "--prefilter-scale", "nan"}),
                          "--prefilter-scale: not a finite number in [0, 4]");
    expect_one_line_error(saagen({command, "--preset", "quick", "--sigma2", "inf"}), "--sigma2: not a finite number");
    expect_one_line_error(saagen({command, "--preset", "quick", "--sigma2", "1e999"}), "--sigma2: not a finite number");
    expect_one_line_error(saagen({command, "--preset", "quick", "--derivatives", "sideways"}),
                          "--derivatives: sideways not in {coarse,fine}");
  }
}

// --truth-samples-scale K renders every ground truth with K times the strata per axis (the quick
// preset's 64 spp at K = 2: 256), and refuses a scale outside [1, 8] in one line.
TEST_F(Cli, BenchScalesTheGroundTruthsSamples) {
  const CliRun run = saagen({"bench", "--preset", "quick", "--scene", "sphere", "--resolution", "8", "--truth-samples-scale", "2"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("errors against the 256-spp ground truth"), std::string::npos) << run.out;
  expect_one_line_error(saagen({"bench", "--preset", "quick", "--truth-samples-scale", "0"}),
                        "--truth-samples-scale: Value 0 not in range 1 to 8");
}

// --resolution sets every scene's pixels and keeps its ground truths' samples: a glTF scene's stay
// at the presets' 4096 spp (saagen/report/presets.hpp), where a small highlight needs them.
TEST_F(Cli, BenchAtAResolutionKeepsAGltfScenesGroundTruthSamples) {
  const fs::path json = scratch_ / "trade.json";
  const CliRun run =
      saagen({"bench", "--preset", "medium", "--scene", "/usr/share/assimp/models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb",
              "--resolution", "16", "--json", json.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::ifstream in(json);
  const std::string config = nlohmann::json::parse(in)["config"].get<std::string>();
  EXPECT_NE(config.find("BoxTextured at 16x16 px, 4096 spp (animation 8x8 px, 4096 spp)"), std::string::npos) << config;
}

TEST_F(Cli, ListPrintsEveryVariant) {
  const CliRun run = saagen({"list"});
  ASSERT_EQ(run.exit_code, 0);
  for (const char* id : {"forward-aniso-slope", "deferred-projected-space", "brdf-beckmann"}) {
    EXPECT_NE(run.out.find(id), std::string::npos) << id;
  }
}

TEST_F(Cli, EmitWritesEveryVariantThenLeavesUnchangedFilesAlone) {
  const fs::path out = scratch_ / "out";
  const CliRun first = saagen({"emit", "--target", "hlsl", "-o", out.string()});
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_EQ(files_in(out).size(), 16u);  // the glint variants included
  EXPECT_TRUE(files_in(out).count("saa_deferred_avg.hlsl"));
  const auto stamp = fs::last_write_time(out / "saa_deferred_avg.hlsl");
  const std::string bytes = read_text(out / "saa_deferred_avg.hlsl");

  const CliRun second = saagen({"emit", "--target", "hlsl", "-o", out.string()});
  ASSERT_EQ(second.exit_code, 0);
  EXPECT_EQ(second.out.find("wrote"), std::string::npos) << second.out;
  EXPECT_EQ(std::count(second.out.begin(), second.out.end(), '\n'), 16);
  EXPECT_EQ(fs::last_write_time(out / "saa_deferred_avg.hlsl"), stamp);  // no needless rebuilds
  EXPECT_EQ(read_text(out / "saa_deferred_avg.hlsl"), bytes);
  EXPECT_EQ(files_in(out).size(), 16u);  // no temporaries left behind
}

TEST_F(Cli, EmitSelectedVariantsWithOptions) {
  const fs::path out = scratch_ / "out";
  const CliRun run = saagen({"emit", "-t", "glsl", "-v", "deferred-sum", "--variant", "forward-axis-projected", "--prefix", "my_",
                             "--sigma2", "0.5", "--kappa", "0.1", "-o", out.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(files_in(out), (std::set<std::string>{"my_deferred_sum.glsl", "my_forward_axis_projected.glsl"}));
  const std::string text = read_text(out / "my_deferred_sum.glsl");
  EXPECT_NE(text.find("const float my_SIGMA2 = 0.5;"), std::string::npos);
  EXPECT_NE(text.find("const float my_KAPPA = 0.1;"), std::string::npos);
}

// Presets and roughness domains: the engine's variant, constants and domain in one option;
// explicit options win; bad names are one line.
TEST_F(Cli, EmitPresetsAndDomains) {
  const fs::path out = scratch_ / "out";
  ASSERT_EQ(saagen({"emit", "--preset", "filament", "-o", out.string()}).exit_code, 0);
  ASSERT_EQ(saagen({"emit", "--preset", "hdrp", "--kappa", "0.1", "-t", "hlsl", "-o", out.string()}).exit_code, 0);
  ASSERT_EQ(saagen({"emit", "-v", "forward-axis-slope", "--domain", "alpha", "-o", out.string()}).exit_code, 0);
  EXPECT_EQ(files_in(out), (std::set<std::string>{"saa_deferred_sum_perceptual.glsl", "saa_deferred_sum_smoothness.hlsl",
                                                  "saa_forward_axis_slope_alpha.glsl"}));
  const std::string filament = read_text(out / "saa_deferred_sum_perceptual.glsl");
  EXPECT_NE(filament.find("const float saa_SIGMA2 = 0.15;"), std::string::npos);
  EXPECT_NE(filament.find("float saa_deferred_sum_fragment_perceptual(float perceptual_roughness, vec3 normal_ws)"), std::string::npos);
  EXPECT_NE(read_text(out / "saa_deferred_sum_smoothness.hlsl").find("static const float saa_KAPPA = 0.1;"), std::string::npos);
  EXPECT_NE(read_text(out / "saa_forward_axis_slope_alpha.glsl").find("vec2 saa_forward_axis_slope_alpha(vec2 alpha,"), std::string::npos);
  const CliRun validate = saagen({"validate", out.string()});
  EXPECT_NE(validate.out.find("3 file(s) validated, 0 failed"), std::string::npos) << validate.out << validate.err;

  const fs::path refused = scratch_ / "refused";
  expect_one_line_error(saagen({"emit", "--preset", "unreal", "-o", refused.string()}),
                        "--preset 'unreal' is not a preset; use one of hdrp, filament, filament-taa, o3de, bevy, vsgl");
  expect_one_line_error(saagen({"emit", "--domain", "linear", "-o", refused.string()}), "--domain 'linear' is not a roughness domain");
  expect_one_line_error(saagen({"emit", "-v", "brdf-beckmann", "--domain", "perceptual", "-o", refused.string()}),
                        "variant 'brdf-beckmann' takes or returns no scalar or per-axis roughness");
  // brdf-ggx's single-roughness mapping composes with every domain (its kernel stays alpha^2).
  const fs::path ggx_domain = scratch_ / "ggx-perceptual";
  const CliRun ggx = saagen({"emit", "-v", "brdf-ggx", "--domain", "perceptual", "-o", ggx_domain.string()});
  EXPECT_EQ(ggx.exit_code, 0) << ggx.err;
  EXPECT_NE(read_text(ggx_domain / "saa_brdf_ggx_perceptual.glsl")
                .find("float saa_ggx_filtered_alpha2_perceptual(float perceptual_roughness, float kernel)"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(refused));

  const auto listing = nlohmann::json::parse(saagen({"list", "--json", "--domain", "smoothness"}).out);
  EXPECT_EQ(listing["roughness_domain"], "smoothness");
  EXPECT_EQ(listing["presets"].size(), 6u);
  for (const auto& variant : listing["variants"]) {
    EXPECT_NE(std::find(variant["roughness_domains"].begin(), variant["roughness_domains"].end(), "smoothness"),
              variant["roughness_domains"].end());
  }
}

// `saagen compile` resolves <saagen/...> names as the include handlers do: generated in memory.
TEST_F(Cli, CompileGeneratesSaagenIncludeNames) {
  const fs::path shader = scratch_ / "material.frag";
  std::ofstream(shader) << "#version 450\n#include <saagen/filament.glsl>\nlayout(location = 0) in vec3 n;\n"
                           "layout(location = 0) out vec4 colour;\n"
                           "void main() { colour = vec4(saa_deferred_sum_fragment_perceptual(0.3, normalize(n))); }\n";
  const CliRun run = saagen({"compile", shader.string(), "-o", (scratch_ / "material.spv").string()});
  EXPECT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_TRUE(fs::exists(scratch_ / "material.spv"));

  const fs::path bad = scratch_ / "bad.frag";
  std::ofstream(bad) << "#version 450\n#include <saagen/filament.glsl?domain=linear>\nvoid main() {}\n";
  expect_one_line_error(saagen({"compile", bad.string(), "-o", (scratch_ / "bad.spv").string()}),
                        bad.string() + ":2: saagen/filament.glsl?domain=linear: --domain 'linear' is not a roughness domain");
  EXPECT_FALSE(fs::exists(scratch_ / "bad.spv"));
}

TEST_F(Cli, ValidateChecksWhatEmitWrote) {
  const fs::path out = scratch_ / "out";
  ASSERT_EQ(saagen({"emit", "-t", "glsl", "-o", out.string()}).exit_code, 0);
  ASSERT_EQ(saagen({"emit", "-t", "hlsl", "-o", out.string()}).exit_code, 0);
  const CliRun good = saagen({"validate", out.string()});
  EXPECT_EQ(good.exit_code, 0) << good.out << good.err;
  EXPECT_NE(good.out.find("32 file(s) validated, 0 failed"), std::string::npos) << good.out;

  // A hand edit that breaks the code is caught and named.
  const fs::path edited = out / "saa_deferred_max.hlsl";
  std::string text = read_text(edited);
  text.replace(text.find("return saturate"), 6, "retrun");
  std::ofstream(edited, std::ios::binary) << text;
  const CliRun bad = saagen({"validate", out.string()});
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.out.find("FAIL " + edited.string()), std::string::npos) << bad.out;
  EXPECT_NE(bad.out.find("32 file(s) validated, 1 failed"), std::string::npos) << bad.out;
}

TEST_F(Cli, ValidateWithoutDirectoryChecksEverything) {
  const CliRun run = saagen({"validate"});
  EXPECT_EQ(run.exit_code, 0) << run.out << run.err;
  // 16 variants (glints included) for each of glsl, gles, hlsl and wgsl (Tint).
  EXPECT_NE(run.out.find("64 file(s) validated, 0 failed"), std::string::npos) << run.out;
}

TEST_F(Cli, RejectsBadInputWithOneLineAndWritesNothing) {
  const fs::path out = scratch_ / "out";
  expect_one_line_error(saagen({"emit", "-v", "deferred-median", "-o", out.string()}),
                        "unknown variant 'deferred-median'; run `saagen list` to see the ids");
  expect_one_line_error(saagen({"emit", "-v", "deferred-sum", "-v", "nope", "-o", out.string()}), "unknown variant 'nope'");
  expect_one_line_error(saagen({"emit", "--target", "metal", "-o", out.string()}), "unknown target 'metal'");
  expect_one_line_error(saagen({"emit", "--sigma2", "abc", "-o", out.string()}), "--sigma2");
  expect_one_line_error(saagen({"emit", "--sigma2", "0", "-o", out.string()}), "--sigma2 0 is out of range: allowed (0, 4]");
  expect_one_line_error(saagen({"emit", "--kappa", "1.5", "-o", out.string()}), "--kappa 1.5 is out of range: allowed [0, 1]");
  expect_one_line_error(saagen({"emit", "--kappa", "nan", "-o", out.string()}), "--kappa nan is out of range");
  expect_one_line_error(saagen({"emit", "--prefix", "x;y", "-o", out.string()}), "invalid prefix 'x;y'");
  expect_one_line_error(saagen({"emit", "--prefix", "gl_", "-o", out.string()}), "'gl_' is reserved in GLSL");
  expect_one_line_error(saagen({"emit"}), "--output is required");
  expect_one_line_error(saagen({"frobnicate"}), "unknown command 'frobnicate'; use list, emit or validate");
  expect_one_line_error(saagen({"validate", (scratch_ / "missing").string()}), "not a directory");
  EXPECT_FALSE(fs::exists(out)) << "a refused command created the output directory";
}

TEST_F(Cli, UnwritableOutputIsOneLineAndLeavesNoPartialFiles) {
  const fs::path blocker = scratch_ / "a-file";
  std::ofstream(blocker) << "not a directory";
  expect_one_line_error(saagen({"emit", "-o", (blocker / "out").string()}), "cannot create the output directory");

  if (::geteuid() != 0) {  // root ignores directory permissions
    const fs::path locked = scratch_ / "locked";
    fs::create_directories(locked);
    fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
    expect_one_line_error(saagen({"emit", "-o", locked.string()}), "cannot write in this directory");
    EXPECT_TRUE(files_in(locked).empty());
  }
}

TEST_F(Cli, RefusesToOverwriteForeignFilesUnlessForced) {
  const fs::path out = scratch_ / "out";
  fs::create_directories(out);
  std::ofstream(out / "saa_deferred_sum.glsl") << "// my own shader\n";
  expect_one_line_error(saagen({"emit", "-o", out.string()}), "was not written by saagen; refusing to overwrite it (use --force)");
  EXPECT_EQ(files_in(out), std::set<std::string>{"saa_deferred_sum.glsl"});  // all or nothing
  EXPECT_EQ(read_text(out / "saa_deferred_sum.glsl"), "// my own shader\n");
  const CliRun forced = saagen({"emit", "--force", "-o", out.string()});
  EXPECT_EQ(forced.exit_code, 0) << forced.err;
  EXPECT_EQ(files_in(out).size(), 16u);
}

TEST_F(Cli, HelpOnEveryCommand) {
  for (const std::vector<std::string>& arguments :
       {std::vector<std::string>{"--help"}, {"list", "--help"}, {"emit", "--help"}, {"validate", "--help"}}) {
    const CliRun run = saagen(arguments);
    EXPECT_EQ(run.exit_code, 0) << arguments.front();
    EXPECT_NE(run.out.find("Usage"), std::string::npos) << run.out;
  }
}

// What a command prints must reach standard output: a full device there is a failure in one line
// with a non-zero exit, for every printing command (it was exit 0 with the output lost).
TEST_F(Cli, StandardOutputWriteFailuresAreOneLineAndNonZero) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  const std::string manifest = (fs::path(SAAGEN_SOURCE_DIR) / "examples" / "scene.saagen.toml").string();
  const std::vector<std::vector<std::string>> commands = {
      {"list", "--json"},
      {"list"},
      {"plan", manifest, "--no-cost"},
      {"plan", "--rules"},
      {"emit", "--manifest", manifest, "-o", (scratch_ / "m").string(), "--list-outputs"},
      {"emit", "-v", "deferred-sum", "-o", (scratch_ / "e").string()},
      {"--version"},
      {"--help"}};
  for (const auto& arguments : commands) {
    std::string command = saagen::test::shell_quote(SAAGEN_CLI_PATH);
    for (const std::string& argument : arguments) command.append(" ").append(saagen::test::shell_quote(argument));
    const fs::path err = scratch_ / "err.txt";
    const int status = std::system((command + " >/dev/full 2>" + saagen::test::shell_quote(err.string())).c_str());
    const std::string text = read_text(err);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1) << command;
    EXPECT_EQ(text, "saagen: error: standard output: write failed (No space left on device); check the file or pipe it goes to\n")
        << command;
  }
  EXPECT_EQ(saagen({"list", "--json"}).exit_code, 0);  // a working stdout is still exit 0
}

// `saagen plan` costs each distinct configuration once (a 1,000-material manifest took 62 s, one
// compile per material): 960 materials repeating 96 configurations under new names get, material
// by material, the cost lines of a plan of the 96 alone. How long that takes is bench_plan's
// (BM_PlanLargeManifest), not a unit test's: a wall-clock bound fails on a loaded or sanitized build.
TEST_F(Cli, PlanCostsEachDistinctConfigurationOnce) {
  ASSERT_EQ(saagen::test::material_key_combinations().size(), 96u);
  const auto manifest = [](std::size_t count) { return saagen::test::manifest_of_materials(count, "scene"); };
  // Per material, its "cost" line.
  const auto costs_of = [](const std::string& plan) {
    std::vector<std::string> costs;
    std::istringstream lines(plan);
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind("  cost ", 0) == 0) costs.push_back(line);
    }
    return costs;
  };
  std::ofstream(scratch_ / "small.toml") << manifest(96);
  std::ofstream(scratch_ / "large.toml") << manifest(960);
  const CliRun small = saagen({"plan", (scratch_ / "small.toml").string()});
  ASSERT_EQ(small.exit_code, 0) << small.err;
  const CliRun large = saagen({"plan", (scratch_ / "large.toml").string()});
  ASSERT_EQ(large.exit_code, 0) << large.err;
  const auto small_costs = costs_of(small.out), large_costs = costs_of(large.out);
  // Materials advised no filter (saagen/advice.hpp) have nothing to cost; the others one line each.
  ASSERT_GT(small_costs.size(), 48u);
  ASSERT_EQ(large_costs.size(), 10 * small_costs.size());
  for (std::size_t index = 0; index < large_costs.size(); ++index)
    EXPECT_EQ(large_costs[index], small_costs[index % small_costs.size()]) << "m" << index;
  EXPECT_GT(std::set<std::string>(small_costs.begin(), small_costs.end()).size(), 10u);  // the configurations do differ
}

}  // namespace
