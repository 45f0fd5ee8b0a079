// Output safety and hostile input, as whole `saagen` processes and through the library: no write
// outside the target (symbolic links are never followed), no foreign file overwritten without
// --force, all-or-nothing outputs (full disks included), and one line for every bad input, fast.
//
// The full disk is emulated with RLIMIT_FSIZE (`ulimit -f` in the child shell, SIGXFSZ ignored
// so that write() fails with EFBIG): tmpfs and loop mounts need privileges a test cannot assume.
#include "support/cli_support.hpp"

#include "saagen/error.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/io/include_expansion.hpp"
#include "saagen/io/ktx2.hpp"
#include "saagen/io/output.hpp"
#include "saagen/products/glints.hpp"
#include "saagen/products/prefilter.hpp"
#include "saagen/saagen.h"
#include "saagen/scene/manifest.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include <fcntl.h>
#include <linux/fs.h>
#include <sys/ioctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;

using saagen::test::CliRun;
using saagen::test::read_text;
using saagen::test::shell_quote;

class Safety : public saagen::test::CliTest {
 protected:
  void expect_one_line_error(const CliRun& run, const std::string& expected) const {
    EXPECT_EQ(run.exit_code, 1) << run.err;
    EXPECT_NE(run.err.find(expected), std::string::npos) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  }

  // Runs saagen with a per-file size limit of `kib` KiB, as a full disk would refuse the write.
  CliRun saagen_with_file_limit(int kib, const std::vector<std::string>& arguments) const {
    std::string command = "trap '' XFSZ; ulimit -f " + std::to_string(kib) + "; exec " + shell_quote(SAAGEN_CLI_PATH);
    for (const std::string& argument : arguments) command.append(" ").append(shell_quote(argument));
    return run_shell(command);
  }

  CliRun run_shell(const std::string& command) const {
    const fs::path out = scratch_ / "shell-out.txt", err = scratch_ / "shell-err.txt";
    const std::string line = "bash -c " + shell_quote(command) + " >" + shell_quote(out.string()) + " 2>" + shell_quote(err.string());
    const int status = std::system(line.c_str());
    CliRun run;
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    run.out = read_text(out);
    run.err = read_text(err);
    fs::remove(out);
    fs::remove(err);
    return run;
  }

  // Every entry of a directory, hidden ones (temporaries) included.
  std::set<std::string> entries(const fs::path& directory) const {
    std::set<std::string> names;
    if (!fs::exists(directory)) return names;
    for (const auto& entry : fs::directory_iterator(directory)) names.insert(entry.path().filename().string());
    return names;
  }

  void write(const fs::path& path, const std::string& text) const {
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
  }

  // A run that must refuse its input before any long work (rendering, generation, reading a
  // stream that never ends). Two checks, neither a timing: the bench and report print progress
  // lines on stderr once they render, so expect_one_line_error's single line says nothing ran
  // first; and a run that hangs is killed (exit 137, so expect_one_line_error fails) after
  // kHangGuardSeconds, a liveness bound far beyond any machine's load, not a speed target.
  static constexpr int kHangGuardSeconds = 300;
  CliRun refused_first(const std::vector<std::string>& arguments) const {
    std::string command = "exec timeout -s KILL " + std::to_string(kHangGuardSeconds) + " " + shell_quote(SAAGEN_CLI_PATH);
    for (const std::string& argument : arguments) command.append(" ").append(shell_quote(argument));
    return run_shell(command);
  }

  static std::vector<std::string> small_dictionary(const fs::path& output) {
    return {"glints", "dictionary", "--count", "4", "--lods", "2", "--resolution", "4", "-o", output.string()};
  }
};

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
// 2. Deeply nested manifests: refused with file:line before toml++ recurses.

TEST_F(Safety, DeeplyNestedManifestIsOneLineNotACrash) {
  std::string header = "[a";
  for (int level = 0; level < 250000; ++level) header += ".a";
  write(scratch_ / "deep.toml", header + "]\n");
  expect_one_line_error(saagen({"plan", (scratch_ / "deep.toml").string()}), "deep.toml:1:");
  expect_one_line_error(saagen({"emit", "--manifest", (scratch_ / "deep.toml").string(), "-o", (scratch_ / "out").string()}),
                        "nested deeper than 32 levels");
  EXPECT_FALSE(fs::exists(scratch_ / "out"));
}

