// The glint dictionary (Chermain et al. 2020 / 2021), its MIP chain, the KTX2 file it is
// written to, and the LEAN moment chains. CPU only. docs/GLINTS.md states the tolerances used here.
#include "support/glint_support.hpp"

#include "saagen/error.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>

namespace {

namespace glints = saagen::glints;
using saagen::test::default_dictionary;
using saagen::test::default_texture;

double gaussian(double x, double sigma) { return std::exp(-0.5 * x * x / (sigma * sigma)) / (sigma * std::sqrt(2.0 * M_PI)); }

TEST(GlintDictionary, IsDeterministicForASeed) {
  glints::DictionaryParams params;
  params.count = 8;
  params.lods = 8;
  const auto first = glints::generate_dictionary(params);
  const auto second = glints::generate_dictionary(params);
  EXPECT_EQ(first.values, second.values);
  params.seed += 1;
  const auto other = glints::generate_dictionary(params);
  EXPECT_NE(first.values, other.values);
  // The last LOD does not depend on the seed: it is the Beckmann marginal.
  for (int d = 0; d < params.count; ++d) {
    for (int x = 0; x < params.resolution; ++x) EXPECT_EQ(first.density(params.lods - 1, d, x), other.density(params.lods - 1, d, x));
  }
}

// Lobes are stored narrower by the variance that the texel mean (dx^2 / 12) and the sampler's
// linear interpolation (dx^2 / 6) add, so that the texture reads back lobes of lobe_sigma
// (docs/GLINTS.md section 1): measured on LOD 0 (one lobe pair) as the standard deviation of the
// linear interpolation between texel centres around each lobe that lies 6 sigma inside (0, x_max).
TEST(GlintDictionary, LobesReadBackWithTheModelsWidth) {
  glints::DictionaryParams params;
  params.count = 32;
  params.lods = 2;
  const double dx = params.range() / params.resolution;
  EXPECT_DOUBLE_EQ(params.stored_lobe_sigma(), std::sqrt(params.lobe_sigma * params.lobe_sigma - dx * dx / 4.0));
  const auto dictionary = glints::generate_dictionary(params);
  const auto read = [&](int d, double x) {  // linear between texel centres, flat beyond the first and last
    const double p = std::clamp(x / dx - 0.5, 0.0, params.resolution - 1.0);
    const int t = std::min(static_cast<int>(p), params.resolution - 2);
    return (1.0 - (p - t)) * dictionary.density(0, d, t) + (p - t) * dictionary.density(0, d, t + 1);
  };
  int lobes = 0;
  double worst = 0.0;
  for (int d = 0; d < params.count; ++d) {
    double mass = 0.0, first = 0.0;
    const double step = dx / 64.0;
    for (double x = 0.5 * step; x < params.range(); x += step) {
      mass += read(d, x) * step;
      first += x * read(d, x) * step;
    }
    const double centre = first / mass, reach = 6.0 * params.lobe_sigma;
    if (centre < reach || centre > params.range() - reach) continue;
    double m0 = 0.0, m1 = 0.0, m2 = 0.0;
    for (double x = centre - reach + 0.5 * step; x < centre + reach; x += step) {
      const double v = read(d, x) * step;
      m0 += v;
      m1 += x * v;
      m2 += x * x * v;
    }
    const double sigma = std::sqrt(m2 / m0 - (m1 / m0) * (m1 / m0));
    worst = std::max(worst, std::fabs(sigma / params.lobe_sigma - 1.0));
    ++lobes;
  }
  std::cout << "[ lobes    ] " << lobes << " LOD-0 lobes read back with sigma within " << worst << " (relative) of " << params.lobe_sigma
            << "; stored with " << params.stored_lobe_sigma() << "\n";
  ASSERT_GE(lobes, 8);
  EXPECT_LT(worst, 0.01);  // without the correction: sqrt(1 + dx^2 / (4 sigma^2)) - 1 = 14 %
  // A texel wider than 2 lobe sigmas holds each lobe as its box; every distribution still
  // integrates to 1.
  params.resolution = 8;
  EXPECT_EQ(params.stored_lobe_sigma(), 0.0);
  const auto coarse = glints::generate_dictionary(params);
  const double coarse_dx = params.range() / params.resolution;
  for (int d = 0; d < params.count; ++d) {
    double sum = 0.0;
    for (int x = 0; x < params.resolution; ++x) sum += coarse.density(0, d, x);
    EXPECT_NEAR(2.0 * coarse_dx * sum, 1.0, 1e-12) << d;
  }
}

// Every single-scale distribution integrates to 1 over [-x_max, x_max]: exactly in double, and
// within the rounding of the stored halves (relative 2^-11 per texel).
TEST(GlintDictionary, EveryDistributionIntegratesToOne) {
  const auto& dictionary = default_dictionary();
  const auto& p = dictionary.params;
  const double dx = p.range() / p.resolution;
  double worst_double = 0.0, worst_half = 0.0;
  const auto& texture = default_texture();
  for (int lod = 0; lod < p.lods; ++lod) {
    for (int d = 0; d < p.count; ++d) {
      double sum = 0.0, sum_half = 0.0;
      const int layer = lod * p.count / 4 + d / 4;
      for (int x = 0; x < p.resolution; ++x) {
        sum += dictionary.density(lod, d, x);
        sum_half += glints::from_half(texture.levels[0][(static_cast<std::size_t>(layer) * p.resolution + x) * 4 + d % 4]);
      }
      worst_double = std::max(worst_double, std::fabs(2.0 * dx * sum - 1.0));
      worst_half = std::max(worst_half, std::fabs(2.0 * dx * sum_half - 1.0));
    }
  }
  std::cout << "[ energy   ] max |integral - 1| over " << p.lods * p.count << " distributions: double " << worst_double
            << ", stored halves " << worst_half << "\n";
  EXPECT_LT(worst_double, 1e-12);
  EXPECT_LT(worst_half, 5e-4);  // 2^-11 relative per texel, errors of both signs
}

// The coarsest LOD is the Beckmann marginal of alpha_dict: a Gaussian of sigma_o = alpha / sqrt(2).
TEST(GlintDictionary, CoarsestLodIsTheBeckmannMarginal) {
  const auto& dictionary = default_dictionary();
  const auto& p = dictionary.params;
  const double sigma = p.alpha / std::sqrt(2.0), dx = p.range() / p.resolution;
  const double peak = gaussian(0.0, sigma);
  double worst = 0.0;
  for (int d = 0; d < p.count; ++d) {
    for (int x = 0; x < p.resolution; ++x) {
      const double centre = (x + 0.5) * dx;
      worst = std::max(worst, std::fabs(dictionary.density(p.lods - 1, d, x) - gaussian(centre, sigma)) / peak);
    }
  }
  std::cout << "[ beckmann ] last LOD vs the Beckmann marginal N(0, " << sigma << "^2) at texel centres: max error " << worst
            << " of the peak\n";
  // Texels hold the mean over the texel, not the value at its centre: the difference is
  // dx^2 / 24 |g''| <= dx^2 / (24 sigma^2) g(0) = 1.6e-4 of the peak; the 4-sigma truncation
  // renormalises by 1 + 6.3e-5.
  EXPECT_LT(worst, 3e-4);
}

// The LODs have 2^l lobes and their variance tends to sigma_o^2 (lobe centres drawn from
// N(0, sigma_o^2 - sigma_lobe^2)).
TEST(GlintDictionary, LodsConvergeToTheTargetVariance) {
  const auto& dictionary = default_dictionary();
  const auto& p = dictionary.params;
  const double sigma2 = 0.5 * p.alpha * p.alpha, dx = p.range() / p.resolution;
  for (int lod = 0; lod < p.lods; ++lod) {
    double mean_variance = 0.0;
    for (int d = 0; d < p.count; ++d) {
      double variance = 0.0;
      for (int x = 0; x < p.resolution; ++x) {
        const double a = x * dx, b = (x + 1) * dx;
        variance += 2.0 * dictionary.density(lod, d, x) * (b * b * b - a * a * a) / 3.0;  // exact for piecewise constant
      }
      mean_variance += variance / p.count;
    }
    if (lod >= 8) {
      EXPECT_NEAR(mean_variance / sigma2, 1.0, 0.02) << "LOD " << lod;
    }
    if (lod == 0 || lod == 4 || lod >= 8) {
      std::cout << "[ variance ] LOD " << lod << ": mean variance / sigma_o^2 = " << mean_variance / sigma2 << "\n";
    }
  }
}

TEST(GlintDictionary, MipChainIsABoxFilterThatKeepsTheSum) {
  const auto levels = glints::dictionary_levels(default_dictionary(), true);
  const auto& p = default_dictionary().params;
  ASSERT_EQ(levels.size(), 7u);  // 64, 32, ..., 1
  const int layers = p.lods * p.count / 4;
  for (std::size_t m = 1; m < levels.size(); ++m) {
    const int width = p.resolution >> m;
    ASSERT_EQ(levels[m].size(), static_cast<std::size_t>(layers) * width * 4);
    for (int layer = 0; layer < layers; layer += 37) {
      for (int c = 0; c < 4; ++c) {
        double fine = 0.0, coarse = 0.0;
        for (int x = 0; x < 2 * width; ++x) fine += levels[m - 1][(static_cast<std::size_t>(layer) * 2 * width + x) * 4 + c];
        for (int x = 0; x < width; ++x) coarse += levels[m][(static_cast<std::size_t>(layer) * width + x) * 4 + c];
        // sum * texel width is the same on every level (texel width doubles)
        EXPECT_NEAR(2.0 * coarse, fine, 1e-12 * fine);
      }
    }
  }
}

// Paper: 192 x 16 x 64 half floats = 384 KiB; "one third more with MIP maps, 512 KiB". The
// payload matches; a 1D chain of 64 texels holds 64 + 32 + ... + 1 = 127 texels (+98.4 %), so
// the MIP-mapped texture is 762 KiB (the 4/3 factor is that of 2D pyramids).
TEST(GlintDictionary, MemoryWithAndWithoutMips) {
  const auto& dictionary = default_dictionary();
  const auto without = glints::dictionary_texture(dictionary, false);
  const auto& with = default_texture();
  EXPECT_EQ(without.width, 64u);
  EXPECT_EQ(without.layers, 16u * 192u / 4u);
  EXPECT_EQ(without.levels.size(), 1u);
  EXPECT_EQ(glints::texture_bytes(without), 384u * 1024u);
  EXPECT_EQ(with.levels.size(), 7u);
  EXPECT_EQ(glints::texture_bytes(with), 192u * 16u * 127u * 2u);
  std::cout << "[ memory   ] dictionary without mips " << glints::texture_bytes(without) / 1024.0 << " KiB, with mips "
            << glints::texture_bytes(with) / 1024.0 << " KiB (+"
            << 100.0 * (glints::texture_bytes(with) / double(glints::texture_bytes(without)) - 1.0)
            << " %); the paper's 512 KiB assumes +1/3\n";
}

TEST(GlintHalf, RoundTripsEveryHalfAndRoundsToNearestEven) {
  for (std::uint32_t bits = 0; bits < 0x10000u; ++bits) {
    const double value = glints::from_half(static_cast<std::uint16_t>(bits));
    if (std::isnan(value)) continue;
    ASSERT_EQ(glints::to_half(value), bits) << bits;
  }
  EXPECT_EQ(glints::to_half(1.0 + std::ldexp(1.0, -11)), 0x3c00u);      // tie -> even (down)
  EXPECT_EQ(glints::to_half(1.0 + 3 * std::ldexp(1.0, -11)), 0x3c02u);  // tie -> even (up)
  EXPECT_EQ(glints::to_half(65519.0), 0x7bffu);
  EXPECT_EQ(glints::to_half(65520.0), 0x7c00u);
  EXPECT_EQ(glints::to_half(std::ldexp(1.0, -25)), 0x0000u);  // tie -> even (zero)
  EXPECT_EQ(glints::to_half(std::ldexp(1.5, -25)), 0x0001u);
}

// ---------------------------------------------------------------------------------------------
// KTX2

std::uint32_t u32_at(const std::vector<std::uint8_t>& bytes, std::size_t at) {
  return bytes[at] | (bytes[at + 1] << 8) | (bytes[at + 2] << 16) | (static_cast<std::uint32_t>(bytes[at + 3]) << 24);
}
std::uint64_t u64_at(const std::vector<std::uint8_t>& bytes, std::size_t at) {
  return u32_at(bytes, at) | (static_cast<std::uint64_t>(u32_at(bytes, at + 4)) << 32);
}

TEST(GlintKtx2, DictionaryFileHasTheSpecLayoutAndReadsBack) {
  const auto& texture = default_texture();
  const auto image = glints::dictionary_ktx2(texture, default_dictionary().params);
  const auto bytes = saagen::write_ktx2(image);
  // Identifier and header fields at the offsets of the KTX 2.0 specification.
  const std::uint8_t identifier[12] = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
  EXPECT_TRUE(std::equal(identifier, identifier + 12, bytes.begin()));
  EXPECT_EQ(u32_at(bytes, 12), 97u);             // VK_FORMAT_R16G16B16A16_SFLOAT
  EXPECT_EQ(u32_at(bytes, 16), 2u);              // typeSize
  EXPECT_EQ(u32_at(bytes, 20), 64u);             // pixelWidth
  EXPECT_EQ(u32_at(bytes, 24), 0u);              // pixelHeight: 1D
  EXPECT_EQ(u32_at(bytes, 28), 0u);              // pixelDepth
  EXPECT_EQ(u32_at(bytes, 32), 768u);            // layerCount
  EXPECT_EQ(u32_at(bytes, 36), 1u);              // faceCount
  EXPECT_EQ(u32_at(bytes, 40), 7u);              // levelCount
  EXPECT_EQ(u32_at(bytes, 44), 0u);              // no supercompression
  EXPECT_EQ(u32_at(bytes, 48), 80u + 24u * 7u);  // the DFD follows the level index
  // Levels: level 0 is the largest and is stored last; every level 8-byte aligned.
  std::uint64_t previous = 0;
  for (int level = 6; level >= 0; --level) {
    const std::uint64_t offset = u64_at(bytes, 80 + 24 * level), length = u64_at(bytes, 88 + 24 * level);
    EXPECT_EQ(offset % 8, 0u);
    EXPECT_GT(offset, previous);
    previous = offset;
    EXPECT_EQ(length, 768u * (64u >> level) * 8u);
  }
  EXPECT_EQ(previous + u64_at(bytes, 88), bytes.size());

  const auto read = saagen::read_ktx2(bytes);
  EXPECT_EQ(read.vk_format, 97u);
  EXPECT_EQ(read.width, 64u);
  EXPECT_EQ(read.layers, 768u);
  ASSERT_EQ(read.levels.size(), image.levels.size());
  for (std::size_t m = 0; m < read.levels.size(); ++m) EXPECT_EQ(read.levels[m], image.levels[m]) << m;
  ASSERT_EQ(read.key_values.size(), 2u);
  EXPECT_EQ(read.key_values[0].first, "KTXwriter");
  EXPECT_EQ(read.key_values[1].first, "saagen.glints");
  const auto description = nlohmann::json::parse(read.key_values[1].second);
  EXPECT_EQ(description.at("count"), 192);
  EXPECT_EQ(description.at("lods"), 16);
  EXPECT_EQ(description.at("resolution"), 64);
  EXPECT_DOUBLE_EQ(description.at("alpha").get<double>(), 0.5);
  std::cout << "[ ktx2     ] dictionary file: " << bytes.size() << " bytes (" << bytes.size() / 1024.0 << " KiB)\n";
}

TEST(GlintKtx2, RejectsDamagedFiles) {
  glints::DictionaryParams params;
  params.count = 4;
  params.lods = 2;
  params.resolution = 8;
  const auto bytes = saagen::write_ktx2(glints::dictionary_ktx2(glints::dictionary_texture(glints::generate_dictionary(params)), params));
  EXPECT_NO_THROW(saagen::read_ktx2(bytes));
  auto truncated = bytes;
  truncated.resize(bytes.size() - 1);
  EXPECT_THROW(saagen::read_ktx2(truncated), saagen::Error);
  auto identifier = bytes;
  identifier[5] = '1';
  EXPECT_THROW(saagen::read_ktx2(identifier), saagen::Error);
  auto format = bytes;
  format[12] = 109;  // claims R32G32B32A32 with half-sized levels
  EXPECT_THROW(saagen::read_ktx2(format), saagen::Error);
}

TEST(GlintKtx2, LeanMomentsFileRoundTrips) {
  const int size = 16;
  std::vector<double> normals;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const double a = 0.3 * std::sin(0.7 * x + 0.2 * y), b = 0.2 * std::cos(0.5 * y);
      const double n = std::sqrt(1.0 + a * a + b * b);
      normals.insert(normals.end(), {-a / n, -b / n, 1.0 / n});
    }
  }
  const auto levels = glints::lean_moments(glints::slopes_from_normals(size, size, normals));
  ASSERT_EQ(levels.size(), 5u);
  const auto read = saagen::read_ktx2(saagen::write_ktx2(glints::lean_ktx2(levels)));
  EXPECT_EQ(read.vk_format, 109u);
  EXPECT_EQ(read.width, 16u);
  EXPECT_EQ(read.height, 16u);
  EXPECT_EQ(read.layers, 2u);
  ASSERT_EQ(read.levels.size(), 5u);
  EXPECT_EQ(read.levels[4].size(), 2u * 16u);
}

