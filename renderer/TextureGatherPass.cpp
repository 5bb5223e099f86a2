#include "renderer/TextureGatherPass.h"

#include "renderer/SssTexturePass.h"
#include "renderer/vk/GraphicsPipeline.h"
#include "renderer/vk/Pipeline.h"
#include "renderer/vk/Rendering.h"
#include "shaders/gbuffer.vert.bindings.h"
#include "shaders/gbuffer.vert.h"
#include "shaders/texture_gather.frag.bindings.h"
#include "shaders/shared/frame.h"
#include "shaders/texture_gather.frag.h"

#include <cstddef>

namespace sss::renderer {

namespace {
constexpr float kLookupBiasUnits = 4.0f;
constexpr float kLookupBiasSlope = 0.0f;

namespace vert = shader::bindings::gbuffer_vert;
namespace frag = shader::bindings::texture_gather_frag;

vk::DescriptorSetLayoutBuilder bindings() {
  return vk::DescriptorSetLayoutBuilder().add(vert::kAll).add(frag::kAll);
}
vk::PipelineHandle build_pipeline(const vk::Context& context, VkPipelineLayout layout) {
  vk::GraphicsPipelineBuilder builder;
  builder.vertex_shader(sss_spv_gbuffer_vert)
      .fragment_shader(sss_spv_texture_gather_frag)
      .color(kLightingFormat)
      .depth(kDepthFormat, vk::DepthTest::ReadOnly, VK_COMPARE_OP_GREATER_OR_EQUAL)  // reversed depth
      .dynamic_depth_bias()
      .cull(VK_CULL_MODE_NONE);
  add_vertex_input(builder);
  return builder.build(context, layout, TextureGatherPass::kName);
}
}  // namespace

TextureGatherPass::TextureGatherPass(const FrameResources& resources)
    : r_(resources),
      program_(r_.context, bindings(), sizeof(shader::DrawPush),
               VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 1, kName,
               [&](VkPipelineLayout layout) { return build_pipeline(r_.context, layout); }) {
  set_ = program_.allocate();
  vk::DescriptorWriter(set_).uniform_buffer(vert::Frame, r_.frame_uniforms).update(r_.context);
}

void TextureGatherPass::set_objects(const SssTexturePass& texture) {
  draws_.clear();
  vk::DescriptorWriter writer(set_);
  const VkSampler linear = r_.samplers.linear.get();
  const auto& objects = texture.objects();
  for (std::uint32_t i = 0; i < shader::kMaxTextureObjects; ++i) {
    // Unused slots repeat object 0 (never read: no draw pushes their index).
    if (objects.empty()) break;
    const std::size_t o = i < objects.size() ? i : 0;
    writer.image(frag::scattered, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                 texture.scattered(o).descriptor(VK_IMAGE_LAYOUT_GENERAL, linear), i);
  }
  for (std::size_t i = 0; i < objects.size(); ++i) draws_.emplace_back(objects[i].instance, int(i));
  writer.update(r_.context);
}

void TextureGatherPass::add_to(graph::FrameGraph& graph) const {
  const FrameTargets& t = r_.targets;
  // The atlases it samples are SssTexturePass's: that pass orders its writes before
  // this fragment shader.
  graph.add_pass(kName).step(
      {{&t.accum, graph::use::kColorAttachmentGeneral}, {&t.depth, graph::use::kDepthTest}},
      [this, &t](VkCommandBuffer cmd) {
        vk::ColorTarget color(t.accum.view());
        color.layout = VK_IMAGE_LAYOUT_GENERAL;
        vk::DepthTarget depth(t.depth.view());
        depth.load = VK_ATTACHMENT_LOAD_OP_LOAD;
        depth.store = VK_ATTACHMENT_STORE_OP_NONE;
        depth.layout = kDepthReadLayout;
        vk::begin_rendering(cmd, t.depth.extent(), {&color, 1}, &depth);
        if (!draws_.empty()) {
          program_.bind(cmd, set_);
          // The lookup's depth need not be bit-identical to the G-buffer's (lavapipe
          // compiles the same vertex shader per pipeline; `invariant` draws a Mesa
          // warning), so it is pulled toward the camera (up: reversed depth) by a few
          // units of depth resolution: the visible surface passes, what lies behind it
          // does not. No slope-scaled term: at a silhouette it let the back of the sphere
          // through (TextureSpaceTest.SphereSeamShowsNoLine: 2.75% there); with this bias
          // no scattering pixel of the bunny, sphere or materials misses its lookup.
          vkCmdSetDepthBias(cmd, kLookupBiasUnits, 0.0f, kLookupBiasSlope);
          for (const auto& [instance, object] : draws_)
            r_.scene.draw_instance(cmd, program_.layout.get(), instance, object);
        }
        vk::end_rendering(cmd);
      });
}

}  // namespace sss::renderer
