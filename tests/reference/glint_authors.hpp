// The authors' glint dictionary generator and glint evaluation, re-implemented from a reading of
// their public code (MIT): ASTex-ICube/real_time_glint_dictgenerator (`dictgenerator` in
// src/tools/imgtool.cpp) and ASTex-ICube/real_time_glint (shader/glint.frag.glsl), which number
// the steps after Chermain et al. 2020 (Alg. 1-3, Eq. 8). Written here, not copied; used only to
// separate the dictionary from the evaluation when saagen's glint contrast is compared with the
// authors' (test_glints_reference, GlintContrast.*; docs/GLINTS.md section 6).
//
// Where they differ from saagen (docs/GLINTS.md sections 1-2):
//   dictionary  lobe centres ~ N(0, sigma_o^2); texel t holds the density at the point t dx (not
//               the mean over a texel), read by the shader at u = (t + 1/2) / R (CLAMP_TO_EDGE);
//               every LOD, the last included, is a sum of 2^l lobe pairs; each LOD is divided by
//               a numerical integral (step 0.001) of its linear interpolation with t at t dx;
//               three distributions per RGB16F texel.
//   evaluation  the cell pyramid is fixed in uv: level l has 2^(L - 1 - l) cells per unit uv, and
//               a cell holds n = density 4^(l - (L - 1)) microfacets, its dictionary LOD round(log4 n
//               + 2 N(0, 1)) from an erfinv of a hashed uniform (0..L; L is the analytic Beckmann
//               SDF); the hash is Hugo Elias' integer hash (as published by Inigo Quilez) of
//               s0 + 1549 t0 times a constant per choice; theta in [0, 2 pi); the EWA loop stops
//               after 100 cells.
#pragma once

#include "support/glint_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

namespace saagen::test::authors {

namespace g = saagen::ref::glints;
using saagen::ref::Vec2;

constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------------
// Dictionary (dictgenerator)

struct Dictionary {
  int count = 192;  // N (a multiple of 3 in theirs: three per RGB texel)
  int lods = 16;
  int resolution = 64;  // their shipped dictionary's (the generator's default is 128)
  double alpha = 0.5;
  double lobe_sigma = 0.02;
  std::vector<double> values;  // [(lod * count + d) * resolution + t]

  double sigma() const { return alpha / std::sqrt(2.0); }
  double range() const { return 4.0 * sigma(); }
  double at(int lod, int d, int t) const { return values[(static_cast<std::size_t>(lod) * count + d) * resolution + t]; }
};

// SplitMix64 and Box-Muller, seeded per distribution as saagen's generator is: the centres of
// distribution d are saagen's (same seed) scaled by sigma_o / sqrt(sigma_o^2 - lobe^2), so the
// two dictionaries differ by their construction only. (The authors draw with
// std::default_random_engine, whose normals are implementation-defined: their draws cannot be
// reproduced.)
class Normals {
 public:
  explicit Normals(std::uint64_t seed) : state_(seed) {}
  double next() {
    const double u1 = 1.0 - uniform(), u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
  }
  static std::uint64_t mix(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }

