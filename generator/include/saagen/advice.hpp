// saagen's advice, in one place: the constants saagen emits and plans with, the content types, and
// what the advice per content type rests on. The planner's one decision (saagen/decision.hpp, the
// same function the bench's verdict uses) chooses per material on the committed measurement
// (generator/data/advice.json; saagen/scene/cost_tables.hpp: committed_advice): the configuration
// that beats no SAA (most accurate, or cheapest for prefer = "speed"), or no filter where none
// does, and no filter where its choice loses to no SAA on the held-out scenes. The planner's
// table-free rules (saagen/scene/planner.hpp), emit's default constants and the emitted headers'
// text about the normal (the templates' {advice:...} fields, filled in by the built-in catalogue)
// read it; examples/INTEGRATION.md quotes it and tests check the examples agree with it.
//
// The measurement: `saagen bench --preset medium --json T.json` (its built-in scenes at 128 x 128
// px and its asset scenes at 64 x 64 px: ClearCoatTest, 2CylinderEngine and the CC0 @pmndrs normal
// maps on the sphere; docs/GLTF_SCENES.md), `bash scripts/held_out.sh OUT` (the held-out scenes),
// then `python3 scripts/advice_data.py T.json OUT/held_out.json > generator/data/advice.json`.
// Under TAA: `saagen bench --preset medium --taa --sigma2 0.0625` (docs/TAA.md).
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
// Under TAA the jitter already integrates the pixel footprint: the best saagen configuration
// improves as sigma^2 falls from 0.25 to 0.0625 on every scene (docs/TAA.md).
inline constexpr double kTaaSigma2 = 0.0625;

// The normal the kernels measure, and what to do with a normal map's detail instead.
inline constexpr std::string_view kFeed = "geometric";
inline constexpr std::string_view kPrefilter = "hdrp";
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

// What the advice per content type rests on. Without TAA the figures are measured, not written
// here: generator/data/advice.json holds every configuration's comparison with no SAA (image and
// flicker error, 95 % intervals) on the scenes the advice is derived from (`saagen bench --preset
// medium`) and on held-out scenes it is only reported on (scripts/held_out.sh), written by
// scripts/advice_data.py and read by the planner (saagen/scene/cost_tables.hpp: committed_advice).
// Under TAA the evidence below is the TAA trade's, measured before the validated criterion, and
// the table-free advice there is no filter.
struct ContentAdvice {
  Content content;
  bool taa;
  std::string_view evidence;
};

inline constexpr std::array<ContentAdvice, 8> kTable = {{
    {Content::curved, false, "generator/data/advice.json"},
    {Content::normal_mapped, false, "generator/data/advice.json"},
    {Content::bumps, false, "generator/data/advice.json"},
    {Content::clearcoat, false, "generator/data/advice.json"},
    {Content::curved, true,
     "saagen bench --preset medium --taa --sigma2 0.0625 (docs/TAA.md), none+taa against the best saagen+taa, tail-preserving "
     "lobe: sphere 0.0258 / 0.00153 against forward-aniso-projected/tail 0.0255 / 0.00154, torus 0.0520 / 0.00363 against "
     "0.0505 / 0.00371, torus knot 0.0424 / 0.00385 against 0.0381 / 0.00420, tubes 0.1888 / 0.03828 against "
     "deferred-aniso/tail 0.1716 / 0.0387 (lower LDR-FLIP, higher TDE; every lobe and sigma2 measured loses in TDE)"},
    {Content::normal_mapped, true,
     "saagen bench --preset medium --taa (docs/TAA.md), none+taa against the best saagen+taa: nmap-sphere 0.0474 / 0.00666 "
     "against deferred-sum:geometric+hdrp/tail 0.0360 / 0.00672, nmap-sphere-fine 0.0485 / 0.00757 against 0.0364 / 0.00757 "
     "(LDR-FLIP 24 % lower, TDE 1 % higher and tied)"},
    {Content::bumps, true,
     "saagen bench --preset medium --taa --sigma2 0.0625 (docs/TAA.md), none+taa against the best saagen+taa: bump_plane "
     "0.4166 / 0.09168 against deferred-avg/tail 0.2643 / 0.0955 (LDR-FLIP 37 % lower, TDE 4 % higher)"},
    {Content::clearcoat, true,
     "not measured under TAA; without TAA no filter already wins on clearcoat (ClearCoatTest-coat none 0.0148 / 0.00541 "
     "against deferred-aniso/tail 0.0153 / 0.00667), and under TAA no filter wins on every other content type (docs/TAA.md)"},
}};

inline constexpr const ContentAdvice& lookup(Content content, bool taa) {
  for (const ContentAdvice& entry : kTable)
    if (entry.content == content && entry.taa == taa) return entry;
  return kTable[0];  // unreachable: the table has every content type with and without TAA
}

}  // namespace saagen::advice
