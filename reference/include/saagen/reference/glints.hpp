// saagen reference: the glinty BRDF of Chermain et al. 2020 with the slope correlation and the
// geometric glint anti-aliasing (GGAA) of Chermain et al. 2021, in double precision, and a
// software sampler for the dictionary texture that follows the Vulkan specification's rules for
// a 1D array image sampled with LINEAR filters, LINEAR mipmaps and MIRRORED_REPEAT addressing.
//
// Mirrors templates/glints/50-glints.saa function by function (same names without the prefix,
// same argument order; the dictionary binding comes first as a `Dictionary`). docs/GLINTS.md
// gives the equations and the texture layout.
#pragma once

#include "saagen/reference/math.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace saagen::ref::glints {

// ---------------------------------------------------------------------------------------------
// Software sampler (Vulkan spec, "Texel Filtering" and "Level-of-Detail Operation")

// A 1D array image with a mip chain, texels as doubles (RGBA). Level m has width
// max(1, width >> m); levels[m] holds layers * level_width(m) * 4 values, layer after layer.
struct Texture1DArray {
  int width = 0;
  int layers = 0;
  std::vector<std::vector<double>> levels;

  int level_count() const { return static_cast<int>(levels.size()); }
  int level_width(int level) const { return width >> level > 0 ? width >> level : 1; }
  const double* texel(int level, int layer, int x) const {
    return &levels[static_cast<std::size_t>(level)][(static_cast<std::size_t>(layer) * level_width(level) + x) * 4];
  }
};

using Texel = std::array<double, 4>;

// How the sampler turns a gradient into a level of detail lambda.
//   exact:    the specification's lambda = log2(rho_max), rho_max = max(|du/dx|, |du/dy|) * width.
//   lavapipe: what llvmpipe computes (measured, docs/GLINTS.md): lambda = 0.5 fastlog2(rho_max^2)
//             with fastlog2(2^e (1 + f)) = e + f (exact at powers of two, up to 0.043 below the
//             exact lambda in between).
enum class LodModel { exact, lavapipe };

// Vulkan MIRRORED_REPEAT of an integer texel coordinate for a level of `size` texels.
int mirrored_repeat(int i, int size);

// lambda for a 1D gradient (before clamping to the level range).
double lod_from_gradients(double du_dx, double du_dy, int width, LodModel model);

// LINEAR filtering inside one level at normalised coordinate u (mirrored repeat), layer index
// already selected.
Texel sample_level(const Texture1DArray& texture, int level, double u, int layer);

// textureLod / SampleLevel: LINEAR mipmap mode between floor(lod) and floor(lod) + 1, lod
// clamped to [0, levels - 1]; the layer is round-to-nearest-even of `layer`, clamped.
Texel texture_lod(const Texture1DArray& texture, double u, double layer, double lod);

// textureGrad / SampleGrad: lambda from the gradients (`model`), then as texture_lod.
Texel texture_grad(const Texture1DArray& texture, double u, double layer, double du_dx, double du_dy, LodModel model = LodModel::exact);

// textureLod at an integer level (what the glint snippets use, the only reads they make):
// LINEAR filtering in that level alone, level clamped to [0, levels - 1] (the sampler's clamp of
// an explicit LOD), layer as texture_lod.
Texel texture_level(const Texture1DArray& texture, double u, double layer, int level);

