// Double-precision reference of templates/glints/50-glints.saa and a software Vulkan sampler for
// the dictionary texture. See saagen/reference/glints.hpp and docs/GLINTS.md.
#include "saagen/reference/glints.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace saagen::ref::glints {
namespace {

constexpr double kRangePerAlpha = 2.82842712474619;  // GLINT_RANGE_PER_ALPHA
constexpr double kRhoMax = 0.999;                    // GLINT_RHO_MAX
constexpr double kInv2Ln2 = 0.721347520444482;       // GLINT_INV_2LN2
constexpr double kTurn = 3.0517578125e-05;           // GLINT_TURN = 2^-15
constexpr double kTinyPositive = 1e-30;              // TINY_POSITIVE
constexpr double kTopLevel = 12.0;                   // GLINT_TOP_LEVEL
constexpr double kSlopeMinZ = 1e-4;                  // SLOPE_MIN_Z

// Round half to even, as the Vulkan layer selection does.
double round_half_even(double v) { return std::nearbyint(v); }

double clamp(double v, double low, double high) { return v < low ? low : (v > high ? high : v); }

}  // namespace

// ---------------------------------------------------------------------------------------------
// Sampler

int mirrored_repeat(int i, int size) {
  const int period = 2 * size;
  int t = i % period;
  if (t < 0) t += period;
  return t < size ? t : period - 1 - t;
}

double lod_from_gradients(double du_dx, double du_dy, int width, LodModel model) {
  const double rx = du_dx * width, ry = du_dy * width;
  if (model == LodModel::exact) {
    const double rho_max = std::max(std::fabs(rx), std::fabs(ry));
    return std::log2(rho_max);  // -inf for a zero gradient: clamped to level 0 by the caller
  }
  // llvmpipe: 0.5 * (exponent + mantissa fraction) of rho_max^2.
  const double rho2 = std::max(rx * rx, ry * ry);
  if (rho2 <= 0.0) return -std::numeric_limits<double>::infinity();
  int exponent = 0;
  const double mantissa = std::frexp(rho2, &exponent);  // rho2 = mantissa 2^exponent, mantissa in [0.5, 1)
  return 0.5 * ((exponent - 1) + (2.0 * mantissa - 1.0));
}

Texel sample_level(const Texture1DArray& texture, int level, double u, int layer) {
  const int size = texture.level_width(level);
  const double coordinate = u * size - 0.5;
  const double base = std::floor(coordinate);
  const double alpha = coordinate - base;
  const int i0 = static_cast<int>(base);
  const double* t0 = texture.texel(level, layer, mirrored_repeat(i0, size));
  const double* t1 = texture.texel(level, layer, mirrored_repeat(i0 + 1, size));
  Texel result;
  for (int c = 0; c < 4; ++c) result[c] = (1.0 - alpha) * t0[c] + alpha * t1[c];
  return result;
}

Texel texture_lod(const Texture1DArray& texture, double u, double layer, double lod) {
  const int layer_index = static_cast<int>(clamp(round_half_even(layer), 0.0, texture.layers - 1.0));
  const int q = texture.level_count() - 1;
  const double d = std::isnan(lod) ? 0.0 : clamp(lod, 0.0, q);
  const double hi = std::floor(d);
  const double delta = d - hi;
  const int level_hi = static_cast<int>(hi);
  const Texel fine = sample_level(texture, level_hi, u, layer_index);
  if (delta == 0.0 || level_hi == q) return fine;
  const Texel coarse = sample_level(texture, level_hi + 1, u, layer_index);
  Texel result;
  for (int c = 0; c < 4; ++c) result[c] = (1.0 - delta) * fine[c] + delta * coarse[c];
  return result;
}

Texel texture_grad(const Texture1DArray& texture, double u, double layer, double du_dx, double du_dy, LodModel model) {
  return texture_lod(texture, u, layer, lod_from_gradients(du_dx, du_dy, texture.width, model));
}

