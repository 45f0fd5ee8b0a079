// KTX2 (Khronos KTX File Format Specification 2.0) for saagen's textures: no supercompression,
// a Basic Data Format Descriptor (Khronos Data Format Specification 1.3), key/value data, levels
// stored smallest first, each aligned to lcm(texel size, 4).
#include "saagen/io/ktx2.hpp"

#include "saagen/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <numeric>

namespace saagen {
namespace {

// ---------------------------------------------------------------------------------------------
// Little-endian byte writing and reading.

void put32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) out.push_back(static_cast<std::uint8_t>(v >> (8 * k)));
}
void set32(std::vector<std::uint8_t>& out, std::size_t at, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) out[at + k] = static_cast<std::uint8_t>(v >> (8 * k));
}
void set64(std::vector<std::uint8_t>& out, std::size_t at, std::uint64_t v) {
  for (int k = 0; k < 8; ++k) out[at + k] = static_cast<std::uint8_t>(v >> (8 * k));
}
void pad_to(std::vector<std::uint8_t>& out, std::size_t alignment) {
  while (out.size() % alignment != 0) out.push_back(0);
}

class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  std::uint32_t u32(std::size_t at) const {
    check(at, 4);
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k) v |= static_cast<std::uint32_t>(bytes_[at + k]) << (8 * k);
    return v;
  }
  std::uint64_t u64(std::size_t at) const {
    check(at, 8);
    std::uint64_t v = 0;
    for (int k = 0; k < 8; ++k) v |= static_cast<std::uint64_t>(bytes_[at + k]) << (8 * k);
    return v;
  }
  void check(std::uint64_t at, std::uint64_t length) const {
    if (at > bytes_.size() || length > bytes_.size() - at) {
      throw Error(fmt::format("KTX2: {} bytes at offset {} lie past the end of the file ({} bytes)", length, at, bytes_.size()));
    }
  }
  std::span<const std::uint8_t> span(std::uint64_t at, std::uint64_t length) const {
    check(at, length);
    return bytes_.subspan(static_cast<std::size_t>(at), static_cast<std::size_t>(length));
  }

 private:
  std::span<const std::uint8_t> bytes_;
};

constexpr std::uint8_t kKtx2Identifier[12] = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};

// The uncompressed formats saagen reads and writes: channel count, bits per channel, and whether
// the channels are signed floats (else unsigned normalised integers).
struct FormatInfo {
  std::uint32_t channels = 0;
  std::uint32_t bits = 0;
  bool is_float = true;
};

FormatInfo format_info(std::uint32_t vk_format) {
  switch (vk_format) {
    case 37:
      return {4, 8, false};  // R8G8B8A8_UNORM
    case 76:
      return {1, 16, true};  // R16_SFLOAT
    case 97:
      return {4, 16, true};  // R16G16B16A16_SFLOAT
    case 100:
      return {1, 32, true};  // R32_SFLOAT
    case 109:
      return {4, 32, true};  // R32G32B32A32_SFLOAT
    default:
      break;
  }
  throw Error(
      fmt::format("KTX2: vkFormat {} is not supported (37: R8G8B8A8_UNORM, 76: R16_SFLOAT, 97: R16G16B16A16_SFLOAT, "
                  "100: R32_SFLOAT, 109: R32G32B32A32_SFLOAT)",
                  vk_format));
}

std::uint32_t texel_bytes(std::uint32_t vk_format) {
  const FormatInfo info = format_info(vk_format);
  return info.channels * info.bits / 8;
}

// The Basic Data Format Descriptor (Khronos Data Format Specification 1.3) of an uncompressed
// format: RGBSDA colour model, BT.709 primaries, linear transfer, one sample per channel (signed
// floats in [-1, 1], or unsigned normalised integers in [0, 2^bits - 1]).
std::vector<std::uint32_t> basic_dfd(std::uint32_t vk_format) {
  const FormatInfo info = format_info(vk_format);
  const std::uint32_t block_size = 24 + 16 * info.channels;
  std::vector<std::uint32_t> words;
  words.push_back(4 + block_size);                     // dfdTotalSize
  words.push_back(0);                                  // vendorId 0 (Khronos), descriptorType 0 (basic)
  words.push_back(2u | (block_size << 16));            // versionNumber 2, descriptorBlockSize
  words.push_back(1u | (1u << 8) | (1u << 16));        // colorModel RGBSDA, primaries BT709, transfer LINEAR, flags 0
  words.push_back(0);                                  // texel block 1x1x1x1
  words.push_back(texel_bytes(vk_format));             // bytesPlane0
  words.push_back(0);                                  // bytesPlane4..7
  const std::uint32_t channel_ids[4] = {0, 1, 2, 15};  // R, G, B, A
  for (std::uint32_t c = 0; c < info.channels; ++c) {
    const std::uint32_t qualifiers = info.is_float ? 0x80 | 0x40 : 0;  // float, signed
    words.push_back((c * info.bits) | ((info.bits - 1) << 16) | ((channel_ids[c] | qualifiers) << 24));
    words.push_back(0);                                                    // sample position
    words.push_back(info.is_float ? 0xBF800000u : 0u);                     // sampleLower: -1.0f or 0
    words.push_back(info.is_float ? 0x3F800000u : (1u << info.bits) - 1);  // sampleUpper: 1.0f or 2^bits - 1
  }
  return words;
}

