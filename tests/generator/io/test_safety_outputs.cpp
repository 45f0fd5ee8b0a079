// Output safety (test_safety, with test_safety_commit.cpp, test_safety_inputs.cpp and
// test_safety_messages.cpp), as whole `saagen` processes and through the library: no write outside
// the target (symbolic links are never followed), no foreign file overwritten without --force, no
// input overwritten, all-or-nothing outputs (full disks included), concurrent runs.
//
// The full disk is emulated with RLIMIT_FSIZE (`ulimit -f` in the child shell, SIGXFSZ ignored
// so that write() fails with EFBIG): tmpfs and loop mounts need privileges a test cannot assume.
#include "safety_support.hpp"

#include "saagen/io/output.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;

using saagen::test::CliRun;
using saagen::test::read_text;
using saagen::test::Safety;
using saagen::test::shell_quote;

// ---------------------------------------------------------------------------------------------
// 1. Symbolic links: never followed, neither at a temporary name nor at the output path.

TEST_F(Safety, LinksAtTheOldPredictableTemporaryNamesAreNotFollowed) {
  write(scratch_ / "victim.txt", "precious\n");
  fs::create_directories(scratch_ / "gd");
  fs::create_symlink("../victim.txt", scratch_ / "gd" / "d2.ktx2.saagen-tmp");
  fs::create_directories(scratch_ / "out");
  for (int pid = 0; pid < 64; ++pid) {  // the old names carried a PID; plant a few
    fs::create_symlink("../victim.txt", scratch_ / "out" / (".saa_deferred_sum.glsl.saagen-tmp-" + std::to_string(::getpid() + pid)));
  }
  ASSERT_EQ(saagen(small_dictionary(scratch_ / "gd" / "d2.ktx2")).exit_code, 0);
  ASSERT_EQ(saagen({"emit", "-v", "deferred-sum", "-o", (scratch_ / "out").string()}).exit_code, 0);
  EXPECT_EQ(read_text(scratch_ / "victim.txt"), "precious\n");
  EXPECT_FALSE(fs::is_symlink(scratch_ / "gd" / "d2.ktx2"));
  EXPECT_FALSE(fs::is_symlink(scratch_ / "out" / "saa_deferred_sum.glsl"));
}

TEST_F(Safety, ALinkAtTheOutputPathIsRefusedAndForceReplacesOnlyTheLink) {
  write(scratch_ / "victim.txt", "precious\n");
  fs::create_directories(scratch_ / "out");
  const fs::path link = scratch_ / "out" / "saa_deferred_sum.glsl";
  fs::create_symlink("../victim.txt", link);
  expect_one_line_error(saagen({"emit", "-v", "deferred-sum", "-o", (scratch_ / "out").string()}), "is a symbolic link");
  const fs::path ktx2_link = scratch_ / "d.ktx2";
  fs::create_symlink("victim.txt", ktx2_link);
  expect_one_line_error(saagen(small_dictionary(ktx2_link)), "is a symbolic link");
  const fs::path spv_link = scratch_ / "s.spv";
  fs::create_symlink("victim.txt", spv_link);
  write(scratch_ / "s.comp", "#version 450\nlayout(local_size_x = 1) in;\nvoid main() {}\n");
  expect_one_line_error(saagen({"compile", (scratch_ / "s.comp").string(), "-o", spv_link.string()}), "is a symbolic link");
  EXPECT_EQ(read_text(scratch_ / "victim.txt"), "precious\n");

  ASSERT_EQ(saagen({"emit", "-v", "deferred-sum", "--force", "-o", (scratch_ / "out").string()}).exit_code, 0);
  EXPECT_FALSE(fs::is_symlink(link));
  EXPECT_NE(read_text(link).find("saagen-marker"), std::string::npos);
  EXPECT_EQ(read_text(scratch_ / "victim.txt"), "precious\n");
}

// ---------------------------------------------------------------------------------------------
// 3. Foreign files: kept unless --force; saagen's own files are recognised by their marker.