Texel texture_level(const Texture1DArray& texture, double u, double layer, int level) {
  const int layer_index = static_cast<int>(clamp(round_half_even(layer), 0.0, texture.layers - 1.0));
  return sample_level(texture, std::clamp(level, 0, texture.level_count() - 1), u, layer_index);
}

SamplerTolerance vulkan_sampler_tolerance(int mipmap_precision_bits, int sub_texel_precision_bits) {
  SamplerTolerance t;
  t.level_weight = std::ldexp(1.0, -mipmap_precision_bits);
  t.texel_weight = std::ldexp(1.0, -sub_texel_precision_bits);
  // The coarser of the specification's mipmapPrecisionBits and the conformance suite's 4 bits
  // (see the header).
  t.lod_accuracy = std::ldexp(1.0, -std::min(mipmap_precision_bits, kConformanceLodBits));
  t.lod_below = 0.0;  // f_x >= max(|m_ux|): lambda >= log2(rho_max) before its accuracy
  t.lod_above = 0.5;  // f_x <= sqrt(2) |m_ux| for a 1D image
  return t;
}

namespace {

// The spacing of binary16 values at x: 2^(e - 10) for 2^e <= |x| < 2^(e+1), e >= -14; 2^-24 below
// (the subnormals).
double half_spacing(double x) {
  int exponent = 0;
  std::frexp(x, &exponent);  // |x| = m 2^exponent, m in [0.5, 1)
  return std::ldexp(1.0, std::max(exponent - 1, -14) - 10);
}

}  // namespace

double half_at_or_below(double x) {
  const double step = half_spacing(x);
  return std::floor(x / step) * step;  // exact: step is a power of two
}

double half_at_or_above(double x) { return -half_at_or_below(-x); }

namespace {

// One level's LINEAR filter at texel coordinate c = u size - 0.5 (piecewise linear in c).
Texel level_at(const Texture1DArray& texture, int level, double c, int layer) {
  const int size = texture.level_width(level);
  const double base = std::floor(c);
  const double alpha = c - base;
  const int i0 = static_cast<int>(base);
  const double* t0 = texture.texel(level, layer, mirrored_repeat(i0, size));
  const double* t1 = texture.texel(level, layer, mirrored_repeat(i0 + 1, size));
  Texel result;
  for (int k = 0; k < 4; ++k) result[k] = (1.0 - alpha) * t0[k] + alpha * t1[k];
  return result;
}

void widen(TexelRange& range, const Texel& value) {
  for (int k = 0; k < 4; ++k) {
    range.low[k] = std::min(range.low[k], value[k]);
    range.high[k] = std::max(range.high[k], value[k]);
  }
}

// The level's filter over texel coordinates within +-e of u size - 0.5: the ends and the knots.
TexelRange level_range(const Texture1DArray& texture, int level, double u, int layer, double e) {
  const double c = u * texture.level_width(level) - 0.5;
  TexelRange range;
  range.low.fill(std::numeric_limits<double>::infinity());
  range.high.fill(-std::numeric_limits<double>::infinity());
  widen(range, level_at(texture, level, c - e, layer));
  widen(range, level_at(texture, level, c + e, layer));
  for (double knot = std::ceil(c - e); knot < c + e; knot += 1.0) widen(range, level_at(texture, level, knot, layer));
  return range;
}

}  // namespace

TexelRange texture_lod_range(const Texture1DArray& texture, double u, double layer, double lod, const SamplerTolerance& t) {
  return texture_grad_range(texture, u, layer, std::numeric_limits<double>::quiet_NaN(), lod, t);
}