TEST(ManifestLimits, NestingAndSizeAreCappedBeforeParsing) {
  const saagen::Catalogue& catalogue = saagen::Catalogue::builtin();
  const auto error_of = [&](const std::string& text) -> std::string {
    try {
      (void)saagen::parse_manifest(text, "m.toml", catalogue);
    } catch (const saagen::Error& error) {
      return error.what();
    }
    return "";
  };
  std::string dotted = "x";
  for (int level = 0; level < 100000; ++level) dotted += ".x";
  EXPECT_EQ(error_of(dotted + " = 1\n").rfind("m.toml:1:", 0), 0u);
  EXPECT_NE(error_of("a = " + std::string(5000, '[') + std::string(5000, ']') + "\n").find("nested deeper than 32"), std::string::npos);
  std::string inline_tables = "a = ";
  for (int level = 0; level < 5000; ++level) inline_tables += "{b = ";
  EXPECT_NE(error_of(inline_tables + "1" + std::string(5000, '}') + "\n").find("nested deeper than 32"), std::string::npos);
  // Multi-line arrays keep their depth across lines; the error names the line.
  EXPECT_EQ(error_of("targets = [\n" + std::string(40, '[') + "\n").rfind("m.toml:2:", 0), 0u);
  EXPECT_NE(error_of("# " + std::string(2 << 20, 'x') + "\n").find("larger than 1024 KiB"), std::string::npos);
  // Non-ASCII outside comments never reaches toml++ 3.3, whose whitespace classification of
  // U+00A1..U+0499 and others is undefined behaviour (in keys, bare values and strings).
  EXPECT_EQ(error_of("targets = [\"glsl\"]\npa\xcc\x88th = 1\n").rfind("m.toml:2:3: non-ASCII byte 0xcc", 0), 0u)
      << error_of("pa\xcc\x88th = 1\n");
  EXPECT_EQ(error_of("x = \"\"\"a \\\n\xc2\xa1"
                     "b\"\"\"\n")
                .rfind("m.toml:2:1: non-ASCII", 0),
            0u);
  EXPECT_EQ(error_of("t = 1\"caf\xc3\xa9\"\n").rfind("m.toml:1:10: non-ASCII", 0), 0u);  // a bare value swallowing a quote
  EXPECT_EQ(error_of("# caf\xc3\xa9\ntargets = []\n").find("non-ASCII"), std::string::npos);
  // Dots in values, strings and comments are not nesting.
  const std::string fine =
      "targets = [\"glsl\"] # a.b.c.d.e.f.g.h.i.j.k.l.m.n.o.p.q.r.s.t.u.v.w.x.y.z.a.b.c.d.e.f.g.h\n"
      "name = \"a.b.c.d.e.f.g.h.i.j.k.l.m.n.o.p.q.r.s.t.u.v.w.x.y.z.a.b.c.d.e.f.g.h\"\n"
      "sigma2 = 0.25\n[[material]]\nname = \"m\"\npath = \"deferred\"\n";
  EXPECT_NE(error_of(fine).find("is not an identifier"), std::string::npos) << error_of(fine);
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

// ---------------------------------------------------------------------------------------------
// 6. Strict readers: PPM headers, LEAN errors naming the file, KTX2 level counts.

TEST(StrictReaders, PpmHeadersAreStrictDecimals) {
  const auto error_of = [](const std::string& text) -> std::string {
    try {
      (void)saagen::glints::slopes_from_ppm(std::vector<std::uint8_t>(text.begin(), text.end()));
    } catch (const saagen::Error& error) {
      return error.what();
    }
    return "";
  };
  EXPECT_NE(error_of("P6 4294967297 1 255\n" + std::string(3, '\x80')).find("not a decimal number"), std::string::npos);
  EXPECT_NE(error_of("P6 2abc 1 255\n" + std::string(6, '\x80')).find("'2abc'"), std::string::npos);
  EXPECT_NE(error_of("P6 -1 1 255\n").find("'-1'"), std::string::npos);
  EXPECT_NE(error_of("P6 4097 4096 255\n").find("larger than 4194304 texels"), std::string::npos);
  EXPECT_EQ(error_of("P6 # comment\n1 1 255\n" + std::string(3, '\x80')), "");
}

// Findings of fuzz/png_fuzzer.cpp: stb_image handed memcpy a null pointer for an empty IDAT chunk
// before the first non-empty one (UBSan): such chunks are dropped, and the image is the same; and
// it allocated what a chunk declares before reading it.
TEST(StrictReaders, PngChunksAreCheckedBeforeStbImage) {
  // A 2 x 2 RGB PNG of flat normals (128, 128, 255), written by hand: signature, IHDR, IDAT, IEND.
  const std::string signature("\x89PNG\r\n\x1a\n", 8);
  const std::string ihdr("\x00\x00\x00\x0dIHDR\x00\x00\x00\x02\x00\x00\x00\x02\x08\x02\x00\x00\x00\xfd\xd4\x9a\x73", 25);
  const std::string idat("\x00\x00\x00\x10\x49\x44\x41\x54\x78\xda\x63\x68\x68\xf8\x0f\x44\x0c\x10\x0a\x00\x35\xf6\x07\xfd\xa1\x29\xec\x43",
                         28);
  const std::string iend("\x00\x00\x00\x00IEND\xae\x42\x60\x82", 12);
  const std::string empty_idat("\x00\x00\x00\x00IDAT\x35\xaf\x06\x1e", 12);
  const auto read = [](const std::string& file) {
    return saagen::prefilter::read_normal_map(std::span(reinterpret_cast<const std::uint8_t*>(file.data()), file.size()), "n.png");
  };
  const auto plain = read(signature + ihdr + idat + iend);
  const auto with_empty = read(signature + ihdr + empty_idat + idat + empty_idat + iend);
  ASSERT_EQ(plain.width, 2);
  EXPECT_EQ(with_empty.width, plain.width);
  EXPECT_EQ(with_empty.height, plain.height);
  EXPECT_EQ(with_empty.normals, plain.normals);

  // A chunk that declares more than the file holds is refused before stb_image grows a buffer
  // to its size (an 80-byte file declaring 1.4 GB made it allocate 2 GB).
  std::string past_the_end = signature + ihdr + idat.substr(0, 8) + "x";
  past_the_end[signature.size() + ihdr.size()] = '\x58';
  try {
    read(past_the_end);
    ADD_FAILURE() << "a chunk past the end was read";
  } catch (const saagen::Error& error) {
    EXPECT_EQ(std::string(error.what()), "n.png: not a readable PNG (chunk 'IDAT' declares 1476395024 bytes, past the end of the file)");
  }
}

TEST(StrictReaders, Ktx2LevelCountIsBoundedByTheImageSize) {
  saagen::glints::DictionaryParams params;
  params.count = 4;
  params.lods = 2;
  params.resolution = 4;
  const auto texture = saagen::glints::dictionary_texture(saagen::glints::generate_dictionary(params));
  auto bytes = saagen::write_ktx2(saagen::glints::dictionary_ktx2(texture, params));
  ASSERT_NO_THROW((void)saagen::read_ktx2(bytes));
  bytes[40] = 40;  // levelCount 40 for a width of 4
  try {
    (void)saagen::read_ktx2(bytes);
    FAIL() << "40 levels accepted";
  } catch (const saagen::Error& error) {
    EXPECT_NE(std::string(error.what()).find("40 levels"), std::string::npos) << error.what();
  }
}

TEST_F(Safety, LeanErrorsNameTheFile) {
  write(scratch_ / "n.ppm", "P6 4294967297 1 255\n\x80\x80\x80");
  expect_one_line_error(saagen({"glints", "lean", (scratch_ / "n.ppm").string(), "-o", (scratch_ / "l.ktx2").string()}),
                        (scratch_ / "n.ppm").string() + ": normal map:");
  EXPECT_FALSE(fs::exists(scratch_ / "l.ktx2"));
}

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
// 8. Inputs that never end or are too large are refused at once.

TEST_F(Safety, DevicesFifosAndHugeInputsAreRefusedFast) {
  expect_one_line_error(refused_first({"plan", "/dev/zero"}), "/dev/zero: is not a regular file");
  expect_one_line_error(refused_first({"compile", "/dev/zero", "--stage", "comp", "-o", (scratch_ / "z.spv").string()}),
                        "/dev/zero: is not a regular file");
  ASSERT_EQ(::mkfifo((scratch_ / "fifo.toml").c_str(), 0600), 0);
  expect_one_line_error(refused_first({"plan", (scratch_ / "fifo.toml").string()}), "is not a regular file");
  write(scratch_ / "big.ppm", "P6 4096 4096 255\n");
  expect_one_line_error(saagen({"glints", "lean", (scratch_ / "big.ppm").string(), "-o", (scratch_ / "l.ktx2").string()}),
                        "larger than 4194304 texels");
  expect_one_line_error(refused_first({"glints", "dictionary", "--count", "65536", "-o", (scratch_ / "d.ktx2").string()}),
                        "lower the count or the LODs");
}

// Every reader behind the input layer: texture prefilter's normal map (devices, FIFOs, directories,
// and images declaring more texels than saagen reads, refused from the header before decoding), the
// bench's ground-truth cache (a FIFO at a cached name, an unwritable cache directory), and trade
// and cost tables holding a number beyond a double's range.
TEST_F(Safety, EveryReaderRefusesWhatWouldHangOrExhaustMemory) {
  const std::string out = (scratch_ / "o.ktx2").string();
  expect_one_line_error(refused_first({"texture", "prefilter", "/dev/zero", "-o", out}), "/dev/zero: is not a regular file");
  ASSERT_EQ(::mkfifo((scratch_ / "fifo.png").c_str(), 0600), 0);
  expect_one_line_error(refused_first({"texture", "prefilter", (scratch_ / "fifo.png").string(), "-o", out}), "is not a regular file");
  expect_one_line_error(saagen({"texture", "prefilter", scratch_.string(), "-o", out}), "is a directory; pass a PNG or KTX2 normal map");

  // A 60-byte PNG declaring 16384 x 16384 RGB texels (stb_image ignores the CRCs, left zero).
  const auto be32 = [](std::uint32_t value) {
    std::string bytes;
    for (int shift = 24; shift >= 0; shift -= 8) bytes += static_cast<char>((value >> shift) & 0xffu);
    return bytes;
  };
  const auto chunk = [&](const std::string& type, const std::string& data) {
    return be32(static_cast<std::uint32_t>(data.size())) + type + data + be32(0);
  };
  const std::string ihdr = be32(16384) + be32(16384) + std::string("\x08\x02\x00\x00\x00", 5);
  write(scratch_ / "huge.png",
        std::string("\x89PNG\r\n\x1A\n", 8) + chunk("IHDR", ihdr) + chunk("IDAT", std::string("x\x01", 2)) + chunk("IEND", ""));
  expect_one_line_error(refused_first({"texture", "prefilter", (scratch_ / "huge.png").string(), "-o", out}),
                        "huge.png: 16384 x 16384 texels is larger than saagen reads (at most 8192 a side and 4096 x 4096 in all)");
  std::string ktx2 = std::string("\xABKTX 20\xBB\r\n\x1A\n", 12) + std::string(68, '\0');
  ktx2[22] = '\x01';  // pixelWidth 65536
  ktx2[24] = '\x01';  // pixelHeight 1
  write(scratch_ / "wide.ktx2", ktx2);
  expect_one_line_error(saagen({"texture", "prefilter", (scratch_ / "wide.ktx2").string(), "-o", out}), "65536 x 1 texels is larger");
  EXPECT_FALSE(fs::exists(out));
  const CliRun help = saagen({"texture", "prefilter", "--help"});
  EXPECT_NE(help.out.find("at most 8192 texels a side and 4096 x 4096 in all"), std::string::npos) << help.out;

  // Trade and cost tables with 1e999: one line naming the file, not an internal error.
  const fs::path manifest = fs::path(SAAGEN_SOURCE_DIR) / "examples" / "scene.saagen.toml";
  write(scratch_ / "overflow.json", R"({"rows": [{"variant": "deferred-sum", "error": 1e999}]})");
  expect_one_line_error(saagen({"plan", manifest.string(), "--no-cost", "--trade-table", (scratch_ / "overflow.json").string()}),
                        (scratch_ / "overflow.json").string() + ": holds a number beyond a double's range");
  expect_one_line_error(saagen({"bench", "--preset", "quick", "--cost", (scratch_ / "overflow.json").string()}),
                        (scratch_ / "overflow.json").string() + ": holds a number beyond a double's range");

  // A cache directory that takes no file would cache nothing, silently.
  expect_one_line_error(saagen({"bench", "--preset", "quick", "--cache", "/proc/self"}), "--cache /proc/self: cannot write in /proc/self");
  expect_one_line_error(saagen({"bench", "--preset", "quick", "--cache", "/proc/self/sub/dir"}), "cannot write in /proc/self");
}

// A FIFO planted at a cached ground truth's name is a cache miss, not a hang; the fresh ground
// truth replaces it.
TEST_F(Safety, AFifoInTheBenchCacheIsAMissNotAHang) {
  const fs::path cache = scratch_ / "cache";
  ASSERT_EQ(saagen({"bench", "--preset", "quick", "--cache", cache.string()}).exit_code, 0);
  const std::set<std::string> cached = entries(cache);
  ASSERT_FALSE(cached.empty());
  const fs::path planted = cache / *cached.begin();
  fs::remove(planted);
  ASSERT_EQ(::mkfifo(planted.c_str(), 0600), 0);
  const CliRun run =
      run_shell("timeout 300 " + shell_quote(SAAGEN_CLI_PATH) + " bench --preset quick --cache " + shell_quote(cache.string()));
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(fs::is_regular_file(planted));
  EXPECT_EQ(entries(cache), cached);
}

// The ground-truth cache is written through the output layer: a file-size limit's SIGXFSZ while a
// cache file is staged removes its temporary (the cache's own writer left gt-....bin.tmpNNNN).
TEST_F(Safety, ASignalWhileWritingTheCacheLeavesNoTemporary) {
  const fs::path cache = scratch_ / "cache";
  const CliRun run = run_shell("ulimit -f 4; exec " + shell_quote(SAAGEN_CLI_PATH) +
                               " bench --scene sphere --preset quick --resolution 32 --cache " + shell_quote(cache.string()));
  EXPECT_EQ(run.exit_code, 128 + SIGXFSZ) << run.err;
  for (const std::string& name : entries(cache)) {
    EXPECT_EQ(name.rfind("gt-", 0), 0u) << name;
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << name;
  }
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

// ---------------------------------------------------------------------------------------------
// All-or-nothing commits: a set of outputs is either wholly replaced or left exactly as it was.

// Every file of a directory, hidden ones (temporaries, backups) included, with its bytes.
std::map<std::string, std::string> snapshot(const fs::path& directory) {
  std::map<std::string, std::string> files;
  if (!fs::exists(directory)) return files;
  for (const auto& entry : fs::directory_iterator(directory)) files[entry.path().filename().string()] = read_text(entry.path());
  return files;
}

// The files a run reports as written, in the order it commits them.
std::vector<std::string> written_paths(const std::string& out) {
  std::vector<std::string> paths;
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("wrote     ", 0) == 0) paths.push_back(line.substr(10));
  }
  return paths;
}

