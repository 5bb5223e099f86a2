#include "renderer/SssSeparablePass.h"

#include "shaders/shared/frame.h"
#include "shaders/sss_separable.comp.bindings.h"
#include "shaders/sss_separable.comp.h"

namespace sss::renderer {

namespace b = shader::bindings::sss_separable_comp;

SssSeparablePass::SssSeparablePass(const FrameResources& resources)
    : r_(resources),
      program_(r_.context, b::kAll, sss_spv_sss_separable_comp, sizeof(shader::BlurPush), 2,
               kName),
      prefix_(resources, 2) {
  horizontal_ = program_.allocate();
  vertical_ = program_.allocate();
  write_descriptors();
}

void SssSeparablePass::write_descriptors() {
  const FrameTargets& t = r_.targets;
  const VkSampler nearest = r_.samplers.nearest.get();
  const auto write = [&](VkDescriptorSet set, const vk::Image& in) {
    vk::DescriptorWriter(set)
        .uniform_buffer(b::Frame, r_.frame_uniforms)
        .storage_buffer(b::Materials, r_.materials)
        .combined_image(b::albedo_tex, t.albedo, nearest)
        .combined_image(b::specular_tex, t.specular, nearest, VK_IMAGE_LAYOUT_GENERAL)
        .combined_image(b::input_tex, in, nearest, VK_IMAGE_LAYOUT_GENERAL)
        .storage_image(b::line_img, t.sss_line)
        .storage_image(b::hdr_img, t.hdr)
        .storage_image(b::display_img, t.display)
        .storage_image(b::scattered_img, t.blur_a)
        .combined_image(b::prefix_tex, t.sss_prefix, nearest, VK_IMAGE_LAYOUT_GENERAL)
        .update(r_.context);
  };
  write(horizontal_, t.irradiance);
  write(vertical_, t.sss_line);
  const vk::Image* inputs[] = {&t.irradiance, &t.sss_line};
  prefix_.write_descriptors(inputs);
}

void SssSeparablePass::add_to(graph::FrameGraph& graph) const {
  const FrameTargets& t = r_.targets;
  using namespace graph::use;
  graph::FrameGraph::PassBuilder pass = graph.add_pass(kName);
  for (int k = 0; k < 2; ++k) {
    const vk::Image& input = k == 0 ? t.irradiance : t.sss_line;
    // The running sums along this pass's lines, then the blur that reads them. The
    // horizontal blur writes sss_line; the vertical one composites into hdr and display,
    // and writes R * E to blur_a for the scattered view. Both halves' sets hold every
    // storage image, so both declare every write (synchronization validation counts a
    // bound storage image as written).
    prefix_.add_step(pass, input, k == 1);
    pass.step({{&t.albedo, kSampled},
               {&t.specular, kComputeRead},
               {&input, kComputeRead},
               {&t.sss_prefix, kComputeRead},
               {&t.sss_line, kComputeWrite},
               {&t.hdr, kComputeWrite},
               {&t.display, kComputeWrite},
               {&t.blur_a, kComputeWrite}},
              [this, k](VkCommandBuffer cmd) {
      shader::BlurPush push;
      push.direction = k == 0 ? shader::vec4{1, 0, 0, 1}
                              : shader::vec4{0, 1, write_scattered_ ? 1.0f : 0.0f, 0};
      program_.bind(cmd, k == 0 ? horizontal_ : vertical_);
      vkCmdPushConstants(cmd, program_.layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                         sizeof(push), &push);
      Program::dispatch(cmd, r_.rect);
    });
  }
}

}  // namespace sss::renderer
