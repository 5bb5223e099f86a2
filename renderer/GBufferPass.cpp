#include "renderer/GBufferPass.h"

#include "renderer/vk/GraphicsPipeline.h"
#include "renderer/vk/Pipeline.h"
#include "renderer/vk/Rendering.h"
#include "shaders/gbuffer.frag.bindings.h"
#include "shaders/gbuffer.frag.h"
#include "shaders/gbuffer.vert.bindings.h"
#include "shaders/gbuffer_sky.frag.bindings.h"
#include "shaders/gbuffer_sky.frag.h"
#include "shaders/gbuffer_sky.vert.bindings.h"
#include "shaders/gbuffer_sky.vert.h"
#include "shaders/gbuffer_uv_stretch.frag.bindings.h"
#include "shaders/texture_irradiance.frag.bindings.h"
#include "shaders/texture_irradiance.vert.bindings.h"
#include "shaders/texture_irradiance_sky.frag.bindings.h"
#include "shaders/texture_irradiance_sky.vert.bindings.h"
#include "shaders/gbuffer_uv_stretch.frag.h"
#include "shaders/gbuffer.vert.h"
#include "shaders/shared/frame.h"

#include <array>
#include <cstddef>
#include <vector>

namespace sss::renderer {

namespace surface = shader::bindings::gbuffer_frag;  // shared/surface.glsl's set

vk::DescriptorSetLayoutBuilder surface_set_bindings() {
  // Every shader that includes shared/surface.glsl, as each uses it.
  return vk::DescriptorSetLayoutBuilder()
      .add(shader::bindings::gbuffer_vert::kAll)
      .add(shader::bindings::gbuffer_frag::kAll)
      .add(shader::bindings::gbuffer_uv_stretch_frag::kAll)
      .add(shader::bindings::gbuffer_sky_vert::kAll)
      .add(shader::bindings::gbuffer_sky_frag::kAll)
      .add(shader::bindings::texture_irradiance_vert::kAll)
      .add(shader::bindings::texture_irradiance_frag::kAll)
      .add(shader::bindings::texture_irradiance_sky_vert::kAll)
      .add(shader::bindings::texture_irradiance_sky_frag::kAll);
}

void write_surface_set(VkDescriptorSet set, const FrameResources& resources) {
  vk::DescriptorWriter writer(set);
  writer.uniform_buffer(surface::Frame, resources.frame_uniforms);
  writer.uniform_buffer(shader::bindings::gbuffer_sky_frag::Lights, resources.lights);
  const std::vector<VkDescriptorImageInfo> textures = resources.scene.texture_descriptors();
  for (uint32_t i = 0; i < textures.size(); ++i)
    writer.image(surface::textures, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, textures[i], i);
  writer.update(resources.context);
}

namespace {

enum class Variant { Frame, UvStretch, Sky };

vk::PipelineHandle build_pipeline(const vk::Context& context, VkPipelineLayout layout,
                                  Variant variant) {
  vk::GraphicsPipelineBuilder builder;
  const bool sky = variant == Variant::Sky;
  builder.vertex_shader(sky ? std::span<const uint32_t>(sss_spv_gbuffer_sky_vert)
                            : std::span<const uint32_t>(sss_spv_gbuffer_vert))
      .fragment_shader(variant == Variant::UvStretch ? std::span<const uint32_t>(sss_spv_gbuffer_uv_stretch_frag)
                       : sky                         ? std::span<const uint32_t>(sss_spv_gbuffer_sky_frag)
                                                     : std::span<const uint32_t>(sss_spv_gbuffer_frag))
      .color(kNormalFormat)
      .color(kAlbedoFormat);
  if (variant == Variant::UvStretch) builder.color(kUvStretchFormat);
  if (sky) builder.color(kSkyBlockedFormat);
  add_vertex_input(builder);
  if (sky) add_sky_vertex_input(builder);
  // Reversed depth (CameraSetup.h): nearer is larger, the buffer clears to 0 (the far plane).
  return builder.depth(kDepthFormat, vk::DepthTest::Write, VK_COMPARE_OP_GREATER)
      .cull(VK_CULL_MODE_NONE)
      .build(context, layout,
             variant == Variant::UvStretch ? "gbuffer uv stretch" : sky ? "gbuffer sky" : "gbuffer");
}
}  // namespace

GBufferPass::GBufferPass(const FrameResources& resources)
    : r_(resources),
      program_(r_.context, surface_set_bindings(), sizeof(shader::DrawPush),
               VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 1, kName,
               [&](VkPipelineLayout layout) { return build_pipeline(r_.context, layout, Variant::Frame); }) {
  set_ = program_.allocate();
  write_surface_set(set_, r_);
}

void GBufferPass::set_uv_stretch(bool on) {
  if (on && !uv_stretch_pipeline_)
    uv_stretch_pipeline_ = build_pipeline(r_.context, program_.layout.get(), Variant::UvStretch);
  uv_stretch_ = on;
}

void GBufferPass::set_sky(bool on) {
  if (on && !sky_pipeline_) sky_pipeline_ = build_pipeline(r_.context, program_.layout.get(), Variant::Sky);
  sky_ = on;
}

void GBufferPass::add_to(graph::FrameGraph& graph) const {
  const FrameTargets& t = r_.targets;
  // The third attachment: the uv-stretch view's, or the sky's (never both).
  const vk::Image* third = uv_stretch_ ? &t.uv_stretch : sky_ ? &t.sky_blocked : nullptr;
  std::vector<graph::ImageUse> uses{{&t.depth, graph::use::kDepthAttachment},
                                    {&t.normal, graph::use::kColorAttachment},
                                    {&t.albedo, graph::use::kColorAttachment}};
  if (third) uses.push_back({third, graph::use::kColorAttachment});
  graph.add_pass(kName).step(std::move(uses), [this, &t, third](VkCommandBuffer cmd) {
    const std::array<vk::ColorTarget, 3> colors = {
        vk::ColorTarget(t.normal.view()), vk::ColorTarget(t.albedo.view()),
        vk::ColorTarget(third ? third->view() : VK_NULL_HANDLE)};
    const vk::DepthTarget depth(t.depth.view(), 0.0f);  // reversed depth: 0 is the far plane
    vk::begin_rendering(cmd, t.depth.extent(),
                        std::span<const vk::ColorTarget>(colors.data(), third ? 3 : 2), &depth);
    program_.bind(cmd, uv_stretch_ ? uv_stretch_pipeline_.get()
                       : sky_      ? sky_pipeline_.get()
                                   : program_.pipeline.get(),
                  set_);
    r_.scene.draw(cmd, program_.layout.get());
    vk::end_rendering(cmd);
  });
}

}  // namespace sss::renderer