TEST_F(Safety, CompileNeverOverwritesItsInputOrAForeignFile) {
  const std::string source = "#version 450\nlayout(local_size_x = 1) in;\nvoid main() {}\n";
  write(scratch_ / "src.comp", source);
  write(scratch_ / "inc" / "common.glsl", "float f() { return 1.0; }\n");
  write(scratch_ / "uses.comp", "#version 450\n#include \"common.glsl\"\nlayout(local_size_x = 1) in;\nvoid main() { f(); }\n");
  expect_one_line_error(saagen({"compile", (scratch_ / "src.comp").string(), "-o", (scratch_ / "src.comp").string(), "--force"}),
                        "is an input of this compilation");
  expect_one_line_error(saagen({"compile", (scratch_ / "uses.comp").string(), "-I", (scratch_ / "inc").string(), "-o",
                                (scratch_ / "inc" / "common.glsl").string(), "--force"}),
                        "is an input of this compilation");
  EXPECT_EQ(read_text(scratch_ / "src.comp"), source);
  write(scratch_ / "foreign.bin", "mine\n");
  expect_one_line_error(saagen({"compile", (scratch_ / "src.comp").string(), "-o", (scratch_ / "foreign.bin").string()}),
                        "was not written by saagen");
  EXPECT_EQ(read_text(scratch_ / "foreign.bin"), "mine\n");
  // Its own output carries the tag: recompiling replaces it, unchanged bytes are left alone.
  ASSERT_EQ(saagen({"compile", (scratch_ / "src.comp").string(), "-o", (scratch_ / "own.spv").string()}).exit_code, 0);
  EXPECT_NE(read_text(scratch_ / "own.spv").find("saagen-output:"), std::string::npos);
  const CliRun again = saagen({"compile", (scratch_ / "src.comp").string(), "-o", (scratch_ / "own.spv").string()});
  EXPECT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("unchanged"), std::string::npos) << again.out;
  EXPECT_EQ(saagen({"compile", (scratch_ / "src.comp").string(), "-o", (scratch_ / "foreign.bin").string(), "--force"}).exit_code, 0);
}

