#include "renderer/SssGaussiansPass.h"

#include "shaders/shared/frame.h"
#include "shaders/sss_gaussians.comp.h"

namespace sss::renderer {

namespace {
vk::DescriptorSetLayoutBuilder bindings() {
  const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
  vk::DescriptorSetLayoutBuilder b;
  b.add(0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs)
      .add(1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs)
      .add(2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, cs)
      .add(4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, cs)
      .add(5, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cs)
      .add(6, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cs);
  return b;
}
}  // namespace

SssGaussiansPass::SssGaussiansPass(const FrameResources& resources, int gaussians)
    : r_(resources),
      gaussians_(gaussians),
      program_(r_.context, bindings(), sss_spv_sss_gaussians_comp, sizeof(shader::BlurPush), 5,
               kName) {
  for (VkDescriptorSet* set : {&h_irradiance_, &h_a_, &h_b_, &v_a_, &v_b_})
    *set = program_.allocate();
  write_descriptors();
}

void SssGaussiansPass::write_descriptors() {
  const FrameTargets& t = r_.targets;
  const VkSampler nearest = r_.samplers.nearest.get();
  const auto write = [&](VkDescriptorSet set, const vk::Image& in, const vk::Image& out) {
    vk::DescriptorWriter(set)
        .uniform_buffer(0, r_.frame_uniforms)
        .storage_buffer(1, r_.materials)
        .combined_image(2, t.surface, nearest, VK_IMAGE_LAYOUT_GENERAL)
        .combined_image(4, in, nearest, VK_IMAGE_LAYOUT_GENERAL)
        .storage_image(5, out)
        .storage_image(6, t.accum)
        .update(r_.context);
  };
  write(h_irradiance_, t.irradiance, t.blur_temp);
  write(h_a_, t.blur_a, t.blur_temp);
  write(h_b_, t.blur_b, t.blur_temp);
  write(v_a_, t.blur_temp, t.blur_a);
  write(v_b_, t.blur_temp, t.blur_b);
}

void SssGaussiansPass::record(VkCommandBuffer cmd, vk::GpuTimer& timer) const {
  auto scope = timer.scope(cmd, kName);
  for (int g = 0; g < gaussians_; ++g) {
    const bool into_a = g % 2 == 0;
    VkDescriptorSet horizontal = g == 0 ? h_irradiance_ : (into_a ? h_b_ : h_a_);
    VkDescriptorSet vertical = into_a ? v_a_ : v_b_;
    for (int pass = 0; pass < 2; ++pass) {
      shader::BlurPush push;
      push.direction = pass == 0 ? shader::vec4{1, 0, float(g), 0} : shader::vec4{0, 1, float(g), 0};
      program_.bind(cmd, pass == 0 ? horizontal : vertical);
      vkCmdPushConstants(cmd, program_.layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                         sizeof(push), &push);
      ComputeProgram::dispatch(cmd, r_.rect);
      compute_barrier(cmd);
    }
  }
}

}  // namespace sss::renderer
