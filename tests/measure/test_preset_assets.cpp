// Content nobody here authored in the medium and full presets (saagen/measure/assets.hpp,
// report::add_preset_assets): the scenes the presets list and their sizes, an @pmndrs/assets
// normal map decoded as Debian's dwebp decodes it, and the one line a missing package gives.
#include "support/cli_support.hpp"

#include "saagen/measure/assets.hpp"
#include "saagen/measure/gltf.hpp"
#include "saagen/measure/renderer.hpp"
#include "saagen/measure/trade.hpp"
#include "saagen/report/report.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

using namespace saagen::measure;
namespace ref = saagen::ref;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> names_from(const std::vector<SceneId>& scenes, std::size_t first) {
  std::vector<std::string> names;
  for (std::size_t i = first; i < scenes.size(); ++i) names.emplace_back(scene_name(scenes[i]));
  return names;
}

// glTF 2.0 Sec. 3.9.3's decoding of an 8-bit texel (r, g, b).
Vec3 texel_normal(int r, int g, int b) {
  return ref::normalize(Vec3{2.0 * (r / 255.0) - 1.0, 2.0 * (g / 255.0) - 1.0, 2.0 * (b / 255.0) - 1.0});
}

}  // namespace

// The presets add six scenes after their built-in ones (the medium preset then its three maps'
// minification sweep, LOD 0, 1, 3 and 4 at its 64 px), at half the preset's width and height
// and the preset's samples per pixel, the animation never below 64 x 64 and 256 spp (the medium
// preset's animation keeps its size and gets 4x its samples, the full preset's is halved to 64 px
// at its own 256 spp); the glTF scenes' ground truths (ClearCoatTest, its coat, 2CylinderEngine)
// at 4096 spp, image and animation; the quick preset adds none.
TEST(PresetAssets, MediumAndFullListTheAssetScenesAtAQuarterOfThePixels) {
  const std::vector<std::string> assets{"ClearCoatTest", "ClearCoatTest-coat", "2CylinderEngine",
                                        "pmndrs-0014",   "pmndrs-0019",        "pmndrs-0010"};
  std::vector<std::string> sweep;
  for (const char* map : {"0014", "0019", "0010"})
    for (const char* lod : {"0", "1", "3", "4"}) sweep.push_back(std::string("pmndrs-") + map + "-lod" + lod);
  EXPECT_EQ(minification_sweep_scenes(), sweep);
  for (const char* preset : {"medium", "full"}) {
    std::vector<std::string> expected = assets;
    if (std::string(preset) == "medium") expected.insert(expected.end(), sweep.begin(), sweep.end());
    TradeConfig config = saagen::report::preset_config(preset);
    const std::size_t built_in = config.scenes.size();
    saagen::report::add_preset_assets(preset, config);
    EXPECT_EQ(names_from(config.scenes, built_in), expected) << preset;
    ASSERT_EQ(config.scene_sizes.size(), expected.size()) << preset;
    for (std::size_t i = 0; i < expected.size(); ++i) {
      const TradeSceneSize& size = config.scene_sizes[i];
      EXPECT_EQ(size.scene, config.scenes[built_in + i]);
      EXPECT_EQ(size.width, config.width / 2);
      EXPECT_EQ(size.height, config.height / 2);
      const bool gltf = i < 3;
      EXPECT_EQ(size.strata, gltf ? 64 : config.strata) << expected[i];
      EXPECT_EQ(size.flicker_width, std::string(preset) == "medium" ? config.flicker_width : config.flicker_width / 2);
      EXPECT_EQ(size.flicker_width, 64);
      // 256 spp: the medium preset's 64 raised, the full preset's own; 4096 for a glTF scene.
      EXPECT_EQ(size.flicker_strata, gltf ? 64 : 16) << expected[i];
      const TradeConfig sized = sized_for_scene(config, size.scene);
      EXPECT_EQ(sized.width, size.width);
      EXPECT_EQ(sized.flicker_height, size.flicker_height);
    }
    for (std::size_t i = 3; i < expected.size(); ++i) EXPECT_TRUE(scene_has_normal_map(config.scenes[built_in + i])) << expected[i];
    EXPECT_EQ(sized_for_scene(config, SceneId::sphere).width, config.width);  // the built-in scenes keep the preset's size
  }
  TradeConfig quick = saagen::report::preset_config("quick");
  const std::vector<SceneId> before = quick.scenes;
  saagen::report::add_preset_assets("quick", quick);
  EXPECT_EQ(quick.scenes, before);
  EXPECT_TRUE(quick.scene_sizes.empty());
}

