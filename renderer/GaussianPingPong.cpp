#include "renderer/GaussianPingPong.h"

#include "shaders/shared/frame.h"

namespace sss::renderer {

static_assert(sizeof(shader::BlurPush) == sizeof(shader::vec4) &&
              sizeof(shader::TexturePush) == sizeof(shader::vec4));

void GaussianPingPong::allocate(Program& program) {
  for (VkDescriptorSet* set : {&h_source, &h_a, &h_b, &v_a, &v_b}) *set = program.allocate();
}

GaussianPingPong::Dispatch GaussianPingPong::dispatch(int g, int pass, float w) const {
  const bool into_a = g % 2 == 0;
  if (pass == 0)
    return {g == 0 ? h_source : (into_a ? h_b : h_a), shader::vec4{1, 0, float(g), w},
            g == 0 ? Role::Source : (into_a ? Role::B : Role::A), Role::Temp};
  return {into_a ? v_a : v_b, shader::vec4{0, 1, float(g), w}, Role::Temp,
          into_a ? Role::A : Role::B};
}

void GaussianPingPong::run(VkCommandBuffer cmd, const Program& program, const Dispatch& d,
                           std::uint32_t width, std::uint32_t height) {
  program.bind(cmd, d.set);
  vkCmdPushConstants(cmd, program.layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(d.push),
                     &d.push);
  Program::dispatch(cmd, width, height);
}

void GaussianPingPong::record(VkCommandBuffer cmd, const Program& program, int count,
                              float w, std::uint32_t width, std::uint32_t height) const {
  for (int g = 0; g < count; ++g)
    for (int pass = 0; pass < 2; ++pass) {
      run(cmd, program, dispatch(g, pass, w), width, height);
      compute_barrier(cmd);
    }
}

}  // namespace sss::renderer
