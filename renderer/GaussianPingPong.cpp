#include "renderer/GaussianPingPong.h"

#include "shaders/shared/frame.h"

namespace sss::renderer {

static_assert(sizeof(shader::BlurPush) == sizeof(shader::vec4) &&
              sizeof(shader::TexturePush) == sizeof(shader::vec4));

void GaussianPingPong::allocate(ComputeProgram& program) {
  for (VkDescriptorSet* set : {&h_source, &h_a, &h_b, &v_a, &v_b}) *set = program.allocate();
}

void GaussianPingPong::record(VkCommandBuffer cmd, const ComputeProgram& program, int count,
                              float w, std::uint32_t width, std::uint32_t height) const {
  for (int g = 0; g < count; ++g) {
    const bool into_a = g % 2 == 0;
    const VkDescriptorSet horizontal = g == 0 ? h_source : (into_a ? h_b : h_a);
    const VkDescriptorSet vertical = into_a ? v_a : v_b;
    for (int pass = 0; pass < 2; ++pass) {
      const shader::vec4 push = pass == 0 ? shader::vec4{1, 0, float(g), w}
                                          : shader::vec4{0, 1, float(g), w};
      program.bind(cmd, pass == 0 ? horizontal : vertical);
      vkCmdPushConstants(cmd, program.layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push),
                         &push);
      ComputeProgram::dispatch(cmd, width, height);
      compute_barrier(cmd);
    }
  }
}

}  // namespace sss::renderer
