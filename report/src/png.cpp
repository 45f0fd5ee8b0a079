// The PNG encoder (see png.hpp): stb_image_write's bytes with saagen's tEXt chunk after IHDR.
#include "saagen/report/png.hpp"

#include "saagen/error.hpp"
#include "saagen/io/output.hpp"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>

namespace saagen::report {
namespace {

std::uint32_t crc32(std::string_view bytes) {
  std::uint32_t crc = 0xffffffffu;
  for (const char c : bytes) {
    crc ^= static_cast<unsigned char>(c);
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void put_be32(std::string& out, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) out += static_cast<char>((value >> shift) & 0xffu);
}

// The PNG with a tEXt chunk `keyword`=`text` after its IHDR chunk (8-byte signature, then IHDR:
// length 13, type, data, CRC = 25 bytes): how report images carry saagen's output tag.
std::string with_text_chunk(const std::string& png, std::string_view keyword, std::string_view text) {
  constexpr std::size_t after_ihdr = 8 + 25;
  std::string chunk = "tEXt";
  chunk.append(keyword).append(1, '\0').append(text);
  std::string out = png.substr(0, after_ihdr);
  put_be32(out, static_cast<std::uint32_t>(chunk.size() - 4));
  out += chunk;
  put_be32(out, crc32(chunk));
  out += png.substr(after_ihdr);
  return out;
}

}  // namespace

std::string encode_tagged_png(int width, int height, int channels, const std::vector<std::uint8_t>& pixels, std::string_view what) {
  std::string png;
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &png, width, height, channels, pixels.data(), width * channels)) throw Error("cannot encode a PNG");
  return with_text_chunk(png, "Software", std::string(output_tag) + " " + std::string(what));
}

}  // namespace saagen::report