TexelRange texture_level_range(const Texture1DArray& texture, double u, double layer, int level, const SamplerTolerance& t) {
  const int layer_index = static_cast<int>(clamp(round_half_even(layer), 0.0, texture.layers - 1.0));
  TexelRange range = level_range(texture, std::clamp(level, 0, texture.level_count() - 1), u, layer_index, t.texel_weight);
  if (t.half_float_result) {
    for (int k = 0; k < 4; ++k) {
      range.low[k] = half_at_or_below(range.low[k]);
      range.high[k] = half_at_or_above(range.high[k]);
    }
  }
  return range;
}

// With du_dx NaN, du_dy is the shader's lambda (textureLod), known exactly.
TexelRange texture_grad_range(const Texture1DArray& texture, double u, double layer, double du_dx, double du_dy,
                              const SamplerTolerance& t) {
  const int layer_index = static_cast<int>(clamp(round_half_even(layer), 0.0, texture.layers - 1.0));
  const int q = texture.level_count() - 1;
  double lo, hi;
  if (std::isnan(du_dx)) {
    lo = hi = std::isnan(du_dy) ? 0.0 : du_dy;
  } else {
    const double base = lod_from_gradients(du_dx, du_dy, texture.width, LodModel::exact);
    lo = base - t.lod_below;
    hi = base + t.lod_above;
  }
  // lambda is computed to lod_accuracy (explicit or from the gradients), then the two levels'
  // weights are snapped to 2^-mipmapPrecisionBits: lambda's fraction within +-level_weight, i.e.
  // lambda itself within that of [lo, hi] (the filter is continuous in lambda).
  lo = clamp(lo - t.lod_accuracy - t.level_weight, 0.0, q);
  hi = clamp(hi + t.lod_accuracy + t.level_weight, 0.0, q);
  if (std::isnan(lo)) lo = 0.0;  // log2(0) = -inf, clamped
  if (std::isnan(hi)) hi = 0.0;
  // The trilinear value is piecewise linear in lambda between integer levels: its range over
  // [lo, hi] is reached at the ends or at an integer level, each with its sub-texel range.
  std::vector<double> lambdas{lo, hi};
  for (double k = std::ceil(lo); k < hi; k += 1.0) lambdas.push_back(k);
  TexelRange range;
  range.low.fill(std::numeric_limits<double>::infinity());
  range.high.fill(-std::numeric_limits<double>::infinity());
  for (double lambda : lambdas) {
    const int level = static_cast<int>(std::floor(lambda));
    const double delta = lambda - level;
    const TexelRange fine = level_range(texture, level, u, layer_index, t.texel_weight);
    if (delta == 0.0 || level == q) {
      widen(range, fine.low);
      widen(range, fine.high);
      continue;
    }
    const TexelRange coarse = level_range(texture, level + 1, u, layer_index, t.texel_weight);
    Texel low, high;
    for (int k = 0; k < 4; ++k) {
      low[k] = (1.0 - delta) * fine.low[k] + delta * coarse.low[k];
      high[k] = (1.0 - delta) * fine.high[k] + delta * coarse.high[k];
    }
    widen(range, low);
    widen(range, high);
  }
  if (t.half_float_result) {
    for (int k = 0; k < 4; ++k) {
      range.low[k] = half_at_or_below(range.low[k]);
      range.high[k] = half_at_or_above(range.high[k]);
    }
  }
  return range;
}

// ---------------------------------------------------------------------------------------------
// The model

double dictionary_range(const Params& params) { return kRangePerAlpha * params.alpha_dict; }

std::int32_t mix(std::int32_t v) {
  // Unsigned arithmetic wraps like GLSL/HLSL int; (v >> k) & mask is a logical shift.
  std::uint32_t u = static_cast<std::uint32_t>(v);
  u = u ^ (u >> 16);
  u = u * 1911520717u;
  u = u ^ (u >> 13);
  u = u * 1366156441u;
  u = u ^ (u >> 16);
  return static_cast<std::int32_t>(u);
}

