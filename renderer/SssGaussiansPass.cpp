#include "renderer/SssGaussiansPass.h"

#include "shaders/shared/frame.h"
#include "shaders/sss_gaussians.comp.bindings.h"
#include "shaders/sss_gaussians.comp.h"

namespace sss::renderer {

namespace b = shader::bindings::sss_gaussians_comp;

SssGaussiansPass::SssGaussiansPass(const FrameResources& resources, int gaussians)
    : r_(resources),
      gaussians_(gaussians),
      program_(r_.context, b::kAll, sss_spv_sss_gaussians_comp, sizeof(shader::BlurPush), 5,
               kName) {
  blur_.allocate(program_);
  write_descriptors();
}

void SssGaussiansPass::write_descriptors() {
  const FrameTargets& t = r_.targets;
  const VkSampler nearest = r_.samplers.nearest.get();
  const auto write = [&](VkDescriptorSet set, const vk::Image& in, const vk::Image& out) {
    vk::DescriptorWriter(set)
        .uniform_buffer(b::Frame, r_.frame_uniforms)
        .storage_buffer(b::Materials, r_.materials)
        .combined_image(b::surface_tex, t.surface, nearest, VK_IMAGE_LAYOUT_GENERAL)
        .combined_image(b::input_tex, in, nearest, VK_IMAGE_LAYOUT_GENERAL)
        .storage_image(b::output_img, out)
        .storage_image(b::accum_img, t.accum)
        .update(r_.context);
  };
  blur_.write(t.irradiance, t.blur_a, t.blur_b, t.blur_temp, write);
}

void SssGaussiansPass::add_to(graph::FrameGraph& graph) const {
  const FrameTargets& t = r_.targets;
  using Role = GaussianPingPong::Role;
  const auto image = [&t](Role role) {
    return role == Role::Source ? &t.irradiance
           : role == Role::A    ? &t.blur_a
           : role == Role::B    ? &t.blur_b
                                : &t.blur_temp;
  };
  graph::FrameGraph::PassBuilder pass = graph.add_pass(kName);
  for (int g = 0; g < gaussians_; ++g)
    for (int k = 0; k < 2; ++k) {
      const GaussianPingPong::Dispatch d = blur_.dispatch(g, k, 0.0f);
      // The vertical dispatch adds its weight x its result to accum (read and written);
      // the horizontal one's set holds accum too, which counts as a write (synchronization
      // validation counts a bound storage image as written).
      pass.step({{&t.surface, graph::use::kComputeRead},
                 {image(d.input), graph::use::kComputeRead},
                 {image(d.output), graph::use::kComputeWrite},
                 {&t.accum, graph::use::kComputeWrite}},
                [this, d](VkCommandBuffer cmd) {
                  GaussianPingPong::run(cmd, program_, d, r_.rect.width(), r_.rect.height());
                });
    }
}

}  // namespace sss::renderer
