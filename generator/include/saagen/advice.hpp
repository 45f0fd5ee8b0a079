// saagen's advice, in one place: per content type and TAA, the figures saagen's own trade measured
// (no SAA and the configurations that decide the advice), from which the planner's one decision
// (saagen/decision.hpp, the same function the bench's verdict uses) chooses per material: the
// configuration that beats no SAA (most accurate, or cheapest for prefer = "speed"), or no filter
// where none does; and how the advice held on content it was not derived from. The planner's table-free rules
// (saagen/scene/planner.hpp), emit's default constants and the emitted headers' text about the
// normal (the templates' {advice:...} fields, filled in by the built-in catalogue) read it;
// examples/INTEGRATION.md quotes it and tests check the examples agree with it.
//
// Figures without TAA: the whole medium preset, its built-in scenes (128 x 128 px) and its asset
// scenes (64 x 64 px: Khronos's ClearCoatTest and 2CylinderEngine, the CC0 @pmndrs normal maps on
// the sphere; docs/GLTF_SCENES.md), 256-spp ground truth, 16-frame animation, six alphas, no
// Fresnel: `saagen bench --preset medium --json T.json`, the means of its "by_content" rows
// (LDR-FLIP / TDE) printed by `python3 scripts/advice_figures.py T.json`, per scene by
// `python3 scripts/beats_baselines.py T.json any`; clearcoat: the coat lobe of ClearCoatTest (its
// scene ClearCoatTest-coat, the trade's "clearcoat" rows). Under TAA: `saagen bench --preset medium
// --taa --sigma2 0.0625` (docs/TAA.md).
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
    "the geometric (interpolated vertex) normal, also on a normal-mapped material filtered anyway (saagen's advice for "
    "normal-mapped content is no filter; `saagen plan` says why), whose map's detail goes into the roughness instead "
    "(`saagen texture prefilter --method hdrp`)";

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

// A measured configuration, as `saagen bench` names it: VARIANT[:FEED][+PREFILTER][/LOBE].
struct Figure {
  std::string_view configuration;
  double flip = 0.0;  // LDR-FLIP
  double tde = 0.0;   // temporal difference error
};

// How the advice held on content it was not derived from (held-out assets): measured there and
// held, measured there and did not hold, or not measured there.
enum class HeldOut { not_measured, held, did_not_hold };

struct ContentAdvice {
  Content content;
  bool taa;
  // The measured configurations the decision chooses among, with the lobe the planner shades GGX
  // with: those that beat no SAA and those that lose where they decide a path's advice (the
  // cheaper deferred form on curved content, so that prefer = "speed" sees it lose), lowest
  // LDR-FLIP first.
  std::array<Figure, 5> measured;
  Figure none;                // no SAA (zero figures under TAA and for clearcoat: see evidence)
  std::string_view evidence;  // what was measured, and what no filter gives up where it wins
  // Where no configuration wins but a material that names its variant is still planned with an
  // advised feed (normal-mapped: the geometric normal and the hdrp bake, kFeed and kPrefilter):
  // that feed's lowest-LDR-FLIP configuration on the content's mean; empty elsewhere.
  Figure named = {};
  HeldOut held_out = HeldOut::not_measured;
  std::string_view held_out_evidence = {};  // what was measured on held-out content
};

