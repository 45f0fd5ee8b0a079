// Runs a deferred roughness-limiter pass (saagen/products/deferred_pass.hpp) on a Vulkan device with the
// resources its header describes: sampled images for the G-buffers (normal, roughness, tangent)
// and a storage image for the output, push constants, (ceil(w/8), ceil(h/8)) workgroups, and
// GPU timestamps around the dispatch. The harness (saagen::harness) binds only buffers and
// combined image samplers, so this small runner builds the pass's own interface on the
// harness's VulkanContext. Header-only; shared by tests/generator/products/test_deferred_pass.cpp and
// bench/bench_deferred_pass.cpp.
#pragma once

#include "saagen/products/deferred_pass.hpp"

#include <algorithm>
#include <cstring>
#include <saagen/harness/bytes.hpp>
#include <saagen/harness/context.hpp>
#include <saagen/harness/error.hpp>
#include <stdexcept>
#include <vector>

// Vulkan structures are initialised as `VkXxx info{VK_STRUCTURE_TYPE_XXX};` (the rest zeroed), as
// in the harness; -Wextra would flag every one.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace saagen::test {

// G-buffer contents, rows top to bottom, 4 floats per texel (RGBA32F); tangent may be empty.
struct GBufferImages {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<float> normal;
  std::vector<float> roughness;
  std::vector<float> tangent;
};

class DeferredPassRunner {
 public:
  // output_format: VK_FORMAT_R32_SFLOAT or VK_FORMAT_R16_SFLOAT (the pass's --output-format).
  DeferredPassRunner(harness::VulkanContext& context, const std::vector<std::uint32_t>& spirv, bool tangents, VkFormat output_format,
                     std::uint32_t width, std::uint32_t height)
      : context_(context), device_(context.device()), tangents_(tangents), output_format_(output_format), width_(width), height_(height) {
    if (output_format != VK_FORMAT_R32_SFLOAT && output_format != VK_FORMAT_R16_SFLOAT) throw std::invalid_argument("output format");
    const VkFormatProperties properties = context.format_properties(output_format);
    if (!(properties.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT)) {
      throw std::runtime_error("the device cannot store to this output format");
    }
    create_images();
    create_staging();
    create_pipeline(spirv);
    create_commands();
  }

  ~DeferredPassRunner() {
    vkDeviceWaitIdle(device_);
    vkDestroyFence(device_, fence_, nullptr);
    vkDestroyCommandPool(device_, command_pool_, nullptr);
    vkDestroyQueryPool(device_, query_pool_, nullptr);
    vkDestroyPipeline(device_, pipeline_, nullptr);
    vkDestroyPipelineLayout(device_, pipeline_layout_, nullptr);
    vkDestroyDescriptorPool(device_, descriptor_pool_, nullptr);
    vkDestroyDescriptorSetLayout(device_, set_layout_, nullptr);
    vkDestroyShaderModule(device_, shader_, nullptr);
    for (Image& image : images_) {
      vkDestroyImageView(device_, image.view, nullptr);
      vkDestroyImage(device_, image.image, nullptr);
      vkFreeMemory(device_, image.memory, nullptr);
    }
    vkDestroyBuffer(device_, staging_, nullptr);
    vkFreeMemory(device_, staging_memory_, nullptr);
  }
  DeferredPassRunner(const DeferredPassRunner&) = delete;
  DeferredPassRunner& operator=(const DeferredPassRunner&) = delete;