// Bytes of a level; throws when the header's sizes overflow 64 bits.
std::size_t level_bytes(const Ktx2Image& image, std::uint32_t level) {
  if (level >= 32) throw Error(fmt::format("KTX2: level {} is beyond the 32 levels a 32-bit size can have", level));
  const std::uint64_t factors[] = {std::max<std::uint32_t>(1, image.width >> level),
                                   image.height == 0 ? 1 : std::max<std::uint32_t>(1, image.height >> level),
                                   image.depth == 0 ? 1 : std::max<std::uint32_t>(1, image.depth >> level),
                                   std::max<std::uint32_t>(1, image.layers),
                                   image.faces,
                                   texel_bytes(image.vk_format)};
  std::uint64_t bytes = 1;
  for (const std::uint64_t factor : factors) {
    if (__builtin_mul_overflow(bytes, factor, &bytes)) throw Error("KTX2: the image's dimensions overflow 64 bits");
  }
  return static_cast<std::size_t>(bytes);
}

// The most levels an image can have: one per halving of its largest dimension, down to 1.
std::uint32_t max_levels(const Ktx2Image& image) {
  const std::uint32_t largest = std::max({image.width, image.height, image.depth});
  return static_cast<std::uint32_t>(std::bit_width(largest));
}

}  // namespace

std::vector<std::uint8_t> write_ktx2(const Ktx2Image& image) {
  const std::uint32_t texel = texel_bytes(image.vk_format);
  const std::uint32_t level_count = static_cast<std::uint32_t>(image.levels.size());
  if (level_count == 0) throw Error("KTX2: an image needs at least one level");
  for (std::uint32_t level = 0; level < level_count; ++level) {
    if (image.levels[level].size() != level_bytes(image, level)) {
      throw Error(fmt::format("KTX2: level {} holds {} bytes, expected {}", level, image.levels[level].size(), level_bytes(image, level)));
    }
  }
  std::vector<std::uint8_t> out(kKtx2Identifier, kKtx2Identifier + 12);
  for (std::uint32_t v : {image.vk_format, image.type_size, image.width, image.height, image.depth, image.layers, image.faces, level_count,
                          0u /* supercompressionScheme: none */}) {
    put32(out, v);
  }
  const std::size_t index_at = out.size();  // dfd/kvd offsets and lengths, sgd offset and length
  out.resize(out.size() + 4 * 4 + 2 * 8, 0);
  const std::size_t level_index_at = out.size();
  out.resize(out.size() + 24 * static_cast<std::size_t>(level_count), 0);

  const std::size_t dfd_at = out.size();
  for (std::uint32_t word : basic_dfd(image.vk_format)) put32(out, word);
  const std::size_t dfd_length = out.size() - dfd_at;

  const std::size_t kvd_at = out.size();
  auto key_values = image.key_values;
  std::sort(key_values.begin(), key_values.end());
  for (const auto& [key, value] : key_values) {
    put32(out, static_cast<std::uint32_t>(key.size() + 1 + value.size() + 1));
    out.insert(out.end(), key.begin(), key.end());
    out.push_back(0);
    out.insert(out.end(), value.begin(), value.end());
    out.push_back(0);
    pad_to(out, 4);
  }
  const std::size_t kvd_length = out.size() - kvd_at;

  set32(out, index_at + 0, static_cast<std::uint32_t>(dfd_at));
  set32(out, index_at + 4, static_cast<std::uint32_t>(dfd_length));
  set32(out, index_at + 8, key_values.empty() ? 0u : static_cast<std::uint32_t>(kvd_at));
  set32(out, index_at + 12, static_cast<std::uint32_t>(kvd_length));
  set64(out, index_at + 16, 0);  // no supercompression global data
  set64(out, index_at + 24, 0);

  // Level data, smallest level first, each aligned to lcm(texel size, 4).
  const std::size_t alignment = std::lcm<std::size_t>(texel, 4);
  for (std::uint32_t level = level_count; level-- > 0;) {
    pad_to(out, alignment);
    const std::size_t at = out.size();
    out.insert(out.end(), image.levels[level].begin(), image.levels[level].end());
    set64(out, level_index_at + 24 * level + 0, at);
    set64(out, level_index_at + 24 * level + 8, image.levels[level].size());
    set64(out, level_index_at + 24 * level + 16, image.levels[level].size());
  }
  return out;
}

