// A builder for graphics pipelines that render with dynamic rendering (no VkRenderPass):
// the attachment formats are part of the pipeline. Viewport and scissor are always
// dynamic (begin_rendering() in Rendering.h sets them); so is the depth bias when
// enabled, for shadow maps.
//
//   PipelineHandle gbuffer = GraphicsPipelineBuilder()
//       .vertex_shader(sss_spv_gbuffer_vert).fragment_shader(sss_spv_gbuffer_frag)
//       .vertex_binding(0, sizeof(Vertex))
//       .vertex_attribute(0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position))
//       .color(VK_FORMAT_R16G16B16A16_SFLOAT).color(VK_FORMAT_R8G8B8A8_UNORM)
//       .depth(VK_FORMAT_D32_SFLOAT, DepthTest::Write)
//       .cull(VK_CULL_MODE_BACK_BIT)
//       .build(ctx, layout.get(), "gbuffer");
#pragma once

#include "renderer/vk/Handle.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace sss::vk {

class Context;

enum class Blend {
  Off,            // replace
  Alpha,          // src·α + dst·(1−α)
  Additive,       // src + dst (accumulating lights)
  Premultiplied,  // src + dst·(1−α)
};

enum class DepthTest {
  Off,       // no depth test
  ReadOnly,  // test, do not write
  Write,     // test and write
};

// Triangle lists, filled: the only kind the renderer draws.
class GraphicsPipelineBuilder {
 public:
  // The spans must stay valid until build().
  GraphicsPipelineBuilder& vertex_shader(std::span<const uint32_t> spirv);
  GraphicsPipelineBuilder& fragment_shader(std::span<const uint32_t> spirv);  // none: depth only

  GraphicsPipelineBuilder& vertex_binding(uint32_t binding, uint32_t stride,
                                          VkVertexInputRate rate = VK_VERTEX_INPUT_RATE_VERTEX);
  GraphicsPipelineBuilder& vertex_attribute(uint32_t location, uint32_t binding, VkFormat format,
                                            uint32_t offset);

  // One colour attachment, in attachment order.
  GraphicsPipelineBuilder& color(VkFormat format, Blend blend = Blend::Off);
  // compare: LESS for a 0-near depth buffer, GREATER for reversed Z.
  GraphicsPipelineBuilder& depth(VkFormat format, DepthTest test,
                                 VkCompareOp compare = VK_COMPARE_OP_LESS);
  GraphicsPipelineBuilder& cull(VkCullModeFlags mode,
                                VkFrontFace front = VK_FRONT_FACE_COUNTER_CLOCKWISE);
  // Depth bias set per draw with vkCmdSetDepthBias (shadow maps).
  GraphicsPipelineBuilder& dynamic_depth_bias();
  GraphicsPipelineBuilder& samples(VkSampleCountFlagBits samples);

  // Throws std::logic_error without a vertex shader or any attachment.
  PipelineHandle build(const Context& context, VkPipelineLayout layout,
                       std::string_view name = {}) const;

 private:
  std::span<const uint32_t> vertex_;
  std::span<const uint32_t> fragment_;
  std::vector<VkVertexInputBindingDescription> bindings_;
  std::vector<VkVertexInputAttributeDescription> attributes_;
  std::vector<VkFormat> color_formats_;
  std::vector<Blend> blends_;
  VkFormat depth_format_ = VK_FORMAT_UNDEFINED;
  DepthTest depth_test_ = DepthTest::Off;
  VkCompareOp depth_compare_ = VK_COMPARE_OP_LESS;
  VkCullModeFlags cull_ = VK_CULL_MODE_NONE;
  VkFrontFace front_ = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  bool dynamic_depth_bias_ = false;
  VkSampleCountFlagBits samples_ = VK_SAMPLE_COUNT_1_BIT;
};

}  // namespace sss::vk
