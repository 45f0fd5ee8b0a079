#include "resources.hpp"

#include "saagen/harness/error.hpp"
#include "saagen/harness/formats.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace saagen::harness {
namespace {

DeviceHandle<VkDeviceMemory> allocate_memory(const VulkanContext& context, const VkMemoryRequirements& requirements,
                                             VkMemoryPropertyFlags preferred, VkMemoryPropertyFlags required) {
  return {context.device(), context.allocate_memory(requirements, preferred, required), vkFreeMemory};
}

// Device memory bound to a new image (device-local when available).
ImageWithView create_image(const VulkanContext& context, const VkImageCreateInfo& image_info, VkImageViewType view_type) {
  ImageWithView result;
  VkImage image = VK_NULL_HANDLE;
  SAAGEN_VK_CHECK(vkCreateImage(context.device(), &image_info, nullptr, &image));
  result.image = {context.device(), image, vkDestroyImage};
  VkMemoryRequirements requirements{};
  vkGetImageMemoryRequirements(context.device(), image, &requirements);
  result.memory = allocate_memory(context, requirements, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
  SAAGEN_VK_CHECK(vkBindImageMemory(context.device(), image, result.memory.get(), 0));

  VkImageViewCreateInfo view_info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  view_info.image = image;
  view_info.viewType = view_type;
  view_info.format = image_info.format;
  view_info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, image_info.mipLevels, 0, image_info.arrayLayers};
  VkImageView view = VK_NULL_HANDLE;
  SAAGEN_VK_CHECK(vkCreateImageView(context.device(), &view_info, nullptr, &view));
  result.view = {context.device(), view, vkDestroyImageView};
  return result;
}

bool is_1d(ImageKind kind) { return kind == ImageKind::image_1d || kind == ImageKind::image_1d_array; }
bool is_array(ImageKind kind) { return kind == ImageKind::image_1d_array || kind == ImageKind::image_2d_array; }

VkImageViewType view_type_of(ImageKind kind) {
  switch (kind) {
    case ImageKind::image_1d:
      return VK_IMAGE_VIEW_TYPE_1D;
    case ImageKind::image_1d_array:
      return VK_IMAGE_VIEW_TYPE_1D_ARRAY;
    case ImageKind::image_2d:
      return VK_IMAGE_VIEW_TYPE_2D;
    case ImageKind::image_2d_array:
      return VK_IMAGE_VIEW_TYPE_2D_ARRAY;
  }
  return VK_IMAGE_VIEW_TYPE_2D;
}

std::uint32_t level_extent(std::uint32_t extent, std::uint32_t level) { return std::max(1u, extent >> level); }

std::uint32_t full_chain_length(std::uint32_t width, std::uint32_t height) {
  std::uint32_t levels = 1;
  for (std::uint32_t largest = std::max(width, height); largest > 1; largest >>= 1) ++levels;
  return levels;
}

void validate_image(const VulkanContext& context, const ImageBinding& binding) {
  const SampledImage& image = binding.image;
  const std::string where = fmt::format("sampled image at binding {}", binding.binding);
  const VkPhysicalDeviceLimits& limits = context.limits();
  if (image.width == 0 || image.height == 0 || image.layers == 0) throw std::invalid_argument(where + ": zero extent");
  if (is_1d(image.kind) && image.height != 1) throw std::invalid_argument(where + ": 1D images need height 1");
  if (!is_array(image.kind) && image.layers != 1) throw std::invalid_argument(where + ": non-array images need 1 layer");
  const std::uint32_t max_extent = is_1d(image.kind) ? limits.maxImageDimension1D : limits.maxImageDimension2D;
  if (image.width > max_extent || image.height > max_extent || image.layers > limits.maxImageArrayLayers) {
    throw std::invalid_argument(where + ": extent exceeds the device limits");
  }
  if (image.levels.empty() || image.levels.size() > full_chain_length(image.width, image.height)) {
    throw std::invalid_argument(
        fmt::format("{}: {} levels given, expected 1..{}", where, image.levels.size(), full_chain_length(image.width, image.height)));
  }
  const std::uint32_t texel = format_info(image.format).texel_bytes();
  for (std::uint32_t level = 0; level < image.levels.size(); ++level) {
    const std::size_t expected = std::size_t{level_extent(image.width, level)} * level_extent(image.height, level) * image.layers * texel;
    if (image.levels[level].size() != expected) {
      throw std::invalid_argument(
          fmt::format("{}: level {} has {} bytes, expected {}", where, level, image.levels[level].size(), expected));
    }
  }
  const VkFormatFeatureFlags features = context.format_properties(image.format).optimalTilingFeatures;
  if (!(features & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT)) throw std::runtime_error(where + ": format cannot be sampled");
  const SamplerDesc& s = binding.sampler;
  const bool linear =
      s.mag_filter == VK_FILTER_LINEAR || s.min_filter == VK_FILTER_LINEAR || s.mipmap_mode == VK_SAMPLER_MIPMAP_MODE_LINEAR;
  if (linear && !(features & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT)) {
    throw std::runtime_error(where + ": format does not support linear filtering");
  }
  if (s.anisotropy_enable && !context.info().sampler_anisotropy) {
    throw std::runtime_error(where + ": the device does not support sampler anisotropy");
  }
  if (s.anisotropy_enable && (s.max_anisotropy < 1.0f || s.max_anisotropy > context.info().max_sampler_anisotropy)) {
    throw std::invalid_argument(
        fmt::format("{}: max_anisotropy {} outside [1, {}]", where, s.max_anisotropy, context.info().max_sampler_anisotropy));
  }
}

DeviceHandle<VkSampler> create_sampler(const VulkanContext& context, const SamplerDesc& desc) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = desc.mag_filter;
  info.minFilter = desc.min_filter;
  info.mipmapMode = desc.mipmap_mode;
  info.addressModeU = desc.address_u;
  info.addressModeV = desc.address_v;
  info.addressModeW = desc.address_w;
  info.mipLodBias = desc.mip_lod_bias;
  info.anisotropyEnable = desc.anisotropy_enable ? VK_TRUE : VK_FALSE;
  info.maxAnisotropy = desc.max_anisotropy;
  info.minLod = desc.min_lod;
  info.maxLod = desc.max_lod;
  info.borderColor = desc.border_color;
  VkSampler sampler = VK_NULL_HANDLE;
  SAAGEN_VK_CHECK(vkCreateSampler(context.device(), &info, nullptr, &sampler));
  return {context.device(), sampler, vkDestroySampler};
}

