#include "saagen/products/prefilter.hpp"

#include "saagen/error.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#include <stb/stb_image.h>

namespace saagen::prefilter {
namespace {

constexpr std::uint32_t kFormatRgba8Unorm = 37;
constexpr std::uint32_t kFormatR16Sfloat = 76;
constexpr std::uint32_t kFormatRgba16Sfloat = 97;
constexpr std::uint32_t kFormatR32Sfloat = 100;
constexpr std::uint32_t kFormatRgba32Sfloat = 109;
constexpr double kTinyLength = 1e-30;  // TINY_POSITIVE of templates/00-common.saa

bool is_power_of_two(int v) { return v > 0 && (v & (v - 1)) == 0; }

void check_size(int width, int height, const std::string& what) {
  if (!is_power_of_two(width) || !is_power_of_two(height)) {
    throw Error(fmt::format("{}: {} x {} is not a power-of-two size; resize the normal map to 2^m x 2^n texels", what, width, height));
  }
}

// The declared size, before decoding: a small file may declare a huge image.
void check_dimensions(long long width, long long height, const std::string& what) {
  if (width > max_normal_map_side || height > max_normal_map_side || width * height > max_normal_map_texels) {
    throw Error(
        fmt::format("{}: {} x {} texels is larger than saagen reads (at most {} a side and {} x {} in all); downscale the normal map", what,
                    width, height, max_normal_map_side, 4096, 4096));
  }
}

bool starts_with(std::span<const std::uint8_t> bytes, std::initializer_list<std::uint8_t> prefix) {
  return bytes.size() >= prefix.size() && std::equal(prefix.begin(), prefix.end(), bytes.begin());
}

// The file as stb_image may decode it. Every chunk must fit in the file: stb_image grows its
// IDAT buffer to what a chunk declares before reading it (an 80-byte file declaring 1.4 GB made
// it allocate 2 GB; found by fuzz/png_fuzzer.cpp). Empty IDAT chunks are dropped: stb_image hands
// memcpy a null pointer for one before the first non-empty IDAT (undefined behaviour, found by
// the same target), and they carry no data. Empty when the file needs no change (no copy).
std::vector<std::uint8_t> png_for_stb(std::span<const std::uint8_t> bytes, const std::string& what) {
  const auto length_at = [&](std::size_t at) {
    return std::uint32_t(bytes[at]) << 24 | std::uint32_t(bytes[at + 1]) << 16 | std::uint32_t(bytes[at + 2]) << 8 | bytes[at + 3];
  };
  const auto type_at = [&](std::size_t at) { return std::string(bytes.begin() + at + 4, bytes.begin() + at + 8); };
  std::vector<std::uint8_t> kept;
  std::size_t copied = 0;
  for (std::size_t at = 8; at + 8 <= bytes.size(); at += 12 + std::size_t{length_at(at)}) {
    const std::string type = type_at(at);
    if (length_at(at) > bytes.size() - at - 8) {
      std::string shown;
      for (const char c : type) shown += std::isalnum(static_cast<unsigned char>(c)) ? c : '?';
      throw Error(
          fmt::format("{}: not a readable PNG (chunk '{}' declares {} bytes, past the end of the file)", what, shown, length_at(at)));
    }
    if (type == "IEND") break;
    if (type != "IDAT" || length_at(at) != 0) continue;
    kept.insert(kept.end(), bytes.begin() + copied, bytes.begin() + at);
    copied = std::min(at + 12, bytes.size());
  }
  if (copied != 0) kept.insert(kept.end(), bytes.begin() + copied, bytes.end());
  return kept;
}

NormalImage read_png(std::span<const std::uint8_t> file, const std::string& what) {
  const std::vector<std::uint8_t> cleaned = png_for_stb(file, what);
  const std::span<const std::uint8_t> bytes = cleaned.empty() ? file : std::span<const std::uint8_t>(cleaned);
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = static_cast<int>(bytes.size());
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(data, size, &width, &height, &channels))
    throw Error(fmt::format("{}: not a readable PNG ({})", what, stbi_failure_reason()));
  check_dimensions(width, height, what);
  const bool sixteen = stbi_is_16_bit_from_memory(data, size) != 0;
  std::vector<double> values;
  if (sixteen) {
    std::unique_ptr<stbi_us, void (*)(void*)> pixels(stbi_load_16_from_memory(data, size, &width, &height, &channels, 0), stbi_image_free);
    if (!pixels) throw Error(fmt::format("{}: not a readable PNG ({})", what, stbi_failure_reason()));
    values.resize(static_cast<std::size_t>(width) * height * channels);
    for (std::size_t k = 0; k < values.size(); ++k) values[k] = pixels.get()[k] / 65535.0;
  } else {
    std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load_from_memory(data, size, &width, &height, &channels, 0), stbi_image_free);
    if (!pixels) throw Error(fmt::format("{}: not a readable PNG ({})", what, stbi_failure_reason()));
    values.resize(static_cast<std::size_t>(width) * height * channels);
    for (std::size_t k = 0; k < values.size(); ++k) values[k] = pixels.get()[k] / 255.0;
  }
  return normals_from_channels(width, height, channels, values, true, what);
}

