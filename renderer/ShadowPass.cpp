#include "renderer/ShadowPass.h"

#include "scene/ShadowFrustum.h"
#include "renderer/vk/GraphicsPipeline.h"
#include "renderer/vk/Pipeline.h"
#include "renderer/vk/Rendering.h"
#include "shaders/shadow.vert.bindings.h"
#include "shaders/shadow.vert.h"
#include "shaders/shared/frame.h"

#include <cstddef>

namespace sss::renderer {

namespace {
namespace b = shader::bindings::shadow_vert;
vk::DescriptorSetLayoutBuilder bindings() { return vk::DescriptorSetLayoutBuilder().add(b::kAll); }
}  // namespace

ShadowPass::ShadowPass(const FrameResources& resources, std::vector<bool> shadowed)
    : r_(resources),
      shadowed_(std::move(shadowed)),
      program_(r_.context, bindings(), sizeof(shader::DrawPush),
               VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 1, kName,
               [&](VkPipelineLayout layout) {
                 return vk::GraphicsPipelineBuilder()
                     .vertex_shader(sss_spv_shadow_vert)
                     .vertex_binding(0, sizeof(GpuVertex))
                     .vertex_attribute(0, 0, VK_FORMAT_R32G32B32_SFLOAT,
                                       offsetof(GpuVertex, position))
                     .depth(kDepthFormat, vk::DepthTest::Write)
                     .cull(VK_CULL_MODE_NONE)
                     .dynamic_depth_bias()
                     .build(r_.context, layout, kName);
               }) {
  set_ = program_.allocate();
  vk::DescriptorWriter(set_).uniform_buffer(b::Lights, r_.lights).update(r_.context);
}

void ShadowPass::add_to(graph::FrameGraph& graph, bool light_depth) const {
  // Each light with the slope-scaled bias for the shadow test and, when something reads
  // thickness, again without it (the bias pushes grazing surfaces up to ~20 texels of
  // depth behind themselves, which read as a too-thin object: issue 20's transmission
  // speckle).
  std::vector<graph::ImageUse> uses{{&r_.targets.shadow, graph::use::kDepthAttachment}};
  if (light_depth) uses.push_back({&r_.targets.light_depth, graph::use::kDepthAttachment});
  graph.add_pass(kName).step(std::move(uses), [this, light_depth](VkCommandBuffer cmd) {
    const float biases[2] = {scene::kShadowSlopeBias, 0.0f};
    const std::vector<vk::ImageViewHandle>* layers[2] = {&r_.targets.shadow_layers,
                                                         &r_.targets.light_depth_layers};
    for (int map = 0; map < (light_depth ? 2 : 1); ++map)
      for (std::size_t layer = 0; layer < layers[map]->size(); ++layer) {
        const vk::DepthTarget target((*layers[map])[layer].get());
        vk::begin_rendering(cmd, r_.targets.shadow.extent(), {}, &target);
        if (layer < shadowed_.size() && shadowed_[layer]) {
          program_.bind(cmd, set_);
          vkCmdSetDepthBias(cmd, 0.0f, 0.0f, biases[map]);
          r_.scene.draw(cmd, program_.layout.get(), static_cast<int>(layer));
        }
        vk::end_rendering(cmd);
      }
  });
}

}  // namespace sss::renderer