// A file is saagen's only when its own tag sits where its format puts it, in saagen's form; the
// tag's text quoted anywhere else (a README, a JSON value, a SPIR-V string, a PNG comment) is not.
TEST(Ownership, TheTagCountsOnlyWhereTheFormatPutsIt) {
  const auto owned = [](const std::string& bytes) { return saagen::written_by_saagen("f", bytes); };
  const std::string emitted =
      "// Generated by saagen 0.1.0 -- do not edit; regenerate with `saagen emit`.\n"
      "// saagen-marker: target=glsl variants=deferred-sum prefix=saa_ kappa=0.18 sigma2=0.25\nfloat x;\n";
  EXPECT_TRUE(owned(emitted));
  EXPECT_FALSE(owned("# My project\n" + emitted));  // quoted in a README
  EXPECT_FALSE(owned("# Notes\nfiles carry `saagen-output:` or `// saagen-marker: target=glsl variants=deferred-sum prefix=saa_`\n"));
  EXPECT_FALSE(owned("// Generated by saagen 0.1.0\n// my own edits\n// saagen-marker: target=glsl variants=deferred-sum prefix=saa_\n"));
  EXPECT_TRUE(owned("<!-- saagen-output: report -->\n# report\n"));
  EXPECT_TRUE(owned("<!DOCTYPE html>\n<!-- saagen-output: report -->\n<html>\n"));
  EXPECT_FALSE(owned("<p>my page</p>\n<!-- saagen-output: report -->\n"));
  EXPECT_FALSE(owned("<!-- saagen-output: -->\n"));
  EXPECT_TRUE(owned("{\"generator\": \"saagen-output: saagen bench\", \"rows\": []}"));
  EXPECT_FALSE(owned("{\"note\": \"saagen-output: saagen bench\", \"rows\": []}"));
  EXPECT_FALSE(owned("{\"x\": {\"generator\": \"saagen-output: saagen bench\"}}"));
  EXPECT_FALSE(owned("{\"generator\": \"my tool, not saagen-output: saagen bench\"}"));

  // SPIR-V: the tag as an OpSourceExtension string counts, the same bytes in an OpString do not.
  const auto spirv = [](std::uint32_t opcode, const std::string& text) {
    std::vector<std::uint32_t> words = {0x07230203u, 0x00010000u, 0u, 10u, 0u};
    std::vector<std::uint32_t> literal((text.size() + 4) / 4, 0u);
    for (std::size_t index = 0; index < text.size(); ++index)
      literal[index / 4] |= std::uint32_t(static_cast<unsigned char>(text[index])) << (8 * (index % 4));
    if (opcode == 7) literal.insert(literal.begin(), 1u);  // OpString's result id
    words.push_back(static_cast<std::uint32_t>((literal.size() + 1) << 16) | opcode);
    words.insert(words.end(), literal.begin(), literal.end());
    std::string bytes;
    for (const std::uint32_t word : words)
      for (int shift = 0; shift < 32; shift += 8) bytes += static_cast<char>((word >> shift) & 0xffu);
    return bytes;
  };
  EXPECT_TRUE(owned(spirv(4, "saagen-output: compiled from s.frag")));
  EXPECT_FALSE(owned(spirv(7, "saagen-output: compiled from s.frag")));
  EXPECT_TRUE(owned(spirv(330, "// saagen-marker: target=spirv variants=deferred-sum prefix=saa_\n")));

  // PNG: saagen's tEXt chunk (keyword Software) before the image data.
  const auto chunk = [](const std::string& type, const std::string& data) {
    std::string bytes;
    for (int shift = 24; shift >= 0; shift -= 8) bytes += static_cast<char>((data.size() >> shift) & 0xffu);
    return bytes + type + data + std::string(4, '\0');
  };
  const std::string png = std::string("\x89PNG\r\n\x1A\n", 8) + chunk("IHDR", std::string(13, '\0'));
  const std::string tag = std::string("Software") + '\0' + "saagen-output: report";
  EXPECT_TRUE(owned(png + chunk("tEXt", tag) + chunk("IDAT", "x") + chunk("IEND", "")));
  EXPECT_FALSE(owned(png + chunk("tEXt", std::string("Comment") + '\0' + "saagen-output: report") + chunk("IEND", "")));
  EXPECT_FALSE(owned(png + chunk("IDAT", tag) + chunk("IEND", "")));
}

TEST_F(Safety, AReadmeQuotingTheTagIsNotOverwritten) {
  // The safety page quotes both tags where it lists which files are saagen's.
  const std::string readme = read_text(fs::path(SAAGEN_SOURCE_DIR) / "docs" / "SAFETY.md");
  ASSERT_NE(readme.find("saagen-output:"), std::string::npos);
  ASSERT_NE(readme.find("// saagen-marker:"), std::string::npos);
  write(scratch_ / "x.md", readme);
  write(scratch_ / "s.frag", "#version 450\nlayout(location = 0) out vec4 c;\nvoid main() { c = vec4(1.0); }\n");
  expect_one_line_error(saagen({"compile", (scratch_ / "s.frag").string(), "-o", (scratch_ / "x.md").string()}),
                        "x.md: exists and was not written by saagen");
  write(scratch_ / "out" / "saa_deferred_sum.glsl", readme);
  expect_one_line_error(saagen({"emit", "-v", "deferred-sum", "-o", (scratch_ / "out").string()}), "was not written by saagen");
  write(scratch_ / "t.json", "{\"comment\": \"saagen-output: saagen bench\"}\n");
  expect_one_line_error(saagen({"bench", "--preset", "quick", "--json", (scratch_ / "t.json").string()}), "was not written by saagen");
  EXPECT_EQ(read_text(scratch_ / "x.md"), readme);
  EXPECT_EQ(read_text(scratch_ / "out" / "saa_deferred_sum.glsl"), readme);
}

