#include "saagen/harness/context.hpp"

#include "instance.hpp"

#include "saagen/harness/error.hpp"
#include "saagen/harness/isa.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace saagen::harness {
namespace {

constexpr const char* install_hint =
    "install mesa-vulkan-drivers (lavapipe) or point VK_ICD_FILENAMES / SAAGEN_VK_DEVICE at a working driver";

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

bool contains_case_insensitive(const std::string& haystack, const std::string& needle) {
  return lowercase(haystack).find(lowercase(needle)) != std::string::npos;
}

std::string join(const std::vector<std::string>& items, const char* separator) {
  std::string joined;
  for (const std::string& item : items) {
    if (!joined.empty()) joined += separator;
    joined += item;
  }
  return joined;
}

std::string api_version_string(std::uint32_t version) {
  return fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(version), VK_API_VERSION_MINOR(version), VK_API_VERSION_PATCH(version));
}

const char* device_type_name(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return "CPU";
    default:
      return "other";
  }
}

std::atomic<std::size_t> validation_messages{0};

// Prints every warning and error of the validation layer as one line and counts those of the
// layer itself (validation and performance types; the loader's general-type notes about ICDs
// without hardware are printed but not counted).
VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT type,
                                                     const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
  const bool error = severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  const bool counted = (type & (VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT)) != 0;
  if (counted) ++validation_messages;
  std::fprintf(stderr, "[validation] %s%s: %s\n", error ? "error" : "warning", counted ? "" : " (loader, not counted)",
               data && data->pMessage ? data->pMessage : "");
  return VK_FALSE;
}

VkDebugUtilsMessengerCreateInfoEXT messenger_info() {
  VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = on_validation_message;
  return info;
}

bool layer_available(const char* name) {
  std::uint32_t count = 0;
  if (vkEnumerateInstanceLayerProperties(&count, nullptr) != VK_SUCCESS) return false;
  std::vector<VkLayerProperties> layers(count);
  if (count > 0 && vkEnumerateInstanceLayerProperties(&count, layers.data()) != VK_SUCCESS) return false;
  for (const VkLayerProperties& layer : layers) {
    if (std::strcmp(layer.layerName, name) == 0) return true;
  }
  return false;
}

}  // namespace

// Creates an instance with no surface extensions (headless), at the highest API version up to
// 1.3 that the loader offers (at least 1.1). With SAAGEN_VK_VALIDATION set, the Khronos
// validation layer and VK_EXT_debug_utils are enabled and `messenger` reports to
// on_validation_message (instance creation and destruction too, through pNext). Throws with an
// install hint when the loader finds no driver or the layer is missing.

VkInstance create_headless_instance(std::uint32_t& api_version, VkDebugUtilsMessengerEXT* messenger) {
  api_version = VK_API_VERSION_1_1;
  std::uint32_t loader_version = VK_API_VERSION_1_0;
  if (vkEnumerateInstanceVersion(&loader_version) == VK_SUCCESS && loader_version >= VK_API_VERSION_1_1) {
    api_version = std::min<std::uint32_t>(loader_version, VK_API_VERSION_1_3);
  } else {
    throw std::runtime_error("the Vulkan loader supports only Vulkan 1.0; the harness needs 1.1: update libvulkan1");
  }
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "saagen-harness";
  app.apiVersion = api_version;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  const bool validation = validation_requested();
  const char* layers[] = {validation_layer_name};
  const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
  VkDebugUtilsMessengerCreateInfoEXT debug = messenger_info();
  if (validation) {
    if (!layer_available(validation_layer_name)) {
      throw std::runtime_error(fmt::format("{} is set but {} is not installed: install vulkan-validationlayers (scripts/install-deps.sh)",
                                           validation_env_var, validation_layer_name));
    }
    info.enabledLayerCount = 1;
    info.ppEnabledLayerNames = layers;
    info.enabledExtensionCount = 1;
    info.ppEnabledExtensionNames = extensions;
    info.pNext = &debug;
  }
  VkInstance instance = VK_NULL_HANDLE;
  const VkResult result = vkCreateInstance(&info, nullptr, &instance);
  if (result == VK_ERROR_INCOMPATIBLE_DRIVER || result == VK_ERROR_INITIALIZATION_FAILED) {
    throw std::runtime_error(fmt::format("no Vulkan device found (vkCreateInstance: {}): {}", vk_result_name(result), install_hint));
  }
  check_vk(result, "vkCreateInstance");
  if (validation && messenger) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    if (create == nullptr || create(instance, &debug, nullptr, messenger) != VK_SUCCESS) {
      vkDestroyInstance(instance, nullptr);
      throw std::runtime_error("validation layer on, but vkCreateDebugUtilsMessengerEXT failed");
    }
  }
  return instance;
}

