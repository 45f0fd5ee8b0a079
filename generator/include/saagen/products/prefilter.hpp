// Normal-map prefiltering (`saagen texture prefilter`): the MIP chain of a tangent-space normal map
// turned into the texture-space roughness of Kaplanyan et al. 2016 Sec. 4, as KTX2.
//
//   toksvig  one channel (R16_SFLOAT, or R32_SFLOAT): per texel of every level, the base roughness
//            combined with Toksvig's variance sigma^2 = (1 - L) / L of the texel's mean-normal
//            length L (Toksvig 2005): alpha'^2 = saturate(alpha^2 + 2 sigma^2), written in the
//            requested domain. Engines sample it in place of their roughness map.
//   unreal, filament-vmf, hdrp
//            the three engines' offline bakes of the same length L, one roughness channel each
//            like toksvig (formulas at engine_alpha2 below): Unreal's composite texture,
//            Filament's roughness-prefilter tool (vMF fit), HDRP's normal-map filtering (vMF fit).
//   --gltf   (any roughness method) R8G8B8A8_UNORM in glTF 2.0's metallicRoughnessTexture layout:
//            G = perceptual roughness (alpha = r^2), B = metallic (--metallic), R = A = 1 (R is
//            occlusion where a pipeline packs occlusion-roughness-metallic together; 1 = none).
//            Linear transfer, as glTF requires of metallicRoughnessTexture.
//   lean     the LEAN slope moments (Olano & Baker 2010) in the layout of glints::lean_ktx2:
//            R32G32B32A32_SFLOAT, a 2-layer array, layer 0 = (E[x], E[y], E[x^2], E[y^2]),
//            layer 1 = (E[xy], 0, 0, 0), s = -n.xy / n.z. The shader forms the covariance
//            (saa_lean_covariance) and the roughness (saa_prefilter_lean*).
// The levels are box reductions of level 0, as measure/normal_map.hpp defines them.
// The key "saagen.prefilter" holds the layout as JSON. docs: docs/GUIDE.md "Normal-map prefiltering".
#pragma once

#include "saagen/domain.hpp"
#include "saagen/products/glints.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace saagen::prefilter {

enum class Method { toksvig, lean, unreal, filament_vmf, hdrp };
// Every method but lean writes one roughness per texel.
bool writes_roughness(Method method);
// The roughness domains are saagen::Domain (saagen/domain.hpp), one definition for emission and
// textures: text names one through find_domain (saagen/emit/engines.hpp).

// Throws saagen::Error naming the allowed values.
Method parse_method(std::string_view text);
std::string_view to_string(Method method);

// alpha^2 to the domain's value and back (inverse of each other on [0, 1]).
double from_alpha2(double alpha2, Domain domain);
double to_alpha2(double value, Domain domain);

// Level 0 of a tangent-space normal map: unit normals with z > 0, 3 per texel, row-major.
struct NormalImage {
  int width = 0;
  int height = 0;
  std::vector<double> normals;
};

// From encoded channels in [0, 1] (n = 2 c - 1), `channels` >= 3 per texel (extra ones ignored),
// or, with `encoded` false, from signed components. Each texel is normalised; throws
// saagen::Error (naming `what`) when the sizes are not powers of two or a texel is not a
// tangent-space normal (z <= 0 or length outside [0.8, 1.2]).
NormalImage normals_from_channels(int width, int height, int channels, std::span<const double> values, bool encoded,
                                  const std::string& what);
// The largest normal map read: at most this many texels a side and in all (4096 x 4096), checked
// from the PNG or KTX2 header before anything is decoded or allocated.
inline constexpr int max_normal_map_side = 8192;
inline constexpr long long max_normal_map_texels = 4096LL * 4096LL;

// A PNG (8 or 16 bits, RGB or RGBA) or KTX2 (R8G8B8A8_UNORM encoded as above; R16G16B16A16_SFLOAT
// or R32G32B32A32_SFLOAT holding signed components) file's bytes; level 0 is used.
NormalImage read_normal_map(std::span<const std::uint8_t> bytes, const std::string& what);

// The normal map of `saagen glints lean`: what read_normal_map reads (PNG, KTX2), or a binary PPM
// (P6, 8 bits), as slopes; at most glints::lean_texel_limit texels. Throws saagen::Error naming
// `what`.
glints::SlopeMap read_lean_slopes(std::span<const std::uint8_t> bytes, const std::string& what);

// One level: per texel the mean of the level-0 unit normals (3 values), of their slopes
// s = -n.xy / n.z (2) and of s s^T as (xx, xy, yy) (3). A non-square map halves its longer side alone.
struct Level {
  int width = 0;
  int height = 0;
  std::vector<double> mean_normal;
  std::vector<double> slope_mean;
  std::vector<double> slope_second;
};
std::vector<Level> build_levels(const NormalImage& image);

// Toksvig 2005 with alpha^2 = 2 sigma^2: saturate(alpha^2 + 2 max((1 - L) / max(L, 1e-30), 0)).
double toksvig_alpha2(double base_alpha2, double mean_length);

// vMF concentration fitted to the mean length (Banerjee et al. 2005; Han et al. 2007 Sec. 4):
// kappa = (3L - L^3) / (1 - L^2), +infinity for L >= 1.
double vmf_kappa(double mean_length);

// The engines' bakes (read from their sources, 2026-11; docs/PREFILTER.md), alpha^2 in and out:
//   unreal        Unreal's composite texture (TextureCompressorModule.cpp ApplyCompositeTexture):
//                 V = max((1 - L) / L - 4e-5, 0) (Toksvig, CompositePower 1), B = 2 V (a - 1),
//                 a' = (B - a) / (B - 1) = (a + 2V(1 - a)) / (1 + 2V(1 - a)): T&K 2021's
//                 projected-space addition of 2V.
//   filament-vmf  Filament tools/roughness-prefilter solveVMF (Karis 2018, "Normal map filtering
//                 using vMF (part 3)"): a' = a + 2 / kappa.
//   hdrp          Unity HDRP CommonMaterial.hlsl TextureNormalVariance + NormalFiltering, variance
//                 stored by NormalMapFilteringTexturePostprocessor.cs capped at 0.03125:
//                 a' = a + min(2 min(1 / (4 kappa), 0.03125), 0.25^2) = a + min(1 / (2 kappa), 0.0625).
// toksvig is toksvig_alpha2. All saturate to [0, 1]. Throws for lean.
double method_alpha2(Method method, double base_alpha2, double mean_length);

struct Options {
  Method method = Method::toksvig;
  Domain domain = Domain::perceptual;
  double roughness = 0.0;  // base roughness, in `domain`, in [0, 1]
  bool float32 = false;    // roughness methods: R32_SFLOAT instead of R16_SFLOAT
  // Roughness methods: the bake's addition to alpha^2 times this, a' = a + scale (bake(a) - a),
  // saturated (1: as published; `saagen bench --prefilter-scale` measures the same scale).
  double scale = 1.0;
  bool gltf = false;      // roughness methods: glTF metallicRoughness layout (top of this file), output perceptual
  double metallic = 0.0;  // --gltf: the B channel, in [0, 1]
  void validate() const;  // throws saagen::Error
};

// The KTX2 image with the full MIP chain and the "saagen.prefilter" JSON (and a saagen marker,
// so that `saagen` may later replace the file without --force).
Ktx2Image prefilter_ktx2(const std::vector<Level>& levels, const Options& options);

}  // namespace saagen::prefilter
