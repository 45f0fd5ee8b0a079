// `saagen glints emit|validate|dictionary|lean`, and the glint variants of `saagen list|emit`, as whole processes.
#include "support/cli_support.hpp"

#include "saagen/error.hpp"
#include "saagen/products/glints.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <sys/wait.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;

using saagen::test::read_text;

class GlintCli : public saagen::test::CliTest {};

TEST_F(GlintCli, EmitsAndValidatesTheSnippets) {
  const fs::path out = scratch_ / "snippets";
  for (const std::string target : {"glsl", "hlsl"}) {
    const auto run = saagen({"glints", "emit", "--target", target, "--kernel-scale", "1", "-o", out.string()});
    ASSERT_EQ(run.exit_code, 0) << run.err;
  }
  EXPECT_TRUE(fs::exists(out / "saa_glints.glsl"));
  EXPECT_TRUE(fs::exists(out / "saa_glints_ggaa.hlsl"));
  EXPECT_NE(read_text(out / "saa_glints_ggaa.glsl").find("glint_kernel_scale=1.0"), std::string::npos);
  const auto validate = saagen({"glints", "validate", out.string()});
  EXPECT_EQ(validate.exit_code, 0) << validate.out << validate.err;
  EXPECT_NE(validate.out.find("4 file(s) validated, 0 failed"), std::string::npos) << validate.out;
  // A second emission leaves the files alone.
  const auto again = saagen({"glints", "emit", "--kernel-scale", "1", "-o", out.string()});
  EXPECT_NE(again.out.find("unchanged"), std::string::npos);
}

// Glints are variants like the others: `saagen list` shows them with the dictionary they read,
// `saagen emit --variant` writes them for GLSL and HLSL, and a SPIR-V library module (which cannot
// leave the dictionary binding to its consumer) is refused in one line.
TEST_F(GlintCli, GlintsAreListedAndEmittedLikeTheOtherVariants) {
  const auto list = saagen({"list"});
  ASSERT_EQ(list.exit_code, 0) << list.err;
  EXPECT_NE(list.out.find("glints-ggaa"), std::string::npos);
  EXPECT_NE(list.out.find("resources: glint_dictionary"), std::string::npos) << list.out;
  const auto json = nlohmann::json::parse(saagen({"list", "--json"}).out);
  const auto ggaa = std::find_if(json["variants"].begin(), json["variants"].end(), [](const auto& v) { return v["id"] == "glints-ggaa"; });
  ASSERT_NE(ggaa, json["variants"].end());
  EXPECT_EQ((*ggaa)["paper"].get<std::string>().rfind("Chermain", 0), 0u);
  EXPECT_FALSE((*ggaa)["equation"].get<std::string>().empty());
  EXPECT_EQ((*ggaa)["render_path"], "forward");
  ASSERT_EQ((*ggaa)["resources"].size(), 1u);
  EXPECT_EQ((*ggaa)["resources"][0]["name"], "glint_dictionary");
  EXPECT_NE((*ggaa)["resources"][0]["example_declaration"]["glsl"].get<std::string>().find("sampler1DArray"), std::string::npos);
  EXPECT_NE((*ggaa)["resources"][0]["example_declaration"]["hlsl"].get<std::string>().find("Texture1DArray"), std::string::npos);
  for (const auto& variant : json["variants"]) {
    if (variant["id"].get<std::string>().rfind("glints", 0) != 0) {
      EXPECT_TRUE(variant["resources"].empty()) << variant["id"];
    }
  }

  const fs::path out = scratch_ / "emitted";
  for (const std::string target : {"glsl", "hlsl"}) {
    const auto run = saagen({"emit", "--target", target, "--variant", "glints-ggaa", "-o", out.string()});
    ASSERT_EQ(run.exit_code, 0) << run.err;
  }
  EXPECT_TRUE(fs::exists(out / "saa_glints_ggaa.glsl"));
  EXPECT_TRUE(fs::exists(out / "saa_glints_ggaa.hlsl"));
  const auto validate = saagen({"validate", out.string()});
  EXPECT_EQ(validate.exit_code, 0) << validate.out << validate.err;

  const auto spirv = saagen({"emit", "--target", "spirv", "--variant", "glints-ggaa", "-o", (scratch_ / "spv").string()});
  EXPECT_NE(spirv.exit_code, 0);
  EXPECT_NE(spirv.err.find("glint_dictionary"), std::string::npos) << spirv.err;
  EXPECT_EQ(std::count(spirv.err.begin(), spirv.err.end(), '\n'), 1) << spirv.err;
  EXPECT_FALSE(fs::exists(scratch_ / "spv"));
  const auto every = saagen({"emit", "--target", "spirv", "-o", (scratch_ / "spv_all").string()});
  ASSERT_EQ(every.exit_code, 0) << every.err;
  EXPECT_EQ(every.out.find("glints"), std::string::npos) << every.out;
}