void destroy_instance(VkInstance instance, VkDebugUtilsMessengerEXT messenger) {
  if (messenger != VK_NULL_HANDLE) {
    auto destroy =
        reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance, messenger, nullptr);
  }
  vkDestroyInstance(instance, nullptr);
}

namespace {

std::vector<VkPhysicalDevice> enumerate_devices(VkInstance instance) {
  std::uint32_t count = 0;
  SAAGEN_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  if (count > 0) SAAGEN_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
  devices.resize(count);
  return devices;
}

VkPhysicalDeviceProperties properties_of(VkPhysicalDevice device) {
  VkPhysicalDeviceProperties properties{};
  vkGetPhysicalDeviceProperties(device, &properties);
  return properties;
}

std::vector<std::string> device_names(const std::vector<VkPhysicalDevice>& devices) {
  std::vector<std::string> names;
  for (VkPhysicalDevice device : devices) names.emplace_back(properties_of(device).deviceName);
  return names;
}

std::vector<std::string> device_extension_names(VkPhysicalDevice device) {
  std::uint32_t count = 0;
  SAAGEN_VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr));
  std::vector<VkExtensionProperties> extensions(count);
  if (count > 0) SAAGEN_VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data()));
  std::vector<std::string> names;
  for (std::uint32_t i = 0; i < count; ++i) names.emplace_back(extensions[i].extensionName);
  return names;
}

bool is_lavapipe(const VkPhysicalDeviceProperties& properties) {
  return properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU || contains_case_insensitive(properties.deviceName, "llvmpipe");
}

std::string requested_device_name(const ContextOptions& options) {
  if (!options.device_name.empty()) return options.device_name;
  if (!options.read_environment) return {};
  const char* from_env = std::getenv(device_env_var);
  return from_env ? std::string(from_env) : std::string();
}

// The first queue family with graphics and compute (graphics implies transfer).
std::uint32_t find_queue_family(VkPhysicalDevice device, std::uint32_t& timestamp_valid_bits) {
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  constexpr VkQueueFlags needed = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  for (std::uint32_t i = 0; i < count; ++i) {
    if ((families[i].queueFlags & needed) == needed) {
      timestamp_valid_bits = families[i].timestampValidBits;
      return i;
    }
  }
  throw std::runtime_error("the Vulkan device has no queue family with both graphics and compute");
}

