// Program: a pipeline with its one descriptor set layout, an optional push-constant block
// and a pool of sets: what every pass of the frame holds, compute or graphics (issue 22:
// one program type). A compute program builds its pipeline from the shader's SPIR-V; a
// graphics program is given a function that builds the pipeline (a GraphicsPipelineBuilder
// with its attachments and vertex input) on the program's layout. bind() binds at the
// program's own bind point.
// compute_barrier() orders one dispatch's storage writes before the next one's reads and
// writes (a global memory barrier: the compute targets stay in GENERAL).
#pragma once

#include "renderer/vk/Descriptors.h"
#include "renderer/vk/Handle.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <span>
#include <string_view>

namespace sss::vk {
class Context;
}

namespace sss::renderer {

struct Program {
  // Compute.
  Program(const vk::Context& context, const vk::DescriptorSetLayoutBuilder& bindings,
          std::span<const uint32_t> spirv, uint32_t push_bytes, uint32_t max_sets,
          std::string_view name);
  // Compute, the set layout from the shader's reflected bindings (its generated kAll).
  Program(const vk::Context& context, std::span<const vk::ShaderBinding> shader,
          std::span<const uint32_t> spirv, uint32_t push_bytes, uint32_t max_sets,
          std::string_view name)
      : Program(context, vk::DescriptorSetLayoutBuilder().add(shader), spirv, push_bytes, max_sets,
                name) {}
  // Graphics: build(layout) returns the pipeline; the push block is seen by push_stages.
  using BuildPipeline = std::function<vk::PipelineHandle(VkPipelineLayout)>;
  Program(const vk::Context& context, const vk::DescriptorSetLayoutBuilder& bindings,
          uint32_t push_bytes, VkShaderStageFlags push_stages, uint32_t max_sets,
          std::string_view name, const BuildPipeline& build);

  VkDescriptorSet allocate() { return pool.allocate(set_layout.get()); }
  // Binds the pipeline and `set` at the program's bind point.
  void bind(VkCommandBuffer cmd, VkDescriptorSet set) const { bind(cmd, pipeline.get(), set); }
  // The same with another pipeline built on this program's layout (a variant of it).
  void bind(VkCommandBuffer cmd, VkPipeline variant, VkDescriptorSet set) const;
  // Groups of SSS_WORKGROUP_2D covering width x height.
  static void dispatch(VkCommandBuffer cmd, uint32_t width, uint32_t height);
  // Groups covering rect (the shaders offset gl_GlobalInvocationID by FrameUniforms::rect).
  template <class Rect>
  static void dispatch(VkCommandBuffer cmd, const Rect& rect) {
    dispatch(cmd, rect.width(), rect.height());
  }

  VkPipelineBindPoint bind_point = VK_PIPELINE_BIND_POINT_COMPUTE;
  vk::DescriptorSetLayoutHandle set_layout;
  vk::PipelineLayoutHandle layout;
  vk::PipelineHandle pipeline;
  vk::DescriptorPool pool;
};

void compute_barrier(VkCommandBuffer cmd);

}  // namespace sss::renderer