// A scene manifest with glints = true: the planner picks the glint variant (GGAA for accuracy,
// the textureLod baseline for speed) with lean_roughness for normal maps, and `emit --manifest`
// writes the dictionary next to the bundle.
TEST_F(GlintCli, ManifestWithGlintsPlansTheGlintVariantAndWritesTheDictionary) {
  const fs::path manifest = scratch_ / "glints.toml";
  std::ofstream(manifest) << "name = \"sparkle\"\ntargets = [\"glsl\", \"hlsl\"]\n"
                             "[[material]]\nname = \"paint\"\npath = \"forward\"\ntangents = true\nnormal_maps = true\nglints = true\n"
                             "[[material]]\nname = \"flakes\"\npath = \"forward\"\ntangents = true\nglints = true\nprefer = \"speed\"\n"
                             "[[material]]\nname = \"ground\"\npath = \"deferred\"\n";
  const auto plan = saagen({"plan", manifest.string()});
  ASSERT_EQ(plan.exit_code, 0) << plan.err;
  EXPECT_NE(plan.out.find("variant   glints-ggaa  [G1]"), std::string::npos) << plan.out;
  EXPECT_NE(plan.out.find("variant   glints  [G2]"), std::string::npos) << plan.out;
  EXPECT_NE(plan.out.find("saa_sparkle_glint_dictionary.ktx2"), std::string::npos) << plan.out;
  EXPECT_NE(plan.out.find("variant   deferred-aniso  [D0]"), std::string::npos) << plan.out;

  const fs::path out = scratch_ / "bundle";
  const auto emit = saagen({"emit", "--manifest", manifest.string(), "-o", out.string()});
  ASSERT_EQ(emit.exit_code, 0) << emit.err;
  const std::string bundle = read_text(out / "saa_sparkle.glsl");
  for (const char* function :
       {"saa_glint_brdf_filtered_fragment", "saa_glint_brdf_fragment", "saa_lean_roughness", "saa_glint_dictionary_grad_value"}) {
    EXPECT_NE(bundle.find(function), std::string::npos) << function;
  }
  const std::string bytes = read_text(out / "saa_sparkle_glint_dictionary.ktx2");
  const auto image = saagen::read_ktx2(std::vector<std::uint8_t>(bytes.begin(), bytes.end()));
  EXPECT_EQ(image.width, 64u);
  EXPECT_EQ(image.layers, 16u * 192u / 4u);
  const auto validate = saagen({"validate", out.string()});
  EXPECT_EQ(validate.exit_code, 0) << validate.out << validate.err;
  // Unchanged on a second run.
  const auto again = saagen({"emit", "--manifest", manifest.string(), "-o", out.string()});
  EXPECT_EQ(again.out.find("wrote"), std::string::npos) << again.out;

  // glints = true on a deferred material: one line with the file position, nothing written.
  const fs::path bad = scratch_ / "bad.toml";
  std::ofstream(bad) << "name = \"s\"\ntargets = [\"glsl\"]\n[[material]]\nname = \"m\"\npath = \"deferred\"\nglints = true\n";
  const auto rejected = saagen({"emit", "--manifest", bad.string(), "-o", (scratch_ / "bad_out").string()});
  EXPECT_NE(rejected.exit_code, 0);
  EXPECT_NE(rejected.err.find("bad.toml:6:"), std::string::npos) << rejected.err;
  EXPECT_NE(rejected.err.find("glints = true needs path = \"forward\" and tangents = true"), std::string::npos) << rejected.err;
  EXPECT_EQ(std::count(rejected.err.begin(), rejected.err.end(), '\n'), 1) << rejected.err;
  EXPECT_FALSE(fs::exists(scratch_ / "bad_out"));
}

