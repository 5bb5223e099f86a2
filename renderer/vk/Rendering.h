// Beginning and ending dynamic rendering (VK_KHR_dynamic_rendering, core in 1.3) over a
// set of attachments, with the viewport and scissor set to the whole render area, which
// is what every full-frame pass wants. The attachments must already be in the layouts
// named here (a barrier before begin_rendering does that).
#pragma once

#include <vulkan/vulkan.h>

#include <span>

namespace sss::vk {

struct ColorTarget {
  ColorTarget() = default;
  explicit ColorTarget(VkImageView image_view, VkClearColorValue clear_value = {})
      : view(image_view), clear(clear_value) {}

  VkImageView view = VK_NULL_HANDLE;
  VkAttachmentLoadOp load = VK_ATTACHMENT_LOAD_OP_CLEAR;
  VkAttachmentStoreOp store = VK_ATTACHMENT_STORE_OP_STORE;
  VkClearColorValue clear{};
  VkImageLayout layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
};

struct DepthTarget {
  DepthTarget() = default;
  explicit DepthTarget(VkImageView image_view, float clear_depth = 1.0f)
      : view(image_view), clear(clear_depth) {}

  VkImageView view = VK_NULL_HANDLE;
  VkAttachmentLoadOp load = VK_ATTACHMENT_LOAD_OP_CLEAR;
  VkAttachmentStoreOp store = VK_ATTACHMENT_STORE_OP_STORE;
  float clear = 1.0f;  // 0 for reversed Z
  VkImageLayout layout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
};

// `depth` may be null. The viewport spans [0, width] × [0, height] with depth [0, 1].
void begin_rendering(VkCommandBuffer cmd, VkExtent2D extent, std::span<const ColorTarget> colors,
                     const DepthTarget* depth = nullptr);
void end_rendering(VkCommandBuffer cmd);

}  // namespace sss::vk