std::vector<double> ktx2_level0_values(const Ktx2Image& image) {
  const std::vector<std::uint8_t>& level = image.levels.front();
  std::vector<double> values;
  if (image.vk_format == kFormatRgba8Unorm) {
    for (std::uint8_t byte : level) values.push_back(byte / 255.0);
  } else if (image.vk_format == kFormatRgba16Sfloat) {
    for (std::size_t at = 0; at + 2 <= level.size(); at += 2)
      values.push_back(glints::from_half(static_cast<std::uint16_t>(level[at] | level[at + 1] << 8)));
  } else {
    for (std::size_t at = 0; at + 4 <= level.size(); at += 4) {
      float f = 0.0f;
      std::memcpy(&f, level.data() + at, 4);
      values.push_back(f);
    }
  }
  return values;
}

NormalImage read_ktx2_normals(std::span<const std::uint8_t> bytes, const std::string& what) {
  if (bytes.size() >= 28) {  // pixelWidth and pixelHeight, little-endian, checked before the levels are read
    const auto u32 = [&](std::size_t at) {
      return std::uint32_t(bytes[at]) | std::uint32_t(bytes[at + 1]) << 8 | std::uint32_t(bytes[at + 2]) << 16 |
             std::uint32_t(bytes[at + 3]) << 24;
    };
    check_dimensions(u32(20), u32(24), what);
  }
  Ktx2Image image;
  try {
    image = read_ktx2(bytes);
  } catch (const Error& error) {
    throw Error(fmt::format("{}: {}", what, error.what()));
  }
  const std::uint32_t format = image.vk_format;
  if (format != kFormatRgba8Unorm && format != kFormatRgba16Sfloat && format != kFormatRgba32Sfloat) {
    throw Error(fmt::format("{}: vkFormat {} is not a normal-map format; use R8G8B8A8_UNORM, R16G16B16A16_SFLOAT or R32G32B32A32_SFLOAT",
                            what, format));
  }
  if (image.height == 0 || image.depth != 0 || image.layers != 0) {
    throw Error(fmt::format("{}: a normal map must be a single 2D image (no array layers, no depth)", what));
  }
  const int width = static_cast<int>(image.width), height = static_cast<int>(image.height);
  check_size(width, height, what);
  return normals_from_channels(width, height, 4, ktx2_level0_values(image), format == kFormatRgba8Unorm, what);
}

void add_texel(const double* n, Level& level) {
  const double sx = -n[0] / n[2], sy = -n[1] / n[2];
  level.mean_normal.insert(level.mean_normal.end(), n, n + 3);
  level.slope_mean.insert(level.slope_mean.end(), {sx, sy});
  level.slope_second.insert(level.slope_second.end(), {sx * sx, sx * sy, sy * sy});
}