std::int32_t cell_seed(int i, int j, int level, bool coherent) {
  if (!coherent) return mix(mix(mix(static_cast<std::int32_t>(static_cast<std::uint32_t>(level) + 1013u)) ^ i) ^ j);
  // (i << level) on 32-bit ints, wrapping like the shader.
  const std::uint32_t si = static_cast<std::uint32_t>(i) << level, sj = static_cast<std::uint32_t>(j) << level;
  return mix(mix(static_cast<std::int32_t>(si + 1013u)) ^ static_cast<std::int32_t>(sj));
}

namespace {

// Bits 17..31 of the mixed seed ^ salt: a uniform 15-bit integer.
int random_bits(std::int32_t seed, std::int32_t salt) {
  return static_cast<int>((static_cast<std::uint32_t>(mix(seed ^ salt)) >> 17) & 32767u);
}

constexpr double kZeta = 2.0;  // the authors' density randomisation (2020 Alg. 3)

}  // namespace

CellRandom cell_random(int i, int j, int level, int count, bool coherent) {
  const std::int32_t seed = cell_seed(i, j, level, coherent);
  CellRandom random;
  random.dx = (mix(seed) & 2147483647) % count;
  random.dy = (mix(seed ^ 1431655765) & 2147483647) % count;
  random.turn = static_cast<double>(random_bits(seed, 858993459) - 16384) * kTurn;
  return random;
}

std::array<int, 16> zeta_thresholds() {
  std::array<int, 16> thresholds{};
  for (int k = -8; k < 8; ++k) {
    const double phi = 0.5 * std::erfc(-(k + 0.5) / kZeta / std::sqrt(2.0));
    thresholds[static_cast<std::size_t>(k + 8)] = static_cast<int>(std::nearbyint(32768.0 * phi));
  }
  return thresholds;
}

int zeta_offset(int u) {
  static const std::array<int, 16> thresholds = zeta_thresholds();
  int offset = -8;
  for (const int t : thresholds) offset += u >= t ? 1 : 0;
  return offset;
}

int cell_dictionary_lod(const Params& params, int i, int j, int level) {
  const std::int32_t seed = cell_seed(i, j, level, params.coherent_seeds);
  const int area = random_bits(seed, 16711935);
  const int zeta = random_bits(seed, 252645135);
  if (!(area < static_cast<int>(params.relative_area * 32768.0))) return -1;  // an integer comparison, as the templates
  return std::clamp(level + zeta_offset(zeta), 0, params.lods - 1);
}

Vec2 inverse_transform(const Params& params, Vec2 v, const Roughness& roughness) {
  const double rho = clamp(roughness.rho, -kRhoMax, kRhoMax);
  const Vec2 scaled{v.x / roughness.alpha_x, v.y / roughness.alpha_y};
  return params.alpha_dict * Vec2{(scaled.x - rho * scaled.y) / std::sqrt(1.0 - rho * rho), scaled.y};
}

double transform_determinant(const Params& params, const Roughness& roughness) {
  const double rho = clamp(roughness.rho, -kRhoMax, kRhoMax);
  return roughness.alpha_x * roughness.alpha_y * std::sqrt(1.0 - rho * rho) / (params.alpha_dict * params.alpha_dict);
}

FootprintAxes footprint_axes(const Params& params, Vec2 duv_dx, Vec2 duv_dy) {
  const bool x_major = dot(duv_dx, duv_dx) >= dot(duv_dy, duv_dy);
  FootprintAxes axes{x_major ? duv_dx : duv_dy, x_major ? duv_dy : duv_dx};
  const double major_length = length(axes.major), minor_length = length(axes.minor);
  const double widest = major_length / params.max_anisotropy;
  if (minor_length > widest) return axes;
  axes.minor = minor_length > kTinyPositive ? axes.minor * (widest / minor_length)
                                            : Vec2{-axes.major.y, axes.major.x} * (1.0 / params.max_anisotropy);
  return axes;
}