 private:
  double uniform() {
    state_ += 0x9e3779b97f4a7c15ULL;
    return static_cast<double>(mix(state_) >> 11) * 0x1.0p-53;
  }
  std::uint64_t state_;
};

// Adds the Gaussian N(centre, s^2) sampled at the points t dx (|t dx - centre| < 8 s: the rest is
// below e^-32 of the peak) to acc.
inline void add_point_lobe(std::vector<double>& acc, double dx, double centre, double s) {
  const int size = static_cast<int>(acc.size());
  const int first = std::max(0, static_cast<int>(std::ceil((centre - 8.0 * s) / dx)));
  const int last = std::min(size - 1, static_cast<int>(std::floor((centre + 8.0 * s) / dx)));
  for (int t = first; t <= last; ++t) {
    const double z = (t * dx - centre) / s;
    acc[static_cast<std::size_t>(t)] += std::exp(-0.5 * z * z) / (s * std::sqrt(2.0 * kPi));
  }
}

// Their normalisation: the integral over x in [-x_max, x_max] in steps of 0.001 of the linear
// interpolation of the texels placed at t dx (indices clamped).
inline double numerical_integral(const std::vector<double>& texels, double range) {
  const int size = static_cast<int>(texels.size());
  const double step = 0.001;
  double sum = 0.0;
  for (int k = 0;; ++k) {
    const double x = -range + k * step;
    if (x > range) break;
    const double s = std::fabs(x) / range * size;
    const int s0 = static_cast<int>(std::floor(s));
    const double f = s - s0;
    sum += ((1.0 - f) * texels[static_cast<std::size_t>(std::clamp(s0, 0, size - 1))] +
            f * texels[static_cast<std::size_t>(std::clamp(s0 + 1, 0, size - 1))]) *
           step;
  }
  return sum;
}

inline Dictionary generate_dictionary(std::uint64_t seed = 2021) {
  Dictionary dictionary;
  const int n = dictionary.count, lods = dictionary.lods, r = dictionary.resolution;
  dictionary.values.assign(static_cast<std::size_t>(lods) * n * r, 0.0);
  const double dx = dictionary.range() / r;
  for (int d = 0; d < n; ++d) {
    Normals normals(Normals::mix(seed ^ Normals::mix(static_cast<std::uint64_t>(d) + 1)));
    std::vector<double> sum(static_cast<std::size_t>(r), 0.0);
    std::vector<double> lod_values(static_cast<std::size_t>(r));
    std::uint64_t pairs = 0;
    for (int lod = 0; lod < lods; ++lod) {
      for (; pairs < (std::uint64_t{1} << lod); ++pairs) {  // LOD l: the first 2^l pairs
        const double mu = dictionary.sigma() * normals.next();
        add_point_lobe(sum, dx, mu, dictionary.lobe_sigma);
        add_point_lobe(sum, dx, -mu, dictionary.lobe_sigma);
      }
      for (int t = 0; t < r; ++t) lod_values[static_cast<std::size_t>(t)] = sum[static_cast<std::size_t>(t)] / (2.0 * pairs);
      const double integral = numerical_integral(lod_values, dictionary.range());
      for (int t = 0; t < r; ++t) dictionary.values[(static_cast<std::size_t>(lod) * n + d) * r + t] = lod_values[t] / integral;
    }
  }
  return dictionary;
}

// The same values in saagen's texture layout (four per RGBA texel, saagen's MIP chain, half
// texels): what saagen's snippet samples when it is given the authors' dictionary.
inline g::Texture1DArray as_saagen_texture(const Dictionary& dictionary) {
  glints::Dictionary transplanted;
  transplanted.params.count = dictionary.count;
  transplanted.params.lods = dictionary.lods;
  transplanted.params.resolution = dictionary.resolution;
  transplanted.params.alpha = dictionary.alpha;
  transplanted.values = dictionary.values;
  return reference_texture(glints::dictionary_texture(transplanted, true));
}

// ---------------------------------------------------------------------------------------------
// Evaluation (glint.frag.glsl: f_P, P22__P_, P22_theta_alpha), without GGAA

// A dictionary as the evaluation reads it: distribution d of LOD `lod` at |x| (x in slope units).
using Lookup = std::function<double(int d, int lod, double abs_x)>;

// Their texture: RGB16F, LINEAR, CLAMP_TO_EDGE, no MIPs; texel t is read at u = (t + 1/2) / R.
inline Lookup texture_lookup(const Dictionary& dictionary) {
  return [&dictionary](int d, int lod, double abs_x) {
    const double p = abs_x / dictionary.range() * dictionary.resolution - 0.5;
    const int t0 = static_cast<int>(std::floor(p));
    const double f = p - t0;
    const auto texel = [&](int t) {
      return glints::from_half(glints::to_half(dictionary.at(lod, d, std::clamp(t, 0, dictionary.resolution - 1))));
    };
    return (1.0 - f) * texel(t0) + f * texel(t0 + 1);
  };
}

// saagen's dictionary through the reference sampler (textureLod at mip 0).
inline Lookup saagen_lookup(const g::Dictionary& dictionary) {
  return [&dictionary](int d, int lod, double abs_x) { return g::dictionary_lod_value(dictionary, abs_x, d, lod); };
}

struct Options {
  int count = 192;
  int lods = 16;
  double alpha_dict = 0.5;
  double max_anisotropy = 8.0;
  double relative_area = 1.0;
  // log2 of the level-0 cells per unit uv: theirs is L - 1 (Dictionary.Pyramid0Size = 2^15).
  // log_density / (2 ln 2) puts one microfacet in a level-0 cell: saagen's grid (section 1).
  double grid_log2 = 15.0;
};

// Hugo Elias' integer hash to [0, 1], 32-bit wrapping.
inline double hash_iq(std::uint32_t n) {
  n = (n << 13U) ^ n;
  n = n * (n * n * 15731U + 789221U) + 1376312589U;
  return static_cast<double>(n & 0x7fffffffU) / static_cast<double>(0x7fffffffU);
}

// Giles' single-precision erfinv approximation (their shader's).
inline double erfinv(double x) {
  double w = -std::log((1.0 - x) * (1.0 + x)), p;
  if (w < 5.0) {
    w -= 2.5;
    p = 2.81022636e-08;
    for (double c :
         {3.43273939e-07, -3.5233877e-06, -4.39150654e-06, 0.00021858087, -0.00125372503, -0.00417768164, 0.246640727, 1.50140941})
      p = c + p * w;
  } else {
    w = std::sqrt(w) - 3.0;
    p = -0.000200214257;
    for (double c : {0.000100950558, 0.00134934322, -0.00367342844, 0.00573950773, -0.0076224613, 0.00943887047, 1.00167406, 2.83297682})
      p = c + p * w;
  }
  return p * x;
}

inline double beckmann_p22(Vec2 slope, double alpha) {
  const double s = alpha / std::sqrt(2.0);
  return std::exp(-0.5 * (slope.x * slope.x + slope.y * slope.y) / (s * s)) / (2.0 * kPi * s * s);
}

// One cell (Alg. 3), isotropic material roughness alpha.
inline double cell_sdf(const Lookup& lookup, const Options& o, Vec2 slope, int level, int i, int j, double alpha, double log_density) {
  const std::uint32_t seed = static_cast<std::uint32_t>(i * (1 << level)) + 1549u * static_cast<std::uint32_t>(j * (1 << level));
  if (hash_iq(seed * 13u) > o.relative_area) return 0.0;
  const double microfacets = std::exp2(2.0 * level - 2.0 * o.grid_log2) * std::exp(log_density);
  const double lod_continuous =
      std::log(microfacets) / (2.0 * std::log(2.0)) + 2.0 * std::sqrt(2.0) * erfinv(2.0 * hash_iq(seed * 2171u) - 1.0);
  const int lod = std::clamp(static_cast<int>(std::round(lod_continuous)), 0, o.lods);
  if (lod == o.lods) return beckmann_p22(slope, alpha);
  const double theta = 2.0 * kPi * hash_iq(seed), c = std::cos(theta), s = std::sin(theta);
  const double scale = alpha / o.alpha_dict, range = 2.0 * std::sqrt(2.0) * o.alpha_dict;
  const Vec2 h{(slope.x * c + slope.y * s) / scale, (-slope.x * s + slope.y * c) / scale};
  if (std::fabs(h.x) > range || std::fabs(h.y) > range) return 0.0;
  const int dx = static_cast<int>(hash_iq(seed * 16807u) * o.count), dy = static_cast<int>(hash_iq(seed * 48271u) * o.count);
  return lookup(dx, lod, std::fabs(h.x)) * lookup(dy, lod, std::fabs(h.y)) / (scale * scale);
}

// The cells of one level under the footprint (Alg. 2: pbrt-v3's EWA loop).
inline double level_sdf(const Lookup& lookup, const Options& o, int level, Vec2 slope, Vec2 uv, Vec2 d0, Vec2 d1, double alpha,
                        double log_density) {
  const double cells = std::exp2(o.grid_log2 - level);
  const Vec2 st{uv.x * cells - 0.5, uv.y * cells - 0.5};
  d0 = {d0.x * cells, d0.y * cells};
  d1 = {d1.x * cells, d1.y * cells};
  double a = d0.y * d0.y + d1.y * d1.y + 1.0, b = -2.0 * (d0.x * d0.y + d1.x * d1.y), c = d0.x * d0.x + d1.x * d1.x + 1.0;
  const double inv_f = 1.0 / (a * c - 0.25 * b * b);
  a *= inv_f;
  b *= inv_f;
  c *= inv_f;
  const double det = 4.0 * a * c - b * b, reach_s = 2.0 * std::sqrt(det * c) / det, reach_t = 2.0 * std::sqrt(a * det) / det;
  double sum = 0.0, weights = 0.0;
  int visited = 0;
  for (int t = static_cast<int>(std::ceil(st.y - reach_t)); t <= static_cast<int>(std::floor(st.y + reach_t)) && visited <= 100; ++t) {
    for (int s = static_cast<int>(std::ceil(st.x - reach_s)); s <= static_cast<int>(std::floor(st.x + reach_s)) && visited <= 100; ++s) {
      const double ds = s - st.x, dt = t - st.y, r2 = a * ds * ds + b * ds * dt + c * dt * dt;
      if (r2 < 1.0) {
        const double w = std::exp(-2.0 * r2) - std::exp(-2.0);
        sum += w * cell_sdf(lookup, o, slope, level, s, t, alpha, log_density);
        weights += w;
      }
      ++visited;
    }
  }
  return sum / weights;
}

// The patch SDF (Alg. 1): the footprint's minor axis (clamped to 1 / max_anisotropy of the
// major) picks the level l = max(0, grid_log2 + log2 |minor|); levels floor(l) and floor(l) + 1
// are blended by frac(l).
inline double sdf(const Lookup& lookup, const Options& o, Vec2 slope, Vec2 uv, Vec2 duv_dx, Vec2 duv_dy, double alpha, double log_density) {
  Vec2 major = duv_dx, minor = duv_dy;
  if (major.x * major.x + major.y * major.y < minor.x * minor.x + minor.y * minor.y) std::swap(major, minor);
  const double major_length = std::hypot(major.x, major.y);
  double minor_length = std::hypot(minor.x, minor.y);
  if (minor_length * o.max_anisotropy < major_length && minor_length > 0.0) {
    const double scale = major_length / (minor_length * o.max_anisotropy);
    minor = {minor.x * scale, minor.y * scale};
    minor_length *= scale;
  }
  const double l = std::max(0.0, o.grid_log2 + std::log2(minor_length));
  const int level = static_cast<int>(std::floor(l));
  const double w = l - level;
  const double fine = level_sdf(lookup, o, level, slope, uv, major, minor, alpha, log_density);
  return w == 0.0 ? fine : (1.0 - w) * fine + w * level_sdf(lookup, o, level + 1, slope, uv, major, minor, alpha, log_density);
}

}  // namespace saagen::test::authors