// What any conforming Vulkan implementation may return for a LINEAR/LINEAR/LINEAR lookup, as
// a per-channel interval [low, high] (the texture-space rules of the Vulkan 1.3 specification,
// chapter "Image Operations"):
//   - "Scale Factor Operation, Level-of-Detail Operation and Image Level(s) Selection": rho_x may
//     be approximated by any f_x with max(|m_ux|, |m_vx|, |m_wx|) <= f_x <= sqrt(2) (|m_ux| +
//     |m_vx| + |m_wx|); for a 1D image lambda is thus in [log2 rho_max, log2 rho_max + 1/2]
//     (textureGrad; textureLod takes lambda from the shader).
//   - VkPhysicalDeviceLimits::mipmapPrecisionBits: the weight of each of the two levels is
//     snapped to 2^-mipmapPrecisionBits (at least 4 bits are required: 1/16 of a level), and
//     "the LOD must be computed with mipmapPrecisionBits of accuracy" (same section), explicit
//     or from the gradients (lavapipe's fastlog2 is up to 0.043 below log2, docs/GLINTS.md).
//   - lod_accuracy: the accuracy the Vulkan conformance suite holds lambda to, which decides
//     what a conforming device is: its filtering and mipmap checks (VK-GL-CTS
//     vktTextureFilteringTests.cpp, tcuTexLookupVerifier's LodPrecision) verify with
//     lodBits = 6 and, when that fails, pass with the lower requirement lodBits = 4, lambda
//     within 2^-4 of a level. So lambda is taken within 2^-min(mipmapPrecisionBits, 4): an
//     NVIDIA H200 (mipmapPrecisionBits 8) returns the finer level alone 0.026 above an integer
//     LOD (docs/GLINTS.md), beyond 8 bits and within 4.
//   - VkPhysicalDeviceLimits::subTexelPrecisionBits: the linear filter's sub-texel position is
//     snapped to 2^-subTexelPrecisionBits of a texel (at least 4 bits).
//   - half_float_result: the image is a 16-bit float format (RGBA16F) and the filtered value may
//     be returned in that format's precision. "Numeric Representation and Computation": the
//     precision requirements "apply to computations performed in Vulkan operations outside of
//     shader execution, such as texture image specification and sampling", and "the
//     representation and/or precision of operations is implicitly limited by the specified
//     format of [...] texel data consumed by Vulkan"; "Floating-Point Format Conversions": a
//     value between two representable ones "is rounded to one or the other. The rounding mode is
//     not defined." So [low, high] becomes [the largest half <= low, the smallest half >= high]:
//     less than one ulp of the result either way (2^-10 relative for |x| >= 2^-14), and below
//     2^-24 (the smallest subnormal half) a value may come back as 0.
// The conformance suite's lower LOD precision requirement (lodBits, see above).
inline constexpr int kConformanceLodBits = 4;

struct SamplerTolerance {
  double lod_below = 0.0;          // textureGrad: lambda may be this far below log2(rho_max)
  double lod_above = 0.0;          // textureGrad: ... and this far above it
  double lod_accuracy = 0.0;       // both lookups: lambda as computed, within this of the above
  double level_weight = 0.0;       // 2^-mipmapPrecisionBits: lambda's fraction (both lookups)
  double texel_weight = 0.0;       // 2^-subTexelPrecisionBits: the texel coordinate
  bool half_float_result = false;  // the result may be rounded either way to a 16-bit float
};

// The half-precision (IEEE 754 binary16) neighbours of x: the largest half <= x and the smallest
// half >= x (subnormals included; |x| below 65504).
double half_at_or_below(double x);
double half_at_or_above(double x);

// The device's freedom from its limits: lod_accuracy 2^-min(mipmapPrecisionBits,
// kConformanceLodBits), level_weight 2^-mipmapPrecisionBits, texel_weight
// 2^-subTexelPrecisionBits, lod_below 0, lod_above 1/2.
SamplerTolerance vulkan_sampler_tolerance(int mipmap_precision_bits, int sub_texel_precision_bits);

struct TexelRange {
  Texel low{}, high{};
};
TexelRange texture_lod_range(const Texture1DArray& texture, double u, double layer, double lod, const SamplerTolerance& tolerance);
// The same for texture_level: an explicit integer LOD with no bias is lambda exactly ("Level-of-
// Detail Operation": lambda' = lambda_base + bias), and "Image Level(s) Selection" takes
// delta = lambda - floor(lambda) = 0, which snapping to any mipmapPrecisionBits leaves 0: one
// level alone, whatever the device's LOD accuracy. Only texel_weight and half_float_result of
// `tolerance` apply (lod_*, level_weight do not).
TexelRange texture_level_range(const Texture1DArray& texture, double u, double layer, int level, const SamplerTolerance& tolerance);
TexelRange texture_grad_range(const Texture1DArray& texture, double u, double layer, double du_dx, double du_dy,
                              const SamplerTolerance& tolerance);

// ---------------------------------------------------------------------------------------------
// The glinty BRDF

// The emission-time options the snippet is emitted with (templates/glints/50-glints.saa).
struct Params {
  int count = 192;              // N distributions (a multiple of 4)
  int lods = 16;                // L LODs
  int resolution = 64;          // R: the texture's level-0 width, which the GGAA lookup's LOD assumes
  double alpha_dict = 0.5;      // Beckmann roughness of the dictionary (sigma_o = alpha / sqrt(2))
  double kernel_scale = 0.5;    // s_K (2021 Eq. 19)
  double max_anisotropy = 8.0;  // largest major / minor axis ratio of the footprint (2020 Alg. 1)
  double relative_area = 1.0;   // probability that a cell holds microfacets (2020 Alg. 3)
  // Level-coherent seeds (2020 Eq. 8), as the templates. false: the seed mixes the level in
  // (each level draws independently), only to measure what coherence buys under a zoom.
  bool coherent_seeds = true;
};

