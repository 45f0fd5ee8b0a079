// The texel layouts of the harness's formats (see formats.hpp).
#include "saagen/harness/formats.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace saagen::harness {

FormatInfo format_info(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R32_SFLOAT:
      return {1, 4, NumericKind::sfloat};
    case VK_FORMAT_R32G32_SFLOAT:
      return {2, 4, NumericKind::sfloat};
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      return {4, 4, NumericKind::sfloat};
    case VK_FORMAT_R16_SFLOAT:
      return {1, 2, NumericKind::sfloat};
    case VK_FORMAT_R16G16_SFLOAT:
      return {2, 2, NumericKind::sfloat};
    case VK_FORMAT_R16G16B16A16_SFLOAT:
      return {4, 2, NumericKind::sfloat};
    case VK_FORMAT_R8G8B8A8_UNORM:
      return {4, 1, NumericKind::unorm};
    default:
      throw std::invalid_argument(fmt::format("VkFormat {} is not supported by the harness", static_cast<int>(format)));
  }
}

}  // namespace saagen::harness