double footprint_lod(const Params& params, Vec2 duv_dx, Vec2 duv_dy, double log_density) {
  const double minor = length(footprint_axes(params, duv_dx, duv_dy).minor);
  return clamp(std::log2(std::max(minor, kTinyPositive)) + log_density * kInv2Ln2, 0.0, params.lods - 1.0);
}

namespace {

double select_channel(const Texel& texel, int channel) { return texel[static_cast<std::size_t>(channel)]; }

double layer_of(const Params& params, int distribution, int level) {
  return static_cast<double>(level * (params.count / 4) + distribution / 4);
}

}  // namespace

namespace {

// One channel of the texture at an integer level; with a tolerance and a side, the low or high end
// of what a conforming sampler may return there (texture_level_range).
double level_value(const Dictionary& dictionary, double u, double layer, int level, int distribution) {
  if (dictionary.tolerance && dictionary.side != 0) {
    const TexelRange range = texture_level_range(*dictionary.texture, u, layer, level, *dictionary.tolerance);
    return select_channel(dictionary.side < 0 ? range.low : range.high, distribution % 4);
  }
  return select_channel(texture_level(*dictionary.texture, u, layer, level), distribution % 4);
}

// log2(x) at either end of the Vulkan allowance when log2_side != 0: 3 ulp outside [0.5, 2.0],
// absolute error < 2^-21 inside ("Precision and Operation of SPIR-V Instructions").
double shader_log2(const Dictionary& dictionary, double x) {
  const double exact = std::log2(x);
  const double allowance = (x >= 0.5 && x <= 2.0) ? 0x1.0p-21 : 3.0 * 0x1.0p-23 * std::fabs(exact);
  return exact + dictionary.log2_side * allowance;
}

}  // namespace

double dictionary_lod_value(const Dictionary& dictionary, double x, int distribution, int level) {
  const double u = x / dictionary_range(dictionary.params);
  if (!(std::fabs(u) < 1.0)) return 0.0;
  return level_value(dictionary, u, layer_of(dictionary.params, distribution, level), 0, distribution);
}

double dictionary_grad_value(const Dictionary& dictionary, double x, double dx_dx, double dx_dy, int distribution, int level) {
  const double to_u = 1.0 / dictionary_range(dictionary.params);
  const double u = x * to_u;
  if (!(std::fabs(u) < 1.0)) return 0.0;
  const double rho = dictionary.params.kernel_scale * to_u * std::max(std::fabs(dx_dx), std::fabs(dx_dy)) * dictionary.params.resolution;
  const double lod = clamp(shader_log2(dictionary, std::max(rho, kTinyPositive)), 0.0, kTopLevel);
  const double fine = std::floor(lod);
  const double t = lod - fine;
  const double layer = layer_of(dictionary.params, distribution, level);
  const double at_fine = level_value(dictionary, u, layer, static_cast<int>(fine), distribution);
  // Weights 1 - t and t are non-negative: the low (high) ends combine into the low (high) end.
  return t == 0.0 ? at_fine : (1.0 - t) * at_fine + t * level_value(dictionary, u, layer, static_cast<int>(fine) + 1, distribution);
}

