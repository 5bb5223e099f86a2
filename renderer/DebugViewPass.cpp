#include "renderer/DebugViewPass.h"

#include "shaders/debug_view.comp.h"
#include "shaders/shared/frame.h"


namespace sss::renderer {

namespace {
vk::DescriptorSetLayoutBuilder bindings() {
  const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
  vk::DescriptorSetLayoutBuilder b;
  b.add(0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs)
      .add(1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs)
      .add(2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs);
  for (uint32_t i = 3; i <= 10; ++i) b.add(i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, cs);
  b.add(11, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cs);
  b.add(12, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, cs);  // normals
  b.add(13, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, cs);  // shadow maps, comparison
  return b;
}
}  // namespace

DebugViewPass::DebugViewPass(const FrameResources& resources)
    : r_(resources),
      program_(r_.context, bindings(), sss_spv_debug_view_comp, sizeof(shader::DebugPush), 1,
               kName) {
  set_ = program_.allocate();
  write_descriptors();
}

void DebugViewPass::write_descriptors() {
  const FrameTargets& t = r_.targets;
  const VkSampler nearest = r_.samplers.nearest.get();
  const VkImageLayout general = VK_IMAGE_LAYOUT_GENERAL;
  vk::DescriptorWriter(set_)
      .uniform_buffer(0, r_.frame_uniforms)
      .uniform_buffer(1, r_.lights)
      .storage_buffer(2, r_.materials)
      .combined_image(3, t.albedo, nearest)
      .combined_image(4, t.depth, nearest, kDepthReadLayout)
      .combined_image(5, t.irradiance, nearest, general)
      .combined_image(6, t.specular, nearest, general)
      .combined_image(7, t.blur_a, nearest, general)
      .combined_image(8, t.accum, nearest, general)
      .combined_image(9, t.light_depth, nearest)
      .combined_image(10, t.uv_stretch, nearest)
      .storage_image(11, t.display)
      .combined_image(12, t.normal, nearest)
      .combined_image(13, t.shadow, r_.samplers.shadow.get())
      .update(r_.context);
}

void DebugViewPass::set_view(DebugView view, const std::array<float, 2>& range) {
  view_ = view;
  range_ = range;
}

void DebugViewPass::add_to(graph::FrameGraph& graph) const {
  const FrameTargets& t = r_.targets;
  using namespace graph::use;
  graph.add_pass(kName).step({{&t.albedo, kSampled},
                              {&t.depth, kSampledDepth},
                              {&t.irradiance, kComputeRead},
                              {&t.specular, kComputeRead},
                              {&t.blur_a, kComputeRead},
                              {&t.accum, kComputeRead},
                              {&t.light_depth, kSampled},
                              {&t.uv_stretch, kSampled},
                              {&t.normal, kSampled},
                              {&t.shadow, kSampled},
                              {&t.display, kComputeWrite}},
                             [this](VkCommandBuffer cmd) {
                               shader::DebugPush push;
                               push.view = {float(static_cast<int>(view_)), range_[0],
                                            range_[1], 0.0f};
                               program_.bind(cmd, set_);
                               vkCmdPushConstants(cmd, program_.layout.get(),
                                                  VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push),
                                                  &push);
                               ComputeProgram::dispatch(cmd, r_.targets.width,
                                                        r_.targets.height);
                             });
}

}  // namespace sss::renderer