// The glint options reach every way of emitting the glint variants: `emit --glint-*` and a
// manifest's glint_* keys set the constants, and the manifest's dictionary is generated with its
// glint_count, glint_lods and glint_alpha; without a glint variant or material they are refused.
TEST_F(GlintCli, GlintOptionsOnEmitAndInManifests) {
  const fs::path out = scratch_ / "emit";
  const auto emitted =
      saagen({"emit", "--variant", "glints-ggaa", "--glint-count", "64", "--glint-relative-area", "0.5", "-o", out.string()});
  ASSERT_EQ(emitted.exit_code, 0) << emitted.err;
  const std::string snippet = read_text(out / "saa_glints_ggaa.glsl");
  EXPECT_NE(snippet.find("saa_GLINT_COUNT = 64.0"), std::string::npos);
  EXPECT_NE(snippet.find("saa_GLINT_RELATIVE_AREA = 0.5"), std::string::npos);
  const auto no_glint = saagen({"emit", "--variant", "deferred-avg", "--glint-count", "64", "-o", (scratch_ / "none").string()});
  EXPECT_EQ(no_glint.exit_code, 1);
  EXPECT_NE(no_glint.err.find("--glint-* options set the glint variants' constants"), std::string::npos) << no_glint.err;
  const auto out_of_range = saagen({"emit", "--variant", "glints", "--glint-count", "3", "-o", (scratch_ / "range").string()});
  EXPECT_EQ(out_of_range.exit_code, 1);
  EXPECT_NE(out_of_range.err.find("--glint-count 3 is out of range"), std::string::npos) << out_of_range.err;
  EXPECT_FALSE(fs::exists(scratch_ / "none"));

  const fs::path manifest = scratch_ / "options.toml";
  std::ofstream(manifest) << "name = \"sparkle\"\ntargets = [\"glsl\"]\nglint_count = 32\nglint_lods = 8\nglint_max_anisotropy = 4\n"
                             "[[material]]\nname = \"paint\"\npath = \"forward\"\ntangents = true\nglints = true\n";
  const fs::path bundle = scratch_ / "bundle";
  const auto scene = saagen({"emit", "--manifest", manifest.string(), "-o", bundle.string()});
  ASSERT_EQ(scene.exit_code, 0) << scene.err;
  const std::string text = read_text(bundle / "saa_sparkle.glsl");
  EXPECT_NE(text.find("saa_GLINT_COUNT = 32.0"), std::string::npos);
  EXPECT_NE(text.find("saa_GLINT_MAX_ANISOTROPY = 4.0"), std::string::npos);
  const std::string bytes = read_text(bundle / "saa_sparkle_glint_dictionary.ktx2");
  const auto dictionary = saagen::read_ktx2(std::vector<std::uint8_t>(bytes.begin(), bytes.end()));
  EXPECT_EQ(dictionary.layers, 8u * 32u / 4u);  // L LODs x N / 4 RGBA layers
  EXPECT_EQ(dictionary.levels.size(), 7u);      // log2(64) + 1 MIP levels of the 64-texel distributions
  const auto entry = std::find_if(dictionary.key_values.begin(), dictionary.key_values.end(),
                                  [](const auto& key_value) { return key_value.first == "saagen.glints"; });
  ASSERT_NE(entry, dictionary.key_values.end());
  const auto description = nlohmann::json::parse(entry->second);
  EXPECT_EQ(description.at("count"), 32);
  EXPECT_EQ(description.at("lods"), 8);

  const fs::path plain = scratch_ / "plain.toml";
  std::ofstream(plain) << "targets = [\"glsl\"]\nglint_count = 32\n[[material]]\nname = \"m\"\npath = \"forward\"\n";
  const auto refused = saagen({"plan", plain.string()});
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.err.find("plain.toml:2:15: key 'glint_count': a glint option, and no material has glints = true"), std::string::npos)
      << refused.err;
}

