// Error reporting for the harness: every VkResult is checked and a failure becomes a
// std::runtime_error naming the Vulkan function and the result code.
#pragma once

#include <vulkan/vulkan.h>

#include <stdexcept>
#include <string>

namespace saagen::harness {

// A device that lacks a feature or extension a run needs (e.g. shaderFloat16 for a module that
// declares the Float16 capability). Thrown before any shader module or pipeline is created;
// what() is the one line "unsupported on DEVICE: FEATURE".
class UnsupportedFeature : public std::runtime_error {
 public:
  UnsupportedFeature(std::string device, std::string feature)
      : std::runtime_error("unsupported on " + device + ": " + feature), device_(std::move(device)), feature_(std::move(feature)) {}
  const std::string& device() const { return device_; }
  const std::string& feature() const { return feature_; }

 private:
  std::string device_;
  std::string feature_;
};

// A device that cannot execute: RADV's null-hardware device (RADV_FORCE_FAMILY set), which only
// compiles (saagen/harness/isa.hpp). VulkanContext throws it before creating a logical device, so
// nothing is ever dispatched on it; summary() describes the physical device.
class NullHardwareDevice : public std::runtime_error {
 public:
  explicit NullHardwareDevice(std::string summary)
      : std::runtime_error(summary +
                           " is RADV's null-hardware device (RADV_FORCE_FAMILY is set): it compiles but cannot execute; "
                           "unset RADV_FORCE_FAMILY to run on a real device, or read its ISA statistics with `saagen bench --isa FAMILY`"),
        summary_(std::move(summary)) {}
  const std::string& summary() const { return summary_; }

 private:
  std::string summary_;
};

// "VK_ERROR_DEVICE_LOST", or "VkResult(-1000012000)" for codes this build does not name.
std::string vk_result_name(VkResult result);

// Throws std::runtime_error("<function> failed: <VkResult name>") unless result is VK_SUCCESS.
// `call` may be a whole call expression; only the function name (up to the first '(') is kept.
void check_vk(VkResult result, const char* call);

}  // namespace saagen::harness

// Checks a Vulkan call: SAAGEN_VK_CHECK(vkCreateBuffer(device, &info, nullptr, &buffer));
#define SAAGEN_VK_CHECK(call) ::saagen::harness::check_vk((call), #call)