// Feature structures chained into VkPhysicalDeviceFeatures2, both for the query and (with the
// same values) for device creation, so that every supported optional feature is enabled.
struct FeatureChain {
  VkPhysicalDeviceFeatures2 core{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  VkPhysicalDevice16BitStorageFeatures storage16{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_16BIT_STORAGE_FEATURES};
  VkPhysicalDeviceShaderFloat16Int8Features float16_int8{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_FLOAT16_INT8_FEATURES};
  VkPhysicalDeviceShaderSubgroupExtendedTypesFeatures subgroup_types{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_SUBGROUP_EXTENDED_TYPES_FEATURES};
  // maintenance4 (core in 1.3) relaxes vertex-output / fragment-input matching: the built-in
  // full-screen vertex shader writes a uv that many fragment shaders do not read, which the
  // validation layer reports otherwise (UNASSIGNED-CoreValidation-Shader-OutputNotConsumed).
  VkPhysicalDeviceMaintenance4Features maintenance4{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_FEATURES};
  bool has_float16_int8 = false;
  bool has_subgroup_types = false;
  bool has_maintenance4 = false;

  FeatureChain(bool float16_int8_available, bool subgroup_types_available, bool maintenance4_available)
      : has_float16_int8(float16_int8_available), has_subgroup_types(subgroup_types_available), has_maintenance4(maintenance4_available) {
    // Only structures of supported versions/extensions may appear in the chain.
    void** next = &core.pNext;
    *next = &storage16;
    next = &storage16.pNext;
    if (has_float16_int8) {
      *next = &float16_int8;
      next = &float16_int8.pNext;
    }
    if (has_subgroup_types) {
      *next = &subgroup_types;
      next = &subgroup_types.pNext;
    }
    if (has_maintenance4) *next = &maintenance4;
  }
  FeatureChain(const FeatureChain&) = delete;
  FeatureChain& operator=(const FeatureChain&) = delete;

  // Keeps only the core features the harness wants: robustBufferAccess and friends stay off
  // because they change performance characteristics the benches measure.
  void restrict_core_features() {
    const VkPhysicalDeviceFeatures supported = core.features;
    VkPhysicalDeviceFeatures wanted{};
    wanted.fragmentStoresAndAtomics = supported.fragmentStoresAndAtomics;
    wanted.vertexPipelineStoresAndAtomics = supported.vertexPipelineStoresAndAtomics;
    wanted.samplerAnisotropy = supported.samplerAnisotropy;
    wanted.shaderFloat64 = supported.shaderFloat64;
    wanted.shaderInt64 = supported.shaderInt64;
    wanted.shaderInt16 = supported.shaderInt16;
    wanted.shaderImageGatherExtended = supported.shaderImageGatherExtended;
    wanted.shaderStorageImageExtendedFormats = supported.shaderStorageImageExtendedFormats;
    core.features = wanted;
  }
};

bool has_extension(const std::vector<std::string>& extensions, const char* name) {
  return std::find(extensions.begin(), extensions.end(), name) != extensions.end();
}

const char* subgroup_stage_names[] = {"vertex", "tess-control", "tess-eval", "geometry", "fragment", "compute"};
const char* subgroup_operation_names[] = {"basic", "vote", "arithmetic", "ballot", "shuffle", "shuffle-relative", "clustered", "quad"};

std::string flag_names(std::uint32_t flags, const char* const* names, std::size_t count) {
  std::vector<std::string> set;
  for (std::size_t bit = 0; bit < count; ++bit) {
    if (flags & (1u << bit)) set.emplace_back(names[bit]);
  }
  return fmt::format("{{{}}}", join(set, ", "));  // (operator+ here trips a GCC 12 -Wrestrict false positive)
}

}  // namespace

bool validation_requested() {
  const char* value = std::getenv(validation_env_var);
  return value != nullptr && *value != '\0' && std::strcmp(value, "0") != 0;
}

std::size_t validation_message_count() { return validation_messages.load(); }

std::string SubgroupInfo::describe() const {
  return fmt::format("size {}, stages {}, operations {}, quad in all stages: {}", size,
                     flag_names(supported_stages, subgroup_stage_names, std::size(subgroup_stage_names)),
                     flag_names(supported_operations, subgroup_operation_names, std::size(subgroup_operation_names)),
                     quad_operations_in_all_stages ? "yes" : "no");
}

std::string DeviceInfo::summary() const {
  return fmt::format(
      "{} ({}, Vulkan {}, driver {} {}); float16 {}, 16-bit storage {}, subgroup {}; timestamps {}", name, device_type_name(type),
      api_version_string(api_version), driver_name, driver_info, shader_float16 ? "yes" : "no", storage_buffer_16bit_access ? "yes" : "no",
      subgroup.describe(),
      timestamps_supported() ? fmt::format("{} valid bits, {} ns/tick", timestamp_valid_bits, timestamp_period_ns) : std::string("no"));
}

VulkanContext::VulkanContext(const ContextOptions& options) {
  create_instance();
  try {
    select_physical_device(options);
    query_device_info();
    if (is_null_hardware(physical_device_)) throw NullHardwareDevice(info_.summary());
    create_device();
  } catch (...) {
    if (device_ != VK_NULL_HANDLE) vkDestroyDevice(device_, nullptr);
    destroy_instance(instance_, messenger_);
    throw;
  }
}

VulkanContext::~VulkanContext() {
  if (device_ != VK_NULL_HANDLE) {
    vkDeviceWaitIdle(device_);  // nothing sensible to do with an error during teardown
    vkDestroyDevice(device_, nullptr);
  }
  if (instance_ != VK_NULL_HANDLE) destroy_instance(instance_, messenger_);
}

void VulkanContext::create_instance() { instance_ = create_headless_instance(instance_api_version_, &messenger_); }

