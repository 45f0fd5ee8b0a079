// Content nobody here authored as the presets' scenes (see assets.hpp).
#include "saagen/measure/assets.hpp"

#include "saagen/measure/gltf.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <sstream>
#include <string_view>

#include <tiny_gltf.h>
#include <webp/decode.h>

// Debian's libtinygltf exports the base64 decoder it reads glTF data URIs with; tiny_gltf.h
// declares it only in its implementation part (TINYGLTF_IMPLEMENTATION, compiled into the
// shared library), so its declaration is repeated here.
namespace tinygltf {
std::string base64_decode(std::string const& encoded_string);
}  // namespace tinygltf

namespace saagen::measure {

namespace {

const std::string kGltfModels = "/usr/share/assimp/models/glTF2/";
const std::string kAssimpTestmodels = "install Debian's assimp-testmodels (scripts/install-deps.sh)";
constexpr const char* kPmndrsMaps[] = {"0014", "0019", "0010"};
constexpr const char* kDataUriPrefix = "data:image/webp;base64,";
constexpr std::uintmax_t kMaxModuleBytes = 64u << 20;  // the package's largest normals module is < 1 MiB
constexpr Vec2 kSphereTiling{2.0, 1.0};                // nmap-sphere's (scene.hpp)
// A 512^2 map repeated (2, 1) times over the sphere: LOD 0.22 at the centre of a 256 x 256 view,
// 2.22 at 64 x 64 (scene.hpp's nmap-sphere).
constexpr int kSphereTilingLodAt64Px = 2;

std::string pmndrs_install() {
  return "install the npm package @pmndrs/assets as package-lock.json pins it (npm ci in the source tree, which "
         "scripts/install-deps.sh runs; or set SAAGEN_NODE_MODULES to the node_modules holding it)";
}

std::string pmndrs_module(const char* map) { return node_modules_dir() + "/@pmndrs/assets/normals/" + map + ".webp.js"; }

bool is_power_of_two(int n) { return n > 0 && (n & (n - 1)) == 0; }

bool all_digits(std::string_view text) {
  return !text.empty() && std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

bool is_base64(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '/' || c == '='; }

}  // namespace

std::string node_modules_dir() {
  if (const char* dir = std::getenv("SAAGEN_NODE_MODULES"); dir && *dir) return dir;
  return SAAGEN_SOURCE_NODE_MODULES;
}

std::vector<PresetAsset> preset_assets() {
  std::vector<PresetAsset> assets{
      {"ClearCoatTest", kGltfModels + "ClearCoat-glTF/ClearCoatTest.gltf", kAssimpTestmodels, {}},
      {"2CylinderEngine", kGltfModels + "2CylinderEngine-glTF-Binary/2CylinderEngine.glb", kAssimpTestmodels, {}},
  };
  for (const char* map : kPmndrsMaps) assets.push_back({std::string("pmndrs-") + map, pmndrs_module(map), pmndrs_install(), {}});
  return assets;
}

namespace {

void check_installed(const PresetAsset& asset) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(asset.path, error))
    throw AssetMissing(asset.scene + ": " + asset.path + " is missing; " + asset.install);
}

std::vector<SceneId> register_asset(const PresetAsset& asset) {
  if (asset.path.ends_with(".webp.js")) return {register_pmndrs_normal_map_scene(asset.path, asset.centre_lod)};
  return register_gltf_scenes(asset.path);
}

}  // namespace

std::vector<std::string> minification_sweep_scenes() {
  std::vector<std::string> scenes;
  for (const char* map : kPmndrsMaps)
    for (int lod : {0, 1, 3, 4}) scenes.push_back(std::string("pmndrs-") + map + "-lod" + std::to_string(lod));
  return scenes;
}

std::vector<SceneId> register_preset_assets() {
  const std::vector<PresetAsset> assets = preset_assets();
  for (const PresetAsset& asset : assets) check_installed(asset);
  std::vector<SceneId> ids;
  for (const PresetAsset& asset : assets)
    for (SceneId id : register_asset(asset)) ids.push_back(id);
  return ids;
}

std::optional<PresetAsset> pmndrs_map_named(const std::string& scene) {
  const std::string prefix = "pmndrs-", lod = "-lod";
  if (!scene.starts_with(prefix) || scene.size() < prefix.size() + 4) return std::nullopt;
  const std::string map = scene.substr(prefix.size(), 4);
  if (!all_digits(map)) return std::nullopt;
  std::optional<int> centre_lod;
  if (scene.size() > prefix.size() + 4) {
    const std::string_view suffix = std::string_view(scene).substr(prefix.size() + 4);
    if (!suffix.starts_with(lod) || suffix.size() != lod.size() + 1 || !all_digits(suffix.substr(lod.size()))) return std::nullopt;
    centre_lod = suffix.back() - '0';
  }
  return PresetAsset{scene, pmndrs_module(map.c_str()), pmndrs_install(), centre_lod};
}

std::vector<SceneId> register_preset_asset(const std::string& scene) {
  std::optional<PresetAsset> found;
  for (const PresetAsset& asset : preset_assets())
    if (asset.scene == scene) found = asset;
  if (!found) found = pmndrs_map_named(scene);
  if (!found) return {};
  check_installed(*found);
  return register_asset(*found);
}

