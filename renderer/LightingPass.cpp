#include "renderer/LightingPass.h"

#include "shaders/lighting.comp.bindings.h"
#include "shaders/lighting.comp.h"

namespace sss::renderer {

namespace b = shader::bindings::lighting_comp;

LightingPass::LightingPass(const FrameResources& resources)
    : r_(resources), program_(r_.context, b::kAll, sss_spv_lighting_comp, 0, 1, kName) {
  set_ = program_.allocate();
  write_descriptors();
}

void LightingPass::write_descriptors() {
  const FrameTargets& t = r_.targets;
  const VkSampler nearest = r_.samplers.nearest.get();
  vk::DescriptorWriter(set_)
      .uniform_buffer(b::Frame, r_.frame_uniforms)
      .uniform_buffer(b::Lights, r_.lights)
      .storage_buffer(b::Materials, r_.materials)
      .combined_image(b::depth_tex, t.depth, nearest, kDepthReadLayout)
      .combined_image(b::normal_tex, t.normal, nearest)
      .combined_image(b::albedo_tex, t.albedo, nearest)
      .combined_image(b::shadow_tex, t.shadow, r_.samplers.shadow.get())
      .storage_image(b::irradiance_img, t.irradiance)
      .storage_image(b::specular_img, t.specular)
      .storage_image(b::surface_img, t.surface)
      .combined_image(b::light_depth_tex, t.light_depth, nearest)
      .combined_image(b::environment_specular_tex, r_.environment.specular(), nearest)
      .combined_image(b::dfg_tex, r_.environment.dfg(), nearest)
      .combined_image(b::sky_blocked_tex, t.sky_blocked, nearest)
      .update(r_.context);
}

void LightingPass::add_to(graph::FrameGraph& graph) const {
  const FrameTargets& t = r_.targets;
  using namespace graph::use;
  graph.add_pass(kName).step({{&t.depth, kSampledDepth},
                              {&t.normal, kSampled},
                              {&t.albedo, kSampled},
                              {&t.shadow, kSampled},
                              {&t.light_depth, kSampled},
                              {&t.sky_blocked, kSampled},  // read only when the G-buffer drew it
                              {&t.irradiance, kComputeWrite},
                              {&t.specular, kComputeWrite},
                              {&t.surface, kComputeWrite}},
                             [this](VkCommandBuffer cmd) {
                               program_.bind(cmd, set_);
                               Program::dispatch(cmd, r_.rect);
                             });
}

}  // namespace sss::renderer
