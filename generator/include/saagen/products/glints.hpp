// Glints: the dictionary of multi-scale 1D slope distributions of Chermain et al. 2020
// with its MIP chains (Chermain et al. 2021), a KTX2 writer and reader for it, LEAN moment MIP
// chains of normal maps, and the emission of the glint snippets (templates/glints/). The math
// and the file layouts are in docs/GLINTS.md.
#pragma once

#include "saagen/emit/emitter.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/io/ktx2.hpp"

#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace saagen::glints {

// ---------------------------------------------------------------------------------------------
// Dictionary

// Caps on a dictionary's generation work (lobes drawn) and size (values held, 8 bytes each):
// about 5x and 170x the defaults, so that a mistyped option fails at once instead of running for minutes.
inline constexpr std::uint64_t dictionary_lobe_limit = std::uint64_t{1} << 24;
inline constexpr std::uint64_t dictionary_value_limit = std::uint64_t{1} << 25;

struct DictionaryParams {
  int count = 192;           // N distributions; a multiple of 4 (four per RGBA16F texel)
  int lods = 16;             // L LODs; LOD k < L - 1 mixes 2^k lobes, LOD L - 1 is the Beckmann marginal
  int resolution = 64;       // R texels per single-scale distribution (a power of two), over x in [0, x_max)
  double alpha = 0.5;        // alpha_dict: Beckmann roughness of the last LOD (sigma_o = alpha / sqrt(2))
  double lobe_sigma = 0.02;  // standard deviation of each lobe
  std::uint64_t seed = 2021;

  // Throws saagen::Error naming the parameter and its allowed values.
  void validate() const;
  double sigma() const;  // sigma_o = alpha / sqrt(2)
  double range() const;  // x_max = 4 sigma_o = 2 sqrt(2) alpha
  // The standard deviation the lobes are stored with, sqrt(max(lobe_sigma^2 - dx^2 / 4, 0)),
  // dx = x_max / R: the texel mean and the sampler's linear interpolation add dx^2 / 4 to a
  // lobe's variance, so the texture reads back lobes of lobe_sigma.
  double stored_lobe_sigma() const;
};

// The distributions in double precision: density(lod, d, texel) is the mean of P_o(x; d, lod)
// over texel [texel, texel + 1) * x_max / R (x >= 0; the distributions are even), its lobes of
// standard deviation stored_lobe_sigma() below the last LOD, normalised so that
// 2 sum_texel density * x_max / R = 1.
struct Dictionary {
  DictionaryParams params;
  std::vector<double> values;  // [(lod * count + d) * resolution + texel]

  double density(int lod, int distribution, int texel) const {
    return values[(static_cast<std::size_t>(lod) * params.count + distribution) * params.resolution + texel];
  }
};

// Deterministic for a given seed (SplitMix64 streams, Box-Muller; see docs/GLINTS.md).
Dictionary generate_dictionary(const DictionaryParams& params);

// The texture engines load: a 1D array image, RGBA16F (VK_FORMAT_R16G16B16A16_SFLOAT), width R,
// layers L * N / 4 (layer = lod * N / 4 + d / 4, channel d % 4), with the full MIP chain
// (level m + 1 = mean of texel pairs of level m) or level 0 only. levels[m] holds the half bits,
// layer after layer, 4 per texel (the KTX2 and Vulkan upload layout).
struct DictionaryTexture {
  std::uint32_t width = 0;
  std::uint32_t layers = 0;
  std::vector<std::vector<std::uint16_t>> levels;
};

DictionaryTexture dictionary_texture(const Dictionary& dictionary, bool mips = true);

// The texture's level data in double precision before rounding to half (same layout, 4 values
// per texel), for tests that separate the MIP filter from the half rounding.
std::vector<std::vector<double>> dictionary_levels(const Dictionary& dictionary, bool mips = true);

// Bytes of texel data (all levels).
std::size_t texture_bytes(const DictionaryTexture& texture);

// IEEE half precision (round to nearest even) and back.
std::uint16_t to_half(double value);
double from_half(std::uint16_t bits);

// The dictionary texture as KTX2 (key "saagen.glints" holds its parameters as JSON).
Ktx2Image dictionary_ktx2(const DictionaryTexture& texture, const DictionaryParams& params);

// ---------------------------------------------------------------------------------------------
// LEAN moment MIP chains (Olano and Baker 2010; Chermain et al. 2021 Sec. 5.2)

// A tangent-space normal map as slopes (-n.x / n.z, -n.y / n.z), 2 per texel, row-major.
struct SlopeMap {
  int width = 0;
  int height = 0;
  std::vector<double> slopes;
};

// Slopes of unit tangent-space normals (3 per texel, n.z > 0).
SlopeMap slopes_from_normals(int width, int height, std::span<const double> normals);
// The largest normal map LEAN chains are computed for (memory grows ~170 bytes per texel).
inline constexpr std::uint64_t lean_texel_limit = 2048 * 2048;
// An 8-bit RGB normal map (n = 2 c / 255 - 1) from a binary PPM (P6) file's bytes. The header's
// numbers are strict decimals; throws saagen::Error on a malformed, truncated or too large map.
SlopeMap slopes_from_ppm(std::span<const std::uint8_t> bytes);

// Level m holds, per texel, (E[x], E[y], E[x^2], E[xy], E[y^2]) over the texels of level 0 it
// covers (2x2 box filter per level, down to 1x1; odd sizes repeat the last row/column).
struct MomentLevel {
  int width = 0;
  int height = 0;
  std::vector<double> moments;  // 5 per texel
};
std::vector<MomentLevel> lean_moments(const SlopeMap& map);

// As KTX2: a 2D array image, R32G32B32A32_SFLOAT, 2 layers: layer 0 = (E[x], E[y], E[x^2],
// E[y^2]), layer 1 = (E[xy], 0, 0, 0), with the MIP chain.
Ktx2Image lean_ktx2(const std::vector<MomentLevel>& levels);

// ---------------------------------------------------------------------------------------------
// Emission

// The catalogue of the glint snippets: templates/*.saa (shared helpers and constants) followed
// by templates/glints/*.saa. Variants "glints" (textureLod baseline) and "glints-ggaa".
const Catalogue& catalogue();

// The default dictionary (generate_dictionary({}) with its MIP chain) as KTX2 bytes: what a scene
// bundle with glints = true ships next to its shader files.
std::vector<std::uint8_t> default_dictionary_ktx2();
// The dictionary that matches emission options (glint_count, glint_lods, glint_resolution and
// glint_alpha of the glint catalogue; the defaults where absent), with its MIP chain, as KTX2 bytes.
std::vector<std::uint8_t> dictionary_ktx2_for(const std::map<std::string, double>& option_values);

// emit_variants over catalogue(); options.variants empty means both glint variants. Option
// names: glint_count, glint_lods, glint_resolution, glint_alpha, glint_kernel_scale (and
// sigma2/kappa, unused). Throws saagen::Error when glint_count is not a multiple of 4 or
// glint_resolution not a power of two.
std::vector<EmittedFile> emit(const EmitOptions& options);

}  // namespace saagen::glints