// Sets or clears the immutable flag (chattr +i / -i); false where the process lacks
// CAP_LINUX_IMMUTABLE or the file system has no such flag.
bool set_immutable(const fs::path& path, bool on) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return false;
  int flags = 0;
  bool done = ::ioctl(fd, FS_IOC_GETFLAGS, &flags) == 0;
  flags = on ? flags | FS_IMMUTABLE_FL : flags & ~FS_IMMUTABLE_FL;
  done = done && ::ioctl(fd, FS_IOC_SETFLAGS, &flags) == 0;
  ::close(fd);
  return done;
}

// Clears the immutable flag of the files it was given when the test ends, failed or not (the
// scratch directory could not be removed otherwise).
class ImmutableFiles {
 public:
  bool add(const fs::path& path) {
    if (!set_immutable(path, true)) return false;
    paths_.push_back(path);
    return true;
  }
  ~ImmutableFiles() {
    for (const fs::path& path : paths_) set_immutable(path, false);
  }

 private:
  std::vector<fs::path> paths_;
};

TEST_F(Safety, AnImmutableFileLeavesTheWholeSetUnchanged) {
  const fs::path out = scratch_ / "out", passes = scratch_ / "pass", glints = scratch_ / "g";
  const CliRun first = saagen({"emit", "-o", out.string(), "--sigma2", "0.5"});
  const CliRun first_pass = saagen({"pass", "-v", "deferred-avg", "-o", passes.string(), "--sigma2", "0.5"});
  auto dictionary = small_dictionary(glints / "d.ktx2");
  dictionary.insert(dictionary.end(), {"--raw", (glints / "d.f32").string()});
  ASSERT_EQ(saagen(dictionary).exit_code, 0);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  ASSERT_EQ(first_pass.exit_code, 0) << first_pass.err;
  // The last file each run commits: under a rename-as-you-go commit, every other file would be new.
  const fs::path emit_victim = written_paths(first.out).back(), pass_victim = passes / "saa_pass_deferred_avg.h";
  ASSERT_TRUE(fs::exists(pass_victim));
  ImmutableFiles immutable;
  if (!immutable.add(emit_victim)) GTEST_SKIP() << "chattr +i is refused here (no CAP_LINUX_IMMUTABLE, or the file system has no flag)";
  ASSERT_TRUE(immutable.add(pass_victim));
  ASSERT_TRUE(immutable.add(glints / "d.f32"));
  const auto emit_before = snapshot(out), pass_before = snapshot(passes), glints_before = snapshot(glints);

  const CliRun emit = saagen({"emit", "-o", out.string()});
  expect_one_line_error(emit, emit_victim.string() + ": cannot be replaced (Operation not permitted: the file is immutable");
  EXPECT_NE(emit.err.find("nothing was changed"), std::string::npos) << emit.err;
  EXPECT_EQ(snapshot(out), emit_before);
  // The pass's header embeds the SPIR-V: neither may be new without the other.
  const CliRun pass = saagen({"pass", "-v", "deferred-avg", "-o", passes.string()});
  expect_one_line_error(pass, pass_victim.string() + ": cannot be replaced");
  EXPECT_EQ(snapshot(passes), pass_before);
  dictionary[3] = "8";  // --count 8: every file of the dictionary changes
  expect_one_line_error(saagen(dictionary), (glints / "d.f32").string() + ": cannot be replaced");
  EXPECT_EQ(snapshot(glints), glints_before);
}

