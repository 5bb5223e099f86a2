// Swapchain: the images a window presents, for a VkSurfaceKHR owned by the Context (no
// window system here: the caller passes the surface's framebuffer size).
//
// vsync on: FIFO. vsync off: MAILBOX, else IMMEDIATE, else FIFO. Images are B8G8R8A8 or
// R8G8B8A8 UNORM (the renderer's display image is sRGB-encoded by hand, so a blit copies
// its codes unchanged) with TRANSFER_DST and COLOR_ATTACHMENT usage.
//
// acquire() and present() return false when the swapchain is out of date (or suboptimal
// after present): call recreate() with the new framebuffer size. A 0x0 surface (a
// minimized window) has no swapchain: valid() is false until recreate() with a real size.
#pragma once

#include "renderer/vk/Handle.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

namespace sss::vk {

class Context;

class Swapchain {
 public:
  Swapchain(const Context& context, VkExtent2D framebuffer_size, bool vsync);
  ~Swapchain();
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;

  // Waits for the device to be idle and replaces the swapchain (the old one is retired
  // through oldSwapchain). A 0 side leaves no swapchain (valid() false).
  void recreate(VkExtent2D framebuffer_size);

  // The index of the next image, signalling `acquired` when it may be written; false when
  // out of date (recreate and skip the frame). Suboptimal counts as acquired.
  bool acquire(VkSemaphore acquired, uint32_t& index);
  // Presents image `index` after `rendered`; false when out of date or suboptimal.
  bool present(uint32_t index, VkSemaphore rendered);

  bool valid() const { return swapchain_ != VK_NULL_HANDLE; }
  VkSwapchainKHR handle() const { return swapchain_; }
  VkFormat format() const { return format_; }
  VkExtent2D extent() const { return extent_; }
  VkPresentModeKHR present_mode() const { return present_mode_; }
  uint32_t min_image_count() const { return min_image_count_; }
  uint32_t image_count() const { return static_cast<uint32_t>(images_.size()); }
  VkImage image(uint32_t i) const { return images_[i]; }
  VkImageView view(uint32_t i) const { return views_[i].get(); }

 private:
  void destroy();

  const Context& context_;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkColorSpaceKHR color_space_ = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
  VkExtent2D extent_{0, 0};
  VkPresentModeKHR present_mode_ = VK_PRESENT_MODE_FIFO_KHR;
  uint32_t min_image_count_ = 2;
  std::vector<VkImage> images_;
  std::vector<ImageViewHandle> views_;
};

}  // namespace sss::vk
