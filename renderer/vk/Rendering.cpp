#include "renderer/vk/Rendering.h"

#include <vector>

namespace sss::vk {

void begin_rendering(VkCommandBuffer cmd, VkExtent2D extent, std::span<const ColorTarget> colors,
                     const DepthTarget* depth) {
  std::vector<VkRenderingAttachmentInfo> color_infos;
  color_infos.reserve(colors.size());
  for (const ColorTarget& c : colors) {
    VkRenderingAttachmentInfo a{};
    a.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
    a.imageView = c.view;
    a.imageLayout = c.layout;
    a.loadOp = c.load;
    a.storeOp = c.store;
    a.clearValue.color = c.clear;
    color_infos.push_back(a);
  }
  VkRenderingAttachmentInfo depth_info{};
  if (depth != nullptr) {
    depth_info.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
    depth_info.imageView = depth->view;
    depth_info.imageLayout = depth->layout;
    depth_info.loadOp = depth->load;
    depth_info.storeOp = depth->store;
    depth_info.clearValue.depthStencil = {depth->clear, 0};
  }

  VkRenderingInfo info{};
  info.sType = VK_STRUCTURE_TYPE_RENDERING_INFO;
  info.renderArea = {{0, 0}, extent};
  info.layerCount = 1;
  info.colorAttachmentCount = static_cast<uint32_t>(color_infos.size());
  info.pColorAttachments = color_infos.data();
  info.pDepthAttachment = depth != nullptr ? &depth_info : nullptr;
  vkCmdBeginRendering(cmd, &info);

  const VkViewport viewport{
      0.0f, 0.0f, static_cast<float>(extent.width), static_cast<float>(extent.height), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, extent};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

void end_rendering(VkCommandBuffer cmd) { vkCmdEndRendering(cmd); }

}  // namespace sss::vk