// Another user's file in a sticky directory (as in /tmp) cannot be renamed over: the run (as
// user nobody) is refused before any file of the set is replaced.
TEST_F(Safety, AnotherUsersFileInAStickyDirectoryLeavesTheWholeSetUnchanged) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to run saagen as another user (setpriv) and to own a file there";
  if (std::system("command -v setpriv >/dev/null 2>&1") != 0) GTEST_SKIP() << "setpriv (util-linux) is not installed";
  const fs::path sticky = scratch_ / "sticky";
  fs::create_directories(sticky);
  fs::permissions(scratch_, fs::perms::all, fs::perm_options::add);
  fs::permissions(sticky, fs::perms::all | fs::perms::sticky_bit);
  const std::string as_nobody = "setpriv --reuid=65534 --regid=65534 --clear-groups " + shell_quote(SAAGEN_CLI_PATH);
  const CliRun first = run_shell(as_nobody + " emit -o " + shell_quote(sticky.string()) + " --sigma2 0.5");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  // The last file committed becomes root's (same bytes, writable by all: only the sticky rule stops a rename over it).
  const fs::path victim = written_paths(first.out).back();
  const std::string bytes = read_text(victim);
  fs::remove(victim);
  write(victim, bytes);
  fs::permissions(victim, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read | fs::perms::group_write |
                              fs::perms::others_read | fs::perms::others_write);
  const auto before = snapshot(sticky);

  const CliRun run = run_shell(as_nobody + " emit -o " + shell_quote(sticky.string()));
  expect_one_line_error(run, victim.string() + ": cannot be replaced (Operation not permitted: another user's file in a sticky directory)");
  EXPECT_NE(run.err.find("nothing was changed"), std::string::npos) << run.err;
  EXPECT_EQ(snapshot(sticky), before);
}

