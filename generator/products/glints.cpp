// Glints: dictionary generation, MIP chains, KTX2, LEAN moments, glint emission.
// See saagen/products/glints.hpp and docs/GLINTS.md.
#include "saagen/products/glints.hpp"

#include "saagen/error.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <map>
#include <numeric>
#include <thread>

namespace saagen {
namespace embedded_glints {
const std::map<std::string, std::string_view>& files();
}

namespace glints {
namespace {

constexpr double kSqrt2 = 1.4142135623730951;
constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------------
// Random numbers: SplitMix64 (Steele, Lea & Flood 2014) and Box-Muller.

std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

class Stream {
 public:
  explicit Stream(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    state_ += 0x9e3779b97f4a7c15ULL;
    return mix64(state_);
  }
  // Uniform in [0, 1) with 53 bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  // Standard normal: Box-Muller, the cosine branch only (one normal per two uniforms).
  double normal() {
    const double u1 = 1.0 - uniform();  // (0, 1]
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
  }

 private:
  std::uint64_t state_;
};

// Phi(b) - Phi(a) for the standard normal, a <= b, without cancellation in the tails.
double normal_mass(double a, double b) {
  if (a >= 0.0) return 0.5 * (std::erfc(a / kSqrt2) - std::erfc(b / kSqrt2));
  if (b <= 0.0) return 0.5 * (std::erfc(-b / kSqrt2) - std::erfc(-a / kSqrt2));
  return 1.0 - 0.5 * (std::erfc(-a / kSqrt2) + std::erfc(b / kSqrt2));
}

// Adds weight * (mean density of N(centre, s^2) over each texel [t dx, (t + 1) dx)) to acc; s = 0
// puts the whole weight in the texel that holds a centre x >= 0 (the last one beyond x_max).
void add_lobe(std::vector<double>& acc, double dx, double centre, double s, double weight) {
  const int size = static_cast<int>(acc.size());
  if (s == 0.0) {
    if (centre >= 0.0) acc[static_cast<std::size_t>(std::min(static_cast<int>(centre / dx), size - 1))] += weight / dx;
    return;
  }
  const double reach = 7.0 * s;
  const int first = std::max(0, static_cast<int>(std::floor((centre - reach) / dx)));
  const int last = std::min(size - 1, static_cast<int>(std::floor((centre + reach) / dx)));
  for (int t = first; t <= last; ++t) {
    acc[static_cast<std::size_t>(t)] += weight * normal_mass((t * dx - centre) / s, ((t + 1) * dx - centre) / s) / dx;
  }
}

// Stores acc normalised so that 2 sum p dx = 1 (the distribution is even).
void store_normalised(const std::vector<double>& acc, double dx, double* out) {
  const double total = 2.0 * dx * std::accumulate(acc.begin(), acc.end(), 0.0);
  for (std::size_t t = 0; t < acc.size(); ++t) out[t] = acc[t] / total;
}

bool is_power_of_two(int v) { return v > 0 && (v & (v - 1)) == 0; }

constexpr std::uint32_t kFormatRgba16Sfloat = 97;   // VK_FORMAT_R16G16B16A16_SFLOAT
constexpr std::uint32_t kFormatRgba32Sfloat = 109;  // VK_FORMAT_R32G32B32A32_SFLOAT

template <class T>
std::vector<std::uint8_t> as_bytes(const std::vector<T>& values) {
  std::vector<std::uint8_t> bytes(values.size() * sizeof(T));
  if (!values.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
  return bytes;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Dictionary

void DictionaryParams::validate() const {
  if (count < 4 || count % 4 != 0 || count > 65536)
    throw Error(fmt::format("glint dictionary: count {} must be a multiple of 4 in [4, 65536]", count));
  if (lods < 2 || lods > 20) throw Error(fmt::format("glint dictionary: lods {} must be in [2, 20]", lods));
  if (!is_power_of_two(resolution) || resolution < 2 || resolution > 4096) {
    throw Error(fmt::format("glint dictionary: resolution {} must be a power of two in [2, 4096]", resolution));
  }
  if (!(alpha > 0.0 && alpha <= 2.0)) throw Error(fmt::format("glint dictionary: alpha {} must be in (0, 2]", alpha));
  // Work and memory caps: lobes drawn (count x 2^(lods - 2)) and double values held.
  const std::uint64_t lobes = static_cast<std::uint64_t>(count) << (lods - 2);
  if (lobes > dictionary_lobe_limit) {
    throw Error(fmt::format("glint dictionary: count {} x 2^(lods - 2) = {} lobes is more than {}; lower the count or the LODs", count,
                            lobes, dictionary_lobe_limit));
  }
  const std::uint64_t values = static_cast<std::uint64_t>(count) * lods * resolution;
  if (values > dictionary_value_limit) {
    throw Error(fmt::format("glint dictionary: count x lods x resolution = {} values is more than {}; lower one of them", values,
                            dictionary_value_limit));
  }
  if (!(lobe_sigma > 0.0 && lobe_sigma < sigma())) {
    throw Error(fmt::format("glint dictionary: lobe sigma {} must be in (0, sigma_o = {})", lobe_sigma, sigma()));
  }
}

double DictionaryParams::sigma() const { return alpha / kSqrt2; }
double DictionaryParams::range() const { return 4.0 * sigma(); }

// Box-averaging a lobe over a texel adds dx^2 / 12 to its variance and the sampler's linear
// interpolation between texel centres adds dx^2 / 6 (the variance of the unit tent), so a lobe
// stored with sqrt(lobe^2 - dx^2 / 4) reads back with the model's lobe variance (docs/GLINTS.md,
// section 1). A texel wider than 2 lobe sigmas holds a lobe as its box (0).
double DictionaryParams::stored_lobe_sigma() const {
  const double dx = range() / resolution;
  return std::sqrt(std::max(lobe_sigma * lobe_sigma - 0.25 * dx * dx, 0.0));
}

Dictionary generate_dictionary(const DictionaryParams& params) {
  params.validate();
  Dictionary dictionary;
  dictionary.params = params;
  const int n = params.count, lods = params.lods, r = params.resolution;
  dictionary.values.assign(static_cast<std::size_t>(lods) * n * r, 0.0);
  const double sigma = params.sigma();
  const double dx = params.range() / r;
  // Lobe centres ~ N(0, sigma^2 - lobe^2): the mixture's variance tends to sigma^2.
  const double centre_sigma = std::sqrt(sigma * sigma - params.lobe_sigma * params.lobe_sigma);
  const double stored_sigma = params.stored_lobe_sigma();
  const std::uint64_t lobes = std::uint64_t{1} << (lods - 2);  // LOD lods - 2 has the most

  // Distributions are independent (one random stream each): threads take them in turn, and
  // the result does not depend on the thread count.
  const auto generate = [&](int d) {
    std::vector<double> acc(static_cast<std::size_t>(r), 0.0);
    Stream stream(mix64(params.seed ^ mix64(static_cast<std::uint64_t>(d) + 1)));
    int next_lod = 0;
    for (std::uint64_t j = 0; j < lobes; ++j) {
      const double mu = centre_sigma * stream.normal();
      // The symmetrised lobe (G(x - mu) + G(x + mu)) / 2, stored for x >= 0.
      add_lobe(acc, dx, mu, stored_sigma, 0.5);
      add_lobe(acc, dx, -mu, stored_sigma, 0.5);
      if (j + 1 == (std::uint64_t{1} << next_lod)) {
        store_normalised(acc, dx, &dictionary.values[(static_cast<std::size_t>(next_lod) * n + d) * r]);
        ++next_lod;
      }
    }
    // The last LOD: the Beckmann marginal, a Gaussian of standard deviation sigma_o.
    std::fill(acc.begin(), acc.end(), 0.0);
    add_lobe(acc, dx, 0.0, sigma, 1.0);
    store_normalised(acc, dx, &dictionary.values[(static_cast<std::size_t>(lods - 1) * n + d) * r]);
  };
  std::atomic<int> next{0};
  const auto worker = [&] {
    for (int d = next++; d < n; d = next++) generate(d);
  };
  const int threads = static_cast<int>(std::clamp<unsigned>(std::thread::hardware_concurrency(), 1u, 16u));
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& thread : pool) thread.join();
  return dictionary;
}

std::vector<std::vector<double>> dictionary_levels(const Dictionary& dictionary, bool mips) {
  const DictionaryParams& p = dictionary.params;
  const int groups = p.count / 4;
  const int layers = p.lods * groups;
  std::vector<std::vector<double>> levels;
  std::vector<double> base(static_cast<std::size_t>(layers) * p.resolution * 4);
  for (int lod = 0; lod < p.lods; ++lod) {
    for (int g = 0; g < groups; ++g) {
      const int layer = lod * groups + g;
      for (int x = 0; x < p.resolution; ++x) {
        for (int c = 0; c < 4; ++c) {
          base[(static_cast<std::size_t>(layer) * p.resolution + x) * 4 + c] = dictionary.density(lod, 4 * g + c, x);
        }
      }
    }
  }
  levels.push_back(std::move(base));
  for (int width = p.resolution; mips && width > 1; width /= 2) {
    const std::vector<double>& fine = levels.back();
    const int half = width / 2;
    std::vector<double> coarse(static_cast<std::size_t>(layers) * half * 4);
    for (int layer = 0; layer < layers; ++layer) {
      for (int x = 0; x < half; ++x) {
        for (int c = 0; c < 4; ++c) {
          const std::size_t a = (static_cast<std::size_t>(layer) * width + 2 * x) * 4 + c;
          coarse[(static_cast<std::size_t>(layer) * half + x) * 4 + c] = 0.5 * (fine[a] + fine[a + 4]);
        }
      }
    }
    levels.push_back(std::move(coarse));
  }
  return levels;
}

DictionaryTexture dictionary_texture(const Dictionary& dictionary, bool mips) {
  DictionaryTexture texture;
  texture.width = static_cast<std::uint32_t>(dictionary.params.resolution);
  texture.layers = static_cast<std::uint32_t>(dictionary.params.lods * dictionary.params.count / 4);
  for (const std::vector<double>& level : dictionary_levels(dictionary, mips)) {
    std::vector<std::uint16_t> halves(level.size());
    std::transform(level.begin(), level.end(), halves.begin(), [](double v) { return to_half(v); });
    texture.levels.push_back(std::move(halves));
  }
  return texture;
}

std::size_t texture_bytes(const DictionaryTexture& texture) {
  std::size_t bytes = 0;
  for (const auto& level : texture.levels) bytes += level.size() * sizeof(std::uint16_t);
  return bytes;
}

std::uint16_t to_half(double value) {
  if (std::isnan(value)) return 0x7e00;
  const std::uint16_t sign = std::signbit(value) ? 0x8000 : 0;
  const double a = std::fabs(value);
  if (a >= 65520.0) return sign | 0x7c00;  // rounds to infinity (65504 is the largest half)
  if (a < 0x1.0p-14) {                     // subnormal (or zero): multiples of 2^-24
    return sign | static_cast<std::uint16_t>(std::nearbyint(a * 0x1.0p24));
  }
  int exponent = 0;
  const double mantissa = std::frexp(a, &exponent);  // a = mantissa 2^exponent, mantissa in [0.5, 1)
  int biased = exponent - 1 + 15;
  int fraction = static_cast<int>(std::nearbyint((2.0 * mantissa - 1.0) * 1024.0));
  if (fraction == 1024) {
    fraction = 0;
    ++biased;
  }
  if (biased >= 31) return sign | 0x7c00;
  return sign | static_cast<std::uint16_t>((biased << 10) | fraction);
}

double from_half(std::uint16_t bits) {
  const double sign = (bits & 0x8000) ? -1.0 : 1.0;
  const int exponent = (bits >> 10) & 0x1f;
  const int fraction = bits & 0x3ff;
  if (exponent == 0) return sign * std::ldexp(fraction, -24);
  if (exponent == 31) return fraction ? std::nan("") : sign * INFINITY;
  return sign * std::ldexp(1024 + fraction, exponent - 25);
}

Ktx2Image dictionary_ktx2(const DictionaryTexture& texture, const DictionaryParams& params) {
  Ktx2Image image;
  image.vk_format = kFormatRgba16Sfloat;
  image.type_size = 2;
  image.width = texture.width;
  image.layers = texture.layers;
  for (const auto& level : texture.levels) image.levels.push_back(as_bytes(level));
  nlohmann::ordered_json description = {
      {"layout",
       "1D array, layer = lod * count / 4 + d / 4, channel = d % 4; texel x covers slopes [x, x + 1) * range / "
       "width (x >= 0, even distributions: sample with MIRRORED_REPEAT at u = slope / range); zero for |u| >= 1"},
      {"count", params.count},
      {"lods", params.lods},
      {"resolution", params.resolution},
      {"alpha", params.alpha},
      {"sigma", params.sigma()},
      {"range", params.range()},
      {"lobe_sigma", params.lobe_sigma},
      {"seed", params.seed},
      {"mip_filter", "box: level m + 1 texel i = (level m texels 2i and 2i + 1) / 2"}};
  image.key_values = {{"KTXwriter", fmt::format("saagen {}", version())}, {"saagen.glints", description.dump()}};
  return image;
}

// ---------------------------------------------------------------------------------------------
// LEAN

SlopeMap slopes_from_normals(int width, int height, std::span<const double> normals) {
  if (width <= 0 || height <= 0 || normals.size() != static_cast<std::size_t>(width) * height * 3) {
    throw Error("normal map: expected width * height * 3 values");
  }
  SlopeMap map{width, height, {}};
  map.slopes.reserve(static_cast<std::size_t>(width) * height * 2);
  for (std::size_t t = 0; t < static_cast<std::size_t>(width) * height; ++t) {
    const double nz = std::max(normals[3 * t + 2], 1e-3);  // normals below the surface are clamped
    map.slopes.push_back(-normals[3 * t] / nz);
    map.slopes.push_back(-normals[3 * t + 1] / nz);
  }
  return map;
}

namespace {

// A PPM header field: decimal digits only, at most 9 of them (no sign, no suffix, no wrap-around).
int ppm_number(const std::string& token, std::string_view field) {
  if (token.empty() || token.size() > 9 || !std::all_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    throw Error(fmt::format("normal map: the PPM {} '{}' is not a decimal number below 10^9", field, token.substr(0, 20)));
  }
  return std::stoi(token);
}

}  // namespace

SlopeMap slopes_from_ppm(std::span<const std::uint8_t> bytes) {
  std::size_t at = 0;
  const auto token = [&]() {
    std::string text;
    while (at < bytes.size()) {
      const char c = static_cast<char>(bytes[at]);
      if (c == '#' && text.empty()) {
        while (at < bytes.size() && bytes[at] != '\n') ++at;
      } else if (std::isspace(static_cast<unsigned char>(c))) {
        ++at;
        if (!text.empty()) return text;
      } else {
        text += c;
        ++at;
        if (text.size() > 16) return text;  // no header field is this long
      }
    }
    return text;
  };
  if (token() != "P6") throw Error("normal map: only binary PPM (P6) files are read");
  const int width = ppm_number(token(), "width"), height = ppm_number(token(), "height"), maximum = ppm_number(token(), "maxval");
  if (width <= 0 || height <= 0 || maximum != 255) throw Error("normal map: expected a P6 header with positive size and maxval 255");
  if (static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) > lean_texel_limit) {
    throw Error(fmt::format("normal map: {} x {} is larger than {} texels (2048 x 2048); downsample it", width, height, lean_texel_limit));
  }
  if (bytes.size() - at < static_cast<std::size_t>(width) * height * 3) throw Error("normal map: the PPM file is truncated");
  std::vector<double> normals;
  normals.reserve(static_cast<std::size_t>(width) * height * 3);
  for (std::size_t t = 0; t < static_cast<std::size_t>(width) * height; ++t) {
    double n[3];
    for (int c = 0; c < 3; ++c) n[c] = 2.0 * bytes[at + 3 * t + c] / 255.0 - 1.0;
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (double v : n) normals.push_back(length > 0.0 ? v / length : 0.0);
  }
  return slopes_from_normals(width, height, normals);
}

std::vector<MomentLevel> lean_moments(const SlopeMap& map) {
  std::vector<MomentLevel> levels;
  MomentLevel base{map.width, map.height, {}};
  for (std::size_t t = 0; t < static_cast<std::size_t>(map.width) * map.height; ++t) {
    const double x = map.slopes[2 * t], y = map.slopes[2 * t + 1];
    for (double v : {x, y, x * x, x * y, y * y}) base.moments.push_back(v);
  }
  levels.push_back(std::move(base));
  while (levels.back().width > 1 || levels.back().height > 1) {
    const MomentLevel& fine = levels.back();
    MomentLevel coarse{std::max(1, fine.width / 2), std::max(1, fine.height / 2), {}};
    coarse.moments.assign(static_cast<std::size_t>(coarse.width) * coarse.height * 5, 0.0);
    for (int y = 0; y < coarse.height; ++y) {
      for (int x = 0; x < coarse.width; ++x) {
        for (int dy = 0; dy < 2; ++dy) {
          for (int dx = 0; dx < 2; ++dx) {
            const int fx = std::min(2 * x + dx, fine.width - 1), fy = std::min(2 * y + dy, fine.height - 1);
            for (int k = 0; k < 5; ++k) {
              coarse.moments[(static_cast<std::size_t>(y) * coarse.width + x) * 5 + k] +=
                  0.25 * fine.moments[(static_cast<std::size_t>(fy) * fine.width + fx) * 5 + k];
            }
          }
        }
      }
    }
    levels.push_back(std::move(coarse));
  }
  return levels;
}

Ktx2Image lean_ktx2(const std::vector<MomentLevel>& levels) {
  if (levels.empty()) throw Error("LEAN: no levels");
  Ktx2Image image;
  image.vk_format = kFormatRgba32Sfloat;
  image.type_size = 4;
  image.width = static_cast<std::uint32_t>(levels.front().width);
  image.height = static_cast<std::uint32_t>(levels.front().height);
  image.layers = 2;
  for (const MomentLevel& level : levels) {
    const std::size_t texels = static_cast<std::size_t>(level.width) * level.height;
    std::vector<float> values(texels * 8, 0.0f);
    for (std::size_t t = 0; t < texels; ++t) {
      const double* m = &level.moments[5 * t];
      values[4 * t + 0] = static_cast<float>(m[0]);
      values[4 * t + 1] = static_cast<float>(m[1]);
      values[4 * t + 2] = static_cast<float>(m[2]);
      values[4 * t + 3] = static_cast<float>(m[4]);
      values[4 * (texels + t)] = static_cast<float>(m[3]);
    }
    image.levels.push_back(as_bytes(values));
  }
  image.key_values = {{"KTXwriter", fmt::format("saagen {}", version())},
                      {"saagen.lean",
                       "2D array, 2 layers: layer 0 = (E[x], E[y], E[x^2], E[y^2]), layer 1 = (E[xy], 0, 0, 0) "
                       "of the slopes (-n.x / n.z, -n.y / n.z); level m + 1 = 2x2 box filter of level m"}};
  return image;
}

// ---------------------------------------------------------------------------------------------
// Emission

const Catalogue& catalogue() {
  static const Catalogue glint_catalogue = [] {
    std::vector<TemplateSource> sources = builtin_template_sources();
    for (const auto& [name, text] : embedded_glints::files()) sources.push_back({name, std::string(text)});
    return Catalogue::parse(sources);
  }();
  return glint_catalogue;
}

std::vector<std::uint8_t> default_dictionary_ktx2() { return dictionary_ktx2_for({}); }

std::vector<std::uint8_t> dictionary_ktx2_for(const std::map<std::string, double>& option_values) {
  DictionaryParams params;
  const auto option = [&](const char* name, double fallback) {
    const auto found = option_values.find(name);
    return found == option_values.end() ? fallback : found->second;
  };
  params.count = static_cast<int>(option("glint_count", params.count));
  params.lods = static_cast<int>(option("glint_lods", params.lods));
  params.resolution = static_cast<int>(option("glint_resolution", params.resolution));
  params.alpha = option("glint_alpha", params.alpha);
  params.validate();
  return write_ktx2(dictionary_ktx2(dictionary_texture(generate_dictionary(params), true), params));
}

std::vector<EmittedFile> emit(const EmitOptions& options) {
  EmitOptions glint_options = options;
  if (glint_options.variants.empty()) glint_options.variants = {"glints", "glints-ggaa"};
  if (const auto count = options.option_values.find("glint_count"); count != options.option_values.end()) {
    if (std::fmod(count->second, 4.0) != 0.0) {
      throw Error(fmt::format("--glint_count {} must be a multiple of 4 (four distributions per RGBA texel)", count->second));
    }
  }
  if (const auto resolution = options.option_values.find("glint_resolution"); resolution != options.option_values.end()) {
    const double r = resolution->second;
    if (r != std::floor(r) || r < 2.0 || r > 4096.0 || !is_power_of_two(static_cast<int>(r))) {
      throw Error(fmt::format("--glint_resolution {} must be a power of two in [2, 4096] (the dictionary's texels per distribution)", r));
    }
  }
  return emit_variants(catalogue(), glint_options);
}

}  // namespace glints
}  // namespace saagen
