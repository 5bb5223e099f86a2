#include "renderer/Program.h"

#include "renderer/vk/Barrier.h"
#include "renderer/vk/Pipeline.h"
#include "shaders/shared/config.h"

#include <string>

namespace sss::renderer {

Program::Program(const vk::Context& context, const vk::DescriptorSetLayoutBuilder& bindings,
                 std::span<const uint32_t> spirv, uint32_t push_bytes, uint32_t max_sets,
                 std::string_view name)
    : bind_point(VK_PIPELINE_BIND_POINT_COMPUTE),
      set_layout(bindings.build(context, name)),
      layout(vk::create_pipeline_layout(context, set_layout.get(), push_bytes,
                                        push_bytes > 0 ? VK_SHADER_STAGE_COMPUTE_BIT : 0, name)),
      pipeline(vk::create_compute_pipeline(context, layout.get(), spirv, nullptr, name)),
      pool(context, bindings, max_sets, name) {}

Program::Program(const vk::Context& context, const vk::DescriptorSetLayoutBuilder& bindings,
                 uint32_t push_bytes, VkShaderStageFlags push_stages, uint32_t max_sets,
                 std::string_view name, const BuildPipeline& build)
    : bind_point(VK_PIPELINE_BIND_POINT_GRAPHICS),
      set_layout(bindings.build(context, name)),
      layout(vk::create_pipeline_layout(context, set_layout.get(), push_bytes,
                                        push_bytes > 0 ? push_stages : 0, name)),
      pipeline(build(layout.get())),
      pool(context, bindings, max_sets, name) {}

void Program::bind(VkCommandBuffer cmd, VkPipeline variant, VkDescriptorSet set) const {
  vkCmdBindPipeline(cmd, bind_point, variant);
  vkCmdBindDescriptorSets(cmd, bind_point, layout.get(), 0, 1, &set, 0, nullptr);
}

void Program::dispatch(VkCommandBuffer cmd, uint32_t width, uint32_t height) {
  vkCmdDispatch(cmd, vk::group_count(width, shader::kWorkgroup2DX),
                vk::group_count(height, shader::kWorkgroup2DY), 1);
}

void compute_barrier(VkCommandBuffer cmd) {
  const VkMemoryBarrier2 barrier = vk::memory_barrier(
      {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT},
      {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
       VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
           VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT});
  vk::pipeline_barrier(cmd, {}, {}, {&barrier, 1});
}

}  // namespace sss::renderer
