#include "renderer/AntialiasPass.h"

#include "shaders/antialias.comp.bindings.h"
#include "shaders/antialias.comp.h"

namespace sss::renderer {

namespace b = shader::bindings::antialias_comp;

AntialiasPass::AntialiasPass(const FrameResources& resources)
    : r_(resources), program_(r_.context, b::kAll, sss_spv_antialias_comp, 0, 1, kName) {
  set_ = program_.allocate();
  write_descriptors();
}

void AntialiasPass::write_descriptors() {
  const FrameTargets& t = r_.targets;
  vk::DescriptorWriter(set_)
      .combined_image(b::source, t.display_source, r_.samplers.linear.get())
      .storage_image(b::display_img, t.display)
      .update(r_.context);
}

void AntialiasPass::add_to(graph::FrameGraph& graph) const {
  const FrameTargets& t = r_.targets;
  using namespace graph::use;
  // The display image as composite left it is copied, so that no pixel reads a
  // neighbour the filter already wrote.
  graph.add_pass(kName)
      .step({{&t.display, kCopySource}, {&t.display_source, kCopyDestination}},
            [this, &t](VkCommandBuffer cmd) {
              VkImageCopy region{};
              region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
              region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
              region.extent = {t.width, t.height, 1};
              vkCmdCopyImage(cmd, t.display.handle(), kCopySource.layout,
                             t.display_source.handle(), kCopyDestination.layout, 1, &region);
            })
      .step({{&t.display_source, kSampled}, {&t.display, kComputeWrite}},
            [this, &t](VkCommandBuffer cmd) {
              program_.bind(cmd, set_);
              Program::dispatch(cmd, r_.targets.width, r_.targets.height);
            });
}

}  // namespace sss::renderer