void transition(VkCommandBuffer cmd, VkImage image, const VkImageSubresourceRange& range, VkImageLayout from, VkImageLayout to,
                VkAccessFlags src_access, VkAccessFlags dst_access, VkPipelineStageFlags src_stage, VkPipelineStageFlags dst_stage) {
  VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  barrier.srcAccessMask = src_access;
  barrier.dstAccessMask = dst_access;
  barrier.oldLayout = from;
  barrier.newLayout = to;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = range;
  vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &barrier);
}

}  // namespace

HostBuffer HostBuffer::create(const VulkanContext& context, VkDeviceSize size, VkBufferUsageFlags usage) {
  HostBuffer result;
  result.size = size;
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer buffer = VK_NULL_HANDLE;
  SAAGEN_VK_CHECK(vkCreateBuffer(context.device(), &info, nullptr, &buffer));
  result.buffer = {context.device(), buffer, vkDestroyBuffer};
  VkMemoryRequirements requirements{};
  vkGetBufferMemoryRequirements(context.device(), buffer, &requirements);
  constexpr VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  result.memory = allocate_memory(context, requirements, host, host);
  SAAGEN_VK_CHECK(vkBindBufferMemory(context.device(), buffer, result.memory.get(), 0));
  void* mapped = nullptr;
  // Unmapped implicitly when the memory is freed.
  SAAGEN_VK_CHECK(vkMapMemory(context.device(), result.memory.get(), 0, VK_WHOLE_SIZE, 0, &mapped));
  result.mapped = static_cast<std::byte*>(mapped);
  std::memset(result.mapped, 0, size);
  return result;
}

