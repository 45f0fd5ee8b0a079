#include "saagen/harness/program.hpp"

#include "fixed_function.hpp"
#include "resources.hpp"

#include "saagen/harness/error.hpp"
#include "saagen/harness/shader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <stdexcept>

namespace saagen::harness {
namespace {

using Clock = std::chrono::steady_clock;

double elapsed_ms(Clock::time_point start) { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); }

// ---------------------------------------------------------------------------------------------
// Descriptor set 0: buffers and combined image samplers, with their Vulkan objects.

struct BoundBuffer {
  std::uint32_t binding = 0;
  bool read_back = false;
  HostBuffer buffer;
};

struct BoundImage {
  std::uint32_t binding = 0;
  SampledImageResource resource;
};

class DescriptorResources {
 public:
  DescriptorResources(const VulkanContext& context, VkCommandPool upload_pool, const std::vector<BufferBinding>& buffers,
                      const std::vector<ImageBinding>& images, VkShaderStageFlags stages);

  VkDescriptorSetLayout layout() const { return layout_.get(); }
  VkDescriptorSet set() const { return set_; }
  void write_buffer(std::uint32_t binding, std::span<const std::byte> bytes);
  std::map<std::uint32_t, Bytes> read_back() const;

 private:
  void create_layout(const std::vector<BufferBinding>& buffers, const std::vector<ImageBinding>& images, VkShaderStageFlags stages);
  void allocate_set(const std::vector<BufferBinding>& buffers, std::size_t image_count);
  void write_descriptors(const std::vector<BufferBinding>& buffers);