namespace {

constexpr double kEwaEdge = 0.1353352832366127;  // GLINT_EWA_EDGE = exp(-2)
constexpr int kMaxCells = 256;                   // GLINT_MAX_CELLS
constexpr int kMaxRows = 40;                     // GLINT_MAX_ROWS

// The cells of one level under the footprint ellipse (glint_level_sdf): EWA weights W_P =
// exp(-2 r^2) - exp(-2) of the ellipse x^T S^-1 x < 1, S = a a^T + b b^T + I in cells,
// normalised by their sum, times the level's weight. exp_side: the shader's exp at either end of
// the Vulkan allowance (3 + 2|x| ulp, x = -2 r^2).
void add_level_cells(const Dictionary& dictionary, Vec2 uv, const FootprintAxes& axes, double log_density, int level, double level_weight,
                     Patch& patch) {
  const Params& params = dictionary.params;
  // Vulkan spec, "Precision and Operation of SPIR-V Instructions": exp2(x): 3 + 2|x| ULP.
  const double exponent = log_density * kInv2Ln2 - level;
  const double scale = std::exp2(exponent) * (1.0 + dictionary.exp2_side * (3.0 + 2.0 * std::fabs(exponent)) * 0x1.0p-23);
  const Vec2 c{uv.x * scale - 0.5, uv.y * scale - 0.5};
  const Vec2 a = axes.major * scale, b = axes.minor * scale;
  const double sxx = a.x * a.x + b.x * b.x + 1.0, sxy = a.x * a.y + b.x * b.y, syy = a.y * a.y + b.y * b.y + 1.0;
  const double conditional = (sxx * syy - sxy * sxy) / syy;
  const double reach = std::sqrt(syy);
  const int first_row = static_cast<int>(std::ceil(c.y - reach));
  const int last_row = std::min(static_cast<int>(std::floor(c.y + reach)), first_row + kMaxRows);
  const std::size_t begin = patch.cells.size();
  double total = 0.0;
  int visited = 0;
  for (int j = first_row; j <= last_row; ++j) {
    const double dy = j - c.y;
    const double centre = c.x + sxy / syy * dy;
    const double half_width = std::sqrt(std::max(conditional * (1.0 - dy * dy / syy), 0.0));
    const int last_column = static_cast<int>(std::floor(centre + half_width));
    for (int i = static_cast<int>(std::ceil(centre - half_width)); i <= last_column && visited < kMaxCells; ++i) {
      const double dx = i - centre;
      const double x = -2.0 * (dx * dx / conditional + dy * dy / syy);
      const double e = std::exp(x) * (1.0 + dictionary.exp2_side * (3.0 + 2.0 * std::fabs(x)) * 0x1.0p-23);
      const double weight = std::max(e - kEwaEdge, 0.0);
      total += weight;
      ++visited;
      const int lod = cell_dictionary_lod(params, i, j, level);
      if (lod < 0 || weight == 0.0) continue;
      PatchCell cell;
      cell.weight = weight;
      cell.level = lod;
      cell.spatial_level = level;
      cell.i = i;
      cell.j = j;
      cell.random = cell_random(i, j, level, params.count, params.coherent_seeds);
      const double angle = 2.0 * kPi * cell.random.turn;
      cell.cos_theta = std::cos(angle);
      cell.sin_theta = std::sin(angle);
      patch.cells.push_back(cell);
    }
  }
  const double norm = level_weight / std::max(total, kTinyPositive);
  for (std::size_t n = begin; n < patch.cells.size(); ++n) patch.cells[n].weight *= norm;
}

// log2 of the minor axis' length, at either end of the Vulkan allowance when log2_side != 0.
double minor_log2(const Dictionary& dictionary, const FootprintAxes& axes) {
  return shader_log2(dictionary, std::max(length(axes.minor), kTinyPositive));
}

}  // namespace

Patch make_patch(const Dictionary& dictionary, Vec2 uv, Vec2 duv_dx, Vec2 duv_dy, double log_density) {
  const Params& params = dictionary.params;
  Patch patch;
  FootprintAxes axes = footprint_axes(params, duv_dx, duv_dy);
  const double unclamped = minor_log2(dictionary, axes) + log_density * kInv2Ln2;
  patch.lod = clamp(unclamped, 0.0, params.lods - 1.0);
  // Above the coarsest level the ellipse shrinks to a minor axis of one cell of level L - 1.
  const double shrink = std::exp2(-std::max(unclamped - (params.lods - 1.0), 0.0));
  axes.major = axes.major * shrink;
  axes.minor = axes.minor * shrink;
  const double level = std::floor(patch.lod);
  const double t = patch.lod - level;
  const int levels[2] = {static_cast<int>(level), static_cast<int>(std::min(level + 1.0, params.lods - 1.0))};
  const double level_weights[2] = {1.0 - t, t};
  for (int k = 0; k < 2; ++k) {
    if (level_weights[k] == 0.0) continue;
    add_level_cells(dictionary, uv, axes, log_density, levels[k], level_weights[k], patch);
  }
  return patch;
}