// The dictionary as the shader sees it: its texture (RGBA, 4 distributions per texel; layer =
// lod * count / 4 + d / 4, channel d % 4) and the options. Every lookup reads integer levels
// (texture_level): the GGAA lookup computes its LOD as the shader does.
struct Dictionary {
  const Texture1DArray* texture = nullptr;
  Params params;
  // With a tolerance and side = -1 (+1), every dictionary lookup returns the low (high) end of
  // what a conforming sampler may return (texture_*_range): the glint functions are sums of
  // non-negative weights times products of non-negative lookups, so they bound the device.
  const SamplerTolerance* tolerance = nullptr;
  int side = 0;
  // The precision the Vulkan specification grants the shader's transcendentals (section
  // "Precision and Operation of SPIR-V Instructions"), applied at the end of the allowance given
  // by the sign (-1, 0 = exact, +1); the tests take the change of the result as part of their
  // bound. log2_side: the footprint LOD's log2(|minor axis|) and the GGAA lookup's
  // log2(rho_max) off by 3 ulp of the result outside [0.5, 2] (at most 3 2^-23 |log2 x|), by
  // 2^-21 absolute inside. exp2_side: the cell
  // scale exp2(x), x = log_density / (2 ln 2) - level, and the EWA weights exp(x), x = -2 r^2,
  // off by (3 + 2|x|) ulp, i.e. by a factor 1 +- (3 + 2|x|) 2^-23.
  int log2_side = 0;
  int exp2_side = 0;
  // trig_side: each cell's rotation (cos theta, sin theta) off by the spec's 2^-11 absolute
  // error of cos and sin in [-pi, pi] (where the shader's theta lies), plus the fp32
  // rounding of the angle (< 2^-20): every cell's product of lookups is taken at the
  // low (-1) or high (+1) end over the four corners of that box (kTrigAllowance).
  int trig_side = 0;
};

// The absolute error the Vulkan spec allows cos and sin in [-pi, pi] (2^-11), plus the rounding
// of the angle 2 pi turn in fp32 (at most two roundings of 2^-24 2 pi each).
inline constexpr double kTrigAllowance = 0x1.0p-11 + 0x1.0p-20;

// x_max = 2 sqrt(2) alpha_dict: the dictionary holds |x| < x_max (4 sigma_o).
double dictionary_range(const Params& params);

// Roughness of Eq. 18: Beckmann (alpha_x, alpha_y) and the slope correlation rho.
struct Roughness {
  double alpha_x = 0.1;
  double alpha_y = 0.1;
  double rho = 0.0;
};

// The 32-bit integer mixer shared with the templates (wrapping arithmetic).
std::int32_t mix(std::int32_t v);

// The seed of cell (i, j) at level l: that of its corner child (i 2^l, j 2^l) at level 0, so a
// cell shares distributions, rotation and LOD offset with that child (2020 Eq. 8, Alg. 3).
std::int32_t cell_seed(int i, int j, int level, bool coherent = true);

// The random choices of cell (i, j) at level l: distributions d_x, d_y in [0, count) and the
// rotation as a fraction of a turn, (turn - 2^14) / 2^15 in [-1/2, 1/2) (exact in fp32).
struct CellRandom {
  int dx = 0;
  int dy = 0;
  double turn = 0.0;
};
CellRandom cell_random(int i, int j, int level, int count, bool coherent = true);

// round(zeta N(0, 1)), zeta = 2, for a uniform 15-bit integer u, by inverse CDF: the number of
// thresholds round(32768 Phi((k + 1/2) / zeta)), k = -8..7, that u reaches, minus 8 (2020 Alg. 3).
int zeta_offset(int u);
// The thresholds themselves (computed here from erfc; the templates spell them as literals).
std::array<int, 16> zeta_thresholds();

// The dictionary LOD of cell (i, j) at level l: clamp(l + zeta_offset, 0, L - 1), or -1 when the
// cell is empty (probability 1 - relative_area) (2020 Alg. 3 lines 3-9).
int cell_dictionary_lod(const Params& params, int i, int j, int level);

// A^-1 v (Eq. 18 without the rotation) and det M = det A.
Vec2 inverse_transform(const Params& params, Vec2 v, const Roughness& roughness);
double transform_determinant(const Params& params, const Roughness& roughness);

// The footprint ellipse's axes in uv: the longer derivative is the major axis, the other is
// lengthened to at least major / max_anisotropy (2020 Alg. 1 lines 3-5).
struct FootprintAxes {
  Vec2 major;
  Vec2 minor;
};
FootprintAxes footprint_axes(const Params& params, Vec2 duv_dx, Vec2 duv_dy);