void submit_and_wait(const VulkanContext& context, VkCommandPool pool, const std::function<void(VkCommandBuffer)>& record) {
  VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocate.commandPool = pool;
  allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocate.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  SAAGEN_VK_CHECK(vkAllocateCommandBuffers(context.device(), &allocate, &cmd));
  struct Free {
    VkDevice device;
    VkCommandPool pool;
    VkCommandBuffer cmd;
    ~Free() { vkFreeCommandBuffers(device, pool, 1, &cmd); }
  } free_on_exit{context.device(), pool, cmd};

  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  SAAGEN_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
  record(cmd);
  SAAGEN_VK_CHECK(vkEndCommandBuffer(cmd));

  VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence_handle = VK_NULL_HANDLE;
  SAAGEN_VK_CHECK(vkCreateFence(context.device(), &fence_info, nullptr, &fence_handle));
  DeviceHandle<VkFence> fence(context.device(), fence_handle, vkDestroyFence);
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  SAAGEN_VK_CHECK(vkQueueSubmit(context.queue(), 1, &submit, fence.get()));
  SAAGEN_VK_CHECK(vkWaitForFences(context.device(), 1, &fence_handle, VK_TRUE, UINT64_MAX));
}

SampledImageResource create_sampled_image(const VulkanContext& context, VkCommandPool pool, const ImageBinding& binding) {
  validate_image(context, binding);
  const SampledImage& desc = binding.image;
  const auto levels = static_cast<std::uint32_t>(desc.levels.size());

  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = is_1d(desc.kind) ? VK_IMAGE_TYPE_1D : VK_IMAGE_TYPE_2D;
  info.format = desc.format;
  info.extent = {desc.width, desc.height, 1};
  info.mipLevels = levels;
  info.arrayLayers = desc.layers;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;

  SampledImageResource result;
  result.image = create_image(context, info, view_type_of(desc.kind));
  result.sampler = create_sampler(context, binding.sampler);

  // Stage all levels in one buffer; each level is one copy region covering every layer.
  std::size_t total = 0;
  for (const Bytes& level : desc.levels) total += level.size();
  HostBuffer staging = HostBuffer::create(context, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  std::vector<VkBufferImageCopy> regions;
  std::size_t offset = 0;
  for (std::uint32_t level = 0; level < levels; ++level) {
    std::memcpy(staging.mapped + offset, desc.levels[level].data(), desc.levels[level].size());
    VkBufferImageCopy region{};
    region.bufferOffset = offset;
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, desc.layers};
    region.imageExtent = {level_extent(desc.width, level), level_extent(desc.height, level), 1};
    regions.push_back(region);
    offset += desc.levels[level].size();
  }

  const VkImage image = result.image.image.get();
  const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, levels, 0, desc.layers};
  submit_and_wait(context, pool, [&](VkCommandBuffer cmd) {
    transition(cmd, image, range, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, VK_ACCESS_TRANSFER_WRITE_BIT,
               VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
    vkCmdCopyBufferToImage(cmd, staging.buffer.get(), image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           static_cast<std::uint32_t>(regions.size()), regions.data());
    transition(cmd, image, range, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
               VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
               VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
  });
  return result;
}

ImageWithView create_color_target(const VulkanContext& context, VkFormat format, std::uint32_t width, std::uint32_t height) {
  format_info(format);  // throws for formats the harness cannot read back
  if (!(context.format_properties(format).optimalTilingFeatures & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT)) {
    throw std::runtime_error(fmt::format("format {} cannot be a color attachment on '{}'", static_cast<int>(format), context.info().name));
  }
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {width, height, 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  return create_image(context, info, VK_IMAGE_VIEW_TYPE_2D);
}

}  // namespace saagen::harness