// The commit hook of these tests: what to do after which step.
struct HookAction {
  saagen::CommitStep step = saagen::CommitStep::renamed;
  std::size_t index = 0;
  std::function<void()> action;
};
HookAction hook_action;

void run_hook_action(saagen::CommitStep step, std::size_t index) {
  if (hook_action.action && step == hook_action.step && index == hook_action.index) hook_action.action();
}

class Commit : public saagen::test::CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    saagen::set_commit_hook(&run_hook_action);
    old_ = {{dir() / "a.txt", "saagen-output: a, old\n"}, {dir() / "b.txt", "saagen-output: b, old\n"}};
    saagen::write_outputs(old_, false);
  }
  void TearDown() override {
    saagen::set_commit_hook(nullptr);
    hook_action = {};
    CliTest::TearDown();
  }
  fs::path dir() const { return scratch_ / "d"; }
  // A new file in directories that do not exist yet, then new bytes for a.txt and b.txt.
  std::vector<saagen::OutputFile> new_set() const {
    return {{dir() / "new" / "deeper" / "c.txt", "saagen-output: c, new\n"},
            {dir() / "a.txt", "saagen-output: a, new\n"},
            {dir() / "b.txt", "saagen-output: b, new\n"}};
  }
  // Runs write_outputs(new_set()) in a child process; its wait status.
  int status_of_child_commit() const {
    const pid_t child = ::fork();
    if (child == 0) {
      const struct rlimit no_core {};
      ::setrlimit(RLIMIT_CORE, &no_core);  // SIGXFSZ's default action dumps core
      try {
        saagen::write_outputs(new_set(), false);
      } catch (...) {
        ::_exit(2);
      }
      ::_exit(0);
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    return status;
  }
  std::vector<saagen::OutputFile> old_;
};

