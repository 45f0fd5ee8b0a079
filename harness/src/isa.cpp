#include "saagen/harness/isa.hpp"

#include "fixed_function.hpp"
#include "instance.hpp"
#include "vk_handle.hpp"

#include "saagen/harness/error.hpp"
#include "saagen/harness/shader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <stdexcept>

namespace saagen::harness {
namespace {

constexpr const char* radv_family_env_var = "RADV_FORCE_FAMILY";

// Sets environment variables for the lifetime of the object and restores the previous values
// (or their absence) afterwards.
class ScopedEnvironment {
 public:
  ScopedEnvironment() = default;
  ScopedEnvironment(const ScopedEnvironment&) = delete;
  ScopedEnvironment& operator=(const ScopedEnvironment&) = delete;
  ~ScopedEnvironment() {
    for (auto it = saved_.rbegin(); it != saved_.rend(); ++it) {
      if (it->second) {
        setenv(it->first.c_str(), it->second->c_str(), 1);
      } else {
        unsetenv(it->first.c_str());
      }
    }
  }
  void set(const char* name, const std::string& value) {
    const char* previous = std::getenv(name);
    saved_.emplace_back(name, previous ? std::optional<std::string>(previous) : std::nullopt);
    setenv(name, value.c_str(), 1);
  }
  void unset(const char* name) {
    const char* previous = std::getenv(name);
    saved_.emplace_back(name, previous ? std::optional<std::string>(previous) : std::nullopt);
    unsetenv(name);
  }

 private:
  std::vector<std::pair<std::string, std::optional<std::string>>> saved_;
};

std::string radv_icd_path() {
  if (const char* from_env = std::getenv(radv_icd_env_var); from_env && *from_env) return from_env;
  const std::filesystem::path directory = "/usr/share/vulkan/icd.d";
  std::error_code error;
  std::vector<std::string> found;
  for (const auto& entry : std::filesystem::directory_iterator(directory, error)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("radeon_icd", 0) == 0 && entry.path().extension() == ".json") found.push_back(entry.path().string());
  }
  if (found.empty()) {
    throw std::runtime_error(
        fmt::format("no RADV ICD manifest (radeon_icd*.json) in {}: install mesa-vulkan-drivers "
                    "(scripts/install-deps.sh) or set {} to its path",
                    directory.string(), radv_icd_env_var));
  }
  std::sort(found.begin(), found.end());
  return found.front();
}

VkPhysicalDeviceDriverProperties driver_properties(VkPhysicalDevice device) {
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  properties.pNext = &driver;
  vkGetPhysicalDeviceProperties2(device, &properties);
  return driver;
}

bool has_device_extension(VkPhysicalDevice device, const char* name) {
  std::uint32_t count = 0;
  SAAGEN_VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr));
  std::vector<VkExtensionProperties> extensions(count);
  if (count > 0) SAAGEN_VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data()));
  return std::any_of(extensions.begin(), extensions.end(),
                     [&](const VkExtensionProperties& extension) { return std::strcmp(extension.extensionName, name) == 0; });
}

double statistic_value(const VkPipelineExecutableStatisticKHR& statistic) {
  switch (statistic.format) {
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR:
      return statistic.value.b32 ? 1.0 : 0.0;
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR:
      return static_cast<double>(statistic.value.i64);
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR:
      return static_cast<double>(statistic.value.u64);
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_FLOAT64_KHR:
      return statistic.value.f64;
    default:
      return 0.0;
  }
}

}  // namespace

const std::vector<std::string>& isa_families() {
  // GFX8 (Polaris), GFX9 (Vega: the paper's RX Vega 56 is a vega10), RDNA1, RDNA2.
  static const std::vector<std::string> families = {"polaris10", "vega10", "navi10", "navi21"};
  return families;
}

bool is_null_hardware(VkPhysicalDevice device) {
  const char* family = std::getenv(radv_family_env_var);
  return family != nullptr && *family != '\0' && driver_properties(device).driverID == VK_DRIVER_ID_MESA_RADV;
}

struct IsaCompiler::Handles {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  PFN_vkGetPipelineExecutablePropertiesKHR executable_properties = nullptr;
  PFN_vkGetPipelineExecutableStatisticsKHR executable_statistics = nullptr;

  ~Handles() {
    if (device != VK_NULL_HANDLE) vkDestroyDevice(device, nullptr);
    if (instance != VK_NULL_HANDLE) destroy_instance(instance, messenger);
  }

  IsaStatistics statistics(VkPipeline pipeline, VkShaderStageFlags stage) const;
};