TEST_F(Safety, DictionaryOwnsOnlyKtx2WithItsKeyAndRawDumpsWithTheirSidecar) {
  std::string ktx2_magic = "\xABKTX 20\xBB\r\n\x1A\n";
  write(scratch_ / "foreign.ktx2", ktx2_magic + std::string(100, '\0'));
  expect_one_line_error(saagen(small_dictionary(scratch_ / "foreign.ktx2")), "was not written by saagen");
  EXPECT_EQ(fs::file_size(scratch_ / "foreign.ktx2"), 112u);

  write(scratch_ / "foreign.f32", "my floats");
  auto with_raw = small_dictionary(scratch_ / "d.ktx2");
  with_raw.insert(with_raw.end(), {"--raw", (scratch_ / "foreign.f32").string()});
  expect_one_line_error(saagen(with_raw), "foreign.f32: exists and was not written by saagen");
  EXPECT_EQ(read_text(scratch_ / "foreign.f32"), "my floats");
  EXPECT_FALSE(fs::exists(scratch_ / "d.ktx2"));  // nothing written

  auto own_raw = small_dictionary(scratch_ / "d.ktx2");
  own_raw.insert(own_raw.end(), {"--raw", (scratch_ / "own.f32").string()});
  ASSERT_EQ(saagen(own_raw).exit_code, 0);
  EXPECT_TRUE(fs::exists(scratch_ / "own.f32.saagen"));
  own_raw[3] = "8";  // another count: new bytes over saagen's own files
  EXPECT_EQ(saagen(own_raw).exit_code, 0);
  write(scratch_ / "own.f32", "edited by hand");  // the sidecar no longer vouches for it
  expect_one_line_error(saagen(own_raw), "own.f32: exists and was not written by saagen");
}

TEST_F(Safety, ReportAndBenchKeepForeignFilesAndFailBeforeRendering) {
  write(scratch_ / "report" / "index.html", "<p>my page</p>\n");
  expect_one_line_error(refused_first({"report", "--preset", "quick", "-o", (scratch_ / "report").string()}),
                        "index.html: exists and was not written by saagen");
  EXPECT_EQ(entries(scratch_ / "report"), std::set<std::string>{"index.html"});
  write(scratch_ / "notes.txt", "my notes\n");
  expect_one_line_error(refused_first({"bench", "--preset", "quick", "--json", (scratch_ / "notes.txt").string()}),
                        "notes.txt: exists and was not written by saagen");
  EXPECT_EQ(read_text(scratch_ / "notes.txt"), "my notes\n");
}