// Mean of the sx x sy children of one coarse texel, for one field with `count` values per texel
// (the order of the sums is measure::NormalMap's: rows, then columns, then one multiplication).
void reduce_field(const std::vector<double>& fine, int fine_width, int x, int y, int sx, int sy, int count, std::vector<double>& out) {
  const double weight = 1.0 / (sx * sy);
  for (int c = 0; c < count; ++c) {
    double sum = 0.0;
    for (int j = 0; j < sy; ++j)
      for (int i = 0; i < sx; ++i) sum = sum + fine[(static_cast<std::size_t>(y * sy + j) * fine_width + x * sx + i) * count + c];
    out.push_back(weight * sum);
  }
}

Level reduce(const Level& fine) {
  Level coarse;
  coarse.width = std::max(1, fine.width / 2);
  coarse.height = std::max(1, fine.height / 2);
  const int sx = fine.width / coarse.width, sy = fine.height / coarse.height;
  for (int y = 0; y < coarse.height; ++y)
    for (int x = 0; x < coarse.width; ++x) {
      reduce_field(fine.mean_normal, fine.width, x, y, sx, sy, 3, coarse.mean_normal);
      reduce_field(fine.slope_mean, fine.width, x, y, sx, sy, 2, coarse.slope_mean);
      reduce_field(fine.slope_second, fine.width, x, y, sx, sy, 3, coarse.slope_second);
    }
  return coarse;
}

template <class T>
void put_value(std::vector<std::uint8_t>& out, T value) {
  std::uint8_t bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.insert(out.end(), bytes, bytes + sizeof(T));
}

// glTF 2.0 metallicRoughnessTexture: G = perceptual roughness, B = metallic, linear 8-bit UNORM.
std::uint8_t unorm8(double value) { return static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0, 1.0) * 255.0)); }

std::vector<std::uint8_t> roughness_level(const Level& level, const Options& options) {
  const double base = to_alpha2(options.roughness, options.domain);
  std::vector<std::uint8_t> out;
  for (std::size_t t = 0; t < level.mean_normal.size() / 3; ++t) {
    const double* m = &level.mean_normal[3 * t];
    const double baked = method_alpha2(options.method, base, std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]));
    const double alpha2 = options.scale == 1.0 ? baked : std::clamp(base + options.scale * (baked - base), 0.0, 1.0);
    if (options.gltf) {
      out.insert(out.end(), {255, unorm8(from_alpha2(alpha2, Domain::perceptual)), unorm8(options.metallic), 255});
      continue;
    }
    const double value = from_alpha2(alpha2, options.domain);
    if (options.float32)
      put_value(out, static_cast<float>(value));
    else
      put_value(out, glints::to_half(value));
  }
  return out;
}

std::string_view roughness_formula(Method method) {
  switch (method) {
    case Method::unreal:
      return "Unreal composite texture: V = max((1 - L) / L - 4e-5, 0), B = 2 V (a - 1), a' = (B - a) / (B - 1), a = base_alpha2 "
             "(TextureCompressorModule ApplyCompositeTexture, CompositePower 1)";
    case Method::filament_vmf:
      return "Filament roughness-prefilter: a' = saturate(base_alpha2 + 2 / kappa), kappa = (3L - L^3) / (1 - L^2) (vMF fit; Karis "
             "2018)";
    case Method::hdrp:
      return "Unity HDRP: a' = saturate(base_alpha2 + min(2 min(1 / (4 kappa), 0.03125), 0.25^2)), kappa = (3L - L^3) / (1 - L^2) "
             "(TextureNormalVariance, NormalFiltering, NormalMapFilteringTexturePostprocessor)";
    default:
      return "a = saturate(base_alpha2 + 2 (1 - L) / L), L = |mean of the unit normals| (Toksvig 2005); stored in the domain";
  }
}