// A glTF asset given with --scene keeps the preset's sizes and takes its ground truths at 4096 spp
// (a mesh's highlight at alpha 0.0025 is smaller than a pixel); a built-in scene keeps the preset's.
TEST(PresetAssets, AGltfSceneOfOnesOwnTakesItsGroundTruthsAt4096Spp) {
  TradeConfig config = saagen::report::preset_config("medium");
  config.scenes = {SceneId::sphere, register_gltf_scene("/usr/share/assimp/models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb")};
  saagen::report::size_preset_assets("medium", config);
  const TradeConfig box = sized_for_scene(config, config.scenes[1]), sphere = sized_for_scene(config, SceneId::sphere);
  EXPECT_EQ(box.width, config.width);
  EXPECT_EQ(box.flicker_width, config.flicker_width);
  EXPECT_EQ(box.strata * box.strata, 4096);
  EXPECT_EQ(box.flicker_strata * box.flicker_strata, 4096);
  EXPECT_EQ(sphere.strata, config.strata);
  EXPECT_EQ(sphere.flicker_strata, config.flicker_strata);
}

// A scene with sizes of its own (TradeConfig::scene_sizes) is rendered, ground truth and 1-spp
// images, at those sizes; the others at the config's.
TEST(PresetAssets, TheTradeRendersEachSceneAtItsOwnSize) {
  TradeConfig config;
  config.width = config.height = 12;
  config.strata = 2;
  config.flicker_width = config.flicker_height = 6;
  config.flicker_strata = 1;
  config.frames = 2;
  config.alphas = {0.1};
  config.fresnel_modes = {false};
  config.variants = {Variant::none};
  config.scenes = {SceneId::sphere, SceneId::torus};
  config.scene_sizes = {{SceneId::torus, 8, 4, 1, 4, 2, 1}};
  config.keep_images = true;
  const TradeTable table = compute_trade_table(config);
  ASSERT_EQ(table.images.size(), 2u);
  for (const ImageSet& set : table.images) {
    const int width = set.scene == SceneId::torus ? 8 : 12, height = set.scene == SceneId::torus ? 4 : 12;
    EXPECT_EQ(set.reference.width, width);
    EXPECT_EQ(set.reference.height, height);
    ASSERT_FALSE(set.variants.empty());
    EXPECT_EQ(set.variants.front().image.width, width);
    EXPECT_EQ(set.variants.front().image.height, height);
  }
  // Each frame of the animation: two ground-truth seeds and the sanity suite's quarter-sample one
  // (strata 1 / 2, at least 1: one sample here).
  EXPECT_EQ(table.ground_truth_samples, 12u * 12u * 4u + 3u * 2u * 6u * 6u * 1u + 8u * 4u * 1u + 3u * 2u * 4u * 2u * 1u);
}

// normals/0014.webp.js decoded here against Debian's dwebp on the same data URI (decoded with
// Python's base64; its PPM's first texel (127, 139, 255) and last (130, 154, 255)): the image's
// top row lands at v = 1 (the map's last row), and the mean tilt |n.xy| over the 512^2 texels
// is dwebp's 0.1276581590280 (docs/PREFILTER.md's 0.13), to the rounding of a sum in another order.
TEST(PresetAssets, PmndrsNormalMapDecodesAsDwebpDoes) {
  const std::string module = node_modules_dir() + "/@pmndrs/assets/normals/0014.webp.js";
  const auto map = decode_webp_normal_map(webp_from_data_uri_module(module), module);
  ASSERT_EQ(map->width(0), 512);
  ASSERT_EQ(map->height(0), 512);
  const Vec3 top_left = map->texel(0, 0, 511).normal, bottom_right = map->texel(0, 511, 0).normal;
  const Vec3 expected_top_left = texel_normal(127, 139, 255), expected_bottom_right = texel_normal(130, 154, 255);
  EXPECT_NEAR(top_left.x, expected_top_left.x, 1e-15);
  EXPECT_NEAR(top_left.y, expected_top_left.y, 1e-15);
  EXPECT_NEAR(bottom_right.x, expected_bottom_right.x, 1e-15);
  EXPECT_NEAR(bottom_right.y, expected_bottom_right.y, 1e-15);
  double tilt = 0.0;
  for (int y = 0; y < 512; ++y)
    for (int x = 0; x < 512; ++x) {
      const Vec3 n = map->texel(0, x, y).normal;
      tilt += std::hypot(n.x, n.y);
    }
  EXPECT_NEAR(tilt / (512.0 * 512.0), 0.1276581590280, 1e-9);

  EXPECT_THROW(decode_webp_normal_map("RIFF not a webp", "x.webp"), AssetError);
  const fs::path text = fs::temp_directory_path() / ("saagen-not-a-module-" + std::to_string(::getpid()) + ".js");
  std::ofstream(text) << "export default 'data:image/png;base64,AAAA'\n";
  try {
    webp_from_data_uri_module(text.string());
    ADD_FAILURE() << "a PNG data URI was read as WebP";
  } catch (const AssetError& error) {
    EXPECT_EQ(std::string(error.what()), text.string() + ": holds no 'data:image/webp;base64,' data URI");
  }
  fs::remove(text);
}

