// The headless instance every harness device is created from (context.cpp): the highest API
// version up to 1.3 the loader offers, and with SAAGEN_VK_VALIDATION set the Khronos validation
// layer reporting to the harness's message counter.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>

namespace saagen::harness {

// Throws with an install hint when the loader finds no driver or the layer is missing.
VkInstance create_headless_instance(std::uint32_t& api_version, VkDebugUtilsMessengerEXT* messenger = nullptr);
void destroy_instance(VkInstance instance, VkDebugUtilsMessengerEXT messenger);

}  // namespace saagen::harness
