// saagen ground-truth renderer: content nobody here authored, as trade scenes of the medium and
// full presets (report::add_preset_assets), installed by the project's scripts
// (scripts/install-deps.sh), never copied into the repository:
//
//   ClearCoatTest, ClearCoatTest-coat, 2CylinderEngine
//       Khronos's glTF 2.0 sample models (CC-BY 4.0; docs/GLTF_SCENES.md), from
//       Debian's assimp-testmodels under /usr/share/assimp/models/glTF2/, loaded as
//       `saagen bench --scene ASSET` loads them (gltf.hpp; the coat lobe is its own scene).
//   pmndrs-0014, pmndrs-0019, pmndrs-0010
//       three of the CC0 tangent-space normal maps of the npm package @pmndrs/assets (pinned by
//       package.json / package-lock.json, installed by npm ci into node_modules): normals/NNNN.webp.js,
//       an ES module whose default export is a 512^2 WebP image as a base64 data URI, decoded
//       with Debian's libwebp. docs/PREFILTER.md chose them by the mean tilt |n.xy| of their
//       texels: 0014 gentle (0.13), 0019 medium (0.21), 0010 rough (0.42). Each is put on the
//       sphere scene as nmap-sphere's procedural map is (scene.hpp: same sphere, camera, light
//       and animation, the map repeated (2, 1) times over the sphere's uv), shaded at the
//       preset's alphas down to 0.0025.
//
// The maps follow glTF's and OpenGL's convention (glTF 2.0 Sec. 3.9.3, normalTexture: "+Y up",
// green grows towards the image's top): the texel c in [0, 1]^3 is the normal
// normalize(2c - 1), its z lifted to 1e-3 where it is below (as the glTF loader does), and the
// image's top row is the map's row at v = 1 (an OpenGL upload), so that the map's +y points
// along +v, the sphere's tangent-space y (Scene::apply_normal_map).
#pragma once

#include "saagen/measure/normal_map.hpp"
#include "saagen/measure/scene.hpp"

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace saagen::measure {

// A preset scene's content is not installed: what() is one line naming the scene, the missing
// file and what to install.
class AssetMissing : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A file that is there but cannot be used (not a data-URI module, not a WebP, not a normal
// map): what() is one line "PATH: what is wrong".
class AssetError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct PresetAsset {
  std::string scene;              // the (first) scene's name
  std::string path;               // the file it is made from
  std::string install;            // what installs it
  std::optional<int> centre_lod;  // a normal map's, when its name asks for one (below)
};

// Where the npm packages are: $SAAGEN_NODE_MODULES when set, else the source tree's
// node_modules (where npm ci puts them).
std::string node_modules_dir();

// The presets' assets, in the presets' order (the glTF assets, then the normal maps).
std::vector<PresetAsset> preset_assets();

// Registers every preset asset's scenes (a glTF asset's coat scene after it) and returns their
// ids in order. Checks first that every file exists: AssetMissing names the first missing one
// and nothing is loaded. GltfError or AssetError for a file that is there but bad.
std::vector<SceneId> register_preset_assets();

// The scenes of one preset asset by its scene's name (a glTF asset's coat scene after it),
// registered; also any map of @pmndrs/assets' normals as "pmndrs-NNNN" on the sphere (the
// held-out maps, scripts/held_out.sh); empty for a name that is neither. AssetMissing as above.
std::vector<SceneId> register_preset_asset(const std::string& scene);
// "pmndrs-NNNN": that normal map of @pmndrs/assets as an asset (not checked to exist);
// "pmndrs-NNNN-lodK" (K = 0 - 9): the same map repeated 2^(K - 2) times as often, so that the
// implicit LOD at the centre of a 64 x 64 image (the medium preset's asset scenes) is K + 0.22
// for the package's 512^2 maps (one less per doubling of the image's side): for sweeping what
// filters do as a map recedes (engines bake their normal-map filtering into the MIP chain).
// "pmndrs-NNNN" is the same as "pmndrs-NNNN-lod2".
std::optional<PresetAsset> pmndrs_map_named(const std::string& scene);
// The medium preset's normal-map minification sweep: each of the presets' three maps at LOD 0, 1,
// 3 and 4 ("pmndrs-NNNN-lodK"; LOD 2 is the map's own preset scene), so that the advice for
// normal-mapped content is derived over the distances at which a map is seen, close up to far.
std::vector<std::string> minification_sweep_scenes();
// Whether a scene is a preset asset's (by name, the coat scenes and any pmndrs-NNNN map included).
bool is_preset_asset_scene(SceneId id);

// The WebP bytes of an ES module holding one base64 data URI 'data:image/webp;base64,...'.
std::string webp_from_data_uri_module(const std::string& path);

// A tangent-space normal map from WebP bytes (see the top of this file); `what` names the
// source in errors (AssetError: not a WebP, a side that is not a power of two).
std::shared_ptr<const NormalMap> decode_webp_normal_map(const std::string& webp, const std::string& what);

// Registers the sphere scene carrying the normal map of an @pmndrs/assets normals module, named
// "pmndrs-" and the module's stem (0014 for normals/0014.webp.js), repeated over the sphere's uv
// as nmap-sphere's map is, or, given a centre LOD K, 2^(K - 2) times as often and named with
// "-lodK" (above); the same path and LOD twice give the same id and decode once. AssetError for
// K outside 0 - 9.
SceneId register_pmndrs_normal_map_scene(const std::string& module_path, std::optional<int> centre_lod = std::nullopt);

}  // namespace saagen::measure