  void upload(const GBufferImages& gbuffer) {
    if (gbuffer.width != width_ || gbuffer.height != height_) throw std::invalid_argument("G-buffer size");
    const std::size_t texels = std::size_t{width_} * height_;
    if (gbuffer.normal.size() != texels * 4 || gbuffer.roughness.size() != texels * 4 ||
        (tangents_ && gbuffer.tangent.size() != texels * 4)) {
      throw std::invalid_argument("G-buffer contents");
    }
    const std::vector<const std::vector<float>*> sources = {&gbuffer.normal, &gbuffer.roughness, tangents_ ? &gbuffer.tangent : nullptr};
    one_time([&](VkCommandBuffer commands) {
      for (std::size_t index = 0; index < sources.size(); ++index) {
        if (!sources[index]) continue;
        std::memcpy(static_cast<char*>(staging_mapped_) + index * texels * 16, sources[index]->data(), texels * 16);
        transition(commands, images_[input_image(index)].image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        const VkBufferImageCopy copy = region(index * texels * 16);
        vkCmdCopyBufferToImage(commands, staging_, images_[input_image(index)].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        transition(commands, images_[input_image(index)].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
      }
      transition(commands, images_[output_image].image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    });
  }

  struct Result {
    std::vector<float> output;   // width * height values, rows top to bottom
    std::vector<double> gpu_ms;  // per repetition (empty without timestamps)
  };

  // Dispatches `repetitions` times (one submission each, timed), then reads the output back.
  Result run(const DeferredPassConstants& constants, std::uint32_t repetitions = 1) {
    Result result;
    const bool timestamps = context_.info().timestamps_supported();
    for (std::uint32_t repetition = 0; repetition < repetitions; ++repetition) {
      one_time([&](VkCommandBuffer commands) {
        if (timestamps) {
          vkCmdResetQueryPool(commands, query_pool_, 0, 2);
          vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, query_pool_, 0);
        }
        vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
        vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_layout_, 0, 1, &set_, 0, nullptr);
        vkCmdPushConstants(commands, pipeline_layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants), &constants);
        const std::uint32_t tile = deferred_pass_abi::tile_size;
        vkCmdDispatch(commands, (width_ + tile - 1) / tile, (height_ + tile - 1) / tile, 1);
        if (timestamps) vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, query_pool_, 1);
        if (repetition + 1 == repetitions) {
          VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
          barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
          barrier.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
          // The copy reads TRANSFER_SRC_OPTIMAL (the validation layer warns on GENERAL), and the
          // image goes back to GENERAL for the next run's storage writes.
          barrier.oldLayout = VK_IMAGE_LAYOUT_GENERAL;
          barrier.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
          barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
          barrier.image = images_[output_image].image;
          barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
          vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1,
                               &barrier);
          const VkBufferImageCopy copy = region(0);
          vkCmdCopyImageToBuffer(commands, images_[output_image].image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging_, 1, &copy);
          barrier.srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
          barrier.dstAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT;
          barrier.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
          barrier.newLayout = VK_IMAGE_LAYOUT_GENERAL;
          vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0, nullptr, 1,
                               &barrier);
        } else {
          VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
          barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
          barrier.dstAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
          vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &barrier, 0,
                               nullptr, 0, nullptr);
        }
      });
      if (timestamps) {
        std::uint64_t ticks[2] = {0, 0};
        SAAGEN_VK_CHECK(vkGetQueryPoolResults(device_, query_pool_, 0, 2, sizeof(ticks), ticks, sizeof(std::uint64_t),
                                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
        result.gpu_ms.push_back(double(ticks[1] - ticks[0]) * context_.info().timestamp_period_ns * 1e-6);
      }
    }
    const std::size_t texels = std::size_t{width_} * height_;
    result.output.resize(texels);
    if (output_format_ == VK_FORMAT_R32_SFLOAT) {
      std::memcpy(result.output.data(), staging_mapped_, texels * 4);
    } else {
      const auto* half = static_cast<const std::uint16_t*>(staging_mapped_);
      for (std::size_t index = 0; index < texels; ++index) result.output[index] = harness::half_to_float(half[index]);
    }
    return result;
  }

 private:
  struct Image {
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
  };
  static constexpr std::size_t output_image = 3;  // images_: normal, roughness, tangent, output
  static std::size_t input_image(std::size_t index) { return index; }

  VkDeviceMemory allocate(const VkMemoryRequirements& requirements, VkMemoryPropertyFlags preferred, VkMemoryPropertyFlags required) {
    return context_.allocate_memory(requirements, preferred, required);
  }

  Image make_image(VkFormat format, VkImageUsageFlags usage) {
    Image image;
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {width_, height_, 1};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    SAAGEN_VK_CHECK(vkCreateImage(device_, &info, nullptr, &image.image));
    VkMemoryRequirements requirements{};
    vkGetImageMemoryRequirements(device_, image.image, &requirements);
    image.memory = allocate(requirements, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
    SAAGEN_VK_CHECK(vkBindImageMemory(device_, image.image, image.memory, 0));
    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = image.image;
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = format;
    view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    SAAGEN_VK_CHECK(vkCreateImageView(device_, &view, nullptr, &image.view));
    return image;
  }

  void create_images() {
    const VkImageUsageFlags input = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    images_.push_back(make_image(VK_FORMAT_R32G32B32A32_SFLOAT, input));
    images_.push_back(make_image(VK_FORMAT_R32G32B32A32_SFLOAT, input));
    images_.push_back(tangents_ ? make_image(VK_FORMAT_R32G32B32A32_SFLOAT, input) : Image{});
    images_.push_back(make_image(output_format_, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT));
  }

  void create_staging() {
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = std::size_t{width_} * height_ * 16 * 3;  // the three inputs side by side; the output fits in the first
    info.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    SAAGEN_VK_CHECK(vkCreateBuffer(device_, &info, nullptr, &staging_));
    VkMemoryRequirements requirements{};
    vkGetBufferMemoryRequirements(device_, staging_, &requirements);
    const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    staging_memory_ = allocate(requirements, host | VK_MEMORY_PROPERTY_HOST_CACHED_BIT, host);
    SAAGEN_VK_CHECK(vkBindBufferMemory(device_, staging_, staging_memory_, 0));
    SAAGEN_VK_CHECK(vkMapMemory(device_, staging_memory_, 0, VK_WHOLE_SIZE, 0, &staging_mapped_));
  }

  void create_pipeline(const std::vector<std::uint32_t>& spirv) {
    namespace abi = deferred_pass_abi;
    std::vector<VkDescriptorSetLayoutBinding> bindings = {
        {abi::binding_normal, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
        {abi::binding_roughness, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
        {abi::binding_output, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
    if (tangents_) bindings.push_back({abi::binding_tangent, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
    VkDescriptorSetLayoutCreateInfo layout{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    layout.bindingCount = static_cast<std::uint32_t>(bindings.size());
    layout.pBindings = bindings.data();
    SAAGEN_VK_CHECK(vkCreateDescriptorSetLayout(device_, &layout, nullptr, &set_layout_));

    const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 3}, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1}};
    VkDescriptorPoolCreateInfo pool{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool.maxSets = 1;
    pool.poolSizeCount = 2;
    pool.pPoolSizes = sizes;
    SAAGEN_VK_CHECK(vkCreateDescriptorPool(device_, &pool, nullptr, &descriptor_pool_));
    VkDescriptorSetAllocateInfo allocate_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    allocate_info.descriptorPool = descriptor_pool_;
    allocate_info.descriptorSetCount = 1;
    allocate_info.pSetLayouts = &set_layout_;
    SAAGEN_VK_CHECK(vkAllocateDescriptorSets(device_, &allocate_info, &set_));

    std::vector<VkDescriptorImageInfo> infos;
    std::vector<VkWriteDescriptorSet> writes;
    infos.reserve(4);
    for (const VkDescriptorSetLayoutBinding& binding : bindings) {
      const bool output = binding.binding == abi::binding_output;
      const std::size_t image = output ? output_image : binding.binding == abi::binding_tangent ? 2 : binding.binding;
      infos.push_back({VK_NULL_HANDLE, images_[image].view, output ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
      VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      write.dstSet = set_;
      write.dstBinding = binding.binding;
      write.descriptorCount = 1;
      write.descriptorType = binding.descriptorType;
      write.pImageInfo = &infos.back();
      writes.push_back(write);
    }
    vkUpdateDescriptorSets(device_, static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);

    const VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(DeferredPassConstants)};
    VkPipelineLayoutCreateInfo pipeline_layout{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pipeline_layout.setLayoutCount = 1;
    pipeline_layout.pSetLayouts = &set_layout_;
    pipeline_layout.pushConstantRangeCount = 1;
    pipeline_layout.pPushConstantRanges = &range;
    SAAGEN_VK_CHECK(vkCreatePipelineLayout(device_, &pipeline_layout, nullptr, &pipeline_layout_));

    VkShaderModuleCreateInfo module{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    module.codeSize = spirv.size() * 4;
    module.pCode = spirv.data();
    SAAGEN_VK_CHECK(vkCreateShaderModule(device_, &module, nullptr, &shader_));
    VkComputePipelineCreateInfo pipeline{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    pipeline.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    pipeline.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pipeline.stage.module = shader_;
    pipeline.stage.pName = "main";
    pipeline.layout = pipeline_layout_;
    SAAGEN_VK_CHECK(vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &pipeline, nullptr, &pipeline_));
  }

  void create_commands() {
    VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool.queueFamilyIndex = context_.queue_family();
    SAAGEN_VK_CHECK(vkCreateCommandPool(device_, &pool, nullptr, &command_pool_));
    VkCommandBufferAllocateInfo allocate_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocate_info.commandPool = command_pool_;
    allocate_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate_info.commandBufferCount = 1;
    SAAGEN_VK_CHECK(vkAllocateCommandBuffers(device_, &allocate_info, &commands_));
    VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    SAAGEN_VK_CHECK(vkCreateFence(device_, &fence, nullptr, &fence_));
    if (context_.info().timestamps_supported()) {
      VkQueryPoolCreateInfo query{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
      query.queryType = VK_QUERY_TYPE_TIMESTAMP;
      query.queryCount = 2;
      SAAGEN_VK_CHECK(vkCreateQueryPool(device_, &query, nullptr, &query_pool_));
    }
  }

  template <class Record>
  void one_time(Record&& record) {
    SAAGEN_VK_CHECK(vkResetCommandBuffer(commands_, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    SAAGEN_VK_CHECK(vkBeginCommandBuffer(commands_, &begin));
    record(commands_);
    SAAGEN_VK_CHECK(vkEndCommandBuffer(commands_));
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commands_;
    SAAGEN_VK_CHECK(vkResetFences(device_, 1, &fence_));
    SAAGEN_VK_CHECK(vkQueueSubmit(context_.queue(), 1, &submit, fence_));
    SAAGEN_VK_CHECK(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX));
  }

  static void transition(VkCommandBuffer commands, VkImage image, VkImageLayout from, VkImageLayout to) {
    VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    barrier.srcAccessMask = from == VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL ? VK_ACCESS_TRANSFER_WRITE_BIT : 0;
    barrier.dstAccessMask = to == VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL ? VK_ACCESS_TRANSFER_WRITE_BIT
                            : to == VK_IMAGE_LAYOUT_GENERAL            ? VK_ACCESS_SHADER_WRITE_BIT
                                                                       : VK_ACCESS_SHADER_READ_BIT;
    barrier.oldLayout = from;
    barrier.newLayout = to;
    barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image;
    barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0, nullptr, 1, &barrier);
  }

  VkBufferImageCopy region(VkDeviceSize offset) const {
    VkBufferImageCopy copy{};
    copy.bufferOffset = offset;
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {width_, height_, 1};
    return copy;
  }

  harness::VulkanContext& context_;
  VkDevice device_;
  bool tangents_;
  VkFormat output_format_;
  std::uint32_t width_, height_;
  std::vector<Image> images_;
  VkBuffer staging_ = VK_NULL_HANDLE;
  VkDeviceMemory staging_memory_ = VK_NULL_HANDLE;
  void* staging_mapped_ = nullptr;
  VkShaderModule shader_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkDescriptorPool descriptor_pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  VkPipelineLayout pipeline_layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkCommandPool command_pool_ = VK_NULL_HANDLE;
  VkCommandBuffer commands_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkQueryPool query_pool_ = VK_NULL_HANDLE;
};

}  // namespace saagen::test

#pragma GCC diagnostic pop