namespace {

Vec2 rotate(Vec2 q, double c, double s) { return {c * q.x + s * q.y, c * q.y - s * q.x}; }

// A cell's product of lookups, product(cos theta, sin theta); with trig_side != 0 its low or high
// end over the corners of the box the spec allows cos and sin (Dictionary::trig_side). The box is
// far below a texel of the dictionary, so the piecewise-linear lookups are linear across it but
// for at most one kink, and the corners hold the ends.
template <class Product>
double cell_product(const Dictionary& dictionary, const PatchCell& cell, Product product) {
  if (dictionary.trig_side == 0) return product(cell.cos_theta, cell.sin_theta);
  double end = product(cell.cos_theta, cell.sin_theta);
  for (const double dc : {-kTrigAllowance, kTrigAllowance}) {
    for (const double ds : {-kTrigAllowance, kTrigAllowance}) {
      const double v = product(cell.cos_theta + dc, cell.sin_theta + ds);
      end = dictionary.trig_side < 0 ? std::min(end, v) : std::max(end, v);
    }
  }
  return end;
}

}  // namespace

double patch_sdf(const Dictionary& dictionary, const Patch& patch, Vec2 slope, const Roughness& roughness) {
  const Vec2 q = inverse_transform(dictionary.params, slope, roughness);
  double mixture = 0.0;
  for (const PatchCell& cell : patch.cells) {
    if (cell.weight == 0.0) continue;
    mixture += cell.weight * cell_product(dictionary, cell, [&](double c, double s) {
                 const Vec2 o = rotate(q, c, s);
                 return dictionary_lod_value(dictionary, o.x, cell.random.dx, cell.level) *
                        dictionary_lod_value(dictionary, o.y, cell.random.dy, cell.level);
               });
  }
  return mixture / transform_determinant(dictionary.params, roughness);
}

double patch_sdf_filtered(const Dictionary& dictionary, const Patch& patch, Vec2 slope, Vec2 dh_dx, Vec2 dh_dy,
                          const Roughness& roughness) {
  const Params& params = dictionary.params;
  const Vec2 q = inverse_transform(params, slope, roughness);
  const Vec2 dq_dx = inverse_transform(params, dh_dx, roughness);
  const Vec2 dq_dy = inverse_transform(params, dh_dy, roughness);
  double mixture = 0.0;
  for (const PatchCell& cell : patch.cells) {
    if (cell.weight == 0.0) continue;
    mixture += cell.weight * cell_product(dictionary, cell, [&](double c, double s) {
                 const Vec2 o = rotate(q, c, s), o_dx = rotate(dq_dx, c, s), o_dy = rotate(dq_dy, c, s);
                 return dictionary_grad_value(dictionary, o.x, o_dx.x, o_dy.x, cell.random.dx, cell.level) *
                        dictionary_grad_value(dictionary, o.y, o_dx.y, o_dy.y, cell.random.dy, cell.level);
               });
  }
  return mixture / transform_determinant(params, roughness);
}

double sdf(const Dictionary& dictionary, Vec2 slope, Vec2 uv, Vec2 duv_dx, Vec2 duv_dy, const Roughness& roughness, double log_density) {
  return patch_sdf(dictionary, make_patch(dictionary, uv, duv_dx, duv_dy, log_density), slope, roughness);
}