std::vector<std::uint8_t> lean_level(const Level& level) {
  std::vector<std::uint8_t> out;
  const std::size_t texels = level.slope_mean.size() / 2;
  for (std::size_t t = 0; t < texels; ++t) {  // layer 0
    for (double v : {level.slope_mean[2 * t], level.slope_mean[2 * t + 1], level.slope_second[3 * t], level.slope_second[3 * t + 2]}) {
      put_value(out, static_cast<float>(v));
    }
  }
  for (std::size_t t = 0; t < texels; ++t) {  // layer 1
    for (double v : {level.slope_second[3 * t + 1], 0.0, 0.0, 0.0}) put_value(out, static_cast<float>(v));
  }
  return out;
}

nlohmann::json layout_json(const std::vector<Level>& levels, const Options& options) {
  nlohmann::json json;
  json["method"] = std::string(to_string(options.method));
  json["levels"] = levels.size();
  json["width"] = levels.front().width;
  json["height"] = levels.front().height;
  json["box_filter"] = "level m + 1 texel = mean of its level-m children; moments of the level-0 unit normals";
  json["base_roughness"] = options.roughness;
  json["domain"] = std::string(to_string(options.domain));
  if (writes_roughness(options.method)) {
    if (options.gltf) {
      json["format"] = "R8G8B8A8_UNORM";
      json["channels"] = {"1 (occlusion: none)", "perceptual roughness", "metallic", "1"};
      json["output_domain"] = "perceptual";
      json["gltf"] = "metallicRoughnessTexture: G = roughness (perceptual, alpha = r^2), B = metallic; linear";
      json["metallic"] = options.metallic;
    } else {
      json["format"] = options.float32 ? "R32_SFLOAT" : "R16_SFLOAT";
      json["channels"] = {"roughness"};
      json["output_domain"] = std::string(to_string(options.domain));
    }
    json["formula"] = std::string(roughness_formula(options.method));
    json["scale"] = options.scale;  // a = base_alpha2 + scale (formula - base_alpha2), saturated
  } else {
    json["format"] = "R32G32B32A32_SFLOAT";
    json["layers"] = {{"E[x]", "E[y]", "E[x^2]", "E[y^2]"}, {"E[xy]", "0", "0", "0"}};
    json["slope"] = "s = (x, y) = -n.xy / n.z of the level-0 unit normals (Olano & Baker 2010)";
    json["formula"] =
        "Sigma_tex = E[s s^T] - E[s] E[s]^T; A = diag(alpha^2) + 2 Sigma_tex (saa_prefilter_lean); the base roughness is not baked in";
  }
  return json;
}

}  // namespace

Method parse_method(std::string_view text) {
  for (Method method : {Method::toksvig, Method::lean, Method::unreal, Method::filament_vmf, Method::hdrp})
    if (text == to_string(method)) return method;
  throw Error(fmt::format("--method '{}' is not one of toksvig, lean, unreal, filament-vmf, hdrp", text));
}

bool writes_roughness(Method method) { return method != Method::lean; }

std::string_view to_string(Method method) {
  switch (method) {
    case Method::toksvig:
      return "toksvig";
    case Method::lean:
      return "lean";
    case Method::unreal:
      return "unreal";
    case Method::filament_vmf:
      return "filament-vmf";
    case Method::hdrp:
      return "hdrp";
  }
  return "toksvig";
}

double from_alpha2(double alpha2, Domain domain) {
  switch (domain) {
    case Domain::alpha2:
      return alpha2;
    case Domain::alpha:
      return std::sqrt(alpha2);
    case Domain::perceptual:
      return std::sqrt(std::sqrt(alpha2));
    case Domain::smoothness:
      return 1.0 - std::sqrt(std::sqrt(alpha2));
  }
  return alpha2;
}