void VulkanContext::select_physical_device(const ContextOptions& options) {
  const std::vector<VkPhysicalDevice> devices = enumerate_devices(instance_);
  if (devices.empty()) throw std::runtime_error(std::string("no Vulkan device found: ") + install_hint);

  const std::string wanted = requested_device_name(options);
  if (!wanted.empty()) {
    for (VkPhysicalDevice device : devices) {
      if (contains_case_insensitive(properties_of(device).deviceName, wanted)) {
        physical_device_ = device;
        return;
      }
    }
    throw std::runtime_error(fmt::format("Vulkan device '{}' not found (requested by --device or {}); available devices: {}", wanted,
                                         device_env_var, join(device_names(devices), "; ")));
  }
  // lavapipe by name first: SwiftShader is a CPU device too, and the loader's order of ICDs is
  // not lavapipe-first.
  physical_device_ = devices.front();
  for (VkPhysicalDevice device : devices) {
    if (contains_case_insensitive(properties_of(device).deviceName, "llvmpipe")) {
      physical_device_ = device;
      return;
    }
  }
  for (VkPhysicalDevice device : devices) {
    if (is_lavapipe(properties_of(device))) {
      physical_device_ = device;
      return;
    }
  }
}

void VulkanContext::query_device_info() {
  const VkPhysicalDeviceProperties basic = properties_of(physical_device_);
  device_extensions_ = device_extension_names(physical_device_);
  limits_ = basic.limits;
  if (basic.apiVersion < VK_API_VERSION_1_1) {
    throw std::runtime_error(fmt::format("Vulkan device '{}' supports only Vulkan {}; the harness needs 1.1", basic.deviceName,
                                         api_version_string(basic.apiVersion)));
  }
  const bool vulkan12 = basic.apiVersion >= VK_API_VERSION_1_2 && instance_api_version_ >= VK_API_VERSION_1_2;

  DeviceInfo& d = info_;
  d.name = basic.deviceName;
  d.type = basic.deviceType;
  d.api_version = basic.apiVersion;
  d.driver_version = basic.driverVersion;
  d.vendor_id = basic.vendorID;
  d.device_id = basic.deviceID;
  d.timestamp_period_ns = basic.limits.timestampPeriod;
  d.max_sampler_anisotropy = basic.limits.maxSamplerAnisotropy;
  d.max_push_constants_size = basic.limits.maxPushConstantsSize;
  std::copy(std::begin(basic.limits.maxComputeWorkGroupCount), std::end(basic.limits.maxComputeWorkGroupCount),
            std::begin(d.max_compute_work_group_count));
  d.max_compute_work_group_invocations = basic.limits.maxComputeWorkGroupInvocations;
  d.max_storage_buffer_range = basic.limits.maxStorageBufferRange;

  VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceFloatControlsProperties float_controls{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FLOAT_CONTROLS_PROPERTIES};
  properties.pNext = &subgroup;
  if (vulkan12) {
    subgroup.pNext = &driver;
    driver.pNext = &float_controls;
  }
  vkGetPhysicalDeviceProperties2(physical_device_, &properties);
  d.subgroup.size = subgroup.subgroupSize;
  d.subgroup.supported_stages = subgroup.supportedStages;
  d.subgroup.supported_operations = subgroup.supportedOperations;
  d.subgroup.quad_operations_in_all_stages = subgroup.quadOperationsInAllStages == VK_TRUE;
  if (vulkan12) {
    d.driver_name = driver.driverName;
    d.driver_info = driver.driverInfo;
    FloatControls& fc = d.float_controls;
    fc.denorm_preserve_float16 = float_controls.shaderDenormPreserveFloat16;
    fc.denorm_preserve_float32 = float_controls.shaderDenormPreserveFloat32;
    fc.denorm_flush_to_zero_float16 = float_controls.shaderDenormFlushToZeroFloat16;
    fc.denorm_flush_to_zero_float32 = float_controls.shaderDenormFlushToZeroFloat32;
    fc.signed_zero_inf_nan_preserve_float16 = float_controls.shaderSignedZeroInfNanPreserveFloat16;
    fc.signed_zero_inf_nan_preserve_float32 = float_controls.shaderSignedZeroInfNanPreserveFloat32;
  }
  queue_family_ = find_queue_family(physical_device_, d.timestamp_valid_bits);
  // Timestamps need the queue's valid bits and, for graphics+compute queues, this limit.
  if (!basic.limits.timestampComputeAndGraphics) d.timestamp_valid_bits = 0;
}