namespace {

// The optional features a kernel may need, each enabled when RADV supports it (it supports them
// all on every family the harness offers).
struct IsaFeatures {
  VkPhysicalDeviceFeatures2 core{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  VkPhysicalDeviceVulkan11Features vulkan11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
  VkPhysicalDeviceVulkan12Features vulkan12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceMaintenance4Features maintenance4{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_FEATURES};
  VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR executables{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR};

  IsaFeatures() {
    core.pNext = &vulkan11;
    vulkan11.pNext = &vulkan12;
    vulkan12.pNext = &maintenance4;
    maintenance4.pNext = &executables;
  }
  IsaFeatures(const IsaFeatures&) = delete;
  IsaFeatures& operator=(const IsaFeatures&) = delete;

  void keep_wanted() {
    const VkPhysicalDeviceFeatures supported = core.features;
    core.features = VkPhysicalDeviceFeatures{};
    core.features.fragmentStoresAndAtomics = supported.fragmentStoresAndAtomics;
    core.features.shaderInt16 = supported.shaderInt16;
    core.features.shaderFloat64 = supported.shaderFloat64;
    core.features.shaderInt64 = supported.shaderInt64;
    core.features.shaderStorageImageWriteWithoutFormat = supported.shaderStorageImageWriteWithoutFormat;
    core.features.shaderStorageImageReadWithoutFormat = supported.shaderStorageImageReadWithoutFormat;
    const VkPhysicalDeviceVulkan11Features v11 = vulkan11;
    vulkan11 = VkPhysicalDeviceVulkan11Features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES, &vulkan12};
    vulkan11.storageBuffer16BitAccess = v11.storageBuffer16BitAccess;
    vulkan11.uniformAndStorageBuffer16BitAccess = v11.uniformAndStorageBuffer16BitAccess;
    vulkan11.storagePushConstant16 = v11.storagePushConstant16;
    vulkan11.storageInputOutput16 = v11.storageInputOutput16;
    const VkPhysicalDeviceVulkan12Features v12 = vulkan12;
    vulkan12 = VkPhysicalDeviceVulkan12Features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &maintenance4};
    vulkan12.shaderFloat16 = v12.shaderFloat16;
    vulkan12.shaderInt8 = v12.shaderInt8;
    vulkan12.storageBuffer8BitAccess = v12.storageBuffer8BitAccess;
    vulkan12.shaderSubgroupExtendedTypes = v12.shaderSubgroupExtendedTypes;
  }
};

}  // namespace

