// Messages (test_safety): entry points and constants that would vanish in the target precision,
// and one line that names the file or the option and says what to do -- empty, repeated and lone
// options, escaped control characters, exact numbers, options checked before long work.
#include "safety_support.hpp"

#include "saagen/error.hpp"
#include "saagen/io/ktx2.hpp"
#include "saagen/saagen.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

using saagen::test::CliRun;
using saagen::test::read_text;
using saagen::test::Safety;
using saagen::test::shell_quote;

// ---------------------------------------------------------------------------------------------
// 7. Entry points and constants that would vanish in the target precision.

TEST_F(Safety, EntryPointsAreChecked) {
  write(scratch_ / "h.hlsl", "RWStructuredBuffer<float> b;\n[numthreads(1, 1, 1)] void cs_main() { b[0] = 1.0; }\n");
  expect_one_line_error(
      saagen({"compile", (scratch_ / "h.hlsl").string(), "--stage", "comp", "--entry", "nope", "-o", (scratch_ / "h.spv").string()}),
      "entry point 'nope' not found");
  EXPECT_EQ(
      saagen({"compile", (scratch_ / "h.hlsl").string(), "--stage", "comp", "--entry", "cs_main", "-o", (scratch_ / "h.spv").string()})
          .exit_code,
      0);
  write(scratch_ / "g.comp", "#version 450\nlayout(local_size_x = 1) in;\nvoid main() {}\n");
  expect_one_line_error(saagen({"compile", (scratch_ / "g.comp").string(), "--entry", "cs_main", "-o", (scratch_ / "g.spv").string()}),
                        "--entry applies to HLSL only");
}

TEST_F(Safety, ConstantsThatRoundToZeroInTheTargetPrecisionAreRefused) {
  expect_one_line_error(saagen({"emit", "--sigma2", "1e-310", "-o", (scratch_ / "o").string()}), "below the smallest normal fp32 number");
  expect_one_line_error(saagen({"emit", "--sigma2", "1e-10", "--precision", "fp16", "-o", (scratch_ / "o").string()}),
                        "below the smallest normal fp16 number");
  EXPECT_EQ(saagen({"emit", "--kappa", "0", "-v", "deferred-sum", "-o", (scratch_ / "o").string()}).exit_code, 0);  // zero is exact
}

// ---------------------------------------------------------------------------------------------
// 9. Messages: one line that names the file or the option and says what to do.

// LEAN moments are floats: a normal within 1e-18 of the surface plane (z = 1e-30 in a float KTX2)
// would store +inf; it is refused naming the texel, and nothing is written.
TEST_F(Safety, LeanMomentsAreFiniteOrTheTexelIsNamed) {
  saagen::Ktx2Image image;
  image.vk_format = 109;  // R32G32B32A32_SFLOAT
  image.type_size = 4;
  image.width = image.height = 2;
  const std::vector<float> texels = {0, 0, 1, 1, 1, 0, 1e-30f, 1, 0, 0, 1, 1, 0, 0, 1, 1};
  image.levels.emplace_back(reinterpret_cast<const std::uint8_t*>(texels.data()),
                            reinterpret_cast<const std::uint8_t*>(texels.data() + texels.size()));
  const std::vector<std::uint8_t> bytes = saagen::write_ktx2(image);
  write(scratch_ / "flat.ktx2", std::string(bytes.begin(), bytes.end()));
  expect_one_line_error(
      saagen({"texture", "prefilter", (scratch_ / "flat.ktx2").string(), "-o", (scratch_ / "lean.ktx2").string(), "--method", "lean"}),
      "texel (1, 0) decodes to (1, 0, 1e-30), a normal within 1e-18 of the surface plane");
  EXPECT_FALSE(fs::exists(scratch_ / "lean.ktx2"));
}

