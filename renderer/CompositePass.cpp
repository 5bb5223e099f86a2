#include "renderer/CompositePass.h"

#include "shaders/composite.comp.bindings.h"
#include "shaders/composite.comp.h"

namespace sss::renderer {

namespace b = shader::bindings::composite_comp;

CompositePass::CompositePass(const FrameResources& resources)
    : r_(resources), program_(r_.context, b::kAll, sss_spv_composite_comp, 0, 1, kName) {
  set_ = program_.allocate();
  write_descriptors();
}

void CompositePass::write_descriptors() {
  const FrameTargets& t = r_.targets;
  const VkSampler nearest = r_.samplers.nearest.get();
  const VkImageLayout general = VK_IMAGE_LAYOUT_GENERAL;
  vk::DescriptorWriter(set_)
      .uniform_buffer(b::Frame, r_.frame_uniforms)
      .storage_buffer(b::Materials, r_.materials)
      .combined_image(b::albedo_tex, t.albedo, nearest)
      .combined_image(b::irradiance_tex, t.irradiance, nearest, general)
      .combined_image(b::specular_tex, t.specular, nearest, general)
      .combined_image(b::accumulated_tex, t.accum, nearest, general)
      .storage_image(b::hdr_img, t.hdr)
      .storage_image(b::display_img, t.display)
      .combined_image(b::background_tex, r_.environment.background(), nearest)
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
                                 Program::dispatch(cmd, r_.targets.display.width(),
                                                          r_.targets.display.height());
                               else
                                 Program::dispatch(cmd, r_.rect);
                             });
}

}  // namespace sss::renderer
