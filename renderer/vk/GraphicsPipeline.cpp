#include "renderer/vk/GraphicsPipeline.h"

#include "renderer/vk/Check.h"
#include "renderer/vk/Context.h"
#include "renderer/vk/Format.h"
#include "renderer/vk/Pipeline.h"

#include <stdexcept>

namespace sss::vk {

namespace {

VkPipelineColorBlendAttachmentState blend_state(Blend blend) {
  VkPipelineColorBlendAttachmentState s{};
  s.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                     VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  if (blend == Blend::Off) return s;
  s.blendEnable = VK_TRUE;
  s.colorBlendOp = VK_BLEND_OP_ADD;
  s.alphaBlendOp = VK_BLEND_OP_ADD;
  switch (blend) {
    case Blend::Alpha:
      s.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
      s.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
      s.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
      s.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
      break;
    case Blend::Additive:
      s.srcColorBlendFactor = VK_BLEND_FACTOR_ONE;
      s.dstColorBlendFactor = VK_BLEND_FACTOR_ONE;
      s.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
      s.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
      break;
    case Blend::Premultiplied:
      s.srcColorBlendFactor = VK_BLEND_FACTOR_ONE;
      s.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
      s.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
      s.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
      break;
    case Blend::Off: break;
  }
  return s;
}

VkPipelineShaderStageCreateInfo stage(VkShaderStageFlagBits which, VkShaderModule module) {
  VkPipelineShaderStageCreateInfo s{};
  s.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  s.stage = which;
  s.module = module;
  s.pName = "main";
  return s;
}

// Filled triangles, culled and wound as asked, with the depth bias set per draw when it is
// dynamic.
VkPipelineRasterizationStateCreateInfo rasterization(VkCullModeFlags cull, VkFrontFace front, bool dynamic_depth_bias) {
  VkPipelineRasterizationStateCreateInfo raster{};
  raster.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = cull;
  raster.frontFace = front;
  raster.depthBiasEnable = dynamic_depth_bias ? VK_TRUE : VK_FALSE;
  raster.lineWidth = 1.0f;
  return raster;
}

VkPipelineDepthStencilStateCreateInfo depth_stencil(DepthTest test, VkCompareOp compare) {
  VkPipelineDepthStencilStateCreateInfo depth{};
  depth.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
  depth.depthTestEnable = test != DepthTest::Off ? VK_TRUE : VK_FALSE;
  depth.depthWriteEnable = test == DepthTest::Write ? VK_TRUE : VK_FALSE;
  depth.depthCompareOp = compare;
  depth.minDepthBounds = 0.0f;
  depth.maxDepthBounds = 1.0f;
  return depth;
}

// The vertex layout; it points into the vectors, which must outlive the pipeline's creation.
VkPipelineVertexInputStateCreateInfo vertex_input_state(
    const std::vector<VkVertexInputBindingDescription>& bindings,
    const std::vector<VkVertexInputAttributeDescription>& attributes) {
  VkPipelineVertexInputStateCreateInfo vertex_input{};
  vertex_input.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
  vertex_input.vertexBindingDescriptionCount = static_cast<uint32_t>(bindings.size());
  vertex_input.pVertexBindingDescriptions = bindings.data();
  vertex_input.vertexAttributeDescriptionCount = static_cast<uint32_t>(attributes.size());
  vertex_input.pVertexAttributeDescriptions = attributes.data();
  return vertex_input;
}

// Dynamic rendering's attachment formats (a depth format with stencil names it for both);
// it points into `colors`, which must outlive the pipeline's creation.
VkPipelineRenderingCreateInfo rendering_formats(const std::vector<VkFormat>& colors, VkFormat depth) {
  VkPipelineRenderingCreateInfo rendering{};
  rendering.sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO;
  rendering.colorAttachmentCount = static_cast<uint32_t>(colors.size());
  rendering.pColorAttachmentFormats = colors.data();
  rendering.depthAttachmentFormat = depth;
  rendering.stencilAttachmentFormat = has_stencil(depth) ? depth : VK_FORMAT_UNDEFINED;
  return rendering;
}

}  // namespace

GraphicsPipelineBuilder& GraphicsPipelineBuilder::vertex_shader(std::span<const uint32_t> spirv) {
  vertex_ = spirv;
  return *this;
}
GraphicsPipelineBuilder& GraphicsPipelineBuilder::fragment_shader(std::span<const uint32_t> spirv) {
  fragment_ = spirv;
  return *this;
}
GraphicsPipelineBuilder& GraphicsPipelineBuilder::vertex_binding(uint32_t binding, uint32_t stride,
                                                                 VkVertexInputRate rate) {
  bindings_.push_back({binding, stride, rate});
  return *this;
}
GraphicsPipelineBuilder& GraphicsPipelineBuilder::vertex_attribute(uint32_t location,
                                                                   uint32_t binding,
                                                                   VkFormat format,
                                                                   uint32_t offset) {
  attributes_.push_back({location, binding, format, offset});
  return *this;
}
GraphicsPipelineBuilder& GraphicsPipelineBuilder::color(VkFormat format, Blend blend) {
  color_formats_.push_back(format);
  blends_.push_back(blend);
  return *this;
}
GraphicsPipelineBuilder& GraphicsPipelineBuilder::depth(VkFormat format, DepthTest test,
                                                        VkCompareOp compare) {
  depth_format_ = format;
  depth_test_ = test;
  depth_compare_ = compare;
  return *this;
}
GraphicsPipelineBuilder& GraphicsPipelineBuilder::cull(VkCullModeFlags mode, VkFrontFace front) {
  cull_ = mode;
  front_ = front;
  return *this;
}
GraphicsPipelineBuilder& GraphicsPipelineBuilder::dynamic_depth_bias() {
  dynamic_depth_bias_ = true;
  return *this;
}
GraphicsPipelineBuilder& GraphicsPipelineBuilder::samples(VkSampleCountFlagBits samples) {
  samples_ = samples;
  return *this;
}

namespace {

// The blend state over `attachments` (which must outlive it).
VkPipelineColorBlendStateCreateInfo color_blend(const std::vector<VkPipelineColorBlendAttachmentState>& attachments) {
  VkPipelineColorBlendStateCreateInfo blend{};
  blend.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
  blend.attachmentCount = static_cast<uint32_t>(attachments.size());
  blend.pAttachments = attachments.data();
  return blend;
}

// The dynamic states `dynamic` (which must outlive it).
VkPipelineDynamicStateCreateInfo dynamic_states(const std::vector<VkDynamicState>& dynamic) {
  VkPipelineDynamicStateCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
  info.dynamicStateCount = static_cast<uint32_t>(dynamic.size());
  info.pDynamicStates = dynamic.data();
  return info;
}

}  // namespace

PipelineHandle GraphicsPipelineBuilder::build(const Context& context, VkPipelineLayout layout,
                                              std::string_view name) const {
  if (vertex_.empty()) throw std::logic_error("graphics pipeline: no vertex shader");
  if (color_formats_.empty() && depth_format_ == VK_FORMAT_UNDEFINED) {
    throw std::logic_error("graphics pipeline: no colour or depth attachment");
  }
  const ShaderModuleHandle vs = create_shader_module(context, vertex_, name);
  ShaderModuleHandle fs;
  std::vector<VkPipelineShaderStageCreateInfo> stages = {
      stage(VK_SHADER_STAGE_VERTEX_BIT, vs.get())};
  if (!fragment_.empty()) {
    fs = create_shader_module(context, fragment_, name);
    stages.push_back(stage(VK_SHADER_STAGE_FRAGMENT_BIT, fs.get()));
  }

  const VkPipelineVertexInputStateCreateInfo vertex_input = vertex_input_state(bindings_, attributes_);

  VkPipelineInputAssemblyStateCreateInfo assembly{};
  assembly.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{};
  viewport.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
  viewport.viewportCount = 1;  // dynamic
  viewport.scissorCount = 1;
  const VkPipelineRasterizationStateCreateInfo raster = rasterization(cull_, front_, dynamic_depth_bias_);
  VkPipelineMultisampleStateCreateInfo multisample{};
  multisample.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
  multisample.rasterizationSamples = samples_;
  const VkPipelineDepthStencilStateCreateInfo depth = depth_stencil(depth_test_, depth_compare_);
  std::vector<VkPipelineColorBlendAttachmentState> attachments;
  for (Blend b : blends_) attachments.push_back(blend_state(b));
  const VkPipelineColorBlendStateCreateInfo blend = color_blend(attachments);
  std::vector<VkDynamicState> dynamic = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  if (dynamic_depth_bias_) dynamic.push_back(VK_DYNAMIC_STATE_DEPTH_BIAS);
  const VkPipelineDynamicStateCreateInfo dynamic_state = dynamic_states(dynamic);

  const VkPipelineRenderingCreateInfo rendering = rendering_formats(color_formats_, depth_format_);

  VkGraphicsPipelineCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
  info.pNext = &rendering;
  info.stageCount = static_cast<uint32_t>(stages.size());
  info.pStages = stages.data();
  info.pVertexInputState = &vertex_input;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = depth_format_ != VK_FORMAT_UNDEFINED ? &depth : nullptr;
  info.pColorBlendState = &blend;
  info.pDynamicState = &dynamic_state;
  info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VK_CHECK(
      vkCreateGraphicsPipelines(context.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
  if (!name.empty()) context.set_object_name(VK_OBJECT_TYPE_PIPELINE, pipeline, name);
  return PipelineHandle(context.device(), pipeline);
}

}  // namespace sss::vk