// A rename that fails after others succeeded (here b.txt became a directory meanwhile) puts back
// the files already replaced (the same inodes), removes the new file and the directories the run
// created, and leaves no temporary or backup.
TEST_F(Commit, AFailedRenamePutsBackEveryFileAndRemovesNewDirectories) {
  struct stat a_before {};
  ASSERT_EQ(::stat((dir() / "a.txt").c_str(), &a_before), 0);
  hook_action = {saagen::CommitStep::renamed, 1, [&] {
                   fs::rename(dir() / "b.txt", dir() / "b.moved");
                   fs::create_directories(dir() / "b.txt" / "inside");
                 }};
  try {
    saagen::write_outputs(new_set(), false);
    ADD_FAILURE() << "the commit succeeded";
  } catch (const saagen::Error& error) {
    EXPECT_EQ(std::string(error.what()), (dir() / "b.txt").string() + ": cannot be replaced (Is a directory); nothing was changed");
  }
  EXPECT_EQ(read_text(dir() / "a.txt"), "saagen-output: a, old\n");
  struct stat a_after {};
  ASSERT_EQ(::stat((dir() / "a.txt").c_str(), &a_after), 0);
  EXPECT_EQ(a_after.st_ino, a_before.st_ino);
  EXPECT_EQ(snapshot(dir()), (std::map<std::string, std::string>{
                                 {"a.txt", "saagen-output: a, old\n"}, {"b.moved", "saagen-output: b, old\n"}, {"b.txt", ""}}));
  EXPECT_FALSE(fs::exists(dir() / "new"));
}

// SIGTERM (or Ctrl-C) arriving between two renames waits until the set is whole: the process
// then ends by the signal, with every file new and no temporary or backup left.
TEST_F(Commit, ASignalBetweenRenamesActsOnceTheSetIsWhole) {
  for (const int signal : {SIGTERM, SIGINT, SIGHUP}) {
    hook_action = {};
    saagen::write_outputs(old_, true);
    fs::remove_all(dir() / "new");
    hook_action = {saagen::CommitStep::renamed, 0, [signal] { ::raise(signal); }};
    const int status = status_of_child_commit();
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal) << "signal " << signal << ", status " << status;
    EXPECT_EQ(snapshot(dir()), (std::map<std::string, std::string>{
                                   {"a.txt", "saagen-output: a, new\n"}, {"b.txt", "saagen-output: b, new\n"}, {"new", ""}}));
    EXPECT_EQ(snapshot(dir() / "new" / "deeper"), (std::map<std::string, std::string>{{"c.txt", "saagen-output: c, new\n"}}));
  }
}

