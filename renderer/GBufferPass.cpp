#include "renderer/GBufferPass.h"

#include "renderer/vk/Barrier.h"
#include "renderer/vk/GraphicsPipeline.h"
#include "renderer/vk/Pipeline.h"
#include "renderer/vk/Rendering.h"
#include "shaders/gbuffer.frag.h"
#include "shaders/gbuffer_uv_stretch.frag.h"
#include "shaders/gbuffer.vert.h"
#include "shaders/shared/frame.h"

#include <array>
#include <cstddef>
#include <vector>

namespace sss::renderer {

vk::DescriptorSetLayoutBuilder surface_set_bindings() {
  vk::DescriptorSetLayoutBuilder b;
  b.add(0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
        VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT);
  b.add(1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT,
        shader::kMaxTextures);
  return b;
}

void write_surface_set(VkDescriptorSet set, const FrameResources& resources) {
  vk::DescriptorWriter writer(set);
  writer.uniform_buffer(0, resources.frame_uniforms);
  const std::vector<VkDescriptorImageInfo> textures = resources.scene.texture_descriptors();
  for (uint32_t i = 0; i < textures.size(); ++i)
    writer.image(1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, textures[i], i);
  writer.update(resources.context);
}

namespace {

vk::PipelineHandle build_pipeline(const vk::Context& context, VkPipelineLayout layout,
                                  bool uv_stretch) {
  vk::GraphicsPipelineBuilder builder;
  builder.vertex_shader(sss_spv_gbuffer_vert)
      .fragment_shader(uv_stretch ? std::span<const uint32_t>(sss_spv_gbuffer_uv_stretch_frag)
                                  : std::span<const uint32_t>(sss_spv_gbuffer_frag))
      .color(kNormalFormat)
      .color(kAlbedoFormat);
  if (uv_stretch) builder.color(kUvStretchFormat);
  add_vertex_input(builder);
  // Reversed depth (CameraSetup.h): nearer is larger, the buffer clears to 0 (the far plane).
  return builder.depth(kDepthFormat, vk::DepthTest::Write, VK_COMPARE_OP_GREATER)
      .cull(VK_CULL_MODE_NONE)
      .build(context, layout, uv_stretch ? "gbuffer uv stretch" : "gbuffer");
}
}  // namespace

GBufferPass::GBufferPass(const FrameResources& resources)
    : r_(resources),
      set_layout_(surface_set_bindings().build(r_.context, kName)),
      layout_(vk::create_pipeline_layout(r_.context, set_layout_.get(), sizeof(shader::DrawPush),
                                         VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                                         kName)),
      pipeline_(build_pipeline(r_.context, layout_.get(), false)),
      pool_(r_.context, surface_set_bindings(), 1, kName) {
  set_ = pool_.allocate(set_layout_.get());
  write_surface_set(set_, r_);
}

void GBufferPass::set_uv_stretch(bool on) {
  if (on && !uv_stretch_pipeline_) uv_stretch_pipeline_ = build_pipeline(r_.context, layout_.get(), true);
  uv_stretch_ = on;
}

void GBufferPass::record(VkCommandBuffer cmd, vk::GpuTimer& timer) const {
  auto scope = timer.scope(cmd, kName);
  const FrameTargets& t = r_.targets;
  const std::array<vk::ColorTarget, 3> colors = {vk::ColorTarget(t.normal.view()),
                                                 vk::ColorTarget(t.albedo.view()),
                                                 vk::ColorTarget(t.uv_stretch.view())};
  const vk::DepthTarget depth(t.depth.view(), 0.0f);  // reversed depth: 0 is the far plane
  vk::begin_rendering(cmd, t.depth.extent(),
                      std::span<const vk::ColorTarget>(colors.data(), uv_stretch_ ? 3 : 2), &depth);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                    uv_stretch_ ? uv_stretch_pipeline_.get() : pipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), 0, 1, &set_, 0,
                          nullptr);
  r_.scene.draw(cmd, layout_.get());
  vk::end_rendering(cmd);
  const vk::Scope color_write{VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                              VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT};
  const vk::Scope depth_write{
      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT};
  const vk::Scope sampled{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
  const vk::Scope depth_read{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
                                 VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                                 VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                             VK_ACCESS_2_SHADER_SAMPLED_READ_BIT |
                                 VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT};
  vk::pipeline_barrier(
      cmd, {vk::image_barrier(t.normal, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, color_write, sampled),
            vk::image_barrier(t.albedo, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, color_write, sampled),
            vk::image_barrier(t.uv_stretch, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, color_write, sampled),
            vk::image_barrier(t.depth, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, kDepthReadLayout,
                              depth_write, depth_read)});
}

}  // namespace sss::renderer
