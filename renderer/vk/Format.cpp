#include "renderer/vk/Format.h"

namespace sss::vk {

namespace {

struct FormatFacts {
  VkFormat format;
  const char* name;
  uint32_t size;
};

#define SSS_FORMAT(f, bytes) \
  { f, #f, bytes }
constexpr FormatFacts kFormats[] = {
    SSS_FORMAT(VK_FORMAT_R8_UNORM, 1),
    SSS_FORMAT(VK_FORMAT_R8_UINT, 1),
    SSS_FORMAT(VK_FORMAT_R8G8_UNORM, 2),
    SSS_FORMAT(VK_FORMAT_R8G8B8A8_UNORM, 4),
    SSS_FORMAT(VK_FORMAT_R8G8B8A8_SRGB, 4),
    SSS_FORMAT(VK_FORMAT_R8G8B8A8_UINT, 4),
    SSS_FORMAT(VK_FORMAT_B8G8R8A8_UNORM, 4),
    SSS_FORMAT(VK_FORMAT_B8G8R8A8_SRGB, 4),
    SSS_FORMAT(VK_FORMAT_A2B10G10R10_UNORM_PACK32, 4),
    SSS_FORMAT(VK_FORMAT_B10G11R11_UFLOAT_PACK32, 4),
    SSS_FORMAT(VK_FORMAT_R16_SFLOAT, 2),
    SSS_FORMAT(VK_FORMAT_R16_UINT, 2),
    SSS_FORMAT(VK_FORMAT_R16G16_SFLOAT, 4),
    SSS_FORMAT(VK_FORMAT_R16G16_UNORM, 4),
    SSS_FORMAT(VK_FORMAT_R16G16B16A16_SFLOAT, 8),
    SSS_FORMAT(VK_FORMAT_R16G16B16A16_UNORM, 8),
    SSS_FORMAT(VK_FORMAT_R32_SFLOAT, 4),
    SSS_FORMAT(VK_FORMAT_R32_UINT, 4),
    SSS_FORMAT(VK_FORMAT_R32G32_SFLOAT, 8),
    SSS_FORMAT(VK_FORMAT_R32G32B32_SFLOAT, 12),
    SSS_FORMAT(VK_FORMAT_R32G32B32A32_SFLOAT, 16),
    SSS_FORMAT(VK_FORMAT_R32G32B32A32_UINT, 16),
    SSS_FORMAT(VK_FORMAT_D16_UNORM, 2),
    SSS_FORMAT(VK_FORMAT_X8_D24_UNORM_PACK32, 4),
    SSS_FORMAT(VK_FORMAT_D32_SFLOAT, 4),
    SSS_FORMAT(VK_FORMAT_S8_UINT, 1),
    SSS_FORMAT(VK_FORMAT_D24_UNORM_S8_UINT, 4),
    SSS_FORMAT(VK_FORMAT_D32_SFLOAT_S8_UINT, 8),  // 4 + 1, padded; copy aspects separately
};
#undef SSS_FORMAT

const FormatFacts* find(VkFormat format) {
  for (const FormatFacts& f : kFormats) {
    if (f.format == format) return &f;
  }
  return nullptr;
}

}  // namespace

uint32_t texel_size(VkFormat format) {
  const FormatFacts* f = find(format);
  return f != nullptr ? f->size : 0;
}

bool is_depth_format(VkFormat format) {
  switch (format) {
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_X8_D24_UNORM_PACK32:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_D16_UNORM_S8_UINT:
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT: return true;
    default: return false;
  }
}

bool has_stencil(VkFormat format) {
  switch (format) {
    case VK_FORMAT_S8_UINT:
    case VK_FORMAT_D16_UNORM_S8_UINT:
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT: return true;
    default: return false;
  }
}

VkImageAspectFlags aspect_of(VkFormat format) {
  VkImageAspectFlags aspect = 0;
  if (is_depth_format(format)) aspect |= VK_IMAGE_ASPECT_DEPTH_BIT;
  if (has_stencil(format)) aspect |= VK_IMAGE_ASPECT_STENCIL_BIT;
  if (aspect == 0) aspect = VK_IMAGE_ASPECT_COLOR_BIT;
  return aspect;
}

std::string format_name(VkFormat format) {
  const FormatFacts* f = find(format);
  if (f != nullptr) return f->name;
  return "VkFormat(" + std::to_string(static_cast<int>(format)) + ")";
}

}  // namespace sss::vk