double to_alpha2(double value, Domain domain) {
  switch (domain) {
    case Domain::alpha2:
      return value;
    case Domain::alpha:
      return value * value;
    case Domain::perceptual:
      return (value * value) * (value * value);
    case Domain::smoothness:
      return ((1.0 - value) * (1.0 - value)) * ((1.0 - value) * (1.0 - value));
  }
  return value;
}

NormalImage normals_from_channels(int width, int height, int channels, std::span<const double> values, bool encoded,
                                  const std::string& what) {
  check_size(width, height, what);
  if (channels < 3) throw Error(fmt::format("{}: has {} channel(s); a normal map needs RGB (x, y, z)", what, channels));
  NormalImage image{width, height, {}};
  const std::size_t texels = static_cast<std::size_t>(width) * height;
  image.normals.reserve(3 * texels);
  for (std::size_t t = 0; t < texels; ++t) {
    double n[3];
    for (int c = 0; c < 3; ++c) n[c] = encoded ? 2.0 * values[t * channels + c] - 1.0 : values[t * channels + c];
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(n[2] > 0.0) || !(std::fabs(length - 1.0) <= 0.2)) {
      throw Error(
          fmt::format("{}: texel ({}, {}) decodes to ({:.3f}, {:.3f}, {:.3f}), not a tangent-space unit normal with z > 0; "
                      "is this a normal map?",
                      what, t % width, t / width, n[0], n[1], n[2]));
    }
    // The slopes -n.xy / n.z and their squares (the LEAN moments, stored as floats) stay finite.
    constexpr double max_slope = 1e18;
    const double slope = std::max(std::fabs(n[0]), std::fabs(n[1])) / n[2];
    if (!(slope <= max_slope)) {
      throw Error(
          fmt::format("{}: texel ({}, {}) decodes to ({:.3g}, {:.3g}, {:.3g}), a normal within {:.0e} of the surface plane: its "
                      "slope {:.3g} would make the slope moments infinite; is this a normal map?",
                      what, t % width, t / width, n[0], n[1], n[2], 1.0 / max_slope, slope));
    }
    for (double v : n) image.normals.push_back(v / length);
  }
  return image;
}

NormalImage read_normal_map(std::span<const std::uint8_t> bytes, const std::string& what) {
  if (starts_with(bytes, {0x89, 'P', 'N', 'G'})) return read_png(bytes, what);
  if (starts_with(bytes, {0xAB, 'K', 'T', 'X', ' ', '2', '0'})) return read_ktx2_normals(bytes, what);
  throw Error(fmt::format("{}: neither a PNG nor a KTX2 file", what));
}

glints::SlopeMap read_lean_slopes(std::span<const std::uint8_t> bytes, const std::string& what) {
  if (starts_with(bytes, {'P', '6'})) {
    try {
      return glints::slopes_from_ppm(bytes);
    } catch (const Error& error) {
      throw Error(fmt::format("{}: {}", what, error.what()));
    }
  }
  if (!starts_with(bytes, {0x89, 'P', 'N', 'G'}) && !starts_with(bytes, {0xAB, 'K', 'T', 'X', ' ', '2', '0'})) {
    throw Error(fmt::format("{}: neither a PNG, a KTX2 nor a binary PPM (P6) file", what));
  }
  const NormalImage image = read_normal_map(bytes, what);
  if (static_cast<std::uint64_t>(image.width) * static_cast<std::uint64_t>(image.height) > glints::lean_texel_limit) {
    throw Error(fmt::format("{}: normal map: {} x {} is larger than {} texels (2048 x 2048); downsample it", what, image.width,
                            image.height, glints::lean_texel_limit));
  }
  return glints::slopes_from_normals(image.width, image.height, image.normals);
}

std::vector<Level> build_levels(const NormalImage& image) {
  check_size(image.width, image.height, "normal map");
  Level base{image.width, image.height, {}, {}, {}};
  for (std::size_t t = 0; t < image.normals.size() / 3; ++t) add_texel(&image.normals[3 * t], base);
  std::vector<Level> levels{std::move(base)};
  while (levels.back().width > 1 || levels.back().height > 1) levels.push_back(reduce(levels.back()));
  return levels;
}