// SIGINT, SIGTERM or SIGXFSZ while the set is staged: no file is replaced, the temporaries and
// the directories the run created are removed.
TEST_F(Commit, ASignalWhileStagingRemovesTemporariesAndNewDirectories) {
  for (const int signal : {SIGINT, SIGTERM, SIGXFSZ}) {
    hook_action = {saagen::CommitStep::staged, 1, [signal] { ::raise(signal); }};
    const int status = status_of_child_commit();
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal) << "signal " << signal << ", status " << status;
    EXPECT_EQ(snapshot(dir()),
              (std::map<std::string, std::string>{{"a.txt", "saagen-output: a, old\n"}, {"b.txt", "saagen-output: b, old\n"}}));
  }
}

// The file-size limit's SIGXFSZ through the command line, into a directory that did not exist.
TEST_F(Safety, AFileSizeSignalRemovesTheDirectoriesTheRunCreated) {
  const std::string command =
      "ulimit -f 8; exec " + shell_quote(SAAGEN_CLI_PATH) + " emit -o " + shell_quote((scratch_ / "new" / "deeper").string());
  const CliRun run = run_shell(command);
  EXPECT_EQ(run.exit_code, 128 + SIGXFSZ) << run.err;
  EXPECT_FALSE(fs::exists(scratch_ / "new"));
}

// ---------------------------------------------------------------------------------------------
// #include as a preprocessor sees it.

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t count = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++count;
  return count;
}

// In-memory files for saagen::expand_includes; counts the lookups.
struct MemoryIncludes {
  std::map<std::string, std::string> files;
  int lookups = 0;
  int generated = 0;
  saagen::IncludeSources sources() {
    return {[this](const std::string& name, const saagen::IncludeFile&) -> std::shared_ptr<const saagen::IncludeFile> {
              ++lookups;
              const auto found = files.find(name);
              if (found == files.end()) return nullptr;
              return std::make_shared<const saagen::IncludeFile>(saagen::IncludeFile{name, name, found->second});
            },
            [this](const std::string& name) -> std::string {
              ++generated;
              return "// generated " + name + "\n";
            }};
  }
  std::string expanded(const std::string& root) {
    std::string text;
    for (const auto& piece : saagen::expand_includes({root, root, files.at(root)}, sources()).pieces) text += piece.text;
    return text;
  }
};

// h0 .. h{levels-1}, each including the next twice; guarded or not.
MemoryIncludes include_bomb(int levels, bool guarded) {
  MemoryIncludes bomb;
  for (int level = 0; level < levels; ++level) {
    const std::string next = "h" + std::to_string(level + 1) + ".glsl";
    std::string body = level + 1 < levels ? "#include \"" + next + "\"\n#include \"" + next + "\"\n" : "float leaf() { return 1.0; }\n";
    const std::string guard = "H" + std::to_string(level);
    bomb.files["h" + std::to_string(level) + ".glsl"] =
        guarded ? "#ifndef " + guard + "\n#define " + guard + "\n" + body + "#endif\n" : body;
  }
  return bomb;
}

TEST(Includes, AGuardedHeaderIsExpandedOncePerGuard) {
  // 21 levels of double includes: 2^21 expansions unguarded; once each (plus one skipped
  // re-include per level) with guards, so the text and the work are linear in the unique text.
  MemoryIncludes bomb = include_bomb(21, true);
  std::size_t unique = 0;
  for (const auto& [name, text] : bomb.files) unique += text.size();
  const std::string text = bomb.expanded("h0.glsl");
  EXPECT_LT(text.size(), 2 * unique);
  EXPECT_EQ(occurrences(text, "float leaf()"), 1);
  EXPECT_EQ(bomb.lookups, 2 * 20);

  // #pragma once, and a guarded header that includes itself.
  MemoryIncludes once;
  once.files = {{"main.glsl", "#include \"a.glsl\"\n#include \"a.glsl\"\n#include \"self.glsl\"\n"},
                {"a.glsl", "#pragma once\n#include \"a.glsl\"\nfloat a;\n"},
                {"self.glsl", "// a header\n#if !defined(SELF)\n#define SELF 1\n#include \"self.glsl\"\nfloat self;\n#endif // SELF\n"}};
  once.files["main.glsl"] += "#include <saagen/x>\n#include <saagen/x>\n";  // generated once per name
  const std::string expanded = once.expanded("main.glsl");
  EXPECT_EQ(once.generated, 1);
  EXPECT_EQ(occurrences(expanded, "// generated saagen/x"), 2) << expanded;
  EXPECT_EQ(occurrences(expanded, "float a;"), 1) << expanded;
  EXPECT_EQ(occurrences(expanded, "float self;"), 1) << expanded;
}