void VulkanContext::create_device() {
  const bool vulkan12 = info_.api_version >= VK_API_VERSION_1_2 && instance_api_version_ >= VK_API_VERSION_1_2;
  std::vector<const char*> extensions;
  const bool float16_ext = !vulkan12 && has_extension(device_extensions_, VK_KHR_SHADER_FLOAT16_INT8_EXTENSION_NAME);
  const bool subgroup_types_ext = !vulkan12 && has_extension(device_extensions_, VK_KHR_SHADER_SUBGROUP_EXTENDED_TYPES_EXTENSION_NAME);
  if (float16_ext) extensions.push_back(VK_KHR_SHADER_FLOAT16_INT8_EXTENSION_NAME);
  if (subgroup_types_ext) extensions.push_back(VK_KHR_SHADER_SUBGROUP_EXTENDED_TYPES_EXTENSION_NAME);

  const bool vulkan13 = info_.api_version >= VK_API_VERSION_1_3 && instance_api_version_ >= VK_API_VERSION_1_3;
  const bool maintenance4_ext = !vulkan13 && has_extension(device_extensions_, VK_KHR_MAINTENANCE_4_EXTENSION_NAME);
  if (maintenance4_ext) extensions.push_back(VK_KHR_MAINTENANCE_4_EXTENSION_NAME);
  FeatureChain features(vulkan12 || float16_ext, vulkan12 || subgroup_types_ext, vulkan13 || maintenance4_ext);
  vkGetPhysicalDeviceFeatures2(physical_device_, &features.core);
  features.restrict_core_features();
  // The 16-bit storage and fp16/int8 structures are enabled as queried (all supported bits).

  DeviceInfo& d = info_;
  const VkPhysicalDeviceFeatures& core = features.core.features;
  d.fragment_stores_and_atomics = core.fragmentStoresAndAtomics;
  d.sampler_anisotropy = core.samplerAnisotropy;
  d.shader_float64 = core.shaderFloat64;
  d.shader_int64 = core.shaderInt64;
  d.shader_int16 = core.shaderInt16;
  d.storage_buffer_16bit_access = features.storage16.storageBuffer16BitAccess;
  d.uniform_and_storage_buffer_16bit_access = features.storage16.uniformAndStorageBuffer16BitAccess;
  d.storage_push_constant_16 = features.storage16.storagePushConstant16;
  d.storage_input_output_16 = features.storage16.storageInputOutput16;
  if (features.has_float16_int8) {
    d.shader_float16 = features.float16_int8.shaderFloat16;
    d.shader_int8 = features.float16_int8.shaderInt8;
  }
  if (features.has_subgroup_types) d.subgroup_extended_types = features.subgroup_types.shaderSubgroupExtendedTypes;

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue_info.queueFamilyIndex = queue_family_;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;

  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  info.pNext = &features.core;  // features come through the chain, pEnabledFeatures stays null
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue_info;
  info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  SAAGEN_VK_CHECK(vkCreateDevice(physical_device_, &info, nullptr, &device_));
  vkGetDeviceQueue(device_, queue_family_, 0, &queue_);
}

std::uint32_t VulkanContext::find_memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags required) const {
  VkPhysicalDeviceMemoryProperties memory{};
  vkGetPhysicalDeviceMemoryProperties(physical_device_, &memory);
  for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
    if ((type_bits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & required) == required) return i;
  }
  throw std::runtime_error(fmt::format("no Vulkan memory type with property flags {:#x} on '{}'", required, info_.name));
}

VkDeviceMemory VulkanContext::allocate_memory(const VkMemoryRequirements& requirements, VkMemoryPropertyFlags preferred,
                                              VkMemoryPropertyFlags required) const {
  std::uint32_t type = 0;
  try {
    type = find_memory_type(requirements.memoryTypeBits, preferred);
  } catch (const std::runtime_error&) {
    type = find_memory_type(requirements.memoryTypeBits, required);
  }
  VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  info.allocationSize = requirements.size;
  info.memoryTypeIndex = type;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  SAAGEN_VK_CHECK(vkAllocateMemory(device_, &info, nullptr, &memory));
  return memory;
}

VkFormatProperties VulkanContext::format_properties(VkFormat format) const {
  VkFormatProperties properties{};
  vkGetPhysicalDeviceFormatProperties(physical_device_, format, &properties);
  return properties;
}