// Empty values are refused, not taken as defaults; an option that applies to another one needs
// it; a GPU family is named once and checked before anything is loaded.
TEST_F(Safety, EmptyValuesRepeatedFamiliesAndLoneOptionsAreRefused) {
  expect_one_line_error(saagen({"report", "-o", ""}), "--output: empty");
  const std::string map = (scratch_ / "n.png").string(), out = (scratch_ / "o.ktx2").string();
  for (const std::string option : {"--scale", "--roughness", "--metallic"}) {
    const CliRun run = saagen({"texture", "prefilter", map, "-o", out, "--gltf", option, ""});
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.err.find(option), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("empty"), std::string::npos) << run.err;
  }
  for (const std::string option : {"--threads", "--json", "--report", "--cache", "--cost"}) {
    const CliRun run = saagen({"bench", option, "", "--preset", "quick"});
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.err.find(option), std::string::npos) << run.err;
    EXPECT_EQ(run.err.find("ground truth"), std::string::npos) << run.err;  // refused before rendering
  }
  const CliRun metallic = saagen({"texture", "prefilter", map, "-o", out, "--metallic", "0.5"});
  EXPECT_NE(metallic.exit_code, 0);
  EXPECT_NE(metallic.err.find("--gltf"), std::string::npos) << metallic.err;
  EXPECT_FALSE(fs::exists(out));
  const CliRun twice = saagen({"bench", "--isa", "vega10,vega10", "--isa-only"});
  EXPECT_NE(twice.exit_code, 0);
  if (twice.err.find("built without the Vulkan harness") == std::string::npos) {
    EXPECT_NE(twice.err.find("'vega10' is named twice"), std::string::npos) << twice.err;
  }
  // --isa is checked before the scenes are loaded (a missing asset would otherwise be reported first).
  const CliRun bogus = saagen({"bench", "--isa", "bogus", "--scene", (scratch_ / "missing.gltf").string()});
  EXPECT_NE(bogus.exit_code, 0);
  EXPECT_NE(bogus.err.find("--isa"), std::string::npos) << bogus.err;
  EXPECT_EQ(bogus.err.find("missing.gltf"), std::string::npos) << bogus.err;
}

TEST_F(Safety, MessagesNameTheFileOrOption) {
  expect_one_line_error(saagen({"plan", "/tmp"}), "/tmp: is a directory; pass a scene manifest");
  write(scratch_ / "v" / "bad.glsl", "// saagen-marker: target=metal variants=deferred-sum prefix=saa_\n");
  expect_one_line_error(saagen({"validate", (scratch_ / "v").string()}), (scratch_ / "v" / "bad.glsl").string() + ": bad saagen marker");
  expect_one_line_error(saagen({"glints", "emit", "--count", "99", "-o", (scratch_ / "g").string()}), "--count 99 must be a multiple of 4");
  expect_one_line_error(saagen({"glints", "emit", "--lods", "99", "-o", (scratch_ / "g").string()}), "--lods 99 is out of range");
  expect_one_line_error(saagen({"emit", "--sigma2", "", "-o", (scratch_ / "e").string()}), "--sigma2 '': not a number");
  expect_one_line_error(saagen({"emit", "-o", ""}), "--output: empty");
  expect_one_line_error(saagen({"compile", (scratch_ / "x.comp").string(), "-I", "/nonexistent", "-o", (scratch_ / "x.spv").string()}),
                        "-I /nonexistent: not a directory");
  write(scratch_ / "bad.comp", "#version 450\nlayout(local_size_x = 1) in;\nvoid main() { undefined_call(); y = 1; }\n");
  expect_one_line_error(saagen({"compile", (scratch_ / "bad.comp").string(), "-o", (scratch_ / "bad.spv").string()}),
                        (scratch_ / "bad.comp").string() + ":3: 'undefined_call'");
  EXPECT_FALSE(fs::exists(scratch_ / "e"));
  EXPECT_FALSE(fs::exists(scratch_ / "g"));
}

// Text quoted into a message (an argument, a file name, a manifest value) can neither break the
// one line nor drive the terminal: control characters are escaped; a huge quote keeps the
// message's beginning and its end (what to do). The same for the C API's last error.
TEST_F(Safety, MessagesEscapeControlCharactersAndStayShort) {
  const CliRun escaped = saagen({"emit", "-v", "a\nb\x1b[31mc\t", "-o", (scratch_ / "e").string()});
  expect_one_line_error(escaped, "unknown variant 'a\\nb\\x1b[31mc\\t'");
  EXPECT_EQ(escaped.err.find('\x1b'), std::string::npos);
  const CliRun huge = saagen({"emit", "-v", std::string(100000, 'x'), "-o", (scratch_ / "e").string()});
  expect_one_line_error(huge, "bytes left out ...]");
  EXPECT_LT(huge.err.size(), saagen::max_message_bytes + 64);
  EXPECT_NE(huge.err.find("run `saagen list` to see the ids\n"), std::string::npos) << huge.err;
  for (const auto& [run, expected] :
       {std::pair{saagen({"fo\no"}), std::string("unknown command 'fo\\no'")},
        std::pair{saagen({"emit", "--bogus\x07", "-o", (scratch_ / "e").string()}), std::string("--bogus\\x07")}}) {
    EXPECT_EQ(run.exit_code, 2);  // usage errors
    EXPECT_NE(run.err.find(expected), std::string::npos) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  }
  write(scratch_ / "m.toml",
        "name = \"scene\"\ntargets = [\"glsl\"]\n[[material]]\nname = \"m\"\npath = \"deferred\"\nprecision = \"fp\\u001b16\"\n");
  const CliRun manifest = saagen({"plan", (scratch_ / "m.toml").string()});
  expect_one_line_error(manifest, "m.toml:6:");
  EXPECT_EQ(manifest.err.find('\x1b'), std::string::npos) << manifest.err;
  EXPECT_FALSE(fs::exists(scratch_ / "e"));

  EXPECT_STREQ(saagen::Error("a\nb\r\x01").what(), "a\\nb\\r\\x01");
  EXPECT_EQ(saagen::one_line("already\\none line"), "already\\none line");  // escaping twice changes nothing
  char* name = nullptr;
  char* text = nullptr;
  EXPECT_NE(saagen_emit("deferred-sum.glsl?prefix=x\ny\x1b", &name, &text), 0);
  const std::string last = saagen_last_error();
  EXPECT_EQ(last.find_first_of("\n\x1b"), std::string::npos) << last;
  EXPECT_NE(last.find("x\\ny\\x1b"), std::string::npos) << last;
}