double toksvig_alpha2(double base_alpha2, double mean_length) {
  const double l = std::max(mean_length, kTinyLength);
  const double variance = std::max((1.0 - l) / l, 0.0);
  return std::clamp(base_alpha2 + 2.0 * variance, 0.0, 1.0);
}

double vmf_kappa(double mean_length) {
  if (!(mean_length < 1.0)) return std::numeric_limits<double>::infinity();
  const double l = std::max(mean_length, 0.0), l2 = l * l;
  return (3.0 * l - l * l2) / (1.0 - l2);
}

double method_alpha2(Method method, double base_alpha2, double mean_length) {
  switch (method) {
    case Method::toksvig:
      return toksvig_alpha2(base_alpha2, mean_length);
    case Method::unreal: {
      const double l = std::min(mean_length, 1.0);
      if (!(l > 0.0)) return 1.0;
      const double variance = std::max((1.0 - l) / l - 4e-5, 0.0);
      const double a = std::clamp(base_alpha2, 0.0, 1.0), b = 2.0 * variance * (a - 1.0);
      return (b - a) / (b - 1.0);
    }
    case Method::filament_vmf:
      return std::clamp(base_alpha2 + 2.0 / vmf_kappa(mean_length), 0.0, 1.0);
    case Method::hdrp:
      return std::clamp(base_alpha2 + std::min(2.0 * std::min(0.25 / vmf_kappa(mean_length), 0.03125), 0.25 * 0.25), 0.0, 1.0);
    case Method::lean:
      break;
  }
  throw Error("internal error: LEAN moments are not one roughness");
}

void Options::validate() const {
  if (!(roughness >= 0.0 && roughness <= 1.0)) throw Error(fmt::format("--roughness {} is outside [0, 1]", roughness));
  if (!writes_roughness(method) && (float32 || gltf))
    throw Error(
        fmt::format("--{} applies to the roughness methods (toksvig, unreal, filament-vmf, hdrp); LEAN moments are always "
                    "R32G32B32A32_SFLOAT",
                    float32 ? "float32" : "gltf"));
  if (float32 && gltf) throw Error("--float32 and --gltf exclude each other: the glTF layout is R8G8B8A8_UNORM");
  if (!(metallic >= 0.0 && metallic <= 1.0)) throw Error(fmt::format("--metallic {} is outside [0, 1]", metallic));
  if (!(scale >= 0.0 && scale <= 4.0)) throw Error(fmt::format("--scale {} is outside [0, 4]", scale));
  if (scale != 1.0 && !writes_roughness(method)) throw Error("--scale applies to the roughness methods; LEAN moments are not scaled");
}

Ktx2Image prefilter_ktx2(const std::vector<Level>& levels, const Options& options) {
  options.validate();
  Ktx2Image image;
  const bool roughness = writes_roughness(options.method);
  if (!roughness)
    image.vk_format = kFormatRgba32Sfloat, image.type_size = 4;
  else if (options.gltf)
    image.vk_format = kFormatRgba8Unorm, image.type_size = 1;
  else
    image.vk_format = options.float32 ? kFormatR32Sfloat : kFormatR16Sfloat, image.type_size = options.float32 ? 4 : 2;
  image.width = static_cast<std::uint32_t>(levels.front().width);
  image.height = static_cast<std::uint32_t>(levels.front().height);
  image.layers = roughness ? 0 : 2;
  for (const Level& level : levels) image.levels.push_back(roughness ? roughness_level(level, options) : lean_level(level));
  image.key_values.emplace_back("saagen.prefilter", layout_json(levels, options).dump());
  image.key_values.emplace_back("saagen.marker",
                                fmt::format("// saagen-marker: target=ktx2 variants=prefilter-{}\n", to_string(options.method)));
  return image;
}

}  // namespace saagen::prefilter
