// Internal building blocks of the programs: host-visible buffers, sampled images with their
// samplers, color targets, and one-shot command submission.
#pragma once

#include "vk_handle.hpp"

#include "saagen/harness/context.hpp"
#include "saagen/harness/description.hpp"

#include <functional>

namespace saagen::harness {

// A buffer in host-visible, host-coherent memory, persistently mapped.
struct HostBuffer {
  DeviceHandle<VkDeviceMemory> memory;  // declared first: destroyed after the buffer
  DeviceHandle<VkBuffer> buffer;
  VkDeviceSize size = 0;
  std::byte* mapped = nullptr;

  static HostBuffer create(const VulkanContext& context, VkDeviceSize size, VkBufferUsageFlags usage);
};

// A device image with one view, used as a sampled image or a color attachment.
struct ImageWithView {
  DeviceHandle<VkDeviceMemory> memory;
  DeviceHandle<VkImage> image;
  DeviceHandle<VkImageView> view;
};

struct SampledImageResource {
  ImageWithView image;
  DeviceHandle<VkSampler> sampler;
};

// Records `record` into a fresh command buffer from `pool`, submits it and waits.
void submit_and_wait(const VulkanContext& context, VkCommandPool pool, const std::function<void(VkCommandBuffer)>& record);

// Creates the image, uploads all levels (via a staging buffer) and leaves it in
// SHADER_READ_ONLY_OPTIMAL; also creates the sampler. Validates the description first.
SampledImageResource create_sampled_image(const VulkanContext& context, VkCommandPool pool, const ImageBinding& binding);

// A width x height 2D image usable as color attachment and transfer source.
ImageWithView create_color_target(const VulkanContext& context, VkFormat format, std::uint32_t width, std::uint32_t height);

}  // namespace saagen::harness
