#include "renderer/SssSeparablePass.h"

#include "shaders/shared/frame.h"
#include "shaders/sss_separable.comp.h"

namespace sss::renderer {

namespace {
vk::DescriptorSetLayoutBuilder bindings() {
  const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
  vk::DescriptorSetLayoutBuilder b;
  b.add(0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs)
      .add(1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs)
      .add(2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, cs)
      .add(4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, cs)
      .add(5, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cs);
  return b;
}
}  // namespace

SssSeparablePass::SssSeparablePass(const FrameResources& resources)
    : r_(resources),
      program_(r_.context, bindings(), sss_spv_sss_separable_comp, sizeof(shader::BlurPush), 2,
               kName) {
  horizontal_ = program_.allocate();
  vertical_ = program_.allocate();
  write_descriptors();
}

void SssSeparablePass::write_descriptors() {
  const FrameTargets& t = r_.targets;
  const VkSampler nearest = r_.samplers.nearest.get();
  const VkSampler linear = r_.samplers.linear.get();
  const auto write = [&](VkDescriptorSet set, const vk::Image& in, const vk::Image& out) {
    vk::DescriptorWriter(set)
        .uniform_buffer(0, r_.frame_uniforms)
        .storage_buffer(1, r_.materials)
        .combined_image(2, t.surface, nearest, VK_IMAGE_LAYOUT_GENERAL)
        .combined_image(4, in, linear, VK_IMAGE_LAYOUT_GENERAL)
        .storage_image(5, out)
        .update(r_.context);
  };
  write(horizontal_, t.irradiance, t.blur_temp);
  write(vertical_, t.blur_temp, t.blur_a);
}

void SssSeparablePass::record(VkCommandBuffer cmd, vk::GpuTimer& timer) const {
  auto scope = timer.scope(cmd, kName);
  for (int pass = 0; pass < 2; ++pass) {
    shader::BlurPush push;
    push.direction = pass == 0 ? shader::vec4{1, 0, 0, 1} : shader::vec4{0, 1, 0, 0};
    program_.bind(cmd, pass == 0 ? horizontal_ : vertical_);
    vkCmdPushConstants(cmd, program_.layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push),
                       &push);
    ComputeProgram::dispatch(cmd, r_.targets.width, r_.targets.height);
    compute_barrier(cmd);
  }
}

}  // namespace sss::renderer
