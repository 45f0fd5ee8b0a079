// GPU cost without a GPU: Mesa's RADV driver creates a "null hardware" device when
// RADV_FORCE_FAMILY names an AMD chip family (no AMD GPU needed). Pipelines compile through ACO,
// AMD's production shader compiler in Mesa, and VK_KHR_pipeline_executable_properties returns the
// statistics of the real ISA: instructions, VGPRs, SGPRs, subgroups per SIMD (occupancy), and
// ACO's latency and inverse-throughput estimates. Nothing ever executes on such a device: the
// IsaCompiler only creates pipelines and reads their statistics (no queue, memory or command
// buffer is ever used).
//
//   IsaCompiler vega10("vega10");   // GFX9, the RX Vega 56 of Tokuyoshi & Kaplanyan 2019, Table 2
//   IsaStatistics stats = vega10.fragment(fragment_spirv, {IsaBinding::storage_buffer(0), ...});
//   stats.instructions, stats.vgprs, stats.inverse_throughput, ...
//
// The environment the RADV ICD reads (VK_ICD_FILENAMES pointed at its manifest, RADV_FORCE_FAMILY)
// is set only while the instance is created and its devices enumerated, then restored, so
// VulkanContexts of the same process keep their own devices. Not thread-safe (setenv).
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace saagen::harness {

// The families the tests and `saagen bench --isa` measure by default, and every family name
// Mesa 22.3's RADV accepts for RADV_FORCE_FAMILY that the harness offers.
inline constexpr const char* isa_default_family = "vega10";
const std::vector<std::string>& isa_families();

// Environment variable overriding where the RADV ICD manifest is (default: the first
// /usr/share/vulkan/icd.d/radeon_icd*.json).
inline constexpr const char* radv_icd_env_var = "SAAGEN_RADV_ICD";

// One descriptor of set 0 the shader uses.
struct IsaBinding {
  std::uint32_t binding = 0;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  static IsaBinding storage_buffer(std::uint32_t binding) { return {binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}; }
  static IsaBinding sampled_image(std::uint32_t binding) { return {binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}; }
  static IsaBinding storage_image(std::uint32_t binding) { return {binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}; }
};

struct IsaLayout {
  std::vector<IsaBinding> bindings;
  std::uint32_t push_constant_bytes = 0;
  std::vector<VkFormat> color_formats;  // fragment pipelines: the colour attachments
};

// The statistics of one pipeline executable (the fragment or compute shader), named as RADV
// reports them. The fields below are the ones the cost model uses; `all` holds every statistic.
struct IsaStatistics {
  std::string family;
  std::string device_name;        // e.g. "AMD RADV VEGA10"
  std::string executable;         // RADV's executable name, e.g. "fragment shader"
  double instructions = 0;        // "Instructions"
  double vgprs = 0;               // "VGPRs"
  double sgprs = 0;               // "SGPRs"
  double subgroups_per_simd = 0;  // "Subgroups per SIMD": the occupancy (waves per SIMD)
  double latency = 0;             // "Latency": ACO's estimate of one wave's cycles
  double inverse_throughput = 0;  // "Inverse Throughput": ACO's estimate of cycles per wave at full occupancy
  double code_size = 0;           // "Code size" in bytes
  std::map<std::string, double> all;
};

class IsaCompiler {
 public:
  // Creates the null-hardware device of `family` (a name of isa_families()). Throws with one
  // line naming what to install or set when the RADV ICD is missing or rejects the family.
  explicit IsaCompiler(const std::string& family);
  ~IsaCompiler();
  IsaCompiler(const IsaCompiler&) = delete;
  IsaCompiler& operator=(const IsaCompiler&) = delete;

  const std::string& family() const { return family_; }
  const std::string& device_name() const { return device_name_; }
  const std::string& driver_info() const { return driver_info_; }

  // Compiles a graphics pipeline (the built-in full-screen vertex shader when `vertex` is empty,
  // then `fragment`) and returns the fragment shader's statistics.
  IsaStatistics fragment(const std::vector<std::uint32_t>& fragment, const IsaLayout& layout,
                         const std::vector<std::uint32_t>& vertex = {}) const;
  // Compiles a compute pipeline and returns its statistics.
  IsaStatistics compute(const std::vector<std::uint32_t>& spirv, const IsaLayout& layout) const;

 private:
  struct Handles;
  std::string family_;
  std::string device_name_;
  std::string driver_info_;
  std::unique_ptr<Handles> handles_;
};

// Whether a physical device is RADV's null-hardware device (RADV with RADV_FORCE_FAMILY set in
// this process): it compiles but cannot execute anything.
bool is_null_hardware(VkPhysicalDevice device);

}  // namespace saagen::harness
