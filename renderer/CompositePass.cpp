#include "renderer/CompositePass.h"

#include "shaders/composite.comp.h"

namespace sss::renderer {

namespace {
vk::DescriptorSetLayoutBuilder bindings() {
  const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
  vk::DescriptorSetLayoutBuilder b;
  b.add(0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs).add(1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs);
  for (uint32_t i : {2, 3, 4, 6}) b.add(i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, cs);
  b.add(7, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cs).add(8, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cs);
  b.add(9, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, cs);
  return b;
}
}  // namespace

CompositePass::CompositePass(const FrameResources& resources)
    : r_(resources), program_(r_.context, bindings(), sss_spv_composite_comp, 0, 1, kName) {
  set_ = program_.allocate();
  write_descriptors();
}

void CompositePass::write_descriptors() {
  const FrameTargets& t = r_.targets;
  const VkSampler nearest = r_.samplers.nearest.get();
  const VkImageLayout general = VK_IMAGE_LAYOUT_GENERAL;
  vk::DescriptorWriter(set_)
      .uniform_buffer(0, r_.frame_uniforms)
      .storage_buffer(1, r_.materials)
      .combined_image(2, t.albedo, nearest)
      .combined_image(3, t.irradiance, nearest, general)
      .combined_image(4, t.specular, nearest, general)
      .combined_image(6, t.accum, nearest, general)
      .storage_image(7, t.hdr)
      .storage_image(8, t.display)
      .combined_image(9, r_.environment.background(), nearest)
      .update(r_.context);
}

void CompositePass::add_to(graph::FrameGraph& graph) const {
  const FrameTargets& t = r_.targets;
  using namespace graph::use;
  graph.add_pass(kName).step({{&t.albedo, kSampled},
                              {&t.irradiance, kComputeRead},
                              {&t.specular, kComputeRead},
                              {&t.accum, kComputeRead},
                              {&t.hdr, kComputeWrite},
                              {&t.display, kComputeWrite}},
                             [this](VkCommandBuffer cmd) {
                               program_.bind(cmd, set_);
                               if (full_frame_)  // the environment behind the geometry
                                 ComputeProgram::dispatch(cmd, r_.targets.display.width(),
                                                          r_.targets.display.height());
                               else
                                 ComputeProgram::dispatch(cmd, r_.rect);
                             });
}

}  // namespace sss::renderer
