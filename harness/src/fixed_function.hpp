// The fixed-function state of the harness's graphics pipelines (a full-viewport triangle list, no
// vertex input, no culling, one sample, no blending): one definition for the executing fragment
// runs (program.cpp) and the ISA-statistics compiles (isa.cpp).
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

namespace saagen::harness::detail {

class FixedFunctionState {
 public:
  FixedFunctionState(std::uint32_t width, std::uint32_t height, std::size_t color_attachments)
      : viewport_{0.0f, 0.0f, static_cast<float>(width), static_cast<float>(height), 0.0f, 1.0f},
        scissor_{{0, 0}, {width, height}},
        blends_(color_attachments) {
    assembly_.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    viewport_state_.viewportCount = 1;
    viewport_state_.pViewports = &viewport_;
    viewport_state_.scissorCount = 1;
    viewport_state_.pScissors = &scissor_;
    raster_.polygonMode = VK_POLYGON_MODE_FILL;
    raster_.cullMode = VK_CULL_MODE_NONE;
    raster_.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    raster_.lineWidth = 1.0f;
    multisample_.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    for (VkPipelineColorBlendAttachmentState& blend : blends_) {
      blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    }
    color_blend_.attachmentCount = static_cast<std::uint32_t>(blends_.size());
    color_blend_.pAttachments = blends_.data();
  }
  // The create info points into this object: neither copied nor moved.
  FixedFunctionState(const FixedFunctionState&) = delete;
  FixedFunctionState& operator=(const FixedFunctionState&) = delete;

  // Fills the fixed-function members of `info` (stages, layout and render pass are the caller's).
  void apply(VkGraphicsPipelineCreateInfo& info) const {
    info.pVertexInputState = &vertex_input_;
    info.pInputAssemblyState = &assembly_;
    info.pViewportState = &viewport_state_;
    info.pRasterizationState = &raster_;
    info.pMultisampleState = &multisample_;
    info.pColorBlendState = &color_blend_;
  }

 private:
  VkViewport viewport_;
  VkRect2D scissor_;
  std::vector<VkPipelineColorBlendAttachmentState> blends_;
  VkPipelineVertexInputStateCreateInfo vertex_input_{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo assembly_{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  VkPipelineViewportStateCreateInfo viewport_state_{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  VkPipelineRasterizationStateCreateInfo raster_{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  VkPipelineMultisampleStateCreateInfo multisample_{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  VkPipelineColorBlendStateCreateInfo color_blend_{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
};

}  // namespace saagen::harness::detail