// ---------------------------------------------------------------------------------------------
// LEAN moment chains

TEST(GlintLean, MomentChainAveragesLevelZero) {
  const int width = 32, height = 8;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> slope(-0.5, 0.5);
  glints::SlopeMap map{width, height, {}};
  for (int t = 0; t < width * height * 2; ++t) map.slopes.push_back(slope(random));
  const auto levels = glints::lean_moments(map);
  ASSERT_EQ(levels.back().width, 1);
  ASSERT_EQ(levels.back().height, 1);
  double mean[5] = {};
  for (int t = 0; t < width * height; ++t) {
    const double x = map.slopes[2 * t], y = map.slopes[2 * t + 1];
    const double m[5] = {x, y, x * x, x * y, y * y};
    for (int k = 0; k < 5; ++k) mean[k] += m[k] / (width * height);
  }
  // 32 x 8 -> ... -> 4 x 1 -> 2 x 1 -> 1 x 1: every level is an exact average of level 0.
  for (int k = 0; k < 5; ++k) EXPECT_NEAR(levels.back().moments[k], mean[k], 1e-14);
  // Variances stay non-negative on every level (Jensen).
  for (const auto& level : levels) {
    for (int t = 0; t < level.width * level.height; ++t) {
      const double* m = &level.moments[5 * t];
      EXPECT_GE(m[2] - m[0] * m[0], -1e-15);
      EXPECT_GE(m[4] - m[1] * m[1], -1e-15);
    }
  }
}

TEST(GlintLean, ReadsBinaryPpmNormalMaps) {
  std::string ppm = "P6\n# a 2x1 normal map\n2 1\n255\n";
  ppm += std::string{static_cast<char>(128), static_cast<char>(128), static_cast<char>(255)};  // (0, 0, 1)
  ppm += std::string{static_cast<char>(255), static_cast<char>(128), static_cast<char>(255)};  // tilted towards +x
  const std::vector<std::uint8_t> bytes(ppm.begin(), ppm.end());
  const auto map = glints::slopes_from_ppm(bytes);
  ASSERT_EQ(map.width, 2);
  ASSERT_EQ(map.height, 1);
  EXPECT_NEAR(map.slopes[0], -1.0 / 255.0, 1e-9);
  EXPECT_NEAR(map.slopes[2], -1.0 / (1.0), 1e-2);  // n = (1, 0.004, 1) / |.|: slope -n.x / n.z = -1
  const std::vector<std::uint8_t> bad = {'P', '3', '\n'};
  EXPECT_THROW(glints::slopes_from_ppm(bad), saagen::Error);
}

}  // namespace
