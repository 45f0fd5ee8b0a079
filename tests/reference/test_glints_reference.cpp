// The double-precision glint reference (saagen/reference/glints.hpp): the software
// Vulkan sampler, the cell hash, the energy of the (filtered) patch SDF, the covariance that M
// (Eq. 18) gives the converged SDF, LEAN, and the BRDF's symmetries. CPU only.
#include "glint_authors.hpp"
#include "support/glint_support.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <random>

namespace {

namespace g = saagen::ref::glints;
using saagen::ref::Sym2;
using saagen::ref::Vec2;
using saagen::ref::Vec3;

// ---------------------------------------------------------------------------------------------
// Sampler

g::Texture1DArray ramp_texture() {
  g::Texture1DArray texture;
  texture.width = 8;
  texture.layers = 2;
  for (int level = 0; level < 4; ++level) {
    std::vector<double> values;
    for (int layer = 0; layer < 2; ++layer) {
      for (int x = 0; x < (8 >> level); ++x) {
        for (double v : {double(x), double(level), double(layer), 1.0}) values.push_back(v);
      }
    }
    texture.levels.push_back(values);
  }
  return texture;
}

TEST(GlintSampler, MirroredRepeatFollowsTheVulkanFormula) {
  // (w - 1) - mirror((i mod 2w) - w), mirror(n) = n >= 0 ? n : -(1 + n)
  for (int size : {1, 2, 8}) {
    for (int i = -40; i < 40; ++i) {
      const int t = ((i % (2 * size)) + 2 * size) % (2 * size);
      const int s = t - size;
      const int expected = (size - 1) - (s >= 0 ? s : -(1 + s));
      EXPECT_EQ(g::mirrored_repeat(i, size), expected) << i << " " << size;
    }
  }
}

TEST(GlintSampler, LinearFilteringMipmapsAndLayers) {
  const auto texture = ramp_texture();
  EXPECT_DOUBLE_EQ(g::texture_lod(texture, 2.5 / 8.0, 1.0, 0.0)[0], 2.0);  // texel centre
  EXPECT_DOUBLE_EQ(g::texture_lod(texture, 3.0 / 8.0, 1.0, 0.0)[0], 2.5);  // between texels
  EXPECT_DOUBLE_EQ(g::texture_lod(texture, 0.0, 0.0, 0.0)[0], 0.0);        // mirrored: texel -1 = texel 0
  EXPECT_DOUBLE_EQ(g::texture_lod(texture, -0.25 / 8.0, 0.0, 0.0)[0], 0.0);
  EXPECT_DOUBLE_EQ(g::texture_lod(texture, 1.0, 0.0, 0.0)[0], 7.0);    // texel 8 mirrors to 7
  EXPECT_DOUBLE_EQ(g::texture_lod(texture, 0.5, 1.4, 0.0)[2], 1.0);    // layer rounds to nearest
  EXPECT_DOUBLE_EQ(g::texture_lod(texture, 0.5, 0.5, 0.0)[2], 0.0);    // ... half to even
  EXPECT_DOUBLE_EQ(g::texture_lod(texture, 0.5, 7.0, 0.0)[2], 1.0);    // ... clamped
  EXPECT_DOUBLE_EQ(g::texture_lod(texture, 0.5, 0.0, 1.25)[1], 1.25);  // linear between levels 1 and 2
  EXPECT_DOUBLE_EQ(g::texture_lod(texture, 0.5, 0.0, 9.0)[1], 3.0);    // clamped to the last level
  EXPECT_DOUBLE_EQ(g::texture_lod(texture, 0.5, 0.0, -2.0)[1], 0.0);
  // textureGrad: lambda = log2(max(|dPdx|, |dPdy|) * width)
  EXPECT_DOUBLE_EQ(g::texture_grad(texture, 0.5, 0.0, 2.0 / 8.0, -0.5 / 8.0)[1], 1.0);
  EXPECT_NEAR(g::texture_grad(texture, 0.5, 0.0, 0.1 / 8.0, -3.0 / 8.0)[1], std::log2(3.0), 1e-15);
  EXPECT_DOUBLE_EQ(g::texture_grad(texture, 0.5, 0.0, 0.0, 0.0)[1], 0.0);
}

// An RGBA16F result may be rounded either way to a half (Vulkan "Floating-Point Format
// Conversions": "rounded to one or the other. The rounding mode is not defined.";
// SamplerTolerance::half_float_result).
TEST(GlintSampler, HalfResultWidensTheRangeToTheNeighbouringHalves) {
  EXPECT_EQ(g::half_at_or_below(1.0454094), 1.0 + 46.0 / 1024.0);  // the NVIDIA example: 1 + 47/1024 above it
  EXPECT_EQ(g::half_at_or_above(1.0454094), 1.0 + 47.0 / 1024.0);
  EXPECT_EQ(g::half_at_or_below(0.75), 0.75);  // halves stay
  EXPECT_EQ(g::half_at_or_above(0.75), 0.75);
  EXPECT_EQ(g::half_at_or_below(0.3), 1228.0 / 4096.0);  // [0.25, 0.5): spacing 2^-12
  EXPECT_EQ(g::half_at_or_above(-0.3), -1228.0 / 4096.0);
  EXPECT_EQ(g::half_at_or_below(-0.3), -1229.0 / 4096.0);
  EXPECT_EQ(g::half_at_or_below(3e-8), 0.0);  // below the smallest subnormal: 0 or 2^-24
  EXPECT_EQ(g::half_at_or_above(3e-8), 0x1.0p-24);
  EXPECT_EQ(g::half_at_or_above(1e-5), 168.0 * 0x1.0p-24);                  // subnormal spacing 2^-24
  EXPECT_EQ(g::half_at_or_above(0x1.0p-14 + 1e-9), 0x1.0p-14 + 0x1.0p-24);  // smallest normal binade: 2^-24
  EXPECT_EQ(g::half_at_or_below(65504.0), 65504.0);

  const auto texture = ramp_texture();
  g::SamplerTolerance tolerance = g::vulkan_sampler_tolerance(8, 8);
  const g::TexelRange plain = g::texture_lod_range(texture, 3.1 / 8.0, 1.0, 0.0, tolerance);
  tolerance.half_float_result = true;
  const g::TexelRange half = g::texture_lod_range(texture, 3.1 / 8.0, 1.0, 0.0, tolerance);
  for (int c = 0; c < 4; ++c) {
    EXPECT_EQ(half.low[c], g::half_at_or_below(plain.low[c]));
    EXPECT_EQ(half.high[c], g::half_at_or_above(plain.high[c]));
    EXPECT_LE(plain.high[c] - plain.low[c], half.high[c] - half.low[c]);
    EXPECT_LE(half.high[c] - plain.high[c], std::max(0x1.0p-10 * std::fabs(plain.high[c]), 0x1.0p-24));  // under one ulp
  }
}

// lambda's accuracy: the coarser of mipmapPrecisionBits and the conformance suite's 4 bits. At
// 0.026 above an integer LOD the finer level alone is within it (an NVIDIA H200 returns that);
// at 0.1 above it is not, and with 2 bits it is again.
TEST(GlintSampler, LodAccuracyIsTheConformanceSuitesWhereTheDeviceClaimsMore) {
  const auto texture = ramp_texture();
  const g::SamplerTolerance eight = g::vulkan_sampler_tolerance(8, 8);
  EXPECT_EQ(eight.lod_accuracy, 0.0625);
  EXPECT_EQ(eight.level_weight, 0x1.0p-8);
  EXPECT_EQ(g::vulkan_sampler_tolerance(2, 8).lod_accuracy, 0.25);
  const double u = 3.1 / 8.0;
  const g::Texel finer_alone = g::texture_lod(texture, u, 1.0, 1.0);
  const g::Texel coarser_alone = g::texture_lod(texture, u, 1.0, 2.0);
  ASSERT_NE(finer_alone[0], coarser_alone[0]);  // the levels differ at u
  auto holds = [&](double lod, const g::SamplerTolerance& tolerance, const g::Texel& value) {
    const g::TexelRange range = g::texture_lod_range(texture, u, 1.0, lod, tolerance);
    for (int c = 0; c < 4; ++c)
      if (value[c] < range.low[c] || value[c] > range.high[c]) return false;
    return true;
  };
  EXPECT_TRUE(holds(1.026, eight, finer_alone));
  EXPECT_FALSE(holds(1.1, eight, finer_alone));
  EXPECT_TRUE(holds(1.1, g::vulkan_sampler_tolerance(2, 8), finer_alone));
  g::SamplerTolerance mipmap_bits_alone = eight;  // the specification's sentence alone
  mipmap_bits_alone.lod_accuracy = mipmap_bits_alone.level_weight;
  EXPECT_FALSE(holds(1.026, mipmap_bits_alone, finer_alone));
}

// The GGAA lookup as the snippet makes it (its own LOD, two integer levels blended) is the exact
// trilinear textureGrad of the specification, and what a device may return for it depends on no
// LOD rule, LOD accuracy or level weight of the sampler: only on the texel coordinate's precision
// and the result's rounding (an explicit integer LOD reads one level alone).
TEST(GlintSampler, GgaaLookupIsTheExactTrilinearLookupAndIgnoresTheDevicesLod) {
  g::Dictionary dictionary = saagen::test::default_reference_dictionary();
  const auto& texture = *dictionary.texture;
  const double to_u = 1.0 / g::dictionary_range(dictionary.params);
  const double s = dictionary.params.kernel_scale * to_u;
  std::mt19937_64 random(17);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const g::SamplerTolerance precise = g::vulkan_sampler_tolerance(8, 8);
  g::SamplerTolerance loose_lod = precise;  // any LOD freedom: it must not enter
  loose_lod.lod_below = loose_lod.lod_above = loose_lod.lod_accuracy = loose_lod.level_weight = 0.5;
  double worst = 0.0;
  for (int k = 0; k < 4000; ++k) {
    const double x = (-1.0 + 2.0 * unit(random)) * g::dictionary_range(dictionary.params);
    // Footprints from a tenth of a texel to past the last level, integer LODs included.
    const double lambda = k % 10 == 0 ? std::floor(-1.0 + 9.0 * unit(random)) : -3.0 + 12.0 * unit(random);
    const double gradient = std::exp2(lambda) / (s * dictionary.params.resolution);
    const double ratio = -1.0 + 2.0 * unit(random);
    const int distribution = static_cast<int>(192.0 * unit(random)), level = static_cast<int>(16.0 * unit(random));
    const double layer = level * 48.0 + distribution / 4;
    dictionary.tolerance = nullptr;
    dictionary.side = 0;
    const double value = g::dictionary_grad_value(dictionary, x, gradient, ratio * gradient, distribution, level);
    const g::Texel grad = g::texture_grad(texture, x * to_u, layer, s * gradient, s * ratio * gradient, g::LodModel::exact);
    worst = std::max(worst, std::fabs(value - grad[distribution % 4]));
    for (const int side : {-1, 1}) {
      dictionary.side = side;
      dictionary.tolerance = &precise;
      const double bound = g::dictionary_grad_value(dictionary, x, gradient, ratio * gradient, distribution, level);
      dictionary.tolerance = &loose_lod;
      EXPECT_EQ(bound, g::dictionary_grad_value(dictionary, x, gradient, ratio * gradient, distribution, level));
      EXPECT_TRUE(side < 0 ? bound <= value : bound >= value);
    }
  }
  EXPECT_LT(worst, 1e-12);
  std::cout << "[ ggaa     ] in-shader LOD and blend vs the exact textureGrad: max difference " << worst << "\n";
}

// lavapipe's LOD (measured, docs/GLINTS.md): exact at powers of two, at most 0.0430 below the
// specification's log2 in between (0.5 (log2(1 + f) - f) peaks at f = 1 / ln 2 - 1).
TEST(GlintSampler, LavapipeLodModelStaysWithinItsBound) {
  double worst = 0.0;
  for (int k = 0; k <= 4000; ++k) {
    const double rho = std::exp2(-3.0 + 10.0 * k / 4000.0);
    const double exact = g::lod_from_gradients(rho / 64.0, 0.0, 64, g::LodModel::exact);
    const double approx = g::lod_from_gradients(rho / 64.0, 0.0, 64, g::LodModel::lavapipe);
    EXPECT_LE(approx, exact + 1e-12);
    worst = std::max(worst, exact - approx);
  }
  const double peak = 0.5 * (std::log2(1.0 / std::log(2.0)) - (1.0 / std::log(2.0) - 1.0));
  EXPECT_NEAR(worst, std::fabs(peak), 1e-4);
  EXPECT_LT(worst, 0.0431);
  EXPECT_DOUBLE_EQ(g::lod_from_gradients(4.0 / 64.0, 1.0 / 64.0, 64, g::LodModel::lavapipe), 2.0);
  std::cout << "[ lod      ] lavapipe model: up to " << worst << " below log2(rho)\n";
}

// ---------------------------------------------------------------------------------------------
// Hash

TEST(GlintHash, CellChoicesAreUniform) {
  // Level 0 only: the cells of level l > 0 share the seeds of their corner children at level 0.
  const int count = 192, bins = 64;
  std::vector<int> dx(count), dy(count), turn(bins);
  int samples = 0;
  for (int j = -120; j < 120; ++j) {
    for (int i = -200; i < 200; ++i) {
      const auto r = g::cell_random(i, j, 0, count);
      ASSERT_GE(r.dx, 0);
      ASSERT_LT(r.dx, count);
      ASSERT_GE(r.turn, -0.5);  // 2 pi turn in [-pi, pi): sin/cos within their precise range
      ASSERT_LT(r.turn, 0.5);
      ++dx[r.dx];
      ++dy[r.dy];
      ++turn[static_cast<int>((r.turn + 0.5) * bins)];
      ++samples;
    }
  }
  const auto chi2 = [&](const std::vector<int>& histogram) {
    const double expected = static_cast<double>(samples) / histogram.size();
    double sum = 0.0;
    for (int n : histogram) sum += (n - expected) * (n - expected) / expected;
    return sum;
  };
  std::cout << "[ hash     ] chi^2: d_x " << chi2(dx) << " (191 dof), d_y " << chi2(dy) << " (191 dof), turn " << chi2(turn)
            << " (63 dof)\n";
  EXPECT_LT(chi2(dx), 191 + 6 * std::sqrt(2.0 * 191));
  EXPECT_LT(chi2(dy), 191 + 6 * std::sqrt(2.0 * 191));
  EXPECT_LT(chi2(turn), 63 + 6 * std::sqrt(2.0 * 63));
  // Neighbouring cells, a parent and a child that is not its corner child, and the two
  // marginals draw different distributions.
  int same = 0;
  for (int i = 0; i < 1000; ++i) {
    same += g::cell_random(i, 0, 0, count).dx == g::cell_random(i + 1, 0, 0, count).dx;
    same += g::cell_random(2 * i + 1, 1, 0, count).dx == g::cell_random(i, 0, 1, count).dx;
    same += g::cell_random(i, 0, 0, count).dx == g::cell_random(i, 0, 0, count).dy;
  }
  EXPECT_LT(same, 40);  // ~3000 / 192 = 16 expected
}

// Chermain et al. 2020 Eq. 8: a cell of level l + 1 draws what its corner child at level l draws
// (distributions, rotation, LOD offset, emptiness), so glints persist across LOD transitions.
TEST(GlintHash, SeedsAreCoherentAcrossLevels) {
  g::Params params;
  params.relative_area = 0.5;
  for (int level = 0; level + 1 < params.lods; ++level) {
    for (int j = -7; j < 7; ++j) {
      for (int i = -9; i < 9; ++i) {
        const auto parent = g::cell_random(i, j, level + 1, params.count);
        const auto child = g::cell_random(2 * i, 2 * j, level, params.count);
        ASSERT_EQ(parent.dx, child.dx);
        ASSERT_EQ(parent.dy, child.dy);
        ASSERT_EQ(parent.turn, child.turn);
        const int parent_lod = g::cell_dictionary_lod(params, i, j, level + 1);
        const int child_lod = g::cell_dictionary_lod(params, 2 * i, 2 * j, level);
        ASSERT_EQ(parent_lod < 0, child_lod < 0);
        // The same Gaussian offset on log4 n = l + 1 and l (until the clamp to [0, L - 1]).
        if (child_lod > 0 && parent_lod < params.lods - 1) {
          ASSERT_EQ(parent_lod, child_lod + 1) << level;
        }
      }
    }
  }
}

// Chermain et al. 2020 Alg. 3 lines 5-9: the dictionary LOD is round(log4 n + zeta N(0, 1)), zeta = 2,
// and a cell is empty with probability 1 - relative area.
TEST(GlintHash, DensityRandomisationAndRelativeArea) {
  // Thresholds: the templates spell them as literals; they are 32768 Phi((k + 1/2) / 2).
  const std::array<int, 16> expected{3, 19, 98, 401, 1313, 3462, 7426, 13150, 19618, 25342, 29306, 31455, 32367, 32670, 32749, 32765};
  EXPECT_EQ(g::zeta_thresholds(), expected);
  EXPECT_EQ(g::zeta_offset(0), -8);
  EXPECT_EQ(g::zeta_offset(32767), 8);
  EXPECT_EQ(g::zeta_offset(16384), 0);
  g::Params params;
  params.relative_area = 0.3;
  const int level = 8;  // far from both clamps (|offset| <= 8 keeps [0, 16])
  double sum = 0.0, sum2 = 0.0;
  int kept = 0, cells = 0;
  for (int j = 0; j < 300; ++j) {
    for (int i = 0; i < 300; ++i) {
      ++cells;
      const int lod = g::cell_dictionary_lod(params, i, j, level);
      if (lod < 0) continue;
      ++kept;
      const double offset = lod - level;
      sum += offset;
      sum2 += offset * offset;
    }
  }
  const double mean = sum / kept, variance = sum2 / kept - mean * mean;
  // round(2 Z) has mean 0 and variance 4 + 1/12 (Sheppard's correction for unit rounding).
  const double standard_error = std::sqrt((4.0 + 1.0 / 12.0) / kept);
  std::cout << "[ zeta     ] kept " << static_cast<double>(kept) / cells << " (0.3), offset mean " << mean << ", variance " << variance
            << " (4.083)\n";
  EXPECT_NEAR(mean, 0.0, 5.0 * standard_error);
  EXPECT_NEAR(variance, 4.0 + 1.0 / 12.0, 5.0 * (4.0 + 1.0 / 12.0) * std::sqrt(2.0 / kept));
  const double p = 0.3, area_error = std::sqrt(p * (1.0 - p) / cells);
  EXPECT_NEAR(static_cast<double>(kept) / cells, p, 5.0 * area_error);
}

// ---------------------------------------------------------------------------------------------
// Glint contrast (Chermain et al. 2020 Alg. 1-3): the spread of P22(slope; P) over surface
// positions, for an isotropic footprint and an 8:1 one of the same major axis. The level comes
// from the minor axis, so the 8:1 footprint reads cells three levels finer and sparkles more;
// zeta mixes dictionary LODs within a level. Before the anisotropic footprint and zeta (the
// major axis, bilinear cells), both footprints measured 0.132 (peak / mean 1.63). The
// comparison with the authors' dictionary and evaluation (glint_authors.hpp) is in
// docs/GLINTS.md section 6.

struct Contrast {
  double contrast = 0.0;        // std / mean over positions, averaged over the slopes
  double peak = 0.0;            // max / mean over positions, averaged over the slopes
  double standard_error = 0.0;  // of `contrast`, from 16 batches of 256 positions
};

// sdf(slope, uv) at 4,096 random positions for each of 4 slopes.
Contrast contrast_of(const std::function<double(Vec2, Vec2)>& sdf) {
  const Vec2 slopes[] = {{0.0, 0.0}, {0.1, 0.05}, {-0.2, 0.1}, {0.3, -0.25}};
  constexpr int positions = 4096, batches = 16;
  Contrast result;
  double batch_variance = 0.0;
  for (const Vec2 slope : slopes) {
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<double> values(positions);
    for (double& v : values) {
      const Vec2 uv{unit(random), unit(random)};
      v = sdf(slope, uv);
    }
    const auto contrast_of = [&](std::size_t begin, std::size_t end) {
      double sum = 0.0, sum2 = 0.0;
      for (std::size_t k = begin; k < end; ++k) {
        sum += values[k];
        sum2 += values[k] * values[k];
      }
      const double n = static_cast<double>(end - begin), mean = sum / n;
      return std::sqrt(std::max(sum2 / n - mean * mean, 0.0)) / mean;
    };
    double sum = 0.0, peak = 0.0;
    for (const double v : values) {
      sum += v;
      peak = std::max(peak, v);
    }
    result.contrast += contrast_of(0, positions) / 4.0;
    result.peak += peak / (sum / positions) / 4.0;
    std::vector<double> per_batch;
    for (int b = 0; b < batches; ++b) per_batch.push_back(contrast_of(b * positions / batches, (b + 1) * positions / batches));
    double mean = 0.0, variance = 0.0;
    for (const double c : per_batch) mean += c / batches;
    for (const double c : per_batch) variance += (c - mean) * (c - mean) / (batches - 1);
    batch_variance += variance / batches / 16.0;  // variance of the mean of 4 slopes
  }
  result.standard_error = std::sqrt(batch_variance);
  return result;
}

constexpr double kAuthorsLogDensity = 27.0;  // the authors' default ln density
constexpr double kAuthorsAlpha = 0.5;        // the authors' default material (and alpha_dict)

Contrast glint_contrast(const g::Dictionary& dictionary, Vec2 duv_dx, Vec2 duv_dy, double log_density = kAuthorsLogDensity) {
  const g::Roughness roughness{kAuthorsAlpha, kAuthorsAlpha, 0.0};
  return contrast_of([&](Vec2 slope, Vec2 uv) { return g::sdf(dictionary, slope, uv, duv_dx, duv_dy, roughness, log_density); });
}

Contrast authors_contrast(const saagen::test::authors::Lookup& lookup, const saagen::test::authors::Options& options, Vec2 duv_dx,
                          Vec2 duv_dy, double log_density = kAuthorsLogDensity) {
  return contrast_of([&](Vec2 slope, Vec2 uv) {
    return saagen::test::authors::sdf(lookup, options, slope, uv, duv_dx, duv_dy, kAuthorsAlpha, log_density);
  });
}

TEST(GlintContrast, AnisotropicFootprintAndDensityRandomisation) {
  const auto dictionary = saagen::test::default_reference_dictionary();
  const double size = std::exp2(-12.0);
  const Contrast isotropic = glint_contrast(dictionary, {size, 0.0}, {0.0, size});
  const Contrast anisotropic = glint_contrast(dictionary, {size, 0.0}, {0.0, size / 8.0});
  std::cout << "[ contrast ] 4096 positions, alpha 0.5, ln density 27: isotropic 2^-12: std/mean " << isotropic.contrast << " (+- "
            << isotropic.standard_error << "), peak/mean " << isotropic.peak << "; 8:1: std/mean " << anisotropic.contrast << " (+- "
            << anisotropic.standard_error << "), peak/mean " << anisotropic.peak << "\n";
  // Pinned figures (measured), within 4 standard errors of the batch estimate.
  EXPECT_NEAR(isotropic.contrast, 0.202, 4.0 * isotropic.standard_error);
  EXPECT_NEAR(anisotropic.contrast, 0.327, 4.0 * anisotropic.standard_error);
  // Above the major-axis, bilinear form of before (0.132) on both footprints; the 8:1
  // footprint sparkles more than the isotropic one, as in the authors' shader.
  EXPECT_GT(isotropic.contrast - 4.0 * isotropic.standard_error, 0.132);
  EXPECT_GT(anisotropic.contrast - 4.0 * anisotropic.standard_error, isotropic.contrast + 4.0 * isotropic.standard_error);
  EXPECT_GT(anisotropic.peak, isotropic.peak);
}

// |a - b| in units of their combined standard error.
double separation(const Contrast& a, const Contrast& b) {
  return std::fabs(a.contrast - b.contrast) / std::hypot(a.standard_error, b.standard_error);
}

// The authors' dictionary algorithm (glint_authors.hpp) with saagen's default seed, as the
// authors' evaluation reads it and in saagen's texture layout.
struct AuthorsDictionary {
  saagen::test::authors::Dictionary values = saagen::test::authors::generate_dictionary(2021);
  g::Texture1DArray texture = saagen::test::authors::as_saagen_texture(values);
  saagen::test::authors::Lookup lookup = saagen::test::authors::texture_lookup(values);
  g::Dictionary in_saagen() const {
    g::Dictionary dictionary;
    dictionary.texture = &texture;
    return dictionary;
  }
};
const AuthorsDictionary& authors_dictionary() {
  static const AuthorsDictionary dictionary;
  return dictionary;
}

// The authors' dictionary algorithm and evaluation against saagen's (docs/GLINTS.md section 6).
// At the footprints above, crossed: saagen's evaluation (the reference, which the snippet matches
// on the GPU) on the authors' dictionary, the authors' evaluation on saagen's, and the authors'
// evaluation and dictionary on saagen's cell grid (one microfacet per level-0 cell instead of 2^15
// level-0 cells per unit uv: at ln density 27 and a 2^-12 footprint their pyramid's level is 3.0,
// saagen's 7.48). Then over an octave of footprints, 2^(-12 + q / 8) for q = 0..7: each grid's
// contrast peaks where its level blend weight is 0 (saagen's at q = 4, the authors' at q = 0), so
// the mean over the octave compares the two without the grids' phase.
// SAAGEN_GLINT_CONTRAST_SWEEP=1 adds the crossed columns to the octave (a minute of CPU).
TEST(GlintContrast, AgainstTheAuthorsDictionaryAndEvaluation) {
  namespace authors = saagen::test::authors;
  const bool crossed_octave = std::getenv("SAAGEN_GLINT_CONTRAST_SWEEP") != nullptr;
  const auto saagen_dictionary = saagen::test::default_reference_dictionary();
  const AuthorsDictionary& theirs = authors_dictionary();
  const authors::Lookup saagen_lookup = authors::saagen_lookup(saagen_dictionary);
  const authors::Options their_grid;
  authors::Options saagen_grid;
  saagen_grid.grid_log2 = kAuthorsLogDensity / (2.0 * std::log(2.0));
  for (const double anisotropy : {1.0, 8.0}) {
    std::array<double, 4> mean{};
    for (int q = 0; q < 8; ++q) {
      const double size = std::exp2(-12.0 + q / 8.0);
      const Vec2 dx{size, 0.0}, dy{0.0, size / anisotropy};
      const Contrast saagen = glint_contrast(saagen_dictionary, dx, dy);
      const Contrast authors = authors_contrast(theirs.lookup, their_grid, dx, dy);
      const bool crossed = q == 0 || crossed_octave;
      const Contrast saagen_on_authors = crossed ? glint_contrast(theirs.in_saagen(), dx, dy) : Contrast{};
      const Contrast authors_on_saagen = crossed ? authors_contrast(saagen_lookup, their_grid, dx, dy) : Contrast{};
      std::cout << "[ contrast ] 2^(-12 + " << q << "/8) " << anisotropy << ":1: saagen " << saagen.contrast << " (+- "
                << saagen.standard_error << "), authors " << authors.contrast << " (+- " << authors.standard_error << ")";
      if (crossed) {
        std::cout << ", saagen on the authors' dictionary " << saagen_on_authors.contrast << " (+- " << saagen_on_authors.standard_error
                  << "), authors on saagen's dictionary " << authors_on_saagen.contrast << " (+- " << authors_on_saagen.standard_error
                  << ")";
      }
      if (q == 0) {
        const Contrast authors_on_saagen_grid = authors_contrast(theirs.lookup, saagen_grid, dx, dy);
        std::cout << ", authors on saagen's cell grid " << authors_on_saagen_grid.contrast << " (+- "
                  << authors_on_saagen_grid.standard_error << ")";
        // The dictionaries: swapping them moves either evaluation by less than 5 %.
        EXPECT_NEAR(saagen_on_authors.contrast, saagen.contrast, 0.05 * saagen.contrast) << anisotropy;
        EXPECT_NEAR(authors_on_saagen.contrast, authors.contrast, 0.05 * authors.contrast) << anisotropy;
        // The evaluations on the same dictionary and cell grid agree within 4 standard errors.
        EXPECT_LT(separation(authors_on_saagen_grid, saagen_on_authors), 4.0) << anisotropy;
        // The gap at this footprint is the grid: on saagen's, the authors' contrast drops by more
        // than 4 standard errors.
        EXPECT_GT(authors.contrast - authors_on_saagen_grid.contrast,
                  4.0 * std::hypot(authors.standard_error, authors_on_saagen_grid.standard_error))
            << anisotropy;
      }
      std::cout << "\n";
      const std::array<double, 4> c = {saagen.contrast, authors.contrast, saagen_on_authors.contrast, authors_on_saagen.contrast};
      for (std::size_t k = 0; k < 4; ++k) mean[k] += c[k] / 8.0;
    }
    std::cout << "[ contrast ] mean over the octave, " << anisotropy << ":1: saagen " << mean[0] << ", authors " << mean[1];
    if (crossed_octave) std::cout << ", saagen on the authors' dictionary " << mean[2] << ", authors on saagen's dictionary " << mean[3];
    std::cout << " (saagen " << 100.0 * (mean[0] / mean[1] - 1.0) << " %)\n";
    // Within 5 % of the authors over the octave.
    EXPECT_NEAR(mean[0], mean[1], 0.05 * mean[1]) << anisotropy;
  }
}

// ---------------------------------------------------------------------------------------------
// Energy: every filtered 1D lookup and the filtered patch SDF integrate to 1 (2021 Sec. 7).

// The texture levels in double (before half rounding), as the reference sampler's input.
g::Texture1DArray double_texture() {
  g::Texture1DArray texture;
  const auto& p = saagen::test::default_dictionary().params;
  texture.width = p.resolution;
  texture.layers = p.lods * p.count / 4;
  texture.levels = saagen::glints::dictionary_levels(saagen::test::default_dictionary(), true);
  return texture;
}

// Trapezoidal rule over u in [-1, 1] with step 1/128: exact for the piecewise-linear
// reconstruction, whose breakpoints (texel centres of every level) lie on the grid.
double integral_over_u(const g::Texture1DArray& texture, int layer, int channel, double gradient, g::LodModel model) {
  const int steps = 2 * 2 * texture.width;
  double sum = 0.0;
  for (int k = 0; k <= steps; ++k) {
    const double u = -1.0 + 2.0 * k / steps;
    const double v = g::texture_grad(texture, u, layer, gradient, 0.3 * gradient, model)[static_cast<std::size_t>(channel)];
    sum += (k == 0 || k == steps ? 0.5 : 1.0) * v;
  }
  return sum * 2.0 / steps;
}

TEST(GlintEnergy, EveryFilteredDistributionIntegratesToOne) {
  const auto exact_texture = double_texture();
  const auto& half_texture = saagen::test::default_reference_texture();
  const double range = saagen::test::default_dictionary().params.range();
  double worst_exact = 0.0, worst_half = 0.0;
  for (int layer = 0; layer < exact_texture.layers; layer += 17) {
    for (double lambda : {-3.0, 0.0, 0.3, 1.5, 2.71, 4.2, 5.5, 6.0, 9.0}) {
      const double gradient = std::exp2(lambda) / exact_texture.width;
      for (int channel = 0; channel < 4; ++channel) {
        for (auto model : {g::LodModel::exact, g::LodModel::lavapipe}) {
          // density in x: integral over x = range * integral over u
          worst_exact = std::max(worst_exact, std::fabs(range * integral_over_u(exact_texture, layer, channel, gradient, model) - 1.0));
          worst_half = std::max(worst_half, std::fabs(range * integral_over_u(half_texture, layer, channel, gradient, model) - 1.0));
        }
      }
    }
  }
  std::cout << "[ energy   ] filtered 1D distributions (45 layers x 4 channels x 9 LODs x 2 LOD models): max |integral - 1| = "
            << worst_exact << " (double texels), " << worst_half << " (half texels)\n";
  EXPECT_LT(worst_exact, 1e-12);
  EXPECT_LT(worst_half, 5e-4);
}

struct Footprint {
  Vec2 uv;
  Vec2 duv_dx, duv_dy;
  double log_density;
  Vec2 dh_dx, dh_dy;  // for GGAA
  g::Roughness roughness;
};

// Midpoint rule over slope space (the caller picks a step well below the narrowest lobe's
// standard deviation in slope space). Returns the mass and the second moments.
std::pair<double, Sym2> integrate_sdf(const g::Dictionary& dictionary, const Footprint& f, bool filtered, double step) {
  const auto patch = g::make_patch(dictionary, f.uv, f.duv_dx, f.duv_dy, f.log_density);
  const double range = g::dictionary_range(dictionary.params) * std::sqrt(2.0) / dictionary.params.alpha_dict;
  const double ex = range * f.roughness.alpha_x * (std::sqrt(1.0 - f.roughness.rho * f.roughness.rho) + std::fabs(f.roughness.rho));
  const double ey = range * f.roughness.alpha_y;
  const int nx = static_cast<int>(std::ceil(ex / step)), ny = static_cast<int>(std::ceil(ey / step));
  double mass = 0.0;
  Sym2 second;
  for (int b = -ny; b < ny; ++b) {
    for (int a = -nx; a < nx; ++a) {
      const Vec2 m{(a + 0.5) * step, (b + 0.5) * step};
      const double p = filtered ? g::patch_sdf_filtered(dictionary, patch, m, f.dh_dx, f.dh_dy, f.roughness)
                                : g::patch_sdf(dictionary, patch, m, f.roughness);
      mass += p;
      second.xx += p * m.x * m.x;
      second.xy += p * m.x * m.y;
      second.yy += p * m.y * m.y;
    }
  }
  const double area = step * step;
  return {mass * area, Sym2{second.xx * area, second.xy * area, second.yy * area}};
}

TEST(GlintEnergy, FilteredPatchSdfIntegratesToOne) {
  const auto dictionary = saagen::test::default_reference_dictionary();
  // Footprints from one microfacet per pixel (LOD 0) to LOD 9.4, with GGAA kernels from below a
  // texel to most of the dictionary's range, and correlated roughness.
  const Footprint footprints[] = {
      {{0.31, 0.77}, {3e-4, 0.0}, {0.0, 2e-4}, 16.0, {0.0, 0.0}, {0.0, 0.0}, {0.12, 0.12, 0.0}},
      {{0.52, 0.13}, {1e-3, 4e-4}, {-2e-4, 8e-4}, 17.0, {0.02, 0.003}, {-0.004, 0.01}, {0.15, 0.1, 0.5}},
      {{0.05, 0.41}, {4e-3, 0.0}, {0.0, 4e-3}, 17.5, {0.1, 0.05}, {0.0, 0.08}, {0.1, 0.2, -0.7}},
      {{0.66, 0.66}, {2e-2, 1e-2}, {0.0, 3e-2}, 20.0, {0.4, 0.0}, {0.0, 0.3}, {0.2, 0.15, 0.3}},
  };
  double worst = 0.0;
  for (const Footprint& f : footprints) {
    for (bool filtered : {false, true}) {
      const double narrowest = 0.02 * std::min(f.roughness.alpha_x, f.roughness.alpha_y) *
                               std::sqrt(1.0 - f.roughness.rho * f.roughness.rho) / dictionary.params.alpha_dict;
      const auto [mass, second] = integrate_sdf(dictionary, f, filtered, narrowest / 4.0);
      const auto patch = g::make_patch(dictionary, f.uv, f.duv_dx, f.duv_dy, f.log_density);
      std::cout << "[ energy   ] l_P = " << patch.lod << ", roughness (" << f.roughness.alpha_x << ", " << f.roughness.alpha_y << ", rho "
                << f.roughness.rho << ")" << (filtered ? ", GGAA" : ", textureLod") << ": integral " << mass << "\n";
      worst = std::max(worst, std::fabs(mass - 1.0));
    }
  }
  // Quadrature of piecewise-linear lobes (kinks at texel centres) on a grid of 1/4 of the
  // narrowest lobe, plus the half rounding of the texels (5e-4).
  EXPECT_LT(worst, 3e-3);
}

// With a footprint at the last LOD every cell reads the Beckmann marginal, and M (Eq. 18) turns
// it into the Gaussian of covariance Sigma = [[sx^2, rho sx sy], [rho sx sy, sy^2]], sigma = alpha
// / sqrt(2): the slope correlation is reproduced (2021 Sec. 5.2, Fig. 10).
TEST(GlintModel, ConvergedSdfHasTheCovarianceOfEq16) {
  const auto dictionary = saagen::test::default_reference_dictionary();
  for (const g::Roughness roughness : {g::Roughness{0.2, 0.2, 0.0}, g::Roughness{0.25, 0.1, 0.6}, g::Roughness{0.1, 0.3, -0.9}}) {
    const Footprint f{{0.4, 0.6}, {1.0, 0.0}, {0.0, 1.0}, 40.0, {0.0, 0.0}, {0.0, 0.0}, roughness};
    const auto [mass, second] = integrate_sdf(dictionary, f, false, 0.004);
    const double sx2 = 0.5 * roughness.alpha_x * roughness.alpha_x, sy2 = 0.5 * roughness.alpha_y * roughness.alpha_y;
    const double sxy = roughness.rho * std::sqrt(sx2 * sy2);
    std::cout << "[ sigma    ] target (" << sx2 << ", " << sxy << ", " << sy2 << "), converged SDF (" << second.xx << ", " << second.xy
              << ", " << second.yy << "), mass " << mass << "\n";
    // 4-sigma truncation lowers the variance by 0.11 %; quadrature and half rounding add less.
    EXPECT_NEAR(second.xx / sx2, 1.0, 0.01);
    EXPECT_NEAR(second.yy / sy2, 1.0, 0.01);
    EXPECT_NEAR(second.xy, sxy, 0.01 * std::sqrt(sx2 * sy2));
  }
}

TEST(GlintModel, BrdfIsReciprocalAndZeroBelowTheHorizon) {
  const auto dictionary = saagen::test::default_reference_dictionary();
  const Vec3 i = saagen::ref::normalize(Vec3{0.3, -0.2, 0.9}), o = saagen::ref::normalize(Vec3{-0.25, 0.3, 0.8});
  const Vec2 uv{0.3, 0.4}, dx{1e-3, 0.0}, dy{0.0, 1e-3};
  const g::Roughness roughness{0.3, 0.2, 0.4};
  const double f = g::brdf(dictionary, i, o, {0.01, -0.02}, uv, dx, dy, roughness, 14.0);
  EXPECT_GT(f, 0.0);
  EXPECT_NEAR(g::brdf(dictionary, o, i, {0.01, -0.02}, uv, dx, dy, roughness, 14.0), f, 1e-12 * f);
  EXPECT_EQ(g::brdf(dictionary, Vec3{0.3, 0.0, -0.95}, o, {}, uv, dx, dy, roughness, 14.0), 0.0);
  // V-cavity: 1 at normal incidence, below 1 at grazing angles.
  EXPECT_DOUBLE_EQ(g::vcavity_g2(Vec3{0, 0, 1}, Vec3{0, 0, 1}, Vec3{0, 0, 1}), 1.0);
  const Vec3 grazing = saagen::ref::normalize(Vec3{1.0, 0.0, 0.05});
  const Vec3 h = saagen::ref::normalize(grazing + Vec3{0, 0, 1});
  EXPECT_LT(g::vcavity_g2(Vec3{0, 0, 1}, grazing, saagen::ref::normalize(Vec3{0.2, 0.0, 1.0})), 1.0);
  EXPECT_GT(g::vcavity_g2(Vec3{0, 0, 1}, grazing, h), 0.0);
}

// ---------------------------------------------------------------------------------------------
// LEAN

TEST(GlintLean, RoughnessFromMoments) {
  // A flat normal map: the material's roughness, no correlation.
  auto r = g::lean_roughness({0.2, 0.1}, {0.0, 0.0}, {0.0, 0.0, 0.0});
  EXPECT_DOUBLE_EQ(r.alpha_x, 0.2);
  EXPECT_DOUBLE_EQ(r.alpha_y, 0.1);
  EXPECT_DOUBLE_EQ(r.rho, 0.0);
  // A constant tilt: the mean moves, the covariance does not.
  r = g::lean_roughness({0.2, 0.1}, {0.3, -0.1}, {0.09, -0.03, 0.01});
  EXPECT_NEAR(r.alpha_x, 0.2, 1e-15);
  EXPECT_NEAR(r.alpha_y, 0.1, 1e-15);
  EXPECT_NEAR(r.rho, 0.0, 1e-14);
  // Slopes spread along the diagonal x = y with variance v each: correlation towards 1.
  const double v = 0.02;
  r = g::lean_roughness({0.1, 0.1}, {0.0, 0.0}, {v, v, v});
  const double total = v + 0.005;
  EXPECT_NEAR(r.alpha_x, std::sqrt(2.0 * total), 1e-15);
  EXPECT_NEAR(r.rho, v / total, 1e-15);
}

}  // namespace
