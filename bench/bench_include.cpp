// Include-handler overhead: the time to compile a user shader that includes a saagen snippet
// through saagen's include handler (generated in memory) against the same shader compiled with
// the emitted file on disk, through shaderc and through glslang. Interleaved rounds, medians,
// ratios measured in one run. Then the #include expansion of `saagen compile` on the guarded
// double-include tree (21 headers, each including the next twice: 2^21 expansions without the
// guards) against the same headers included once each (a chain): linear in the unique text
// means a ratio near 1 (the tree has twice the include lines).
//   build/bench/bench_include [--rounds N]
#include "support/include_shaders.hpp"

#include "saagen/integrate/include_handler.hpp"
#include "saagen/io/include_expansion.hpp"
#include "saagen/io/output.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <sstream>
#include <string>

#include <unistd.h>

namespace {

namespace fs = std::filesystem;

constexpr const char* include_name = "saagen/deferred-avg.glsl?domain=perceptual";
constexpr const char* call = "saa_deferred_avg_perceptual";

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The on-disk baseline: a name is a path under `root` (what a file-system includer does).
class DiskShadercIncluder : public shaderc::CompileOptions::IncluderInterface {
 public:
  explicit DiskShadercIncluder(fs::path root) : root_(std::move(root)) {}
  shaderc_include_result* GetInclude(const char* requested, shaderc_include_type, const char*, size_t) override {
    auto* file = new File{(root_ / requested).string(), {}, {}};
    file->content = read_text(file->path);
    file->result = {file->path.c_str(), file->path.size(), file->content.c_str(), file->content.size(), file};
    return &file->result;
  }
  void ReleaseInclude(shaderc_include_result* result) override { delete static_cast<File*>(result->user_data); }

 private:
  struct File {
    std::string path, content;
    shaderc_include_result result;
  };
  fs::path root_;
};

class DiskGlslangIncluder : public glslang::TShader::Includer {
 public:
  explicit DiskGlslangIncluder(fs::path root) : root_(std::move(root)) {}
  IncludeResult* includeSystem(const char* name, const char*, size_t) override {
    auto* content = new std::string(read_text(root_ / name));
    return new IncludeResult((root_ / name).string(), content->data(), content->size(), content);
  }
  void releaseInclude(IncludeResult* result) override {
    if (!result) return;
    delete static_cast<std::string*>(result->userData);
    delete result;
  }

 private:
  fs::path root_;
};

double milliseconds(const std::function<void()>& body) {
  const auto start = std::chrono::steady_clock::now();
  body();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// h0 .. h20 in memory, guarded, each including the next `includes` times.
std::map<std::string, std::string> guarded_headers(int includes) {
  constexpr int levels = 21;
  std::map<std::string, std::string> files;
  for (int level = 0; level < levels; ++level) {
    const std::string guard = "H" + std::to_string(level);
    std::string body;
    for (int copy = 0; copy < includes && level + 1 < levels; ++copy) body += "#include \"h" + std::to_string(level + 1) + ".glsl\"\n";
    if (level + 1 == levels) body = "float leaf() { return 1.0; }\n";
    files["h" + std::to_string(level) + ".glsl"] = "#ifndef " + guard + "\n#define " + guard + "\n" + body + "#endif\n";
  }
  return files;
}

// The expanded text's size (so that the work is not optimised away).
std::size_t expand(const std::map<std::string, std::string>& files) {
  const saagen::IncludeSources sources{
      [&](const std::string& name, const saagen::IncludeFile&) -> std::shared_ptr<const saagen::IncludeFile> {
        return std::make_shared<const saagen::IncludeFile>(saagen::IncludeFile{name, name, files.at(name)});
      },
      [](const std::string&) -> std::string { return {}; }};
  std::size_t size = 0;
  for (const auto& piece : saagen::expand_includes({"h0.glsl", "h0.glsl", files.at("h0.glsl")}, sources).pieces) size += piece.text.size();
  return size;
}

}  // namespace

int main(int argc, char** argv) {
  int rounds = 21;
  if (argc == 3 && std::string(argv[1]) == "--rounds") rounds = std::max(1, std::atoi(argv[2]));

  // The emitted file on disk, under the name the shader includes.
  const fs::path root = fs::temp_directory_path() / ("saagen_bench_include_" + std::to_string(::getpid()));
  const saagen::EmittedFile file = saagen::resolve_include(include_name, {});
  saagen::write_outputs({{root / "saa_deferred_avg_perceptual.glsl", file.content}}, false);
  const std::string include_handler = std::string("#include <") + include_name + ">";
  const std::string include_disk = "#include <saa_deferred_avg_perceptual.glsl>";

  std::vector<double> shaderc_handler, shaderc_disk, glslang_handler, glslang_disk;
  bool ok = true;
  for (int round = 0; round < rounds; ++round) {
    shaderc_handler.push_back(milliseconds([&] {
      ok &= saagen::test::compile_with_shaderc(saagen::test::glsl_user_shader(include_handler, call, false), false,
                                               std::make_unique<saagen::ShadercIncluder>())
                .ok;
    }));
    shaderc_disk.push_back(milliseconds([&] {
      ok &= saagen::test::compile_with_shaderc(saagen::test::glsl_user_shader(include_disk, call, false), false,
                                               std::make_unique<DiskShadercIncluder>(root))
                .ok;
    }));
    glslang_handler.push_back(milliseconds([&] {
      saagen::GlslangIncluder includer;
      ok &= saagen::test::compile_with_glslang(saagen::test::glsl_user_shader(include_handler, call, true), false, includer).ok;
    }));
    glslang_disk.push_back(milliseconds([&] {
      DiskGlslangIncluder includer(root);
      ok &= saagen::test::compile_with_glslang(saagen::test::glsl_user_shader(include_disk, call, true), false, includer).ok;
    }));
  }
  fs::remove_all(root);
  if (!ok) {
    std::fprintf(stderr, "bench_include: a compile failed\n");
    return 1;
  }
  std::printf("include-handler overhead, %d interleaved rounds, medians (%s):\n", rounds, include_name);
  std::printf("  shaderc  handler %.2f ms  on disk %.2f ms  ratio %.3f\n", median(shaderc_handler), median(shaderc_disk),
              median(shaderc_handler) / median(shaderc_disk));
  std::printf("  glslang  handler %.2f ms  on disk %.2f ms  ratio %.3f\n", median(glslang_handler), median(glslang_disk),
              median(glslang_handler) / median(glslang_disk));

  const auto tree = guarded_headers(2), chain = guarded_headers(1);
  std::vector<double> tree_ms, chain_ms;
  std::size_t tree_bytes = 0, chain_bytes = 0;
  for (int round = 0; round < rounds; ++round) {
    tree_ms.push_back(milliseconds([&] { tree_bytes = expand(tree); }));
    chain_ms.push_back(milliseconds([&] { chain_bytes = expand(chain); }));
  }
  std::printf("#include expansion, 21 guarded headers, %d interleaved rounds, medians:\n", rounds);
  std::printf("  each included twice %.3f ms (%zu bytes)  once %.3f ms (%zu bytes)  ratio %.3f\n", median(tree_ms), tree_bytes,
              median(chain_ms), chain_bytes, median(tree_ms) / median(chain_ms));
  return 0;
}
