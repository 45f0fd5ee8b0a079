// A headless Vulkan instance + logical device, chosen by name, environment or preference for
// the lavapipe CPU driver. Optional features the later tests need (fp16 arithmetic, 16-bit
// storage, fragment stores, anisotropy, ...) are enabled whenever the device supports them, and
// DeviceInfo says which ones are on.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

namespace saagen::harness {

// Environment variable naming the device (case-insensitive substring of its name).
inline constexpr const char* device_env_var = "SAAGEN_VK_DEVICE";

// Environment variable that turns the Khronos validation layer on for every instance the harness
// creates (any value but "" or "0"; ctest sets it for every vulkan-labelled test). When set and
// the layer is not installed, creating a context throws (install vulkan-validationlayers).
inline constexpr const char* validation_env_var = "SAAGEN_VK_VALIDATION";
inline constexpr const char* validation_layer_name = "VK_LAYER_KHRONOS_validation";

// Whether SAAGEN_VK_VALIDATION asks for the validation layer.
bool validation_requested();
// Warnings and errors the validation layer has reported in this process (each is also printed
// to stderr as one "[validation] ..." line). Tests fail when it is not 0 (tests/support/vulkan_validation.cpp).
std::size_t validation_message_count();

struct ContextOptions {
  // Case-insensitive substring of the device name, e.g. from a `--device NAME` flag. When
  // empty, SAAGEN_VK_DEVICE is consulted; when that is empty too, lavapipe is preferred
  // (VK_PHYSICAL_DEVICE_TYPE_CPU or a name containing "llvmpipe"), then the first device.
  std::string device_name;
  bool read_environment = true;
};

struct SubgroupInfo {
  std::uint32_t size = 0;
  VkShaderStageFlags supported_stages = 0;
  VkSubgroupFeatureFlags supported_operations = 0;
  bool quad_operations_in_all_stages = false;

  bool supports(VkSubgroupFeatureFlags operations, VkShaderStageFlags stages) const {
    return (supported_operations & operations) == operations && (supported_stages & stages) == stages;
  }
  // "size 8, stages {compute, fragment}, operations {basic, vote, ..., quad}, quad in all stages: no"
  std::string describe() const;
};

struct FloatControls {
  bool denorm_preserve_float16 = false;
  bool denorm_preserve_float32 = false;
  bool denorm_flush_to_zero_float16 = false;
  bool denorm_flush_to_zero_float32 = false;
  bool signed_zero_inf_nan_preserve_float16 = false;
  bool signed_zero_inf_nan_preserve_float32 = false;
};

struct DeviceInfo {
  std::string name;
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  std::uint32_t api_version = 0;     // VK_MAKE_API_VERSION encoding, as reported by the device
  std::uint32_t driver_version = 0;  // vendor-specific encoding
  std::uint32_t vendor_id = 0;
  std::uint32_t device_id = 0;
  std::string driver_name;  // e.g. "llvmpipe" (empty before Vulkan 1.2)
  std::string driver_info;  // e.g. "Mesa 22.3.6 (LLVM 15.0.6)"

  // Enabled features (each is on exactly when the device supports it).
  bool shader_float16 = false;
  bool shader_int8 = false;
  bool shader_int16 = false;
  bool shader_int64 = false;
  bool shader_float64 = false;
  bool storage_buffer_16bit_access = false;
  bool uniform_and_storage_buffer_16bit_access = false;
  bool storage_push_constant_16 = false;
  bool storage_input_output_16 = false;
  bool subgroup_extended_types = false;
  bool fragment_stores_and_atomics = false;
  bool sampler_anisotropy = false;

  SubgroupInfo subgroup;
  FloatControls float_controls;

  // Timestamps: usable when the chosen queue has timestamp_valid_bits > 0.
  std::uint32_t timestamp_valid_bits = 0;
  float timestamp_period_ns = 0.0f;
  bool timestamps_supported() const { return timestamp_valid_bits > 0; }

  float max_sampler_anisotropy = 1.0f;
  std::uint32_t max_push_constants_size = 0;
  std::uint32_t max_compute_work_group_count[3] = {0, 0, 0};
  std::uint32_t max_compute_work_group_invocations = 0;
  std::uint32_t max_storage_buffer_range = 0;

  bool is_cpu() const { return type == VK_PHYSICAL_DEVICE_TYPE_CPU; }
  // One line: name, type, API version, driver, fp16, subgroup and timestamp support.
  std::string summary() const;
};

// Owns the instance, the logical device and one queue that supports graphics and compute.
// Not copyable or movable: programs keep a reference to it and must not outlive it.
class VulkanContext {
 public:
  explicit VulkanContext(const ContextOptions& options = {});
  ~VulkanContext();
  VulkanContext(const VulkanContext&) = delete;
  VulkanContext& operator=(const VulkanContext&) = delete;

  const DeviceInfo& info() const { return info_; }

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physical_device() const { return physical_device_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  std::uint32_t queue_family() const { return queue_family_; }
  const VkPhysicalDeviceLimits& limits() const { return limits_; }

  // Index of a memory type allowed by type_bits with all `required` flags; throws if none.
  std::uint32_t find_memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags required) const;
  // New device memory for `requirements`, of a type with the `preferred` flags where the device has
  // one, else with the `required` ones; the caller frees it (vkFreeMemory). Throws if none.
  VkDeviceMemory allocate_memory(const VkMemoryRequirements& requirements, VkMemoryPropertyFlags preferred,
                                 VkMemoryPropertyFlags required) const;
  VkFormatProperties format_properties(VkFormat format) const;

  // Names of all devices the loader reports (creates a temporary instance).
  static std::vector<std::string> available_devices();

  // Throws UnsupportedFeature ("unsupported on DEVICE: FEATURE") when `spirv` declares a
  // capability whose Vulkan feature is not enabled on this device (Float16 -> shaderFloat16,
  // Int16, Int64, Float64, 16-bit storage, subgroup operations in `stage`). The harness calls it
  // before creating any shader module, so a missing feature never reaches the driver.
  void require_capabilities(const std::vector<std::uint32_t>& spirv, VkShaderStageFlags stage) const;

 private:
  void create_instance();
  void select_physical_device(const ContextOptions& options);
  void query_device_info();
  void create_device();

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  std::uint32_t queue_family_ = 0;
  std::uint32_t instance_api_version_ = VK_API_VERSION_1_1;
  VkPhysicalDeviceLimits limits_{};
  std::vector<std::string> device_extensions_;  // supported by the chosen device
  DeviceInfo info_;
};

// Removes `--device NAME` or `--device=NAME` from argv (adjusting argc) and returns NAME, or an
// empty string when the flag is absent. Lets test and bench mains forward the flag to
// ContextOptions::device_name.
std::string take_device_flag(int& argc, char** argv);

}  // namespace saagen::harness