// No command writes over one of its own inputs, with or without --force, whatever name the output
// has (compared by file identity); one file named twice among one run's outputs is refused.
TEST_F(Safety, NoCommandWritesOverItsInputsNorOneFileTwice) {
  const std::string manifest = "name = \"scene\"\ntargets = [\"glsl\"]\n[[material]]\nname = \"m\"\npath = \"deferred\"\n";
  write(scratch_ / "out" / "saa_scene.glsl", manifest);
  expect_one_line_error(
      saagen({"emit", "--manifest", (scratch_ / "out" / "saa_scene.glsl").string(), "-o", (scratch_ / "out").string(), "--force"}),
      "saa_scene.glsl: is an input of this command");
  EXPECT_EQ(read_text(scratch_ / "out" / "saa_scene.glsl"), manifest);
  ASSERT_EQ(saagen({"emit", "--manifest", (scratch_ / "out" / "saa_scene.glsl").string(), "-o", (scratch_ / "bundle").string()}).exit_code,
            0);

  write(scratch_ / "in.ktx2", "not decoded: refused before decoding");
  expect_one_line_error(saagen({"texture", "prefilter", (scratch_ / "in.ktx2").string(), "-o", (scratch_ / "in.ktx2").string(), "--force"}),
                        "in.ktx2: is an input of this command");
  fs::create_hard_link(scratch_ / "in.ktx2", scratch_ / "hard.ktx2");  // another name of the same file
  expect_one_line_error(
      saagen({"texture", "prefilter", (scratch_ / "in.ktx2").string(), "-o", (scratch_ / "hard.ktx2").string(), "--force"}),
      "hard.ktx2: is an input of this command");
  EXPECT_EQ(read_text(scratch_ / "in.ktx2"), "not decoded: refused before decoding");
  write(scratch_ / "n.ppm", "P6 1 1 255\n\x80\x80\xff");
  expect_one_line_error(saagen({"glints", "lean", (scratch_ / "n.ppm").string(), "-o", (scratch_ / "n.ppm").string(), "--force"}),
                        "n.ppm: is an input of this command");

  // Two outputs of one run that are one file: through a linked directory, or a hard link.
  fs::create_directory_symlink(".", scratch_ / "L");
  auto twice = small_dictionary(scratch_ / "r.f32");
  twice.insert(twice.end(), {"--raw", (scratch_ / "L" / "r.f32").string()});
  expect_one_line_error(saagen(twice), "two names of one file");
  EXPECT_FALSE(fs::exists(scratch_ / "r.f32"));
  write(scratch_ / "a.f32", "x");
  ASSERT_EQ(saagen({"glints", "dictionary", "--count", "4", "--lods", "2", "--resolution", "4", "-o", (scratch_ / "d.ktx2").string(),
                    "--raw", (scratch_ / "a.f32").string(), "--force"})
                .exit_code,
            0);
  fs::create_hard_link(scratch_ / "a.f32", scratch_ / "b.ktx2");
  auto hard = small_dictionary(scratch_ / "b.ktx2");
  hard.insert(hard.end(), {"--raw", (scratch_ / "a.f32").string(), "--force"});
  expect_one_line_error(saagen(hard), "two names of one file");
  // --isa-table and --json as one file: a saagen built without the Vulkan harness (scripts/sanitize.sh
  // builds without it) refuses --isa before the outputs are checked, in one line as well.
  const CliRun isa_twice = saagen({"bench", "--preset", "quick", "--isa", "vega10", "--isa-table", (scratch_ / "t.json").string(), "--json",
                                   (scratch_ / "L" / "t.json").string()});
  const bool harness = isa_twice.err.find("built without the Vulkan harness") == std::string::npos;
  expect_one_line_error(isa_twice, harness ? "would be written twice" : "built without the Vulkan harness");
}

// ---------------------------------------------------------------------------------------------
// 4. All or nothing: repeated arguments are refused before writing; a failed write (a full disk)
// leaves no temporary and no changed file.

TEST_F(Safety, RepeatedVariantsWriteNothing) {
  expect_one_line_error(saagen({"pass", "-o", (scratch_ / "p").string(), "--variant", "deferred-sum", "--variant", "deferred-sum"}),
                        "--variant deferred-sum: named twice");
  expect_one_line_error(saagen({"emit", "--target", "spirv", "-v", "deferred-sum", "-v", "deferred-sum", "-o", (scratch_ / "s").string()}),
                        "--variant deferred-sum: named twice");
  EXPECT_FALSE(fs::exists(scratch_ / "p"));
  EXPECT_FALSE(fs::exists(scratch_ / "s"));
}

TEST_F(Safety, DictionaryChecksTheRawPathBeforeWritingTheTexture) {
  write(scratch_ / "blocker", "a file, not a directory");
  auto arguments = small_dictionary(scratch_ / "d.ktx2");
  arguments.insert(arguments.end(), {"--raw", (scratch_ / "blocker" / "raw.f32").string()});
  expect_one_line_error(saagen(arguments), "cannot create the output directory");
  EXPECT_FALSE(fs::exists(scratch_ / "d.ktx2"));
}