bool is_preset_asset_scene(SceneId id) {
  if (!registered_scene(id)) return false;
  const std::string_view name = scene_name(id);
  for (const PresetAsset& asset : preset_assets())
    if (name == asset.scene || name == asset.scene + "-coat") return true;
  return pmndrs_map_named(std::string(name)).has_value();
}

std::string webp_from_data_uri_module(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) throw AssetError(path + ": does not exist or is not a regular file");
  if (std::filesystem::file_size(path, error) > kMaxModuleBytes) throw AssetError(path + ": larger than 64 MiB, not a normals module");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  const std::string module = text.str();
  const std::size_t prefix = module.find(kDataUriPrefix);
  if (prefix == std::string::npos) throw AssetError(path + ": holds no 'data:image/webp;base64,' data URI");
  const std::size_t begin = prefix + std::char_traits<char>::length(kDataUriPrefix);
  std::size_t end = begin;
  while (end < module.size() && is_base64(module[end])) ++end;
  if (end == module.size() || (module[end] != '\'' && module[end] != '"' && module[end] != '`'))
    throw AssetError(path + ": the WebP data URI does not end in a quote (a character outside base64 at byte " + std::to_string(end) + ")");
  return tinygltf::base64_decode(module.substr(begin, end - begin));
}

std::shared_ptr<const NormalMap> decode_webp_normal_map(const std::string& webp, const std::string& what) {
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(webp.data());
  int width = 0, height = 0;
  if (!WebPGetInfo(bytes, webp.size(), &width, &height)) throw AssetError(what + ": not a WebP image (libwebp's WebPGetInfo)");
  if (!is_power_of_two(width) || !is_power_of_two(height) || width > 4096 || height > 4096)
    throw AssetError(what + ": " + std::to_string(width) + " x " + std::to_string(height) +
                     " texels; a normal map needs power-of-two sides up to 4096 (MIP chain)");
  std::uint8_t* rgb = WebPDecodeRGB(bytes, webp.size(), &width, &height);
  if (!rgb) throw AssetError(what + ": libwebp could not decode the image (WebPDecodeRGB)");
  std::vector<Vec3> normals(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  for (int row = 0; row < height; ++row) {
    const std::uint8_t* texel = rgb + static_cast<std::size_t>(row) * static_cast<std::size_t>(width) * 3;
    // The image's top row at v = 1 (see assets.hpp).
    Vec3* out = normals.data() + static_cast<std::size_t>(height - 1 - row) * static_cast<std::size_t>(width);
    for (int x = 0; x < width; ++x, texel += 3) {
      Vec3 n{2.0 * (texel[0] / 255.0) - 1.0, 2.0 * (texel[1] / 255.0) - 1.0, 2.0 * (texel[2] / 255.0) - 1.0};
      if (!(n.z >= 1e-3)) n.z = 1e-3;
      out[x] = ref::normalize(n);
    }
  }
  WebPFree(rgb);
  return std::make_shared<const NormalMap>(width, height, std::move(normals));
}

SceneId register_pmndrs_normal_map_scene(const std::string& module_path, std::optional<int> centre_lod) {
  if (centre_lod && (*centre_lod < 0 || *centre_lod > 9))
    throw AssetError(module_path + ": LOD " + std::to_string(*centre_lod) + " is outside 0 - 9");
  static std::mutex mutex;
  std::lock_guard lock(mutex);
  const std::string stem = std::filesystem::path(module_path).filename().string();
  const std::string suffix = centre_lod ? "-lod" + std::to_string(*centre_lod) : "";
  const std::string name = "pmndrs-" + stem.substr(0, stem.find('.')) + suffix;
  std::error_code error;
  const std::filesystem::path canonical = std::filesystem::weakly_canonical(module_path, error);
  const std::string key = (error ? module_path : canonical.string()) + suffix;
  try {
    // Registered before: the same id for the same file, an error for another.
    if (const auto existing = scene_from_name(name); existing && registered_scene(*existing))
      return register_scene(*registered_scene(*existing), key);
  } catch (const std::invalid_argument& e) {
    throw AssetError(module_path + ": " + e.what());
  }
  std::shared_ptr<const NormalMap> map = decode_webp_normal_map(webp_from_data_uri_module(module_path), module_path);
  RegisteredScene scene;
  scene.name = name;
  scene.has_normal_map = true;
  const std::string source = "@pmndrs/assets normals/" + stem;
  // Each level doubles the texels per pixel: 2^(lod - 2) times nmap-sphere's tiling.
  const Vec2 tiling = std::ldexp(1.0, centre_lod.value_or(kSphereTilingLodAt64Px) - kSphereTilingLodAt64Px) * kSphereTiling;
  scene.make = [name, map, source, tiling](double rotation_radians) {
    // nmap-sphere with this map (scene.cpp): the sphere scene's sphere, camera, light and pivot.
    const Scene base = make_scene(SceneId::sphere, rotation_radians);
    const Scene sphere(name, std::make_shared<Sphere>(1.0), Rigid{}, base.camera(), base.light(), {0.0, 0.0, -1.0}, rotation_radians);
    return sphere.with_normal_map(map, tiling, source);
  };
  try {
    return register_scene(std::move(scene), key);
  } catch (const std::invalid_argument& e) {
    throw AssetError(module_path + ": " + e.what());
  }
}

}  // namespace saagen::measure
