// GaussianPingPong: the incremental Gaussian blur (shaders/shared/gaussian_blur.glsl) that
// the screen path (SssGaussiansPass) and the texture path (SssTexturePass) share. Gaussian g
// blurs the previous one's result by the difference of their variances: horizontally into
// `temp`, then vertically into `a` (g even) or `b` (g odd), and its shader adds w_g x the
// result to the accumulation. Five descriptor sets serve every g: the horizontal pass reads
// the source (g = 0) or the previous vertical result, the vertical pass reads temp.
#pragma once

#include "renderer/Program.h"
#include "renderer/vk/Image.h"
#include "shaders/shared/frame.h"

#include <vulkan/vulkan.h>

#include <cstdint>

namespace sss::renderer {

struct GaussianPingPong {
  VkDescriptorSet h_source = VK_NULL_HANDLE, h_a = VK_NULL_HANDLE, h_b = VK_NULL_HANDLE;
  VkDescriptorSet v_a = VK_NULL_HANDLE, v_b = VK_NULL_HANDLE;

  void allocate(Program& program);
  // Calls write(set, input, output) for each of the five sets.
  template <class Write>
  void write(const vk::Image& source, const vk::Image& a, const vk::Image& b,
             const vk::Image& temp, Write&& write) const {
    write(h_source, source, temp);
    write(h_a, a, temp);
    write(h_b, b, temp);
    write(v_a, temp, a);
    write(v_b, temp, b);
  }
  // The images of write(): which one a dispatch reads and which it writes.
  enum class Role { Source, A, B, Temp };
  struct Dispatch {
    VkDescriptorSet set;
    shader::vec4 push;  // BlurPush, TexturePush: the direction (1, 0) or (0, 1), g, `w`
    Role input, output;
  };
  // Gaussian g's horizontal (pass 0) or vertical (pass 1) dispatch.
  Dispatch dispatch(int g, int pass, float w) const;
  // Binds its set and push constant and dispatches over width x height.
  static void run(VkCommandBuffer cmd, const Program& program, const Dispatch& d,
                  std::uint32_t width, std::uint32_t height);
  // Gaussians 0 .. count - 1, each a horizontal then a vertical dispatch, with a compute
  // barrier after each (the texture path's atlases, which the frame graph does not track).
  void record(VkCommandBuffer cmd, const Program& program, int count, float w,
              std::uint32_t width, std::uint32_t height) const;
};

}  // namespace sss::renderer