Ktx2Image read_ktx2(std::span<const std::uint8_t> bytes) {
  const Reader in(bytes);
  in.check(0, 80);
  if (!std::equal(kKtx2Identifier, kKtx2Identifier + 12, bytes.begin()))
    throw Error("KTX2: the file does not start with the KTX 20 identifier");
  Ktx2Image image;
  image.vk_format = in.u32(12);
  image.type_size = in.u32(16);
  image.width = in.u32(20);
  image.height = in.u32(24);
  image.depth = in.u32(28);
  image.layers = in.u32(32);
  image.faces = in.u32(36);
  const std::uint32_t level_count = in.u32(40);
  if (in.u32(44) != 0) throw Error("KTX2: supercompressed files are not supported");
  const std::uint32_t texel = texel_bytes(image.vk_format);
  if (image.type_size != format_info(image.vk_format).bits / 8)
    throw Error(fmt::format("KTX2: typeSize {} does not match vkFormat {}", image.type_size, image.vk_format));
  if (image.width == 0 || image.faces != 1 || level_count == 0)
    throw Error("KTX2: expected a non-empty image with one face and explicit levels");
  if (level_count > max_levels(image)) {
    throw Error(fmt::format("KTX2: {} levels for an image of {} x {} x {} (at most {})", level_count, image.width, image.height,
                            image.depth, max_levels(image)));
  }
  const std::uint32_t dfd_at = in.u32(48), dfd_length = in.u32(52), kvd_at = in.u32(56), kvd_length = in.u32(60);
  if (in.u64(64) != 0 || in.u64(72) != 0) throw Error("KTX2: unexpected supercompression global data");

  // DFD: the total size word, then the basic block.
  in.check(dfd_at, dfd_length);
  if (dfd_length < 4 || in.u32(dfd_at) != dfd_length || dfd_length % 4 != 0) throw Error("KTX2: malformed data format descriptor");
  for (std::uint32_t at = dfd_at; at < dfd_at + dfd_length; at += 4) image.dfd.push_back(in.u32(at));
  if (image.dfd != basic_dfd(image.vk_format)) throw Error("KTX2: the data format descriptor does not describe vkFormat");

  in.check(kvd_at, kvd_length);
  for (std::uint64_t at = kvd_at; at < std::uint64_t{kvd_at} + kvd_length;) {
    const std::uint32_t length = in.u32(at);
    const auto entry = in.span(at + 4, length);
    const auto nul = std::find(entry.begin(), entry.end(), std::uint8_t{0});
    if (nul == entry.end()) throw Error("KTX2: a key/value entry has no NUL after its key");
    std::string key(entry.begin(), nul);
    std::string value(nul + 1, entry.end());
    if (!value.empty() && value.back() == '\0') value.pop_back();
    image.key_values.emplace_back(std::move(key), std::move(value));
    at += 4 + length;
    at = (at + 3) / 4 * 4;
  }

  const std::size_t alignment = std::lcm<std::size_t>(texel, 4);
  std::uint64_t previous_offset = bytes.size() + 1;
  for (std::uint32_t level = 0; level < level_count; ++level) {
    const std::uint64_t offset = in.u64(80 + 24 * level), length = in.u64(88 + 24 * level), raw = in.u64(96 + 24 * level);
    if (length != raw || length != level_bytes(image, level)) {
      throw Error(fmt::format("KTX2: level {} has {} bytes, expected {}", level, length, level_bytes(image, level)));
    }
    if (offset % alignment != 0) throw Error(fmt::format("KTX2: level {} is not aligned to {} bytes", level, alignment));
    if (offset >= previous_offset) throw Error("KTX2: levels must be stored smallest first");
    previous_offset = offset;
    const auto data = in.span(offset, length);
    image.levels.emplace_back(data.begin(), data.end());
  }
  return image;
}

}  // namespace saagen
