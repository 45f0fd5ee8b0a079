// The bench presets (`saagen bench --preset`): the trade configuration of each, and the asset
// scenes the medium and full presets add.
#pragma once

#include "saagen/measure/trade.hpp"

#include <string_view>

namespace saagen::report {

// The preset configurations: "full" (256 x 256, 1024 spp, 32 flicker frames, every scene, alpha
// and Fresnel mode) and "quick" (64 x 64, 64 spp, 4 frames; for smoke tests).
measure::TradeConfig preset_config(std::string_view preset);

// The medium and full presets' scenes of content nobody here authored (measure/assets.hpp:
// ClearCoatTest and its coat, 2CylinderEngine, three @pmndrs/assets normal maps on the sphere;
// the medium preset also those maps' minification sweep, measure::minification_sweep_scenes, whose
// LODs hold at its 64 px asset size): registers them and appends them to config.scenes, then
// size_preset_assets; nothing for the quick preset. Error (one line: the scene, the missing file, what to install) when a package
// is missing, before anything is loaded.
void add_preset_assets(std::string_view preset, measure::TradeConfig& config);
// The sizes the preset measures its asset scenes at (TradeConfig::scene_sizes), for those in
// config.scenes: the medium preset 64 x 64, the full preset 128 x 128 (a quarter of the preset's
// pixels, so that six more scenes keep the presets' run times) at the preset's samples per pixel;
// the animation never below 64 x 64 px and 256 spp, where the sanity suite ranks a one-frame delay
// below another ground-truth seed on every asset scene (docs/GLTF_SCENES.md). Every glTF scene (the
// presets' and any given with --scene, at the preset's sizes) takes its ground truths, image and
// animation, at 4096 spp at least: its smooth highlights are smaller than a pixel, and at alpha
// 0.0025 the verdict turns with the ground truth's samples up to there (docs/TEMPORAL.md, "A
// ground truth that has not converged").
void size_preset_assets(std::string_view preset, measure::TradeConfig& config);

}  // namespace saagen::report
