// Shader modules, pipeline layouts and compute pipelines. The SPIR-V comes from the
// build (shaders/*.comp compiled by cmake/Shaders.cmake and embedded as uint32_t
// arrays), so a pipeline is created from a span of words:
//
//   #include "shaders/selftest_fill.comp.h"
//   auto pipeline = create_compute_pipeline(ctx, layout.get(), sss_spv_selftest_fill_comp);
//
// Graphics pipelines have their builder in GraphicsPipeline.h.
#pragma once

#include "renderer/vk/Handle.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <string_view>

namespace sss::vk {

class Context;

// Throws std::invalid_argument when the words are not SPIR-V (empty, wrong magic).
ShaderModuleHandle create_shader_module(const Context& context, std::span<const uint32_t> spirv,
                                        std::string_view name = {});

// Throws std::invalid_argument when the push constants exceed maxPushConstantsSize.
PipelineLayoutHandle create_pipeline_layout(
    const Context& context, std::span<const VkDescriptorSetLayout> set_layouts,
    std::span<const VkPushConstantRange> push_constants = {}, std::string_view name = {});

// A layout with one descriptor set (or none) and one push-constant range (or none).
PipelineLayoutHandle create_pipeline_layout(const Context& context,
                                            VkDescriptorSetLayout set_layout,
                                            uint32_t push_constant_bytes,
                                            VkShaderStageFlags push_stages,
                                            std::string_view name = {});

// Entry point "main"; `specialization` may be null.
PipelineHandle create_compute_pipeline(const Context& context, VkPipelineLayout layout,
                                       std::span<const uint32_t> spirv,
                                       const VkSpecializationInfo* specialization = nullptr,
                                       std::string_view name = {});

// Workgroups needed to cover `items` with groups of `group_size`.
constexpr uint32_t group_count(uint32_t items, uint32_t group_size) {
  return (items + group_size - 1) / group_size;
}

}  // namespace sss::vk
