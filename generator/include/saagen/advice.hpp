// saagen's advice, in one place: the constants saagen emits and plans with, the content types, and
// what the advice per content type rests on. The planner's one decision (saagen/decision.hpp, the
// same function the bench's verdict uses) chooses per material on the committed measurement
// (generator/data/advice.json; saagen/scene/cost_tables.hpp: committed_advice): the configuration
// that beats no SAA (under TAA: TAA alone) (most accurate, or cheapest for prefer = "speed"), or
// no filter where none does, and no filter where its choice loses on the held-out scenes. The planner's
// table-free rules (saagen/scene/planner.hpp), emit's default constants and the emitted headers'
// text about the normal (the templates' {advice:...} fields, filled in by the built-in catalogue)
// read it; examples/INTEGRATION.md quotes it and tests check the examples agree with it.
//
// The measurement: `saagen bench --preset medium --json T.json` (its built-in scenes at 128 x 128
// px and its asset scenes at 64 x 64 px: ClearCoatTest, 2CylinderEngine and the CC0 @pmndrs normal
// maps on the sphere; docs/GLTF_SCENES.md), `bash scripts/held_out.sh OUT` (the held-out scenes),
// then `python3 scripts/advice_data.py T.json OUT/held_out.json > generator/data/advice.json`.
// Under TAA the same two measurements with `--taa --sigma2 0.0625`, each configuration against
// none+taa (docs/TAA.md), passed as the script's third and fourth tables. The figures are
// measured, not written here.
#pragma once

#include <array>
#include <optional>
#include <string_view>

namespace saagen::advice {

// The pixel-filter variance and kernel clamp saagen emits and plans by default: with the
// tail-preserving filtered GGX, the pixel filter's own variance (T&K 2019's 0.25, the ground
// truth's filter) measured best (docs/FILTERED_GGX.md); kappa is T&K 2019's 0.18.
inline constexpr double kSigma2 = 0.25;
inline constexpr double kKappa = 0.18;
// Under TAA the jitter already integrates the pixel footprint, so the kernel is a quarter of the
// footprint's; with the verdict's metrics 0.0625 and 0.25 are within their intervals on most
// scenes (docs/TAA.md).
inline constexpr double kTaaSigma2 = 0.0625;

// The LOD bias, in MIP levels, at which a prefiltered material samples its normal map and the
// map's bake (the roughness map, the mean normal's length, LEAN's moments): one level coarser than
// the implicit LOD, the level whose texels span two pixels, whose box has a zero at the pixel
// grid's Nyquist frequency, so that the normal variation the grid cannot show moves from the
// shading normal into the bake instead of aliasing under the bake's wider lobe (docs/PREFILTER.md,
// "The LOD bias"; the trade's prefiltered rows are measured so: TradeConfig::prefilter_lod_bias).
// The other rows (no SAA, the engines, the filters without a bake) keep the implicit LOD.
inline constexpr int kPrefilterLodBias = 1;
// As the emitted headers and `saagen plan` state it (templates: {advice:prefilter_sampling}).
inline constexpr std::string_view kPrefilterSamplingText =
    "sample the normal map and its bake one MIP level coarser than the implicit LOD, with the sample's bias argument "
    "(GLSL and GLSL ES texture(map, uv, 1.0), HLSL SampleBias(s, uv, 1.0), WGSL textureSampleBias(map, s, uv, 1.0); "
    "docs/PREFILTER.md: The LOD bias)";
static_assert(kPrefilterLodBias == 1, "kPrefilterSamplingText states the bias as 1.0");
// The lobe GGX is shaded with: the tail-preserving filtered GGX (ggx_brdf_filtered_*).
inline constexpr std::string_view kLobe = "tail";
// As the emitted headers state it (templates: {advice:normal}).
inline constexpr std::string_view kNormalText =
    "the normal `saagen plan` names for the material (its normal line): the normal-mapped normal where the measured "
    "configuration is fed it, else the geometric (interpolated vertex) normal, whose map's detail goes into the roughness "
    "instead (`saagen texture prefilter --method hdrp`)";

enum class Content { curved, normal_mapped, bumps, clearcoat };

// The manifest's `content` values, in Content's order.
inline constexpr std::array<std::string_view, 4> kContentNames = {"curved", "normal-mapped", "bumps", "clearcoat"};
inline constexpr std::string_view name(Content content) { return kContentNames[static_cast<int>(content)]; }
inline constexpr std::optional<Content> content_named(std::string_view text) {
  for (std::size_t index = 0; index < kContentNames.size(); ++index)
    if (kContentNames[index] == text) return static_cast<Content>(index);
  return std::nullopt;
}
// The content type's name in a trade table's "by_content" rows (`saagen bench --json`; clearcoat:
// the coat lobe's scene of a KHR_materials_clearcoat asset, NAME-coat).
inline constexpr std::string_view table_content(Content content) { return content == Content::bumps ? "bump" : name(content); }

}  // namespace saagen::advice