// Numbers that would be wrong rather than refused: --seed wrapped (-1) or saturated (2^64) by the
// option parser; kappa = -0.0 emitted as "-0.0"; a manifest value that rounds to 0 in the
// materials' precision reported as a command-line option, without its file:line:column.
TEST_F(Safety, SeedsNegativeZeroAndManifestNumbersAreExact) {
  for (const std::string seed : {"-1", "18446744073709551616", "1e23", "0x10", " 5", "", "+5"}) {
    auto arguments = small_dictionary(scratch_ / "d.ktx2");
    arguments.insert(arguments.end(), {"--seed", seed});
    expect_one_line_error(saagen(arguments), "--seed '" + seed + "': not a whole number in [0, 18446744073709551615]");
  }
  EXPECT_FALSE(fs::exists(scratch_ / "d.ktx2"));
  auto largest = small_dictionary(scratch_ / "d.ktx2");
  largest.insert(largest.end(), {"--seed", "18446744073709551615"});
  ASSERT_EQ(saagen(largest).exit_code, 0);
  const std::string with_largest = read_text(scratch_ / "d.ktx2");
  largest.back() = "0";
  ASSERT_EQ(saagen(largest).exit_code, 0);
  EXPECT_NE(read_text(scratch_ / "d.ktx2"), with_largest);  // the seed is used, not clamped

  ASSERT_EQ(saagen({"emit", "-v", "deferred-sum", "--kappa", "-0", "-o", (scratch_ / "k").string()}).exit_code, 0);
  const std::string emitted = read_text(scratch_ / "k" / "saa_deferred_sum.glsl");
  EXPECT_NE(emitted.find("const float saa_KAPPA = 0.0;"), std::string::npos);
  EXPECT_NE(emitted.find(" kappa=0.0 "), std::string::npos);
  EXPECT_EQ(emitted.find("-0.0"), std::string::npos);
  const std::string manifest_head = "name = \"scene\"\ntargets = [\"glsl\"]\n";
  const std::string material = "[[material]]\nname = \"m\"\npath = \"deferred\"\n";
  write(scratch_ / "zero.toml", manifest_head + "kappa = -0.0\n" + material);
  ASSERT_EQ(saagen({"emit", "--manifest", (scratch_ / "zero.toml").string(), "-o", (scratch_ / "z").string()}).exit_code, 0);
  EXPECT_EQ(read_text(scratch_ / "z" / "saa_scene.glsl").find("-0.0"), std::string::npos);

  write(scratch_ / "tiny.toml", manifest_head + "sigma2 = 1e-10\n" + material + "precision = \"fp16\"\n");
  for (const std::string command : {"plan", "emit"}) {
    std::vector<std::string> arguments = {command};
    if (command == "emit") arguments.push_back("--manifest");
    arguments.insert(arguments.end(), {(scratch_ / "tiny.toml").string(), "--no-cost"});
    if (command == "emit") arguments.back() = "-o", arguments.push_back((scratch_ / "t").string());
    expect_one_line_error(saagen(arguments), "tiny.toml:3:10: key 'sigma2': 1e-10 is below the smallest normal fp16 number");
  }
  write(scratch_ / "subnormal.toml", manifest_head + "kappa = 1e-310\n" + material);
  expect_one_line_error(saagen({"plan", (scratch_ / "subnormal.toml").string()}),
                        "subnormal.toml:3:9: key 'kappa': 1e-310 is below the smallest normal fp32 number");
  for (const std::string value : {"nan", "inf", "-inf", "-nan"}) {
    for (const std::string key : {"sigma2", "kappa"}) {
      write(scratch_ / "bad.toml", manifest_head + key + " = " + value + "\n" + material);
      expect_one_line_error(saagen({"plan", (scratch_ / "bad.toml").string()}),
                            "bad.toml:3:" + std::to_string(key.size() + 4) + ": key '" + key + "'");
    }
  }
  EXPECT_FALSE(fs::exists(scratch_ / "t"));
}

