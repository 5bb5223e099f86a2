// A VkImage (optimal tiling) with its own memory block and a view of all its mips and
// layers. Layouts are not tracked: passes state them in their barriers
// (renderer/vk/Barrier.h), which keeps every transition visible at the point of use.
//
// The view of a depth or depth-stencil image covers the depth aspect only, which is what
// sampling (shadow maps, the G-buffer's depth) and depth attachments need; barriers use
// aspect(), which includes stencil when the format has it.
#pragma once

#include "renderer/vk/Handle.h"
#include "renderer/vk/Memory.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <utility>

namespace sss::vk {

class Context;

// The common case in one line, Image(ctx, {w, h, format, usage, "name"}); the other
// fields are set by name afterwards.
struct ImageDesc {
  ImageDesc() = default;
  ImageDesc(uint32_t w, uint32_t h, VkFormat image_format, VkImageUsageFlags usage_flags,
            std::string debug_name = {})
      : width(w),
        height(h),
        format(image_format),
        usage(usage_flags),
        name(std::move(debug_name)) {}

  uint32_t width = 0;
  uint32_t height = 0;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkImageUsageFlags usage = 0;
  uint32_t mip_levels = 1;
  uint32_t array_layers = 1;  // 6 (or 6·n) for cube views
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  VkImageViewType view_type = VK_IMAGE_VIEW_TYPE_2D;  // 2D, 2D_ARRAY, CUBE, CUBE_ARRAY
  MemoryUsage memory = MemoryUsage::DeviceLocal;
  std::string name;  // debug name for tools and validation messages
};

class Image {
 public:
  Image() = default;  // empty
  // Throws std::invalid_argument for an empty or inconsistent description, VulkanError
  // when the device cannot make it (format/usage unsupported, size over the limits).
  Image(const Context& context, const ImageDesc& desc);

  // Moving leaves the source empty.
  Image(Image&& other) noexcept;
  Image& operator=(Image&& other) noexcept;

  VkImage handle() const { return image_.get(); }
  VkImageView view() const { return view_.get(); }
  const ImageDesc& desc() const { return desc_; }
  VkFormat format() const { return desc_.format; }
  uint32_t width() const { return desc_.width; }
  uint32_t height() const { return desc_.height; }
  VkExtent2D extent() const { return {desc_.width, desc_.height}; }
  VkImageAspectFlags aspect() const { return aspect_; }
  // The device memory it holds (vkGetImageMemoryRequirements' size).
  VkDeviceSize memory_bytes() const { return bytes_; }
  explicit operator bool() const { return static_cast<bool>(image_); }

  // Every mip and layer, with aspect().
  VkImageSubresourceRange full_range() const;
  // One mip level, all layers, for copies.
  VkImageSubresourceLayers subresource_layers(uint32_t mip = 0) const;
  VkDescriptorImageInfo descriptor(VkImageLayout layout, VkSampler sampler = VK_NULL_HANDLE) const {
    return {sampler, view_.get(), layout};
  }

  // A 2D view of one layer and mip (rendering into one face of a shadow cube, one cascade).
  ImageViewHandle create_view(uint32_t layer, uint32_t mip = 0) const;

 private:
  ImageViewHandle make_view(VkImageViewType type, uint32_t base_mip, uint32_t mips,
                            uint32_t base_layer, uint32_t layers) const;

  // Declared in this order so that the view goes first and the memory last.
  MemoryHandle memory_;
  ImageHandle image_;
  ImageViewHandle view_;
  ImageDesc desc_;
  VkImageAspectFlags aspect_ = 0;
  VkDeviceSize bytes_ = 0;
};

}  // namespace sss::vk