std::vector<std::string> VulkanContext::available_devices() {
  std::uint32_t api_version = 0;
  VkInstance instance = create_headless_instance(api_version);
  std::vector<std::string> names;
  try {
    names = device_names(enumerate_devices(instance));
  } catch (...) {
    vkDestroyInstance(instance, nullptr);
    throw;
  }
  vkDestroyInstance(instance, nullptr);
  return names;
}

std::string take_device_flag(int& argc, char** argv) {
  std::string name;
  int out = 1;
  for (int in = 1; in < argc; ++in) {
    const std::string arg = argv[in];
    if (arg == "--device" && in + 1 < argc) {
      name = argv[++in];
    } else if (arg.rfind("--device=", 0) == 0) {
      name = arg.substr(std::strlen("--device="));
    } else {
      argv[out++] = argv[in];
    }
  }
  argc = out;
  argv[out] = nullptr;  // argv[argc] is null by convention
  return name;
}

}  // namespace saagen::harness

namespace saagen::harness {

void VulkanContext::require_capabilities(const std::vector<std::uint32_t>& spirv, VkShaderStageFlags stage) const {
  // SPIR-V 1.6 Sec. 2.4: the OpCapability instructions (opcode 17) open the module after the
  // 5-word header. Vulkan spec, Appendix A "Capabilities": a capability may be used only when
  // its feature is enabled (or its extension / core version supported).
  constexpr std::uint32_t op_capability = 17;
  const DeviceInfo& d = info_;
  const auto subgroup = [&](VkSubgroupFeatureFlags operation) { return d.subgroup.supports(operation, stage); };
  for (std::size_t at = 5; at < spirv.size();) {
    const std::uint32_t words = spirv[at] >> 16, opcode = spirv[at] & 0xffffu;
    if (opcode != op_capability || words < 2 || at + 1 >= spirv.size()) break;
    const std::uint32_t capability = spirv[at + 1];
    at += words;
    const char* missing = nullptr;
    switch (capability) {
      case 9:
        if (!d.shader_float16) missing = "shaderFloat16 (SPIR-V capability Float16)";
        break;
      case 10:
        if (!d.shader_float64) missing = "shaderFloat64 (SPIR-V capability Float64)";
        break;
      case 11:
        if (!d.shader_int64) missing = "shaderInt64 (SPIR-V capability Int64)";
        break;
      case 22:
        if (!d.shader_int16) missing = "shaderInt16 (SPIR-V capability Int16)";
        break;
      case 39:
        if (!d.shader_int8) missing = "shaderInt8 (SPIR-V capability Int8)";
        break;
      case 4433:
        if (!d.storage_buffer_16bit_access) missing = "storageBuffer16BitAccess";
        break;
      case 4434:
        if (!d.uniform_and_storage_buffer_16bit_access) missing = "uniformAndStorageBuffer16BitAccess";
        break;
      case 4435:
        if (!d.storage_push_constant_16) missing = "storagePushConstant16";
        break;
      case 4436:
        if (!d.storage_input_output_16) missing = "storageInputOutput16";
        break;
      case 61:
        if (!subgroup(VK_SUBGROUP_FEATURE_BASIC_BIT)) missing = "subgroup basic operations in this stage";
        break;
      case 62:
        if (!subgroup(VK_SUBGROUP_FEATURE_VOTE_BIT)) missing = "subgroup vote operations in this stage";
        break;
      case 63:
        if (!subgroup(VK_SUBGROUP_FEATURE_ARITHMETIC_BIT)) missing = "subgroup arithmetic operations in this stage";
        break;
      case 64:
        if (!subgroup(VK_SUBGROUP_FEATURE_BALLOT_BIT)) missing = "subgroup ballot operations in this stage";
        break;
      case 65:
        if (!subgroup(VK_SUBGROUP_FEATURE_SHUFFLE_BIT)) missing = "subgroup shuffle operations in this stage";
        break;
      case 66:
        if (!subgroup(VK_SUBGROUP_FEATURE_SHUFFLE_RELATIVE_BIT)) missing = "subgroup relative shuffle operations in this stage";
        break;
      case 67:
        if (!subgroup(VK_SUBGROUP_FEATURE_CLUSTERED_BIT)) missing = "subgroup clustered operations in this stage";
        break;
      case 68:
        if (!subgroup(VK_SUBGROUP_FEATURE_QUAD_BIT)) missing = "subgroup quad operations in this stage";
        break;
      default:
        break;
    }
    if (missing) throw UnsupportedFeature(d.name, missing);
  }
}

}  // namespace saagen::harness
