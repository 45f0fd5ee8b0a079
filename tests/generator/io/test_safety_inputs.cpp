// Hostile input (test_safety): deeply nested and oversized manifests refused before parsing,
// strict readers (PPM, PNG, KTX2, LEAN), inputs that never end or are too large refused at once
// (devices, FIFOs, the bench's cache), and #include expanded as a preprocessor sees it.
#include "safety_support.hpp"

#include "saagen/error.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/io/include_expansion.hpp"
#include "saagen/io/ktx2.hpp"
#include "saagen/products/glints.hpp"
#include "saagen/products/prefilter.hpp"
#include "saagen/scene/manifest.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
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
