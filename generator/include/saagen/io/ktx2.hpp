#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace saagen {

// KTX2 (Khronos KTX File Format Specification 2.0): no supercompression, a Basic Data Format
// Descriptor, key/value data, levels stored smallest first, each aligned to lcm(texel size, 4).

struct Ktx2Image {
  std::uint32_t vk_format = 0;  // 37: R8G8B8A8_UNORM, 76: R16_SFLOAT, 97: R16G16B16A16_SFLOAT,
                                // 100: R32_SFLOAT, 109: R32G32B32A32_SFLOAT
  std::uint32_t type_size = 0;  // bytes per channel: 1, 2 or 4
  std::uint32_t width = 0;
  std::uint32_t height = 0;  // 0 for 1D images
  std::uint32_t depth = 0;   // 0 unless 3D
  std::uint32_t layers = 0;  // 0: not an array
  std::uint32_t faces = 1;
  std::vector<std::vector<std::uint8_t>> levels;                // level 0 first, each in Vulkan upload layout
  std::vector<std::pair<std::string, std::string>> key_values;  // written sorted by key
  std::vector<std::uint32_t> dfd;                               // read back by read_ktx2 (the writer builds it from vk_format)
};

std::vector<std::uint8_t> write_ktx2(const Ktx2Image& image);
// Throws saagen::Error on anything that is not a well-formed uncompressed KTX2 file.
Ktx2Image read_ktx2(std::span<const std::uint8_t> bytes);

}  // namespace saagen