TEST(Includes, AnExpansionBeyondTheBudgetIsOneLine) {
  MemoryIncludes bomb = include_bomb(26, false);
  try {
    bomb.expanded("h0.glsl");
    ADD_FAILURE() << "the unguarded bomb expanded";
  } catch (const saagen::Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("#include expansions in all (an include bomb?)"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
  MemoryIncludes wide;  // few includes, much text
  wide.files = {{"main.glsl", "#include \"big.glsl\"\n#include \"big.glsl\"\n#include \"big.glsl\"\n#include \"big.glsl\"\n"},
                {"big.glsl", std::string(20 << 20, ' ')}};
  EXPECT_THROW(wide.expanded("main.glsl"), saagen::Error);
}

TEST(Includes, IncludesInSkippedBranchesAndCommentsAreNotResolved) {
  MemoryIncludes sources;
  sources.files = {{"main.glsl",
                    "#define LEVEL 2\n"
                    "#if 0\n#include \"missing.glsl\"\n#endif\n"
                    "// #include \"missing.glsl\"\n"
                    "/* a comment\n#include \"missing.glsl\"\n*/\n"
                    "#ifdef NOT_DEFINED\n#include \"missing.glsl\"\n#elif LEVEL > 1 && defined(LEVEL)\n#include \"found.glsl\"\n"
                    "#else\n#include \"missing.glsl\"\n#endif\n"
                    "#if (LEVEL << 2) == 8 ? 0 : 1\n#include \"missing.glsl\"\n#endif\n"
                    "#undef LEVEL\n#ifdef LEVEL\n#include \"missing.glsl\"\n#endif\n"},
                   {"found.glsl", "float found;\n"}};
  const std::string text = sources.expanded("main.glsl");
  EXPECT_NE(text.find("float found;"), std::string::npos) << text;
  EXPECT_EQ(sources.lookups, 1);

  // A macro that doubles per level (2^40 tokens) leaves the condition to glslang at once.
  std::string doubling = "#define B0 1\n";
  for (int level = 1; level <= 40; ++level) {
    const std::string previous = "B" + std::to_string(level - 1);
    doubling += "#define B" + std::to_string(level) + " " + previous + " " + previous + "\n";
  }
  sources.files["main.glsl"] = doubling + "#if B40\n#include \"found.glsl\"\n#endif\n";
  EXPECT_NE(sources.expanded("main.glsl").find("float found;"), std::string::npos);

  // What glslang predefines is glslang's to decide: a missing include there becomes an #error
  // line that fires only if the branch is compiled.
  sources.files["main.glsl"] = "#ifdef VULKAN\n#include \"missing.glsl\"\n#endif\n";
  const saagen::IncludeExpansion deferred =
      saagen::expand_includes({"main.glsl", "main.glsl", sources.files["main.glsl"]}, sources.sources());
  ASSERT_EQ(deferred.pieces.size(), 1u);
  EXPECT_EQ(deferred.pieces[0].text, "#ifdef VULKAN\n#error saagen_unresolved_include_0\n#endif\n");
  EXPECT_EQ(saagen::deferred_include_error(deferred, "main.glsl:2: '#error' : saagen_unresolved_include_0"),
            "main.glsl:2: #include \"missing.glsl\" not found next to the file or in the -I directories");
  // A compiled include that is missing is one line with the file and line.
  sources.files["main.glsl"] = "float x;\n#if 1\n#include \"missing.glsl\"\n#endif\n";
  try {
    sources.expanded("main.glsl");
    ADD_FAILURE() << "a missing include was accepted";
  } catch (const saagen::Error& error) {
    EXPECT_EQ(std::string(error.what()), "main.glsl:3: #include \"missing.glsl\" not found next to the file or in the -I directories");
  }
}

TEST_F(Safety, CompileResolvesIncludesAsThePreprocessorDoes) {
  write(scratch_ / "s.frag",
        "#version 450\n#if 0\n#include \"missing.glsl\"\n#endif\n// #include \"missing.glsl\"\n#include \"self.glsl\"\n"
        "#ifndef VULKAN\n#include \"missing.glsl\"\n#endif\n"
        "layout(location = 0) out vec4 color;\nvoid main() { color = vec4(self_value()); }\n");
  write(scratch_ / "self.glsl",
        "#ifndef SELF_GLSL\n#define SELF_GLSL\n#include \"self.glsl\"\nfloat self_value() { return 0.5; }\n#endif\n");
  const CliRun run = saagen({"compile", (scratch_ / "s.frag").string(), "-o", (scratch_ / "s.spv").string()});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  // For OpenGL, VULKAN is not defined: the missing include is compiled, and reported.
  const CliRun opengl = saagen({"compile", (scratch_ / "s.frag").string(), "--client", "opengl", "-o", (scratch_ / "g.spv").string()});
  expect_one_line_error(opengl, "s.frag:8: #include \"missing.glsl\" not found next to the file or in the -I directories");
  // The 21-level guarded double-include bomb compiles (it took 31 s and 1 GB).
  MemoryIncludes bomb = include_bomb(21, true);
  for (const auto& [name, text] : bomb.files) write(scratch_ / "bomb" / name, text);
  write(scratch_ / "bomb" / "b.frag",
        "#version 450\n#include \"h0.glsl\"\nlayout(location = 0) out vec4 color;\nvoid main() { color = vec4(leaf()); }\n");
  const CliRun guarded = saagen({"compile", (scratch_ / "bomb" / "b.frag").string(), "-o", (scratch_ / "b.spv").string()});
  EXPECT_EQ(guarded.exit_code, 0) << guarded.err;
}

}  // namespace
