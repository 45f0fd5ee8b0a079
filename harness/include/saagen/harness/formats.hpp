// Texel layout of the formats the harness can upload (sampled images, resources.cpp) or read back
// (color attachments, program.cpp).
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>

namespace saagen::harness {

enum class NumericKind { sfloat, unorm };
struct FormatInfo {
  std::uint32_t components = 0;
  std::uint32_t bytes_per_component = 0;
  NumericKind numeric = NumericKind::sfloat;
  std::uint32_t texel_bytes() const { return components * bytes_per_component; }
};
// Supported: R32/R32G32/R32G32B32A32_SFLOAT, R16/R16G16/R16G16B16A16_SFLOAT, R8G8B8A8_UNORM.
// Throws std::invalid_argument for anything else.
FormatInfo format_info(VkFormat format);

}  // namespace saagen::harness