  const VulkanContext& context_;
  std::vector<BoundBuffer> buffers_;
  std::vector<BoundImage> images_;
  DeviceHandle<VkDescriptorSetLayout> layout_;
  DeviceHandle<VkDescriptorPool> pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;  // freed with the pool
};

VkDescriptorType descriptor_type(BufferKind kind) {
  return kind == BufferKind::uniform ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

std::size_t buffer_size(const BufferBinding& buffer) { return std::max(buffer.size, buffer.data.size()); }

void validate_bindings(const VulkanContext& context, const std::vector<BufferBinding>& buffers, const std::vector<ImageBinding>& images) {
  std::set<std::uint32_t> seen;
  auto claim = [&seen](std::uint32_t binding) {
    if (!seen.insert(binding).second) throw std::invalid_argument(fmt::format("binding {} is used twice", binding));
  };
  for (const BufferBinding& buffer : buffers) {
    claim(buffer.binding);
    const std::size_t size = buffer_size(buffer);
    const std::uint32_t range =
        buffer.kind == BufferKind::uniform ? context.limits().maxUniformBufferRange : context.limits().maxStorageBufferRange;
    if (size == 0) throw std::invalid_argument(fmt::format("buffer at binding {} has size 0", buffer.binding));
    if (size > range) {
      throw std::invalid_argument(fmt::format("buffer at binding {} has {} bytes, the device allows {}", buffer.binding, size, range));
    }
  }
  for (const ImageBinding& image : images) claim(image.binding);
}

DescriptorResources::DescriptorResources(const VulkanContext& context, VkCommandPool upload_pool, const std::vector<BufferBinding>& buffers,
                                         const std::vector<ImageBinding>& images, VkShaderStageFlags stages)
    : context_(context) {
  validate_bindings(context, buffers, images);
  for (const BufferBinding& desc : buffers) {
    const VkBufferUsageFlags usage =
        desc.kind == BufferKind::uniform ? VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT : VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    BoundBuffer bound{desc.binding, desc.read_back, HostBuffer::create(context, buffer_size(desc), usage)};
    if (!desc.data.empty()) std::memcpy(bound.buffer.mapped, desc.data.data(), desc.data.size());
    buffers_.push_back(std::move(bound));
  }
  for (const ImageBinding& desc : images) {
    images_.push_back(BoundImage{desc.binding, create_sampled_image(context, upload_pool, desc)});
  }
  create_layout(buffers, images, stages);
  allocate_set(buffers, images.size());
  write_descriptors(buffers);
}

void DescriptorResources::create_layout(const std::vector<BufferBinding>& buffers, const std::vector<ImageBinding>& images,
                                        VkShaderStageFlags stages) {
  std::vector<VkDescriptorSetLayoutBinding> bindings;
  for (const BufferBinding& buffer : buffers) bindings.push_back({buffer.binding, descriptor_type(buffer.kind), 1, stages, nullptr});
  for (const ImageBinding& image : images) {
    bindings.push_back({image.binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, stages, nullptr});
  }
  VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  info.bindingCount = static_cast<std::uint32_t>(bindings.size());
  info.pBindings = bindings.data();
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  SAAGEN_VK_CHECK(vkCreateDescriptorSetLayout(context_.device(), &info, nullptr, &layout));
  layout_ = {context_.device(), layout, vkDestroyDescriptorSetLayout};
}

void DescriptorResources::allocate_set(const std::vector<BufferBinding>& buffers, std::size_t image_count) {
  std::map<VkDescriptorType, std::uint32_t> counts;
  for (const BufferBinding& buffer : buffers) ++counts[descriptor_type(buffer.kind)];
  if (image_count > 0) counts[VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER] = static_cast<std::uint32_t>(image_count);
  std::vector<VkDescriptorPoolSize> sizes;
  for (const auto& [type, count] : counts) sizes.push_back({type, count});
  if (sizes.empty()) sizes.push_back({VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1});  // a pool needs one size

  VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
  pool_info.pPoolSizes = sizes.data();
  VkDescriptorPool pool = VK_NULL_HANDLE;
  SAAGEN_VK_CHECK(vkCreateDescriptorPool(context_.device(), &pool_info, nullptr, &pool));
  pool_ = {context_.device(), pool, vkDestroyDescriptorPool};

  VkDescriptorSetLayout layout = layout_.get();
  VkDescriptorSetAllocateInfo allocate{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  allocate.descriptorPool = pool;
  allocate.descriptorSetCount = 1;
  allocate.pSetLayouts = &layout;
  SAAGEN_VK_CHECK(vkAllocateDescriptorSets(context_.device(), &allocate, &set_));
}

void DescriptorResources::write_descriptors(const std::vector<BufferBinding>& buffers) {
  // Infos are sized up front so the pointers stored in the writes stay valid.
  std::vector<VkDescriptorBufferInfo> buffer_infos(buffers_.size());
  std::vector<VkDescriptorImageInfo> image_infos(images_.size());
  std::vector<VkWriteDescriptorSet> writes;
  for (std::size_t i = 0; i < buffers_.size(); ++i) {
    buffer_infos[i] = {buffers_[i].buffer.buffer.get(), 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set_;
    write.dstBinding = buffers_[i].binding;
    write.descriptorCount = 1;
    write.descriptorType = descriptor_type(buffers[i].kind);
    write.pBufferInfo = &buffer_infos[i];
    writes.push_back(write);
  }
  for (std::size_t i = 0; i < images_.size(); ++i) {
    image_infos[i] = {images_[i].resource.sampler.get(), images_[i].resource.image.view.get(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set_;
    write.dstBinding = images_[i].binding;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    write.pImageInfo = &image_infos[i];
    writes.push_back(write);
  }
  vkUpdateDescriptorSets(context_.device(), static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

void DescriptorResources::write_buffer(std::uint32_t binding, std::span<const std::byte> bytes) {
  for (BoundBuffer& bound : buffers_) {
    if (bound.binding != binding) continue;
    if (bytes.size() > bound.buffer.size) {
      throw std::invalid_argument(
          fmt::format("write_buffer: {} bytes do not fit the {}-byte buffer at binding {}", bytes.size(), bound.buffer.size, binding));
    }
    if (!bytes.empty()) std::memcpy(bound.buffer.mapped, bytes.data(), bytes.size());
    return;
  }
  throw std::invalid_argument(fmt::format("write_buffer: no buffer at binding {}", binding));
}

std::map<std::uint32_t, Bytes> DescriptorResources::read_back() const {
  std::map<std::uint32_t, Bytes> result;
  for (const BoundBuffer& bound : buffers_) {
    if (!bound.read_back) continue;
    result[bound.binding].assign(bound.buffer.mapped, bound.buffer.mapped + bound.buffer.size);
  }
  return result;
}

// ---------------------------------------------------------------------------------------------
// Shaders and pipeline layout.

DeviceHandle<VkShaderModule> create_shader_module(const VulkanContext& context, const ShaderDesc& shader, const char* role) {
  constexpr std::uint32_t spirv_magic = 0x07230203u;
  if (shader.spirv.size() < 5 || shader.spirv[0] != spirv_magic) {
    throw std::invalid_argument(fmt::format("{} shader: not a SPIR-V module ({} words)", role, shader.spirv.size()));
  }
  const VkShaderStageFlags stage = std::string(role) == "compute"  ? VK_SHADER_STAGE_COMPUTE_BIT
                                   : std::string(role) == "vertex" ? VK_SHADER_STAGE_VERTEX_BIT
                                                                   : VK_SHADER_STAGE_FRAGMENT_BIT;
  context.require_capabilities(shader.spirv, stage);  // "unsupported on DEVICE: FEATURE" before the driver sees it
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = shader.spirv.size() * sizeof(std::uint32_t);
  info.pCode = shader.spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  SAAGEN_VK_CHECK(vkCreateShaderModule(context.device(), &info, nullptr, &module));
  return {context.device(), module, vkDestroyShaderModule};
}

// Keeps a VkSpecializationInfo and the arrays it points into alive together.
struct Specialization {
  std::vector<VkSpecializationMapEntry> entries;
  std::vector<std::uint32_t> data;
  VkSpecializationInfo info{};

  explicit Specialization(const std::vector<SpecConstant>& constants) {
    for (const SpecConstant& constant : constants) {
      entries.push_back({constant.id, static_cast<std::uint32_t>(data.size() * sizeof(std::uint32_t)), sizeof(std::uint32_t)});
      data.push_back(constant.bits);
    }
    info.mapEntryCount = static_cast<std::uint32_t>(entries.size());
    info.pMapEntries = entries.data();
    info.dataSize = data.size() * sizeof(std::uint32_t);
    info.pData = data.data();
  }
  Specialization(const Specialization&) = delete;
  Specialization& operator=(const Specialization&) = delete;
  const VkSpecializationInfo* get() const { return entries.empty() ? nullptr : &info; }
};

void validate_push_constants(const VulkanContext& context, const Bytes& bytes) {
  if (bytes.size() % 4 != 0) throw std::invalid_argument("push constants: size must be a multiple of 4");
  if (bytes.size() > context.limits().maxPushConstantsSize) {
    throw std::invalid_argument(
        fmt::format("push constants: {} bytes, the device allows {}", bytes.size(), context.limits().maxPushConstantsSize));
  }
}

DeviceHandle<VkPipelineLayout> create_pipeline_layout(const VulkanContext& context, VkDescriptorSetLayout set_layout,
                                                      std::size_t push_constant_bytes, VkShaderStageFlags stages) {
  const VkPushConstantRange range{stages, 0, static_cast<std::uint32_t>(push_constant_bytes)};
  VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  info.setLayoutCount = 1;
  info.pSetLayouts = &set_layout;
  info.pushConstantRangeCount = push_constant_bytes > 0 ? 1 : 0;
  info.pPushConstantRanges = &range;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  SAAGEN_VK_CHECK(vkCreatePipelineLayout(context.device(), &info, nullptr, &layout));
  return {context.device(), layout, vkDestroyPipelineLayout};
}

// ---------------------------------------------------------------------------------------------
// Command submission with host and GPU timing.

class Submitter {
 public:
  explicit Submitter(const VulkanContext& context) : context_(context) {
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = context.queue_family();
    VkCommandPool pool = VK_NULL_HANDLE;
    SAAGEN_VK_CHECK(vkCreateCommandPool(context.device(), &pool_info, nullptr, &pool));
    pool_ = {context.device(), pool, vkDestroyCommandPool};

    VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocate.commandPool = pool;
    allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate.commandBufferCount = 1;
    SAAGEN_VK_CHECK(vkAllocateCommandBuffers(context.device(), &allocate, &cmd_));  // freed with the pool

    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    SAAGEN_VK_CHECK(vkCreateFence(context.device(), &fence_info, nullptr, &fence));
    fence_ = {context.device(), fence, vkDestroyFence};

    if (context.info().timestamps_supported()) {
      VkQueryPoolCreateInfo query_info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
      query_info.queryType = VK_QUERY_TYPE_TIMESTAMP;
      query_info.queryCount = 2;
      VkQueryPool queries = VK_NULL_HANDLE;
      SAAGEN_VK_CHECK(vkCreateQueryPool(context.device(), &query_info, nullptr, &queries));
      queries_ = {context.device(), queries, vkDestroyQueryPool};
    }
  }

  VkCommandPool pool() const { return pool_.get(); }

  // Records: [reset queries] prologue, [timestamp 0] body, [timestamp 1] epilogue; then submits
  // `repetitions` times, timing each submission.
  template <typename Prologue, typename Body, typename Epilogue>
  void record(bool timestamps, Prologue prologue, Body body, Epilogue epilogue) {
    use_timestamps_ = timestamps && queries_;
    SAAGEN_VK_CHECK(vkResetCommandBuffer(cmd_, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    SAAGEN_VK_CHECK(vkBeginCommandBuffer(cmd_, &begin));
    if (use_timestamps_) vkCmdResetQueryPool(cmd_, queries_.get(), 0, 2);
    prologue(cmd_);
    if (use_timestamps_) vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries_.get(), 0);
    body(cmd_);
    if (use_timestamps_) vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_.get(), 1);
    epilogue(cmd_);
    SAAGEN_VK_CHECK(vkEndCommandBuffer(cmd_));
  }

  void submit(std::uint32_t repetitions, Timing& timing) {
    if (repetitions == 0) throw std::invalid_argument("RunOptions::repetitions must be at least 1");
    VkFence fence = fence_.get();
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd_;
    for (std::uint32_t rep = 0; rep < repetitions; ++rep) {
      const Clock::time_point start = Clock::now();
      SAAGEN_VK_CHECK(vkQueueSubmit(context_.queue(), 1, &submit, fence));
      SAAGEN_VK_CHECK(vkWaitForFences(context_.device(), 1, &fence, VK_TRUE, UINT64_MAX));
      timing.host_ms.push_back(elapsed_ms(start));
      SAAGEN_VK_CHECK(vkResetFences(context_.device(), 1, &fence));
      if (use_timestamps_) timing.gpu_ms.push_back(read_gpu_ms());
    }
  }

 private:
  double read_gpu_ms() const {
    std::uint64_t ticks[2] = {0, 0};
    SAAGEN_VK_CHECK(vkGetQueryPoolResults(context_.device(), queries_.get(), 0, 2, sizeof(ticks), ticks, sizeof(std::uint64_t),
                                          VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    const std::uint32_t bits = context_.info().timestamp_valid_bits;
    const std::uint64_t mask = bits >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << bits) - 1;
    const std::uint64_t elapsed = (ticks[1] - ticks[0]) & mask;  // modular: survives one wrap-around
    return static_cast<double>(elapsed) * context_.info().timestamp_period_ns * 1e-6;
  }

  const VulkanContext& context_;
  DeviceHandle<VkCommandPool> pool_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  DeviceHandle<VkFence> fence_;
  DeviceHandle<VkQueryPool> queries_;
  bool use_timestamps_ = false;
};

// Makes shader writes of a previous submission visible to this one (repetitions), and all
// writes visible to the host at the end.
void shader_write_barrier(VkCommandBuffer cmd, VkPipelineStageFlags stages) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
  vkCmdPipelineBarrier(cmd, stages, stages, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

void host_read_barrier(VkCommandBuffer cmd, VkPipelineStageFlags src_stages, VkAccessFlags src_access) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = src_access;
  barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, src_stages, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

void set_push_constant_bytes(Bytes& current, Bytes bytes) {
  if (bytes.size() != current.size()) {
    throw std::invalid_argument(
        fmt::format("set_push_constants: {} bytes given, the program was built with {}", bytes.size(), current.size()));
  }
  current = std::move(bytes);
}

std::vector<float> texels_to_floats(const std::byte* data, std::size_t texel_count, const FormatInfo& format) {
  const std::size_t count = texel_count * format.components;
  std::vector<float> values(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::byte* component = data + i * format.bytes_per_component;
    if (format.numeric == NumericKind::unorm) {
      values[i] = static_cast<float>(std::to_integer<std::uint8_t>(*component)) / 255.0f;
    } else if (format.bytes_per_component == 2) {
      std::uint16_t half = 0;
      std::memcpy(&half, component, 2);
      values[i] = half_to_float(half);
    } else {
      std::memcpy(&values[i], component, 4);
    }
  }
  return values;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Public helpers.

SpecConstant SpecConstant::from_int(std::uint32_t id, std::int32_t value) { return {id, static_cast<std::uint32_t>(value)}; }

SpecConstant SpecConstant::from_float(std::uint32_t id, float value) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  return {id, bits};
}

double Timing::min(const std::vector<double>& samples) {
  if (samples.empty()) return std::numeric_limits<double>::quiet_NaN();
  return *std::min_element(samples.begin(), samples.end());
}

double Timing::median(const std::vector<double>& samples) {
  if (samples.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::vector<double> sorted = samples;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t mid = sorted.size() / 2;
  return sorted.size() % 2 ? sorted[mid] : 0.5 * (sorted[mid - 1] + sorted[mid]);
}

const Bytes& RunResult::buffer(std::uint32_t binding) const {
  const auto found = buffers.find(binding);
  if (found == buffers.end()) {
    throw std::out_of_range(fmt::format("RunResult: no read-back buffer at binding {}", binding));
  }
  return found->second;
}

// ---------------------------------------------------------------------------------------------
// Compute.

struct ComputeProgram::Impl {
  VulkanContext& context;
  Submitter submitter;
  DescriptorResources resources;
  DeviceHandle<VkPipelineLayout> layout;
  DeviceHandle<VkPipeline> pipeline;
  Bytes push_constants;
  DispatchSize groups;
  double pipeline_create_ms = 0.0;

  Impl(VulkanContext& ctx, const ComputeRun& run)
      : context(ctx),
        submitter(ctx),
        resources(ctx, submitter.pool(), run.buffers, run.images, VK_SHADER_STAGE_COMPUTE_BIT),
        push_constants(run.push_constants) {
    validate_push_constants(ctx, push_constants);
    set_groups(run.groups);
    layout = create_pipeline_layout(ctx, resources.layout(), push_constants.size(), VK_SHADER_STAGE_COMPUTE_BIT);
    const Clock::time_point start = Clock::now();
    create_pipeline(run.shader);
    pipeline_create_ms = elapsed_ms(start);
  }

  void create_pipeline(const ShaderDesc& shader) {
    DeviceHandle<VkShaderModule> module = create_shader_module(context, shader, "compute");
    const Specialization specialization(shader.spec_constants);
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module.get();
    info.stage.pName = shader.entry_point.c_str();
    info.stage.pSpecializationInfo = specialization.get();
    info.layout = layout.get();
    VkPipeline handle = VK_NULL_HANDLE;
    SAAGEN_VK_CHECK(vkCreateComputePipelines(context.device(), VK_NULL_HANDLE, 1, &info, nullptr, &handle));
    pipeline = {context.device(), handle, vkDestroyPipeline};
  }

  void set_groups(DispatchSize size) {
    const std::uint32_t* max = context.info().max_compute_work_group_count;
    if (size.x == 0 || size.y == 0 || size.z == 0 || size.x > max[0] || size.y > max[1] || size.z > max[2]) {
      throw std::invalid_argument(
          fmt::format("dispatch ({}, {}, {}) outside 1..({}, {}, {})", size.x, size.y, size.z, max[0], max[1], max[2]));
    }
    groups = size;
  }

  RunResult run(const RunOptions& options) {
    constexpr VkPipelineStageFlags compute = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
    submitter.record(
        options.gpu_timestamps,
        [&](VkCommandBuffer cmd) {
          shader_write_barrier(cmd, compute);
          vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.get());
          const VkDescriptorSet set = resources.set();
          vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout.get(), 0, 1, &set, 0, nullptr);
          if (!push_constants.empty()) {
            vkCmdPushConstants(cmd, layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, static_cast<std::uint32_t>(push_constants.size()),
                               push_constants.data());
          }
        },
        [&](VkCommandBuffer cmd) { vkCmdDispatch(cmd, groups.x, groups.y, groups.z); },
        [&](VkCommandBuffer cmd) { host_read_barrier(cmd, compute, VK_ACCESS_SHADER_WRITE_BIT); });
    RunResult result;
    result.timing.pipeline_create_ms = pipeline_create_ms;
    submitter.submit(options.repetitions, result.timing);
    result.buffers = resources.read_back();
    return result;
  }
};

ComputeProgram::ComputeProgram(VulkanContext& context, const ComputeRun& run) : impl_(std::make_unique<Impl>(context, run)) {}
ComputeProgram::~ComputeProgram() = default;
void ComputeProgram::write_buffer(std::uint32_t binding, std::span<const std::byte> bytes) {
  impl_->resources.write_buffer(binding, bytes);
}
void ComputeProgram::set_push_constants(Bytes bytes) { set_push_constant_bytes(impl_->push_constants, std::move(bytes)); }
void ComputeProgram::set_groups(DispatchSize groups) { impl_->set_groups(groups); }
RunResult ComputeProgram::run(const RunOptions& options) { return impl_->run(options); }

RunResult run_compute(VulkanContext& context, const ComputeRun& run, const RunOptions& options) {
  return ComputeProgram(context, run).run(options);
}

// ---------------------------------------------------------------------------------------------
// Fragment.

namespace {

constexpr VkShaderStageFlags graphics_stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;

// One color attachment and the host buffer it is copied into after the draw.
struct ColorOutput {
  VkFormat format = VK_FORMAT_UNDEFINED;
  ImageWithView target;
  HostBuffer readback;
};

DeviceHandle<VkRenderPass> create_render_pass(const VulkanContext& context, const std::vector<VkFormat>& formats) {
  std::vector<VkAttachmentDescription> attachments;
  std::vector<VkAttachmentReference> references;
  for (std::uint32_t i = 0; i < formats.size(); ++i) {
    VkAttachmentDescription attachment{};
    attachment.format = formats[i];
    attachment.samples = VK_SAMPLE_COUNT_1_BIT;
    attachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachment.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachment.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachment.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    attachment.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;  // ready for the copy to the host
    attachments.push_back(attachment);
    references.push_back({i, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL});
  }
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = static_cast<std::uint32_t>(references.size());
  subpass.pColorAttachments = references.data();

  // In: the previous repetition's copy must finish reading before we clear (write-after-read).
  // Out: color writes must land before the copy to the readback buffer.
  const VkSubpassDependency dependencies[2] = {
      {VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0,
       VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, 0},
      {0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
       VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT, 0},
  };
  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = static_cast<std::uint32_t>(attachments.size());
  info.pAttachments = attachments.data();
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 2;
  info.pDependencies = dependencies;
  VkRenderPass pass = VK_NULL_HANDLE;
  SAAGEN_VK_CHECK(vkCreateRenderPass(context.device(), &info, nullptr, &pass));
  return {context.device(), pass, vkDestroyRenderPass};
}

void validate_framebuffer(const VulkanContext& context, const FragmentRun& run) {
  const VkPhysicalDeviceLimits& limits = context.limits();
  if (run.width == 0 || run.height == 0 || run.width > limits.maxFramebufferWidth || run.height > limits.maxFramebufferHeight) {
    throw std::invalid_argument(
        fmt::format("framebuffer {}x{} outside 1..{}x{}", run.width, run.height, limits.maxFramebufferWidth, limits.maxFramebufferHeight));
  }
  if (run.color_formats.empty() || run.color_formats.size() > limits.maxColorAttachments) {
    throw std::invalid_argument(
        fmt::format("{} color attachments requested, the device allows 1..{}", run.color_formats.size(), limits.maxColorAttachments));
  }
}

}  // namespace

struct FragmentProgram::Impl {
  VulkanContext& context;
  Submitter submitter;
  DescriptorResources resources;
  std::uint32_t width;
  std::uint32_t height;
  std::array<float, 4> clear_color;
  std::vector<ColorOutput> outputs;
  DeviceHandle<VkRenderPass> render_pass;
  DeviceHandle<VkFramebuffer> framebuffer;
  DeviceHandle<VkPipelineLayout> layout;
  DeviceHandle<VkPipeline> pipeline;
  Bytes push_constants;
  double pipeline_create_ms = 0.0;

  Impl(VulkanContext& ctx, const FragmentRun& run)
      : context(ctx),
        submitter(ctx),
        resources(ctx, submitter.pool(), run.buffers, run.images, graphics_stages),
        width(run.width),
        height(run.height),
        clear_color(run.clear_color),
        push_constants(run.push_constants) {
    validate_framebuffer(ctx, run);
    validate_push_constants(ctx, push_constants);
    create_outputs(run.color_formats);
    render_pass = create_render_pass(ctx, run.color_formats);
    create_framebuffer();
    layout = create_pipeline_layout(ctx, resources.layout(), push_constants.size(), graphics_stages);
    const Clock::time_point start = Clock::now();
    create_pipeline(run);
    pipeline_create_ms = elapsed_ms(start);
  }

  void create_outputs(const std::vector<VkFormat>& formats) {
    for (VkFormat format : formats) {
      const VkDeviceSize bytes = VkDeviceSize{width} * height * format_info(format).texel_bytes();
      outputs.push_back(ColorOutput{format, create_color_target(context, format, width, height),
                                    HostBuffer::create(context, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT)});
    }
  }

  void create_framebuffer() {
    std::vector<VkImageView> views;
    for (const ColorOutput& output : outputs) views.push_back(output.target.view.get());
    VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    info.renderPass = render_pass.get();
    info.attachmentCount = static_cast<std::uint32_t>(views.size());
    info.pAttachments = views.data();
    info.width = width;
    info.height = height;
    info.layers = 1;
    VkFramebuffer handle = VK_NULL_HANDLE;
    SAAGEN_VK_CHECK(vkCreateFramebuffer(context.device(), &info, nullptr, &handle));
    framebuffer = {context.device(), handle, vkDestroyFramebuffer};
  }

  void create_pipeline(const FragmentRun& run) {
    ShaderDesc vertex_desc = run.vertex;
    if (vertex_desc.spirv.empty()) vertex_desc = ShaderDesc{fullscreen_vertex_spirv(), "main", {}};
    DeviceHandle<VkShaderModule> vertex = create_shader_module(context, vertex_desc, "vertex");
    DeviceHandle<VkShaderModule> fragment = create_shader_module(context, run.fragment, "fragment");
    const Specialization vertex_spec(vertex_desc.spec_constants);
    const Specialization fragment_spec(run.fragment.spec_constants);

    VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                 {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vertex.get();
    stages[0].pName = vertex_desc.entry_point.c_str();
    stages[0].pSpecializationInfo = vertex_spec.get();
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = fragment.get();
    stages[1].pName = run.fragment.entry_point.c_str();
    stages[1].pSpecializationInfo = fragment_spec.get();

    const detail::FixedFunctionState fixed_function(width, height, outputs.size());

    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    info.stageCount = 2;
    info.pStages = stages;
    fixed_function.apply(info);
    info.layout = layout.get();
    info.renderPass = render_pass.get();
    info.subpass = 0;
    VkPipeline handle = VK_NULL_HANDLE;
    SAAGEN_VK_CHECK(vkCreateGraphicsPipelines(context.device(), VK_NULL_HANDLE, 1, &info, nullptr, &handle));
    pipeline = {context.device(), handle, vkDestroyPipeline};
  }

  void draw(VkCommandBuffer cmd) {
    std::vector<VkClearValue> clears(outputs.size());
    for (VkClearValue& clear : clears) std::copy(clear_color.begin(), clear_color.end(), clear.color.float32);
    VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    begin.renderPass = render_pass.get();
    begin.framebuffer = framebuffer.get();
    begin.renderArea = {{0, 0}, {width, height}};
    begin.clearValueCount = static_cast<std::uint32_t>(clears.size());
    begin.pClearValues = clears.data();
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.get());
    const VkDescriptorSet set = resources.set();
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout.get(), 0, 1, &set, 0, nullptr);
    if (!push_constants.empty()) {
      vkCmdPushConstants(cmd, layout.get(), graphics_stages, 0, static_cast<std::uint32_t>(push_constants.size()), push_constants.data());
    }
    vkCmdDraw(cmd, 3, 1, 0, 0);  // the full-screen triangle
    vkCmdEndRenderPass(cmd);
  }

  void copy_outputs(VkCommandBuffer cmd) {
    for (ColorOutput& output : outputs) {
      VkBufferImageCopy region{};
      region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      region.imageExtent = {width, height, 1};
      vkCmdCopyImageToBuffer(cmd, output.target.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, output.readback.buffer.get(), 1,
                             &region);
    }
    host_read_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                      VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_SHADER_WRITE_BIT);
  }

  RunResult run(const RunOptions& options) {
    constexpr VkPipelineStageFlags shader_stages = VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    submitter.record(
        options.gpu_timestamps, [&](VkCommandBuffer cmd) { shader_write_barrier(cmd, shader_stages); },
        [&](VkCommandBuffer cmd) { draw(cmd); }, [&](VkCommandBuffer cmd) { copy_outputs(cmd); });
    RunResult result;
    result.timing.pipeline_create_ms = pipeline_create_ms;
    submitter.submit(options.repetitions, result.timing);
    result.buffers = resources.read_back();
    for (const ColorOutput& output : outputs) {
      const FormatInfo format = format_info(output.format);
      result.attachments.push_back(Attachment{output.format, width, height, format.components,
                                              texels_to_floats(output.readback.mapped, std::size_t{width} * height, format)});
    }
    return result;
  }
};

FragmentProgram::FragmentProgram(VulkanContext& context, const FragmentRun& run) : impl_(std::make_unique<Impl>(context, run)) {}
FragmentProgram::~FragmentProgram() = default;
void FragmentProgram::write_buffer(std::uint32_t binding, std::span<const std::byte> bytes) {
  impl_->resources.write_buffer(binding, bytes);
}
void FragmentProgram::set_push_constants(Bytes bytes) { set_push_constant_bytes(impl_->push_constants, std::move(bytes)); }
RunResult FragmentProgram::run(const RunOptions& options) { return impl_->run(options); }

RunResult run_fragment(VulkanContext& context, const FragmentRun& run, const RunOptions& options) {
  return FragmentProgram(context, run).run(options);
}

}  // namespace saagen::harness