TEST_F(Safety, AFullDiskLeavesNoTemporaryAndNoChangedFile) {
  const fs::path out = scratch_ / "out";
  ASSERT_EQ(saagen({"emit", "-o", out.string(), "--sigma2", "0.5"}).exit_code, 0);
  std::map<std::string, std::string> before;
  for (const std::string& name : entries(out)) before[name] = read_text(out / name);
  // 8 KiB per file: the small files stage, the BRDF files (14 KiB) cannot.
  const CliRun run = saagen_with_file_limit(8, {"emit", "-o", out.string()});
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_NE(run.err.find("write failed (File too large)"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("; nothing was changed"), std::string::npos) << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  std::map<std::string, std::string> after;
  for (const std::string& name : entries(out)) after[name] = read_text(out / name);
  EXPECT_EQ(after, before);  // no temporary left, every file as it was

  const CliRun dictionary = saagen_with_file_limit(
      16, {"glints", "dictionary", "-o", (scratch_ / "g" / "d.ktx2").string(), "--raw", (scratch_ / "g" / "d.f32").string()});
  EXPECT_EQ(dictionary.exit_code, 1) << dictionary.err;
  EXPECT_EQ(entries(scratch_ / "g"), std::set<std::string>{});
}

// A signal that ends the process while outputs are staged (here the file-size limit's SIGXFSZ,
// not ignored; Ctrl-C and SIGTERM take the same handler) removes the temporaries first, and no
// output has been renamed yet: the directory is as it was. They were left behind.
TEST_F(Safety, ASignalDuringStagingLeavesNoTemporary) {
  const fs::path out = scratch_ / "out";
  ASSERT_EQ(saagen({"emit", "-o", out.string(), "--sigma2", "0.5"}).exit_code, 0);
  std::map<std::string, std::string> before;
  for (const std::string& name : entries(out)) before[name] = read_text(out / name);
  std::string command = "ulimit -f 8; exec " + shell_quote(SAAGEN_CLI_PATH) + " emit -o " + shell_quote(out.string());
  const CliRun run = run_shell(command);
  EXPECT_EQ(run.exit_code, 128 + SIGXFSZ) << run.err;  // ended by the signal, as before
  std::map<std::string, std::string> after;
  for (const std::string& name : entries(out)) after[name] = read_text(out / name);
  EXPECT_EQ(after, before);
}

// ---------------------------------------------------------------------------------------------
// 5. Concurrent runs to one output do not collide; unchanged outputs are not rewritten.

TEST_F(Safety, ConcurrentRunsToOneOutputAllSucceedAndUnchangedFilesKeepTheirInode) {
  const fs::path output = scratch_ / "cc" / "d.ktx2";
  std::string pair = "";
  for (const int run : {0, 1}) {
    std::string command = shell_quote(SAAGEN_CLI_PATH);
    for (const std::string& argument : small_dictionary(output)) command.append(" ").append(shell_quote(argument));
    pair.append(command)
        .append(" >/dev/null 2>>")
        .append(shell_quote((scratch_ / "errors.txt").string()))
        .append(run == 0 ? " & " : "; wait");
  }
  for (int round = 0; round < 10; ++round) {
    fs::remove_all(scratch_ / "cc");
    EXPECT_EQ(run_shell(pair).exit_code, 0);
  }
  EXPECT_EQ(read_text(scratch_ / "errors.txt"), "");
  EXPECT_EQ(entries(scratch_ / "cc"), std::set<std::string>{"d.ktx2"});
  struct stat first {
  }, second{};
  ASSERT_EQ(::stat(output.c_str(), &first), 0);
  const CliRun again = saagen(small_dictionary(output));
  EXPECT_NE(again.out.find("unchanged"), std::string::npos) << again.out;
  ASSERT_EQ(::stat(output.c_str(), &second), 0);
  EXPECT_EQ(first.st_ino, second.st_ino);
}

}  // namespace
