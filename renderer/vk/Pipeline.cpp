#include "renderer/vk/Pipeline.h"

#include "renderer/vk/Check.h"
#include "renderer/vk/Context.h"

#include <stdexcept>
#include <string>

namespace sss::vk {

namespace {
constexpr uint32_t kSpirvMagic = 0x07230203;
}

ShaderModuleHandle create_shader_module(const Context& context, std::span<const uint32_t> spirv,
                                        std::string_view name) {
  if (spirv.size() < 5 || spirv[0] != kSpirvMagic) {
    throw std::invalid_argument("shader module \"" + std::string(name) +
                                "\": the words are not SPIR-V (no magic number)");
  }
  VkShaderModuleCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  info.codeSize = spirv.size_bytes();
  info.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  VK_CHECK(vkCreateShaderModule(context.device(), &info, nullptr, &module));
  if (!name.empty()) context.set_object_name(VK_OBJECT_TYPE_SHADER_MODULE, module, name);
  return ShaderModuleHandle(context.device(), module);
}

PipelineLayoutHandle create_pipeline_layout(const Context& context,
                                            std::span<const VkDescriptorSetLayout> set_layouts,
                                            std::span<const VkPushConstantRange> push_constants,
                                            std::string_view name) {
  const uint32_t limit = context.info().limits.maxPushConstantsSize;
  for (const VkPushConstantRange& range : push_constants) {
    if (range.offset + range.size > limit) {
      throw std::invalid_argument("pipeline layout \"" + std::string(name) +
                                  "\": push constants end at " +
                                  std::to_string(range.offset + range.size) +
                                  " bytes, the device allows " + std::to_string(limit));
    }
  }
  VkPipelineLayoutCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  info.setLayoutCount = static_cast<uint32_t>(set_layouts.size());
  info.pSetLayouts = set_layouts.data();
  info.pushConstantRangeCount = static_cast<uint32_t>(push_constants.size());
  info.pPushConstantRanges = push_constants.data();
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VK_CHECK(vkCreatePipelineLayout(context.device(), &info, nullptr, &layout));
  if (!name.empty()) context.set_object_name(VK_OBJECT_TYPE_PIPELINE_LAYOUT, layout, name);
  return PipelineLayoutHandle(context.device(), layout);
}

PipelineLayoutHandle create_pipeline_layout(const Context& context,
                                            VkDescriptorSetLayout set_layout,
                                            uint32_t push_constant_bytes,
                                            VkShaderStageFlags push_stages, std::string_view name) {
  const VkPushConstantRange range{push_stages, 0, push_constant_bytes};
  return create_pipeline_layout(
      context,
      set_layout != VK_NULL_HANDLE ? std::span<const VkDescriptorSetLayout>(&set_layout, 1)
                                   : std::span<const VkDescriptorSetLayout>(),
      push_constant_bytes != 0 ? std::span<const VkPushConstantRange>(&range, 1)
                               : std::span<const VkPushConstantRange>(),
      name);
}

PipelineHandle create_compute_pipeline(const Context& context, VkPipelineLayout layout,
                                       std::span<const uint32_t> spirv,
                                       const VkSpecializationInfo* specialization,
                                       std::string_view name) {
  // The module is only needed while the pipeline is created.
  const ShaderModuleHandle module = create_shader_module(context, spirv, name);
  VkComputePipelineCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module.get();
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = specialization;
  info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VK_CHECK(
      vkCreateComputePipelines(context.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
  if (!name.empty()) context.set_object_name(VK_OBJECT_TYPE_PIPELINE, pipeline, name);
  return PipelineHandle(context.device(), pipeline);
}

}  // namespace sss::vk