IsaCompiler::IsaCompiler(const std::string& family) : family_(family), handles_(std::make_unique<Handles>()) {
  if (std::find(isa_families().begin(), isa_families().end(), family) == isa_families().end()) {
    std::string known;
    for (const std::string& name : isa_families()) known += (known.empty() ? "" : ", ") + name;
    throw std::runtime_error(fmt::format("unknown GPU family '{}'; allowed: {}", family, known));
  }
  {
    // The loader reads VK_ICD_FILENAMES when the instance is created; RADV reads
    // RADV_FORCE_FAMILY when it enumerates its devices (and creates its shader cache, kept off
    // so that every pipeline is compiled and carries its statistics).
    ScopedEnvironment environment;
    environment.set("VK_ICD_FILENAMES", radv_icd_path());
    environment.unset("VK_DRIVER_FILES");
    environment.set(radv_family_env_var, family);
    environment.set("MESA_SHADER_CACHE_DISABLE", "true");
    std::uint32_t api_version = 0;
    handles_->instance = create_headless_instance(api_version, &handles_->messenger);
    if (api_version < VK_API_VERSION_1_3) {
      throw std::runtime_error("the Vulkan loader offers less than Vulkan 1.3; the ISA statistics need 1.3: update libvulkan1");
    }
    std::uint32_t count = 0;
    SAAGEN_VK_CHECK(vkEnumeratePhysicalDevices(handles_->instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    if (count > 0) SAAGEN_VK_CHECK(vkEnumeratePhysicalDevices(handles_->instance, &count, devices.data()));
    for (VkPhysicalDevice device : devices) {
      if (driver_properties(device).driverID == VK_DRIVER_ID_MESA_RADV) handles_->physical = device;
    }
  }
  if (handles_->physical == VK_NULL_HANDLE) {
    throw std::runtime_error(fmt::format("RADV created no device for {}={}: install mesa-vulkan-drivers (scripts/install-deps.sh)",
                                         radv_family_env_var, family));
  }
  VkPhysicalDeviceProperties properties{};
  vkGetPhysicalDeviceProperties(handles_->physical, &properties);
  device_name_ = properties.deviceName;
  driver_info_ = driver_properties(handles_->physical).driverInfo;
  if (properties.apiVersion < VK_API_VERSION_1_3) {
    throw std::runtime_error(fmt::format("{} offers Vulkan {}.{}; the ISA statistics need 1.3", device_name_,
                                         VK_API_VERSION_MAJOR(properties.apiVersion), VK_API_VERSION_MINOR(properties.apiVersion)));
  }
  if (!has_device_extension(handles_->physical, VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME)) {
    throw std::runtime_error(fmt::format("{} lacks {}", device_name_, VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME));
  }

  IsaFeatures features;
  vkGetPhysicalDeviceFeatures2(handles_->physical, &features.core);
  features.keep_wanted();
  features.executables.pipelineExecutableInfo = VK_TRUE;
  // A device needs one queue; it is never fetched or submitted to.
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue.queueFamilyIndex = 0;
  queue.queueCount = 1;
  queue.pQueuePriorities = &priority;
  const char* extensions[] = {VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME};
  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  info.pNext = &features.core;
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue;
  info.enabledExtensionCount = 1;
  info.ppEnabledExtensionNames = extensions;
  SAAGEN_VK_CHECK(vkCreateDevice(handles_->physical, &info, nullptr, &handles_->device));
  handles_->executable_properties = reinterpret_cast<PFN_vkGetPipelineExecutablePropertiesKHR>(
      vkGetDeviceProcAddr(handles_->device, "vkGetPipelineExecutablePropertiesKHR"));
  handles_->executable_statistics = reinterpret_cast<PFN_vkGetPipelineExecutableStatisticsKHR>(
      vkGetDeviceProcAddr(handles_->device, "vkGetPipelineExecutableStatisticsKHR"));
  if (!handles_->executable_properties || !handles_->executable_statistics) {
    throw std::runtime_error(fmt::format("{}: no vkGetPipelineExecutable*KHR entry points", device_name_));
  }
}

IsaCompiler::~IsaCompiler() = default;

IsaStatistics IsaCompiler::Handles::statistics(VkPipeline pipeline, VkShaderStageFlags stage) const {
  VkPipelineInfoKHR pipeline_info{VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR};
  pipeline_info.pipeline = pipeline;
  std::uint32_t count = 0;
  SAAGEN_VK_CHECK(executable_properties(device, &pipeline_info, &count, nullptr));
  std::vector<VkPipelineExecutablePropertiesKHR> executables(count, {VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR});
  SAAGEN_VK_CHECK(executable_properties(device, &pipeline_info, &count, executables.data()));
  for (std::uint32_t index = 0; index < count; ++index) {
    if ((executables[index].stages & stage) == 0) continue;
    VkPipelineExecutableInfoKHR executable{VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR};
    executable.pipeline = pipeline;
    executable.executableIndex = index;
    std::uint32_t statistic_count = 0;
    SAAGEN_VK_CHECK(executable_statistics(device, &executable, &statistic_count, nullptr));
    std::vector<VkPipelineExecutableStatisticKHR> statistics(statistic_count, {VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR});
    SAAGEN_VK_CHECK(executable_statistics(device, &executable, &statistic_count, statistics.data()));
    IsaStatistics result;
    result.executable = executables[index].name;
    for (std::uint32_t at = 0; at < statistic_count; ++at) result.all[statistics[at].name] = statistic_value(statistics[at]);
    const auto take = [&](const char* name) {
      const auto found = result.all.find(name);
      if (found == result.all.end()) {
        throw std::runtime_error(fmt::format("the {} executable reports no \"{}\" statistic (is ACO the compiler? unset RADV_DEBUG=llvm)",
                                             result.executable, name));
      }
      return found->second;
    };
    result.instructions = take("Instructions");
    result.vgprs = take("VGPRs");
    result.sgprs = take("SGPRs");
    result.subgroups_per_simd = take("Subgroups per SIMD");
    result.latency = take("Latency");
    result.inverse_throughput = take("Inverse Throughput");
    result.code_size = take("Code size");
    return result;
  }
  throw std::runtime_error("the pipeline has no executable of the requested stage");
}

namespace {

DeviceHandle<VkShaderModule> shader_module(VkDevice device, const std::vector<std::uint32_t>& spirv) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = spirv.size() * sizeof(std::uint32_t);
  info.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  SAAGEN_VK_CHECK(vkCreateShaderModule(device, &info, nullptr, &module));
  return {device, module, vkDestroyShaderModule};
}

struct Layouts {
  DeviceHandle<VkDescriptorSetLayout> set;
  DeviceHandle<VkPipelineLayout> pipeline;
};

Layouts pipeline_layout(VkDevice device, const IsaLayout& layout, VkShaderStageFlags stages) {
  std::vector<VkDescriptorSetLayoutBinding> bindings;
  for (const IsaBinding& binding : layout.bindings) bindings.push_back({binding.binding, binding.type, 1, stages, nullptr});
  VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  set_info.bindingCount = static_cast<std::uint32_t>(bindings.size());
  set_info.pBindings = bindings.data();
  VkDescriptorSetLayout set = VK_NULL_HANDLE;
  SAAGEN_VK_CHECK(vkCreateDescriptorSetLayout(device, &set_info, nullptr, &set));
  Layouts layouts;
  layouts.set = {device, set, vkDestroyDescriptorSetLayout};

  const VkPushConstantRange range{stages, 0, layout.push_constant_bytes};
  VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  info.setLayoutCount = 1;
  info.pSetLayouts = &set;
  info.pushConstantRangeCount = layout.push_constant_bytes > 0 ? 1 : 0;
  info.pPushConstantRanges = &range;
  VkPipelineLayout pipeline = VK_NULL_HANDLE;
  SAAGEN_VK_CHECK(vkCreatePipelineLayout(device, &info, nullptr, &pipeline));
  layouts.pipeline = {device, pipeline, vkDestroyPipelineLayout};
  return layouts;
}

DeviceHandle<VkRenderPass> render_pass(VkDevice device, const std::vector<VkFormat>& formats) {
  std::vector<VkAttachmentDescription> attachments;
  std::vector<VkAttachmentReference> references;
  for (VkFormat format : formats) {
    VkAttachmentDescription attachment{};
    attachment.format = format;
    attachment.samples = VK_SAMPLE_COUNT_1_BIT;
    attachment.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachment.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachment.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachment.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    attachment.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    references.push_back({static_cast<std::uint32_t>(attachments.size()), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL});
    attachments.push_back(attachment);
  }
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = static_cast<std::uint32_t>(references.size());
  subpass.pColorAttachments = references.data();
  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = static_cast<std::uint32_t>(attachments.size());
  info.pAttachments = attachments.data();
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  VkRenderPass pass = VK_NULL_HANDLE;
  SAAGEN_VK_CHECK(vkCreateRenderPass(device, &info, nullptr, &pass));
  return {device, pass, vkDestroyRenderPass};
}

}  // namespace

IsaStatistics IsaCompiler::fragment(const std::vector<std::uint32_t>& fragment, const IsaLayout& layout,
                                    const std::vector<std::uint32_t>& vertex) const {
  const VkDevice device = handles_->device;
  const auto vertex_module = shader_module(device, vertex.empty() ? fullscreen_vertex_spirv() : vertex);
  const auto fragment_module = shader_module(device, fragment);
  const Layouts layouts = pipeline_layout(device, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT);
  const auto pass = render_pass(device, layout.color_formats);

  VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                               {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vertex_module.get();
  stages[0].pName = "main";
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fragment_module.get();
  stages[1].pName = "main";
  const detail::FixedFunctionState fixed_function(64, 64, layout.color_formats.size());

  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.flags = VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR;
  info.stageCount = 2;
  info.pStages = stages;
  fixed_function.apply(info);
  info.layout = layouts.pipeline.get();
  info.renderPass = pass.get();
  VkPipeline pipeline = VK_NULL_HANDLE;
  SAAGEN_VK_CHECK(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
  const DeviceHandle<VkPipeline> owned(device, pipeline, vkDestroyPipeline);
  IsaStatistics statistics = handles_->statistics(pipeline, VK_SHADER_STAGE_FRAGMENT_BIT);
  statistics.family = family_;
  statistics.device_name = device_name_;
  return statistics;
}

IsaStatistics IsaCompiler::compute(const std::vector<std::uint32_t>& spirv, const IsaLayout& layout) const {
  const VkDevice device = handles_->device;
  const auto module = shader_module(device, spirv);
  const Layouts layouts = pipeline_layout(device, layout, VK_SHADER_STAGE_COMPUTE_BIT);
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.flags = VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR;
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module.get();
  info.stage.pName = "main";
  info.layout = layouts.pipeline.get();
  VkPipeline pipeline = VK_NULL_HANDLE;
  SAAGEN_VK_CHECK(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
  const DeviceHandle<VkPipeline> owned(device, pipeline, vkDestroyPipeline);
  IsaStatistics statistics = handles_->statistics(pipeline, VK_SHADER_STAGE_COMPUTE_BIT);
  statistics.family = family_;
  statistics.device_name = device_name_;
  return statistics;
}

}  // namespace saagen::harness
