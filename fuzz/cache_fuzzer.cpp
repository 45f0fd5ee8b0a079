// libFuzzer target: the ground-truth cache's reader (cached_ground_truth over a cache folder),
// through its public path. At start-up the target renders one tiny ground truth (3x2 pixels,
// two materials, one sample per pixel) through an empty cache, which writes the entry's file;
// each input then replaces that file before the same call is made again.
//
// The input's first byte chooses what the file becomes:
//   0      the rest of the input, as the whole file;
//   other  the file as written, changed by the rest of the input: a 4-byte little-endian length
//          to cut it to (0xffffffff: keep it whole), then 5-byte records (4-byte little-endian
//          offset modulo the file's length, counted from the end when its top bit is set, 1 byte
//          to XOR there);
// the input is empty: the file as written.
//
// Whatever the file holds, a read from the cache (cache_hit) must give exactly the ground truth
// that was rendered (the key states everything the pixels depend on: a file that differs in
// them is corrupt, and a corrupt file is a miss that renders again); a miss must render the same
// pixels again. Any exception, crash or sanitizer report is a finding.
#include "fuzz_support.hpp"

#include "saagen/measure/renderer.hpp"
#include "saagen/measure/scene.hpp"
#include "saagen/measure/trade.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using namespace saagen::measure;
constexpr const char* target = "cache_fuzzer";

struct Fixture {
  fs::path dir;   // the cache folder
  fs::path file;  // the entry's file in it
  Scene scene = make_scene(SceneId::sphere);
  GroundTruthSettings settings;
  std::vector<Material> materials{{0.05, false}, {0.3, true}};
  GroundTruth rendered;  // what the first call rendered
  std::string written;   // the file it wrote
};

std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool same(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

bool same(const GroundTruth& a, const GroundTruth& b) {
  if (a.images.size() != b.images.size() || !same(a.coverage, b.coverage)) return false;
  for (std::size_t index = 0; index < a.images.size(); ++index)
    if (!same(a.images[index], b.images[index])) return false;
  return true;
}

Fixture& fixture() {
  static Fixture* const instance = [] {
    auto* f = new Fixture;
    std::error_code error;
    const fs::path base = fs::is_directory("/dev/shm", error) ? fs::path("/dev/shm") : fs::temp_directory_path();
    std::string pattern = (base / "saagen-cache-fuzz-XXXXXX").string();
    if (!mkdtemp(pattern.data())) saagen::fuzz::finding(target, "cannot create a cache folder", pattern);
    f->dir = pattern;
    std::atexit([] {
      std::error_code ignored;
      fs::remove_all(fixture().dir, ignored);
    });
    f->settings.width = 3;
    f->settings.height = 2;
    f->settings.strata = 1;
    f->settings.threads = 1;
    f->file = f->dir / ground_truth_cache_file(ground_truth_cache_key(f->scene, f->settings, f->materials));
    bool hit = true;
    f->rendered = cached_ground_truth(f->scene, f->settings, f->materials, f->dir.string(), {}, &hit);
    f->written = read_all(f->file);
    if (hit || f->written.empty()) saagen::fuzz::finding(target, "the first call did not render and write", f->file.string());
    return f;
  }();
  return *instance;
}

std::uint32_t little_endian(const std::uint8_t* bytes) {
  return static_cast<std::uint32_t>(bytes[0]) | static_cast<std::uint32_t>(bytes[1]) << 8 | static_cast<std::uint32_t>(bytes[2]) << 16 |
         static_cast<std::uint32_t>(bytes[3]) << 24;
}

std::string file_for(const Fixture& f, const std::uint8_t* data, std::size_t size) {
  if (size == 0) return f.written;
  if (data[0] == 0) return std::string(reinterpret_cast<const char*>(data + 1), size - 1);
  std::string file = f.written;
  std::size_t at = 1;
  if (at + 4 <= size) {
    const std::uint32_t length = little_endian(data + at);
    if (length != 0xffffffffu && length < file.size()) file.resize(length);
    at += 4;
  }
  for (; at + 5 <= size && !file.empty(); at += 5) {
    const std::uint32_t offset = little_endian(data + at);
    const std::size_t index = (offset & 0x7fffffffu) % file.size();
    file[offset & 0x80000000u ? file.size() - 1 - index : index] ^= static_cast<char>(data[at + 4]);
  }
  return file;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  fixture();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using saagen::fuzz::finding;
  Fixture& f = fixture();
  const std::string file = file_for(f, data, size);
  {
    std::ofstream out(f.file, std::ios::binary | std::ios::trunc);
    out.write(file.data(), static_cast<std::streamsize>(file.size()));
    if (!out) finding(target, "cannot write the cache file", f.file.string());
  }
  bool hit = false;
  GroundTruth gt;
  try {
    gt = cached_ground_truth(f.scene, f.settings, f.materials, f.dir.string(), {}, &hit);
  } catch (const std::exception& error) {
    finding(target, "an exception from the cache", error.what());
  }
  if (!same(gt, f.rendered))
    finding(target, hit ? "a cache read that differs from the rendered ground truth" : "a miss that renders other pixels",
            std::to_string(file.size()) + " bytes");
  if (!hit && file == f.written) finding(target, "the file as written is not read back", f.file.string());
  // Nothing but the entry (a temporary left behind would be a leak of the writer's).
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(f.dir, error))
    if (entry.path() != f.file) finding(target, "a file left in the cache folder", entry.path().string());
  return 0;
}