// l_P = clamp(log2(|minor|) + log_density / (2 ln 2), 0, L - 1) (2020 Alg. 1 line 6).
double footprint_lod(const Params& params, Vec2 duv_dx, Vec2 duv_dy, double log_density);

// One 1D distribution at x, 0 for |x| >= x_max: at MIP level 0 / filtered over the kernel-scaled
// derivatives of x: lambda = log2(max(|du/dx|, |du/dy|) R) clamped to [0, 12] (textureGrad's
// exact rule for a 1D image, computed by the shader), the levels floor(lambda) and
// floor(lambda) + 1 read with texture_level and blended with weight lambda - floor(lambda).
double dictionary_lod_value(const Dictionary& dictionary, double x, int distribution, int level);
double dictionary_grad_value(const Dictionary& dictionary, double x, double dx_dx, double dx_dy, int distribution, int level);

// The footprint's cells: for each of the two levels of Eq. 3 the cells under the footprint
// ellipse, their weights (w(l) W_P(l, s) / sum_s W_P(l, s), EWA) and random choices; empty cells
// (relative area) are left out but count in the normalisation. Depends only on uv, the footprint
// and the density.
struct PatchCell {
  double weight = 0.0;
  int level = 0;          // the dictionary LOD the cell reads (after zeta)
  int spatial_level = 0;  // the level of the cell grid
  int i = 0, j = 0;       // the cell at that level
  CellRandom random;
  double cos_theta = 1.0;
  double sin_theta = 0.0;
};
struct Patch {
  std::vector<PatchCell> cells;
  double lod = 0.0;  // l_P
};
Patch make_patch(const Dictionary& dictionary, Vec2 uv, Vec2 duv_dx, Vec2 duv_dy, double log_density);

// The patch SDF of Eq. 3 (textureLod) and its GGAA-filtered form (Eqs. 10, 19); the
// derivatives dh_* are those of the projected half vector (Eq. 21) or of the slope (Eq. 20).
double patch_sdf(const Dictionary& dictionary, const Patch& patch, Vec2 slope, const Roughness& roughness);
double patch_sdf_filtered(const Dictionary& dictionary, const Patch& patch, Vec2 slope, Vec2 dh_dx, Vec2 dh_dy, const Roughness& roughness);

double sdf(const Dictionary& dictionary, Vec2 slope, Vec2 uv, Vec2 duv_dx, Vec2 duv_dy, const Roughness& roughness, double log_density);
double sdf_filtered(const Dictionary& dictionary, Vec2 slope, Vec2 dh_dx, Vec2 dh_dy, Vec2 uv, Vec2 duv_dx, Vec2 duv_dy,
                    const Roughness& roughness, double log_density);

// V-cavity masking-shadowing: min(1, 2 h.z o.z / o.h, 2 h.z i.z / i.h); 0 below the horizon.
double vcavity_g2(Vec3 i, Vec3 o, Vec3 h);

// The BRDF f(i, o) = G2 D / (4 i.z o.z), D = P22(h~ - mean_slope) / h.z^4, without Fresnel.
double brdf(const Dictionary& dictionary, Vec3 i, Vec3 o, Vec2 mean_slope, Vec2 uv, Vec2 duv_dx, Vec2 duv_dy, const Roughness& roughness,
            double log_density);
double brdf_filtered(const Dictionary& dictionary, Vec3 i, Vec3 o, Vec2 mean_slope, Vec2 dh_dx, Vec2 dh_dy, Vec2 uv, Vec2 duv_dx,
                     Vec2 duv_dy, const Roughness& roughness, double log_density);
// The same with a precomputed patch (ground-truth renderers evaluate many directions per patch).
double patch_brdf(const Dictionary& dictionary, const Patch& patch, Vec3 i, Vec3 o, Vec2 mean_slope, const Roughness& roughness);
double patch_brdf_filtered(const Dictionary& dictionary, const Patch& patch, Vec3 i, Vec3 o, Vec2 mean_slope, Vec2 dh_dx, Vec2 dh_dy,
                           const Roughness& roughness);

// Half-vector slope h~ = -h.xy / h.z (h.z clamped to 1e-4, SLOPE_MIN_Z) of normalize(i + o).
Vec2 half_slope(Vec3 i, Vec3 o);

// LEAN (Olano & Baker 2010; 2021 Sec. 5.2): the roughness (sqrt(2 Sigma_xx), sqrt(2 Sigma_yy),
// rho) of Sigma = second - mean mean^T + diag(alpha^2) / 2. second = (E[x^2], E[xy], E[y^2]).
Roughness lean_roughness(Vec2 alpha, Vec2 mean, Sym2 second);

}  // namespace saagen::ref::glints