inline constexpr std::array<ContentAdvice, 8> kTable = {{
    {Content::curved,
     false,
     {{{"forward-aniso-projected/tail", 0.0253, 0.01184},
       {"deferred-aniso/tail", 0.0259, 0.01187},
       {"forward-axis-projected/tail", 0.0280, 0.01195},
       {"deferred-avg/tail", 0.0497, 0.01553}}},
     {"none", 0.0308, 0.01436},
     "sphere, torus, tubes, torus knot, 2CylinderEngine; saagen bench --preset medium; the isotropic deferred kernels lose "
     "to no SAA there (deferred-avg/tail 0.0497 / 0.01553)",
     {},
     HeldOut::did_not_hold,
     "on three curved, textured models of Debian's assimp-testmodels that the advice was not derived from (converted to glTF "
     "with assimp; saagen bench --preset medium --scene ASSET.glb) every SAA configuration raised TDE over no SAA, the advised "
     "ones included (forward-aniso-projected/tail +18 % to +47 %, deferred-aniso/tail +3 % to +20 %), while the image metrics "
     "fell"},
    {Content::normal_mapped,
     false,
     {{{"deferred-aniso/tail", 0.0553, 0.01654},
       {"deferred-aniso:geometric+hdrp/tail", 0.0577, 0.01585},
       {"deferred-sum:geometric+hdrp/tail", 0.0604, 0.01607}}},
     {"none", 0.0605, 0.01458},
     "nmap-sphere, nmap-sphere-fine, the base lobe of ClearCoatTest and the CC0 @pmndrs maps 0014, 0019 and 0010 on the "
     "sphere; saagen bench --preset medium; every configuration raises TDE over no SAA on the mean; the advised feed for a "
     "filtered normal-mapped material, the geometric normal with HDRP's bake of the map into the roughness sampled one MIP "
     "level coarser, lowers LDR-FLIP and raises TDE (deferred-aniso:geometric+hdrp/tail 0.0577 / 0.01585, "
     "deferred-sum:geometric+hdrp/tail 0.0604 / 0.01607): it beats no SAA in both on the two built-in spheres (nmap-sphere "
     "forward-axis-projected:geometric+hdrp/tail 0.0296 / 0.00674 against 0.0390 / 0.00701, nmap-sphere-fine "
     "deferred-sum:geometric+hdrp/tail 0.0327 / 0.00767 against 0.0432 / 0.00777), lowers LDR-FLIP 1 - 6 % and raises TDE "
     "2 % on pmndrs-0019 and pmndrs-0010, and raises both on pmndrs-0014 (LDR-FLIP +50 - 56 %, TDE +18 - 21 %) and "
     "ClearCoatTest (+5 - 37 %, +30 - 36 %) (saagen bench --preset medium, its per-scene verdict); the normal-mapped normal "
     "without a bake lowers LDR-FLIP more and raises TDE more (deferred-aniso/tail 0.0553 / 0.01654); a named variant, for "
     "the LDR-FLIP gain, is fed the geometric normal with the hdrp bake and the +1 LOD bias",
     {"deferred-aniso:geometric+hdrp/tail", 0.0577, 0.01585}},
    {Content::bumps,
     false,
     {{{"forward-aniso-projected/tail", 0.2285, 0.19895}, {"deferred-max/tail", 0.3337, 0.13761}}},
     {"none", 0.3372, 0.14127},
     "bump_plane; saagen bench --preset medium; the lowest LDR-FLIP, forward-aniso-projected/tail "
     "0.2285 / 0.19895, raises TDE"},
    {Content::clearcoat,
     false,
     {{{"deferred-aniso/tail", 0.0153, 0.00667}, {"forward-aniso-projected/tail", 0.0160, 0.00703}}},
     {"none", 0.0148, 0.00541},
     "ClearCoatTest-coat, the coat lobe of ClearCoatTest (docs/GLTF_SCENES.md); every configuration raises both LDR-FLIP "
     "and TDE over no SAA, the best deferred-aniso/tail 0.0153 / 0.00667 and forward-aniso-projected/tail 0.0160 / 0.00703; "
     "the base lobe under the coat is normal-mapped content"},
    {Content::curved,
     true,
     {},
     {},
     "saagen bench --preset medium --taa --sigma2 0.0625 (docs/TAA.md), none+taa against the best saagen+taa, tail-preserving "
     "lobe: sphere 0.0258 / 0.00153 against forward-aniso-projected/tail 0.0255 / 0.00154, torus 0.0520 / 0.00363 against "
     "0.0505 / 0.00371, torus knot 0.0424 / 0.00385 against 0.0381 / 0.00420, tubes 0.1888 / 0.03828 against "
     "deferred-aniso/tail 0.1716 / 0.0387 (lower LDR-FLIP, higher TDE; every lobe and sigma2 measured loses in TDE)"},
    {Content::normal_mapped,
     true,
     {},
     {},
     "saagen bench --preset medium --taa (docs/TAA.md), none+taa against the best saagen+taa: nmap-sphere 0.0474 / 0.00666 "
     "against deferred-sum:geometric+hdrp/tail 0.0360 / 0.00672, nmap-sphere-fine 0.0485 / 0.00757 against 0.0364 / 0.00757 "
     "(LDR-FLIP 24 % lower, TDE 1 % higher and tied)"},
    {Content::bumps,
     true,
     {},
     {},
     "saagen bench --preset medium --taa --sigma2 0.0625 (docs/TAA.md), none+taa against the best saagen+taa: bump_plane "
     "0.4166 / 0.09168 against deferred-avg/tail 0.2643 / 0.0955 (LDR-FLIP 37 % lower, TDE 4 % higher)"},
    {Content::clearcoat,
     true,
     {},
     {},
     "not measured under TAA; without TAA no filter already wins on clearcoat (ClearCoatTest-coat none 0.0148 / 0.00541 "
     "against deferred-aniso/tail 0.0153 / 0.00667), and under TAA no filter wins on every other content type (docs/TAA.md)"},
}};

inline constexpr const ContentAdvice& lookup(Content content, bool taa) {
  for (const ContentAdvice& entry : kTable)
    if (entry.content == content && entry.taa == taa) return entry;
  return kTable[0];  // unreachable: the table has every content type with and without TAA
}

}  // namespace saagen::advice
