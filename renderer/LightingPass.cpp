#include "renderer/LightingPass.h"

#include "shaders/lighting.comp.h"

namespace sss::renderer {

namespace {
vk::DescriptorSetLayoutBuilder bindings() {
  const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
  vk::DescriptorSetLayoutBuilder b;
  b.add(0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs)
      .add(1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs)
      .add(2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs);
  for (uint32_t i = 3; i <= 6; ++i) b.add(i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, cs);
  b.add(10, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, cs);  // shadow depth: thickness
  b.add(11, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, cs);  // environment: prefiltered levels
  b.add(12, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, cs);  // environment: DFG table
  for (uint32_t i = 7; i <= 9; ++i) b.add(i, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cs);
  return b;
}
}  // namespace

LightingPass::LightingPass(const FrameResources& resources)
    : r_(resources), program_(r_.context, bindings(), sss_spv_lighting_comp, 0, 1, kName) {
  set_ = program_.allocate();
  write_descriptors();
}

void LightingPass::write_descriptors() {
  const FrameTargets& t = r_.targets;
  const VkSampler nearest = r_.samplers.nearest.get();
  vk::DescriptorWriter(set_)
      .uniform_buffer(0, r_.frame_uniforms)
      .uniform_buffer(1, r_.lights)
      .storage_buffer(2, r_.materials)
      .combined_image(3, t.depth, nearest, kDepthReadLayout)
      .combined_image(4, t.normal, nearest)
      .combined_image(5, t.albedo, nearest)
      .combined_image(6, t.shadow, r_.samplers.shadow.get())
      .storage_image(7, t.irradiance)
      .storage_image(8, t.specular)
      .storage_image(9, t.surface)
      .combined_image(10, t.light_depth, nearest)
      .combined_image(11, r_.environment.specular(), nearest)
      .combined_image(12, r_.environment.dfg(), nearest)
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
                              {&t.irradiance, kComputeWrite},
                              {&t.specular, kComputeWrite},
                              {&t.surface, kComputeWrite}},
                             [this](VkCommandBuffer cmd) {
                               program_.bind(cmd, set_);
                               ComputeProgram::dispatch(cmd, r_.rect);
                             });
}

}  // namespace sss::renderer
