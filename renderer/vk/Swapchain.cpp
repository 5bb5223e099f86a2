#include "renderer/vk/Swapchain.h"

#include "renderer/vk/Check.h"
#include "renderer/vk/Context.h"

#include <algorithm>
#include <array>

namespace sss::vk {

namespace {

VkSurfaceFormatKHR choose_format(VkPhysicalDevice gpu, VkSurfaceKHR surface) {
  uint32_t count = 0;
  VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(gpu, surface, &count, nullptr));
  std::vector<VkSurfaceFormatKHR> formats(count);
  VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(gpu, surface, &count, formats.data()));
  for (VkFormat wanted : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM})
    for (const VkSurfaceFormatKHR& f : formats)
      if (f.format == wanted && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) return f;
  throw VulkanError(VK_ERROR_FORMAT_NOT_SUPPORTED,
                    "the surface has no B8G8R8A8_UNORM or R8G8B8A8_UNORM format");
}

VkPresentModeKHR choose_present_mode(VkPhysicalDevice gpu, VkSurfaceKHR surface, bool vsync) {
  if (vsync) return VK_PRESENT_MODE_FIFO_KHR;  // always supported
  uint32_t count = 0;
  VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(gpu, surface, &count, nullptr));
  std::vector<VkPresentModeKHR> modes(count);
  VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(gpu, surface, &count, modes.data()));
  for (VkPresentModeKHR wanted : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
    if (std::find(modes.begin(), modes.end(), wanted) != modes.end()) return wanted;
  return VK_PRESENT_MODE_FIFO_KHR;
}

}  // namespace

Swapchain::Swapchain(const Context& context, VkExtent2D framebuffer_size, bool vsync)
    : context_(context) {
  const VkSurfaceFormatKHR f = choose_format(context.physical_device(), context.surface());
  format_ = f.format;
  color_space_ = f.colorSpace;
  present_mode_ = choose_present_mode(context.physical_device(), context.surface(), vsync);
  recreate(framebuffer_size);
}

Swapchain::~Swapchain() {
  context_.wait_idle();
  destroy();
}

void Swapchain::destroy() {
  views_.clear();
  images_.clear();
  if (swapchain_ != VK_NULL_HANDLE) vkDestroySwapchainKHR(context_.device(), swapchain_, nullptr);
  swapchain_ = VK_NULL_HANDLE;
}

void Swapchain::recreate(VkExtent2D framebuffer_size) {
  context_.wait_idle();
  VkSurfaceCapabilitiesKHR caps{};
  VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(context_.physical_device(),
                                                     context_.surface(), &caps));
  VkExtent2D extent = caps.currentExtent;
  if (extent.width == UINT32_MAX) {  // the surface takes the swapchain's size
    extent.width = std::clamp(framebuffer_size.width, caps.minImageExtent.width,
                              caps.maxImageExtent.width);
    extent.height = std::clamp(framebuffer_size.height, caps.minImageExtent.height,
                               caps.maxImageExtent.height);
  }
  if (framebuffer_size.width == 0 || framebuffer_size.height == 0 || extent.width == 0 ||
      extent.height == 0) {
    destroy();
    extent_ = {0, 0};
    return;
  }
  constexpr VkImageUsageFlags usage =
      VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  if ((caps.supportedUsageFlags & usage) != usage)
    throw VulkanError(VK_ERROR_FEATURE_NOT_PRESENT,
                      "the surface's images cannot be blit and render targets");
  uint32_t count = std::max(caps.minImageCount + 1, 2u);
  if (caps.maxImageCount > 0) count = std::min(count, caps.maxImageCount);

  VkSwapchainCreateInfoKHR info{};
  info.sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR;
  info.surface = context_.surface();
  info.minImageCount = count;
  info.imageFormat = format_;
  info.imageColorSpace = color_space_;
  info.imageExtent = extent;
  info.imageArrayLayers = 1;
  info.imageUsage = usage;
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = (caps.supportedTransforms & VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR) != 0
                          ? VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR
                          : caps.currentTransform;
  info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  for (VkCompositeAlphaFlagBitsKHR a :
       {VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR, VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR,
        VK_COMPOSITE_ALPHA_PRE_MULTIPLIED_BIT_KHR, VK_COMPOSITE_ALPHA_POST_MULTIPLIED_BIT_KHR}) {
    if ((caps.supportedCompositeAlpha & a) != 0) {
      info.compositeAlpha = a;
      break;
    }
  }
  info.presentMode = present_mode_;
  info.clipped = VK_TRUE;
  info.oldSwapchain = swapchain_;
  VkSwapchainKHR created = VK_NULL_HANDLE;
  VK_CHECK(vkCreateSwapchainKHR(context_.device(), &info, nullptr, &created));
  destroy();
  swapchain_ = created;
  extent_ = extent;
  min_image_count_ = count;
  context_.set_object_name(VK_OBJECT_TYPE_SWAPCHAIN_KHR, swapchain_, "swapchain");

  uint32_t n = 0;
  VK_CHECK(vkGetSwapchainImagesKHR(context_.device(), swapchain_, &n, nullptr));
  images_.resize(n);
  VK_CHECK(vkGetSwapchainImagesKHR(context_.device(), swapchain_, &n, images_.data()));
  for (VkImage image : images_) {
    VkImageViewCreateInfo view{};
    view.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    view.image = image;
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = format_;
    view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView handle = VK_NULL_HANDLE;
    VK_CHECK(vkCreateImageView(context_.device(), &view, nullptr, &handle));
    views_.emplace_back(context_.device(), handle);
  }
}

bool Swapchain::acquire(VkSemaphore acquired, uint32_t& index) {
  if (!valid()) return false;
  const VkResult r = vkAcquireNextImageKHR(context_.device(), swapchain_, UINT64_MAX, acquired,
                                           VK_NULL_HANDLE, &index);
  if (r == VK_ERROR_OUT_OF_DATE_KHR) return false;
  if (r != VK_SUBOPTIMAL_KHR) VK_CHECK(r);
  return true;
}

bool Swapchain::present(uint32_t index, VkSemaphore rendered) {
  VkPresentInfoKHR info{};
  info.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR;
  info.waitSemaphoreCount = 1;
  info.pWaitSemaphores = &rendered;
  info.swapchainCount = 1;
  info.pSwapchains = &swapchain_;
  info.pImageIndices = &index;
  // Not serialised with Context::submit: the viewer submits and presents from one thread.
  const VkResult r = vkQueuePresentKHR(context_.queue(), &info);
  if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) return false;
  VK_CHECK(r);
  return true;
}

}  // namespace sss::vk
