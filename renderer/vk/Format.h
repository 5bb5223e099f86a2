// Facts about the VkFormats the renderer uses: texel size (for staging copies), the
// image aspect (colour, depth, stencil) and a name for messages.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>

namespace sss::vk {

// Bytes per texel of an uncompressed format; 0 for formats this table does not know
// (block-compressed, multi-planar, exotic packings).
uint32_t texel_size(VkFormat format);

bool is_depth_format(VkFormat format);  // has a depth component
bool has_stencil(VkFormat format);      // has a stencil component

// VK_IMAGE_ASPECT_COLOR_BIT, or DEPTH (| STENCIL) for depth formats.
VkImageAspectFlags aspect_of(VkFormat format);

// "VK_FORMAT_R16G16B16A16_SFLOAT", or "VkFormat(97)" when not in the table.
std::string format_name(VkFormat format);

}  // namespace sss::vk
