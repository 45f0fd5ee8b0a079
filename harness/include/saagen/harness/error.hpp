// Error reporting for the harness: every VkResult is checked and a failure becomes a
// std::runtime_error naming the Vulkan function and the result code.
#pragma once

#include <vulkan/vulkan.h>

#include <string>

namespace saagen::harness {

// "VK_ERROR_DEVICE_LOST", or "VkResult(-1000012000)" for codes this build does not name.
std::string vk_result_name(VkResult result);

// Throws std::runtime_error("<function> failed: <VkResult name>") unless result is VK_SUCCESS.
// `call` may be a whole call expression; only the function name (up to the first '(') is kept.
void check_vk(VkResult result, const char* call);

}  // namespace saagen::harness

// Checks a Vulkan call: SAAGEN_VK_CHECK(vkCreateBuffer(device, &info, nullptr, &buffer));
#define SAAGEN_VK_CHECK(call) ::saagen::harness::check_vk((call), #call)
