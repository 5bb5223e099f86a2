// ComputeProgram: a compute pipeline with its one descriptor set layout, an optional
// push-constant block and a pool of sets: what every compute pass of the frame holds.
// compute_barrier() orders one dispatch's storage writes before the next one's reads and
// writes (a global memory barrier: the compute targets stay in GENERAL).
#pragma once

#include "renderer/vk/Descriptors.h"
#include "renderer/vk/Handle.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <string_view>

namespace sss::vk {
class Context;
}

namespace sss::renderer {

struct ComputeProgram {
  ComputeProgram(const vk::Context& context, const vk::DescriptorSetLayoutBuilder& bindings,
                 std::span<const uint32_t> spirv, uint32_t push_bytes, uint32_t max_sets,
                 std::string_view name);
  // The set layout from the shader's reflected bindings (its generated kAll).
  ComputeProgram(const vk::Context& context, std::span<const vk::ShaderBinding> shader,
                 std::span<const uint32_t> spirv, uint32_t push_bytes, uint32_t max_sets,
                 std::string_view name)
      : ComputeProgram(context, vk::DescriptorSetLayoutBuilder().add(shader), spirv, push_bytes,
                       max_sets, name) {}

  VkDescriptorSet allocate() { return pool.allocate(set_layout.get()); }
  void bind(VkCommandBuffer cmd, VkDescriptorSet set) const;
  // Groups of SSS_WORKGROUP_2D covering width x height.
  static void dispatch(VkCommandBuffer cmd, uint32_t width, uint32_t height);
  // Groups covering rect (the shaders offset gl_GlobalInvocationID by FrameUniforms::rect).
  template <class Rect>
  static void dispatch(VkCommandBuffer cmd, const Rect& rect) {
    dispatch(cmd, rect.width(), rect.height());
  }

  vk::DescriptorSetLayoutHandle set_layout;
  vk::PipelineLayoutHandle layout;
  vk::PipelineHandle pipeline;
  vk::DescriptorPool pool;
};

void compute_barrier(VkCommandBuffer cmd);

}  // namespace sss::renderer