// "pmndrs-NNNN-lodK" puts the map on the sphere repeated so that the implicit LOD at the centre
// of a 64 x 64 image (the medium preset's asset size) is K + 0.22 (scene.hpp's nmap-sphere:
// 0.224 - 0.253 over the central eighth at 256 px, two more at a quarter of the side): the
// minification sweep's scenes. Each is an asset scene (sized as the presets size them), the
// plain name is LOD 2's tiling, and a malformed or out-of-range suffix is no map's name.
TEST(PresetAssets, APmndrsMapAtAnLodIsRepeatedToThatLodAtTheCentre) {
  const int size = 64;
  for (int lod : {0, 2, 4}) {
    const std::string name = "pmndrs-0014-lod" + std::to_string(lod);
    const std::optional<PresetAsset> asset = pmndrs_map_named(name);
    ASSERT_TRUE(asset.has_value()) << name;
    EXPECT_EQ(asset->centre_lod, lod);
    const std::vector<SceneId> ids = register_preset_asset(name);
    ASSERT_EQ(ids.size(), 1u);
    EXPECT_EQ(scene_name(ids[0]), name);
    EXPECT_TRUE(is_preset_asset_scene(ids[0]));
    EXPECT_EQ(register_preset_asset(name), ids);  // the same id again
    const GBuffer g = render_gbuffer(make_scene(ids[0]), size, size, 2);
    double lo = 1e9, hi = -1e9;
    for (int y = size / 2 - 4; y < size / 2 + 4; ++y)
      for (int x = size / 2 - 4; x < size / 2 + 4; ++x) {
        lo = std::min(lo, g.at(x, y).lod);
        hi = std::max(hi, g.at(x, y).lod);
      }
    EXPECT_GE(lo, lod + 0.22) << name;
    EXPECT_LE(hi, lod + 0.26) << name;
  }
  const std::string plain = make_scene(register_preset_asset("pmndrs-0014").at(0)).describe();
  EXPECT_NE(plain.find("tiling=(2,1)"), std::string::npos);
  EXPECT_NE(make_scene(register_preset_asset("pmndrs-0014-lod0").at(0)).describe().find("tiling=(0.5,0.25)"), std::string::npos);
  EXPECT_FALSE(pmndrs_map_named("pmndrs-0014").value().centre_lod.has_value());
  for (const char* bad :
       {"pmndrs-0014-lod", "pmndrs-0014-lod10", "pmndrs-0014-lodx", "pmndrs-0014-lo2", "pmndrs-0014lod2", "pmndrs-001-lod2"})
    EXPECT_FALSE(pmndrs_map_named(bad).has_value()) << bad;
}

class PresetAssetsCli : public saagen::test::CliTest {};

// Without @pmndrs/assets installed, the medium preset is one line naming the scene, the file
// and what to install, a non-zero exit, and no output written.
TEST_F(PresetAssetsCli, AMissingPackageIsOneLineNamingWhatToInstall) {
  const fs::path missing = scratch_ / "no-node-modules";
  ::setenv("SAAGEN_NODE_MODULES", missing.c_str(), 1);
  const fs::path json = scratch_ / "trade.json";
  const auto run = saagen({"bench", "--preset", "medium", "--json", json.string(), "--cache", (scratch_ / "cache").string()});
  ::unsetenv("SAAGEN_NODE_MODULES");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_EQ(run.err, "saagen: error: preset medium: pmndrs-0014: " + (missing / "@pmndrs/assets/normals/0014.webp.js").string() +
                         " is missing; install the npm package @pmndrs/assets as package-lock.json pins it (npm ci in the source "
                         "tree, which scripts/install-deps.sh runs; or set SAAGEN_NODE_MODULES to the node_modules holding it)\n");
  EXPECT_EQ(run.out, "");
  EXPECT_FALSE(fs::exists(json));
}
