// libFuzzer target: the glTF 2.0 loader (load_gltf: tinygltf, the asset checks, node walk,
// accessors, tangents, textures, BVH) and the trade scenes made from an accepted asset
// (make_gltf_scene, make_gltf_coat_scene), each rendered as a tiny ground truth.
//
// The input is a small file tree: the asset first (asset.glb when it starts with the GLB magic
// "glTF", else asset.gltf), then any number of sections "\0SAAGEN-FILE:NAME\n" + the file's
// bytes, which the asset's URIs may name (buffers, images). scripts/fuzz.sh packs the
// Debian assimp-testmodels samples this way (fuzz/README.md). The tree is written to a private
// temporary folder for each input, since load_gltf reads files.
//
// A rejected asset must fail with one GltfError line starting with "<asset path>: "; any other
// exception, crash or sanitizer report is a finding. An accepted asset must be consistent: one
// material per object, in range; finite bounds that hold every vertex; a summary free of
// control characters other than line breaks.
#include "fuzz_support.hpp"

#include "saagen/measure/gltf.hpp"
#include "saagen/measure/renderer.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>

#include <unistd.h>

namespace {

namespace fs = std::filesystem;
constexpr const char* target = "gltf_fuzzer";
constexpr std::string_view kSection{"\0SAAGEN-FILE:", 13};

// A private folder for this process's inputs (tmpfs when there is one), removed at exit.
const fs::path& work_dir() {
  static const fs::path dir = [] {
    std::error_code error;
    const fs::path base = fs::is_directory("/dev/shm", error) ? fs::path("/dev/shm") : fs::temp_directory_path();
    std::string pattern = (base / "saagen-gltf-fuzz-XXXXXX").string();
    if (!mkdtemp(pattern.data())) saagen::fuzz::finding(target, "cannot create a work folder", pattern);
    std::atexit([] {
      std::error_code ignored;
      fs::remove_all(work_dir(), ignored);
    });
    return fs::path(pattern);
  }();
  return dir;
}

bool plain_name(std::string_view name) {
  if (name.empty() || name.size() > 64 || name.front() == '.') return false;
  for (const char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '.' || c == '-')) return false;
  return true;
}

void write_file(const fs::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) saagen::fuzz::finding(target, "cannot write the input", path.string());
}

// Writes the input's file tree into the work folder (emptied first); returns the asset's path.
std::string unpack(std::string_view input) {
  const fs::path& dir = work_dir();
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(dir, error)) fs::remove_all(entry.path(), error);
  std::size_t end = input.find(kSection);
  const std::string_view asset = input.substr(0, end);
  const bool binary = asset.substr(0, 4) == "glTF";
  const fs::path asset_path = dir / (binary ? "asset.glb" : "asset.gltf");
  while (end != std::string_view::npos) {
    const std::size_t name_at = end + kSection.size();
    const std::size_t line = input.find('\n', name_at);
    if (line == std::string_view::npos) break;
    end = input.find(kSection, line + 1);
    const std::string_view name = input.substr(name_at, line - name_at);
    const std::string_view bytes = input.substr(line + 1, end == std::string_view::npos ? std::string_view::npos : end - line - 1);
    if (plain_name(name) && name != asset_path.filename().string()) write_file(dir / std::string(name), bytes);
  }
  write_file(asset_path, asset);
  return asset_path.string();
}

void check_text(std::string_view what, std::string_view text) {
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 && c != '\n') || byte == 0x7f) saagen::fuzz::finding(target, what.data(), text);
  }
}

bool finite(const saagen::measure::Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Every pixel of a 4x3 ground truth (one sample per pixel, one thread) of `scene`.
void render_tiny(const saagen::measure::Scene& scene) {
  saagen::measure::GroundTruthSettings settings;
  settings.width = 4;
  settings.height = 3;
  settings.strata = 1;
  settings.threads = 1;
  const saagen::measure::Material materials[] = {{0.05, false}, {0.5, true}};
  const saagen::measure::GroundTruth gt = saagen::measure::render_ground_truth(scene, settings, materials);
  if (gt.images.size() != 2 || gt.coverage.size() != 12) saagen::fuzz::finding(target, "ground truth of the wrong shape", scene.name());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using saagen::fuzz::finding;
  const std::string path = unpack(std::string_view(reinterpret_cast<const char*>(data), size));
  // Smaller than the defaults, so that one input stays within milliseconds and megabytes; the
  // checks against them are the same code.
  saagen::measure::GltfLimits limits;
  limits.max_triangles = 20'000;
  limits.max_vertices = 60'000;
  limits.max_texture_size = 256;
  limits.max_texels = 256 * 256 * 4;
  limits.max_file_bytes = 1u << 20;
  std::shared_ptr<saagen::measure::GltfAsset> asset;
  try {
    asset = std::make_shared<saagen::measure::GltfAsset>(saagen::measure::load_gltf(path, limits));
  } catch (const saagen::measure::GltfError& error) {
    // One line; control characters it quotes from the asset (tinygltf's "last read: '...'") are
    // escaped where the CLI prints it (saagen::Error's one_line).
    saagen::fuzz::check_message(target, error.what(), path + ": ");
    return 0;
  } catch (const std::exception& error) {
    finding(target, "an exception other than GltfError", error.what());
  }
  if (!asset->mesh) finding(target, "accepted asset without a mesh", path);
  if (asset->object_material.size() != static_cast<std::size_t>(asset->primitives))
    finding(target, "objects and materials disagree", std::to_string(asset->object_material.size()));
  for (const int material : asset->object_material)
    if (material < 0 || static_cast<std::size_t>(material) >= asset->materials.size())
      finding(target, "object material out of range", std::to_string(material));
  if (!finite(asset->bounds_lo) || !finite(asset->bounds_hi)) finding(target, "non-finite bounds", asset->summary());
  for (const auto& vertex : asset->mesh->vertices()) {
    const auto& p = vertex.position;
    if (!finite(p) || p.x < asset->bounds_lo.x || p.y < asset->bounds_lo.y || p.z < asset->bounds_lo.z || p.x > asset->bounds_hi.x ||
        p.y > asset->bounds_hi.y || p.z > asset->bounds_hi.z)
      finding(target, "a vertex outside the bounds or not finite", asset->summary());
  }
  check_text("summary with control characters", asset->summary());
  for (const auto& material : asset->materials) check_text("material description with control characters", material.describe());
  render_tiny(saagen::measure::make_gltf_scene(asset));
  if (asset->coat_surfaces) render_tiny(saagen::measure::make_gltf_coat_scene(asset));
  return 0;
}
