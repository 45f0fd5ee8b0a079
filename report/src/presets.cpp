// The bench presets (see presets.hpp).
#include "saagen/report/presets.hpp"

#include "saagen/error.hpp"
#include "saagen/measure/assets.hpp"
#include "saagen/measure/gltf.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <exception>
#include <string>

namespace saagen::report {

measure::TradeConfig preset_config(std::string_view preset) {
  measure::TradeConfig config;
  // Every scene: the analytic ones and the real-content ones (normal maps with MIPs, a mesh),
  // and low roughness down to perceptual 0.05 (alpha 0.0025) and 0.08 (alpha 0.0064).
  config.scenes.assign(measure::all_scenes().begin(), measure::all_scenes().end());
  config.scenes.insert(config.scenes.end(), measure::content_scenes().begin(), measure::content_scenes().end());
  config.alphas = {0.0025, 0.0064, 0.01, 0.05, 0.1, 0.3};
  if (preset == "full") return config;
  if (preset == "medium") {
    // Every scene and alpha at a quarter of the pixels and samples, without Fresnel: the main
    // job's preset (about 35 minutes on 2 cores the first time, 18 with its ground truths cached;
    // docs/GUIDE.md), where the full preset takes hours.
    config.width = config.height = 128;
    config.strata = 16;
    config.flicker_width = config.flicker_height = 64;
    config.flicker_strata = 8;
    config.frames = 16;
    config.rotation_degrees_per_frame = 0.5;
    config.fresnel_modes = {false};
    return config;
  }
  if (preset == "quick") {
    config.width = config.height = 64;
    config.strata = 8;
    config.flicker_width = config.flicker_height = 32;
    config.flicker_strata = 4;
    config.frames = 4;
    config.scenes.assign(measure::all_scenes().begin(), measure::all_scenes().end());
    config.alphas = {0.01, 0.1};
    config.fresnel_modes = {false};
    return config;
  }
  throw Error(fmt::format("unknown preset '{}'; choose full, medium or quick", preset));
}

// The asset scenes' animation: never below 64 x 64 px and 256 spp (the full preset's ground truth).
constexpr int kMinAssetAnimationSize = 64;
constexpr int kMinAssetAnimationStrata = 16;

// The strata per axis of a glTF scene's ground truths at the least (64: 4096 spp). A mesh's
// highlight at alpha 0.0025 covers a small part of a pixel; with fewer samples its two seeds
// catch different parts of it, and the verdict there turned with the samples: between 64 and
// 1024 spp on the teapots, between 256 and 4096 on ClearCoatTest and 2CylinderEngine
// (docs/TEMPORAL.md). Where 4096 is still too few, the sanity suite's stable rule names the
// cell. A mesh covers few pixels, so these cost seconds; the normal-mapped spheres keep the
// preset's samples.
constexpr int kMinGltfStrata = 64;

// A glTF scene's size with its ground truths' samples raised to kMinGltfStrata.
measure::TradeSceneSize with_gltf_samples(measure::TradeSceneSize size) {
  if (!measure::gltf_asset_of(size.scene)) return size;
  size.strata = std::max(size.strata, kMinGltfStrata);
  size.flicker_strata = std::max(size.flicker_strata, kMinGltfStrata);
  return size;
}

void size_preset_assets(std::string_view preset, measure::TradeConfig& config) {
  if (preset != "medium" && preset != "full") return;
  // A large asset framed in the view has small highlights that move a fraction of a pixel per
  // frame. At 32 x 32 px they fall between the pixels, and with a 64-spp ground truth its two
  // seeds differ as much as the ground truth shown a frame late: the sanity suite could not rank
  // the delayed clip below another seed (2CylinderEngine at 32 px; ClearCoatTest's coat at 64 px
  // and 64 spp: its lag interval spanned 0). At 64 px and 256 spp every asset scene passes.
  const int width = config.width / 2, flicker_width = std::max(config.flicker_width / 2, kMinAssetAnimationSize);
  const int flicker_strata = std::max(config.flicker_strata, kMinAssetAnimationStrata);
  for (const measure::SceneId id : config.scenes) {
    if (measure::is_preset_asset_scene(id)) {
      config.scene_sizes.push_back(with_gltf_samples({id, width, width, config.strata, flicker_width, flicker_width, flicker_strata}));
    } else if (measure::gltf_asset_of(id)) {
      config.scene_sizes.push_back(with_gltf_samples(
          {id, config.width, config.height, config.strata, config.flicker_width, config.flicker_height, config.flicker_strata}));
    }
  }
}

void add_preset_assets(std::string_view preset, measure::TradeConfig& config) {
  if (preset != "medium" && preset != "full") return;
  std::vector<measure::SceneId> assets;
  try {
    assets = measure::register_preset_assets();
    if (preset == "medium")
      for (const std::string& scene : measure::minification_sweep_scenes())
        for (const measure::SceneId id : measure::register_preset_asset(scene)) assets.push_back(id);
  } catch (const measure::AssetMissing& missing) {
    throw Error(fmt::format("preset {}: {}", preset, missing.what()));
  } catch (const std::exception& bad) {  // GltfError, AssetError: "PATH: what is wrong"
    throw Error(fmt::format("preset {}: {}", preset, bad.what()));
  }
  for (const measure::SceneId id : assets)
    if (std::find(config.scenes.begin(), config.scenes.end(), id) == config.scenes.end()) config.scenes.push_back(id);
  size_preset_assets(preset, config);
}

}  // namespace saagen::report
