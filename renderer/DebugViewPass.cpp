#include "renderer/DebugViewPass.h"

#include "shaders/debug_view.comp.bindings.h"
#include "shaders/debug_view.comp.h"
#include "shaders/shared/frame.h"


namespace sss::renderer {

namespace b = shader::bindings::debug_view_comp;

DebugViewPass::DebugViewPass(const FrameResources& resources)
    : r_(resources),
      program_(r_.context, b::kAll, sss_spv_debug_view_comp, sizeof(shader::DebugPush), 1,
               kName) {
  set_ = program_.allocate();
  write_descriptors();
}

void DebugViewPass::write_descriptors() {
  const FrameTargets& t = r_.targets;
  const VkSampler nearest = r_.samplers.nearest.get();
  const VkImageLayout general = VK_IMAGE_LAYOUT_GENERAL;
  vk::DescriptorWriter(set_)
      .uniform_buffer(b::Frame, r_.frame_uniforms)
      .uniform_buffer(b::Lights, r_.lights)
      .storage_buffer(b::Materials, r_.materials)
      .combined_image(b::albedo_tex, t.albedo, nearest)
      .combined_image(b::depth_tex, t.depth, nearest, kDepthReadLayout)
      .combined_image(b::irradiance_tex, t.irradiance, nearest, general)
      .combined_image(b::specular_tex, t.specular, nearest, general)
      .combined_image(b::scattered_tex, t.blur_a, nearest, general)
      .combined_image(b::accumulated_tex, t.accum, nearest, general)
      .combined_image(b::light_depth_tex, t.light_depth, nearest)
      .combined_image(b::uv_stretch_tex, t.uv_stretch, nearest)
      .storage_image(b::display_img, t.display)
      .combined_image(b::normal_tex, t.normal, nearest)
      .combined_image(b::shadow_tex, t.shadow, r_.samplers.shadow.get())
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
                               Program::dispatch(cmd, r_.targets.width,
                                                        r_.targets.height);
                             });
}

}  // namespace sss::renderer