TEST_F(GlintCli, RejectsBadOptionsInOneLine) {
  const auto run = saagen({"glints", "emit", "--count", "98", "-o", (scratch_ / "x").string()});
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find("multiple of 4"), std::string::npos) << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_FALSE(fs::exists(scratch_ / "x"));
  const auto dictionary = saagen({"glints", "dictionary", "--resolution", "48", "-o", (scratch_ / "d.ktx2").string()});
  EXPECT_NE(dictionary.exit_code, 0);
  EXPECT_NE(dictionary.err.find("power of two"), std::string::npos) << dictionary.err;
}

TEST_F(GlintCli, WritesTheDictionaryAndRawData) {
  const fs::path file = scratch_ / "dict.ktx2", raw = scratch_ / "dict.f32";
  const auto run = saagen({"glints", "dictionary", "--count", "8", "--lods", "6", "--resolution", "32", "--seed", "7", "-o", file.string(),
                           "--raw", raw.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string bytes = read_text(file);
  const auto image = saagen::read_ktx2(std::vector<std::uint8_t>(bytes.begin(), bytes.end()));
  EXPECT_EQ(image.width, 32u);
  EXPECT_EQ(image.layers, 12u);  // 6 LODs x 8 / 4
  EXPECT_EQ(image.levels.size(), 6u);
  const auto description = nlohmann::json::parse(image.key_values.at(1).second);
  EXPECT_EQ(description.at("seed"), 7);
  EXPECT_EQ(fs::file_size(raw), 12u * 32u * 4u * 4u);
  // Same parameters, same bytes (deterministic); a foreign file is not overwritten.
  ASSERT_EQ(
      saagen({"glints", "dictionary", "--count", "8", "--lods", "6", "--resolution", "32", "--seed", "7", "-o", file.string()}).exit_code,
      0);
  EXPECT_EQ(read_text(file), bytes);
  std::ofstream(scratch_ / "foreign.ktx2") << "not a texture";
  EXPECT_NE(saagen({"glints", "dictionary", "--count", "8", "--lods", "6", "-o", (scratch_ / "foreign.ktx2").string()}).exit_code, 0);
}

TEST_F(GlintCli, WritesLeanMomentsOfAPpmNormalMap) {
  std::string ppm = "P6\n4 4\n255\n";
  for (int t = 0; t < 16; ++t) ppm += std::string{static_cast<char>(100 + 8 * t), static_cast<char>(128), static_cast<char>(250)};
  std::ofstream(scratch_ / "normals.ppm", std::ios::binary) << ppm;
  const fs::path file = scratch_ / "lean.ktx2";
  const auto run = saagen({"glints", "lean", (scratch_ / "normals.ppm").string(), "-o", file.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string bytes = read_text(file);
  const auto image = saagen::read_ktx2(std::vector<std::uint8_t>(bytes.begin(), bytes.end()));
  EXPECT_EQ(image.vk_format, 109u);
  EXPECT_EQ(image.width, 4u);
  EXPECT_EQ(image.layers, 2u);
  EXPECT_EQ(image.levels.size(), 3u);
}

}  // namespace