double sdf_filtered(const Dictionary& dictionary, Vec2 slope, Vec2 dh_dx, Vec2 dh_dy, Vec2 uv, Vec2 duv_dx, Vec2 duv_dy,
                    const Roughness& roughness, double log_density) {
  return patch_sdf_filtered(dictionary, make_patch(dictionary, uv, duv_dx, duv_dy, log_density), slope, dh_dx, dh_dy, roughness);
}

double vcavity_g2(Vec3 i, Vec3 o, Vec3 h) {
  if (!(i.z > 0.0 && o.z > 0.0 && h.z > 0.0)) return 0.0;
  const double masking = 2.0 * h.z * o.z / std::max(dot(o, h), kTinyPositive);
  const double shadowing = 2.0 * h.z * i.z / std::max(dot(i, h), kTinyPositive);
  return std::min(1.0, std::min(masking, shadowing));
}

Vec2 half_slope(Vec3 i, Vec3 o) {
  const Vec3 sum = i + o;
  const Vec3 h = sum / std::sqrt(std::max(dot(sum, sum), kTinyPositive));
  const double hz = std::max(h.z, kSlopeMinZ);
  return {-h.x / hz, -h.y / hz};
}

namespace {

// G2 / (4 i.z o.z h.z^4): the BRDF is this times the SDF.
double brdf_factor(Vec3 i, Vec3 o) {
  const Vec3 sum = i + o;
  const Vec3 h = sum / std::sqrt(std::max(dot(sum, sum), kTinyPositive));
  const double hz = std::max(h.z, kSlopeMinZ);
  return vcavity_g2(i, o, h) / (hz * hz * hz * hz) / std::max(4.0 * i.z * o.z, kTinyPositive);
}

}  // namespace

double patch_brdf(const Dictionary& dictionary, const Patch& patch, Vec3 i, Vec3 o, Vec2 mean_slope, const Roughness& roughness) {
  const double factor = brdf_factor(i, o);
  if (factor == 0.0) return 0.0;
  return factor * patch_sdf(dictionary, patch, half_slope(i, o) - mean_slope, roughness);
}

double patch_brdf_filtered(const Dictionary& dictionary, const Patch& patch, Vec3 i, Vec3 o, Vec2 mean_slope, Vec2 dh_dx, Vec2 dh_dy,
                           const Roughness& roughness) {
  const double factor = brdf_factor(i, o);
  if (factor == 0.0) return 0.0;
  return factor * patch_sdf_filtered(dictionary, patch, half_slope(i, o) - mean_slope, dh_dx, dh_dy, roughness);
}

double brdf(const Dictionary& dictionary, Vec3 i, Vec3 o, Vec2 mean_slope, Vec2 uv, Vec2 duv_dx, Vec2 duv_dy, const Roughness& roughness,
            double log_density) {
  return patch_brdf(dictionary, make_patch(dictionary, uv, duv_dx, duv_dy, log_density), i, o, mean_slope, roughness);
}

double brdf_filtered(const Dictionary& dictionary, Vec3 i, Vec3 o, Vec2 mean_slope, Vec2 dh_dx, Vec2 dh_dy, Vec2 uv, Vec2 duv_dx,
                     Vec2 duv_dy, const Roughness& roughness, double log_density) {
  return patch_brdf_filtered(dictionary, make_patch(dictionary, uv, duv_dx, duv_dy, log_density), i, o, mean_slope, dh_dx, dh_dy,
                             roughness);
}

Roughness lean_roughness(Vec2 alpha, Vec2 mean, Sym2 second) {
  const double sxx = std::max(second.xx - mean.x * mean.x + 0.5 * alpha.x * alpha.x, kTinyPositive);
  const double sxy = second.xy - mean.x * mean.y;
  const double syy = std::max(second.yy - mean.y * mean.y + 0.5 * alpha.y * alpha.y, kTinyPositive);
  return {std::sqrt(2.0 * sxx), std::sqrt(2.0 * syy), sxy / std::sqrt(sxx * syy)};
}

}  // namespace saagen::ref::glints
