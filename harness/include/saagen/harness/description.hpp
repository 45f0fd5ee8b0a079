// Declarative test cases, in the spirit of Amber: a shader (SPIR-V + entry point), the
// resources bound to descriptor set 0, push-constant bytes, and either a dispatch size
// (compute) or a framebuffer (fragment). Programs in program.hpp turn these into Vulkan work.
#pragma once

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <saagen/harness/bytes.hpp>
#include <string>
#include <vector>

namespace saagen::harness {

// A 32-bit specialization constant (int, uint, bool or float bits).
struct SpecConstant {
  std::uint32_t id = 0;
  std::uint32_t bits = 0;

  static SpecConstant from_uint(std::uint32_t id, std::uint32_t value) { return {id, value}; }
  static SpecConstant from_int(std::uint32_t id, std::int32_t value);
  static SpecConstant from_float(std::uint32_t id, float value);
  static SpecConstant from_bool(std::uint32_t id, bool value) { return {id, value ? 1u : 0u}; }
};

struct ShaderDesc {
  std::vector<std::uint32_t> spirv;
  std::string entry_point = "main";
  std::vector<SpecConstant> spec_constants;
};

enum class BufferKind { storage, uniform };

// A host-visible buffer at (set 0, binding). Its size is max(size, data.size()); bytes past
// `data` start as zero. With read_back, its final contents appear in RunResult::buffers.
struct BufferBinding {
  std::uint32_t binding = 0;
  BufferKind kind = BufferKind::storage;
  Bytes data;
  std::size_t size = 0;
  bool read_back = true;
};

// An input buffer initialised with `values`; not read back.
template <typename T>
BufferBinding input_buffer(std::uint32_t binding, const std::vector<T>& values) {
  return BufferBinding{binding, BufferKind::storage, to_bytes(values), 0, false};
}

// A zero-initialised output buffer of `count` elements of T; read back.
template <typename T>
BufferBinding output_buffer(std::uint32_t binding, std::size_t count) {
  return BufferBinding{binding, BufferKind::storage, {}, count * sizeof(T), true};
}

struct SamplerDesc {
  VkFilter mag_filter = VK_FILTER_NEAREST;
  VkFilter min_filter = VK_FILTER_NEAREST;
  VkSamplerMipmapMode mipmap_mode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  VkSamplerAddressMode address_u = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  VkSamplerAddressMode address_v = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  VkSamplerAddressMode address_w = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  float mip_lod_bias = 0.0f;
  bool anisotropy_enable = false;  // requires DeviceInfo::sampler_anisotropy
  float max_anisotropy = 1.0f;     // must not exceed DeviceInfo::max_sampler_anisotropy
  float min_lod = 0.0f;
  float max_lod = VK_LOD_CLAMP_NONE;
  VkBorderColor border_color = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;

  // Same address mode on all axes.
  SamplerDesc& address(VkSamplerAddressMode mode) {
    address_u = address_v = address_w = mode;
    return *this;
  }
};

enum class ImageKind { image_1d, image_1d_array, image_2d, image_2d_array };

// A sampled image with `levels.size()` mip levels (at most the full chain). Level l has
// extent max(1, width >> l) x max(1, height >> l) (height is 1 for 1D kinds) and its bytes hold
// all layers, layer after layer, each layer row after row, texels tightly packed.
// Supported formats: see format_info() in formats.hpp (R32G32B32A32_SFLOAT,
// R16G16B16A16_SFLOAT, ...).
struct SampledImage {
  ImageKind kind = ImageKind::image_2d;
  VkFormat format = VK_FORMAT_R32G32B32A32_SFLOAT;
  std::uint32_t width = 1;
  std::uint32_t height = 1;
  std::uint32_t layers = 1;
  std::vector<Bytes> levels;
};

// A combined image sampler at (set 0, binding).
struct ImageBinding {
  std::uint32_t binding = 0;
  SampledImage image;
  SamplerDesc sampler;
};

struct DispatchSize {
  std::uint32_t x = 1, y = 1, z = 1;
};

struct ComputeRun {
  ShaderDesc shader;
  std::vector<BufferBinding> buffers;
  std::vector<ImageBinding> images;
  Bytes push_constants;  // size must be a multiple of 4 (or empty)
  DispatchSize groups;
};

// Draws one full-screen triangle (3 vertices, no vertex buffers) into color attachments
// `color_formats[i]` at location i, each width x height, cleared to clear_color first. The
// built-in vertex shader (used when `vertex.spirv` is empty) also writes
// `layout(location = 0) out vec2 uv` in [0,1] across the framebuffer; fragment shaders
// normally derive everything from gl_FragCoord so that ddx/ddy are true 2x2-quad differences.
// Buffers and images are visible to the vertex and fragment stages; fragment-stage storage
// writes need DeviceInfo::fragment_stores_and_atomics.
struct FragmentRun {
  ShaderDesc fragment;
  ShaderDesc vertex;
  std::uint32_t width = 1;
  std::uint32_t height = 1;
  std::vector<VkFormat> color_formats = {VK_FORMAT_R32G32B32A32_SFLOAT};
  std::array<float, 4> clear_color = {0.0f, 0.0f, 0.0f, 0.0f};
  std::vector<BufferBinding> buffers;
  std::vector<ImageBinding> images;
  Bytes push_constants;
};

}  // namespace saagen::harness