TEST_F(Safety, LongCommandsCheckTheirOptionsAndOutputsFirst) {
  write(scratch_ / "a-file", "x");
  expect_one_line_error(refused_first({"report", "--preset", "quick", "-o", (scratch_ / "a-file").string()}),
                        "cannot create the output directory");
  expect_one_line_error(refused_first({"bench", "--preset", "quick", "--json", (scratch_ / "a-file" / "t.json").string()}),
                        "cannot create the output directory");
  expect_one_line_error(refused_first({"bench", "--preset", "quick", "--cache", (scratch_ / "a-file").string()}), "is not a directory");
  expect_one_line_error(refused_first({"bench", "--preset", "quick", "--threads", "-1"}), "--threads -1");
}

// `saagen bench --isa`: an unknown family or an ISA option without --isa fails in one line before
// anything is compiled or rendered.
TEST_F(Safety, IsaOptionsAreCheckedFirst) {
  expect_one_line_error(refused_first({"bench", "--isa-only"}), "--isa-only and --isa-table need --isa");
  expect_one_line_error(refused_first({"bench", "--isa-table", (scratch_ / "t.json").string()}), "need --isa");
  EXPECT_FALSE(fs::exists(scratch_ / "t.json"));
  const CliRun unknown_family = refused_first({"bench", "--isa", "gfx3000", "--isa-only"});
  // The GPU families are the Vulkan harness's (scripts/sanitize.sh builds without it).
  if (unknown_family.err.find("built without the Vulkan harness") != std::string::npos) GTEST_SKIP() << unknown_family.err;
  expect_one_line_error(unknown_family, "unknown GPU family 'gfx3000'; allowed: ");
  expect_one_line_error(refused_first({"bench", "--isa", "vega10,", "--isa-only"}), "unknown GPU family ''");
}

// The ISA table carries saagen's tag, so that the documented regeneration command can be run again
// over its own file; --json (the trade table) with --isa-only (no trade computed) is refused.
TEST_F(Safety, TheIsaTableIsRewrittenWithoutForceAndJsonNeedsTheTrade) {
  // A table an earlier run wrote (its generator marker) is rewritten without --force.
  const fs::path table = scratch_ / "i.json";
  write(table, R"({"generator": "saagen-output: saagen bench --isa", "rows": []})");
  const CliRun rewrite = saagen({"bench", "--isa", "vega10", "--isa-only", "--isa-table", table.string()});
  if (rewrite.err.find("built without the Vulkan harness") != std::string::npos) GTEST_SKIP() << rewrite.err;
  EXPECT_EQ(rewrite.exit_code, 0) << rewrite.err;
  const nlohmann::json written = nlohmann::json::parse(read_text(table));
  EXPECT_EQ(written.at("generator"), "saagen-output: saagen bench --isa");
  EXPECT_FALSE(written.at("rows").empty());
  expect_one_line_error(saagen({"bench", "--isa", "vega10", "--isa-only", "--json", (scratch_ / "t.json").string()}),
                        "--isa-only computes no trade table to write");
  EXPECT_FALSE(fs::exists(scratch_ / "t.json"));
}

TEST_F(Safety, TradeTablesWithNegativeErrorsOrUnknownIdsAreRefused) {
  const fs::path manifest = fs::path(SAAGEN_SOURCE_DIR) / "examples" / "scene.saagen.toml";
  write(scratch_ / "negative.json", R"({"rows": [{"variant": "deferred-sum", "error": -1}]})");
  expect_one_line_error(saagen({"plan", manifest.string(), "--no-cost", "--trade-table", (scratch_ / "negative.json").string()}),
                        "rows[0]: \"error\" must not be negative");
  write(scratch_ / "unknown.json", R"({"rows": [{"variant": "deferred-median", "error": 0.1}]})");
  expect_one_line_error(saagen({"plan", manifest.string(), "--no-cost", "--trade-table", (scratch_ / "unknown.json").string()}),
                        "rows[0]: unknown variant \"deferred-median\"");
}

TEST_F(Safety, UnreadableDirectoriesAreOneLine) {
  if (::geteuid() == 0) GTEST_SKIP() << "root reads every directory";
  fs::create_directories(scratch_ / "locked");
  fs::permissions(scratch_ / "locked", fs::perms::none);
  expect_one_line_error(saagen({"validate", (scratch_ / "locked").string()}), "cannot be listed");
  expect_one_line_error(saagen({"emit", "-o", (scratch_ / "locked" / "out").string()}), "locked");
}

}  // namespace
