#include "renderer/LinePrefix.h"

#include "renderer/vk/Pipeline.h"
#include "shaders/shared/config.h"
#include "shaders/shared/frame.h"
#include "shaders/sss_prefix.comp.bindings.h"
#include "shaders/sss_prefix.comp.h"

#include <algorithm>
#include <stdexcept>

namespace sss::renderer {

namespace b = shader::bindings::sss_prefix_comp;

LinePrefix::LinePrefix(const FrameResources& resources, int max_inputs)
    : r_(resources),
      program_(r_.context, b::kAll, sss_spv_sss_prefix_comp, sizeof(shader::BlurPush),
               uint32_t(max_inputs), kName) {
  for (int i = 0; i < max_inputs; ++i) sets_.push_back(program_.allocate());
}

void LinePrefix::write_descriptors(std::span<const vk::Image* const> inputs) {
  if (inputs.size() > sets_.size()) throw std::logic_error("LinePrefix: more inputs than sets");
  const FrameTargets& t = r_.targets;
  const VkSampler nearest = r_.samplers.nearest.get();
  inputs_.assign(inputs.begin(), inputs.end());
  for (std::size_t i = 0; i < inputs.size(); ++i)
    vk::DescriptorWriter(sets_[i])
        .uniform_buffer(b::Frame, r_.frame_uniforms)
        .storage_buffer(b::Materials, r_.materials)
        .combined_image(b::input_tex, *inputs[i], nearest, VK_IMAGE_LAYOUT_GENERAL)
        .storage_image(b::prefix_img, t.sss_prefix)
        .combined_image(b::surface_tex, t.surface, nearest, VK_IMAGE_LAYOUT_GENERAL)
        .update(r_.context);
}

void LinePrefix::add_step(graph::FrameGraph::PassBuilder& pass, const vk::Image& input,
                          bool vertical) const {
  const auto it = std::find(inputs_.begin(), inputs_.end(), &input);
  if (it == inputs_.end()) throw std::logic_error("LinePrefix: an input without a descriptor set");
  const VkDescriptorSet set = sets_[std::size_t(it - inputs_.begin())];
  pass.step({{&input, graph::use::kComputeRead},
             {&r_.targets.surface, graph::use::kComputeRead},
             {&r_.targets.sss_prefix, graph::use::kComputeWrite}},
            [this, set, vertical](VkCommandBuffer cmd) {
              program_.bind(cmd, set);
              shader::BlurPush push;
              push.direction = vertical ? shader::vec4{0, 1, 0, 0} : shader::vec4{1, 0, 0, 0};
              vkCmdPushConstants(cmd, program_.layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                                 sizeof(push), &push);
              // One workgroup per row (horizontal) or column (vertical) of the rect
              // (sss_prefix.comp).
              const uint32_t lines = vertical ? r_.rect.width() : r_.rect.height();
              vkCmdDispatch(cmd, std::max(lines, 1u), 1, 1);
            });
}

}  // namespace sss::renderer
