#include "renderer/vk/Image.h"

#include "renderer/vk/Check.h"
#include "renderer/vk/Context.h"
#include "renderer/vk/Format.h"

#include <stdexcept>
#include <utility>

namespace sss::vk {

namespace {

bool is_cube(VkImageViewType type) {
  return type == VK_IMAGE_VIEW_TYPE_CUBE || type == VK_IMAGE_VIEW_TYPE_CUBE_ARRAY;
}

// Image usages and the format feature each needs (Vulkan spec, "Valid Usage" of
// VkImageCreateInfo: the usage must be supported by the format's features).
struct UsageFeature {
  VkImageUsageFlags usage;
  VkFormatFeatureFlags feature;
  const char* name;
};
constexpr UsageFeature kUsageFeatures[] = {
    {VK_IMAGE_USAGE_SAMPLED_BIT, VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT, "a sampled image"},
    {VK_IMAGE_USAGE_STORAGE_BIT, VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT, "a storage image"},
    {VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT,
     "a colour attachment"},
    {VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT,
     "a depth attachment"},
    {VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_FORMAT_FEATURE_TRANSFER_SRC_BIT, "a transfer source"},
    {VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_FORMAT_FEATURE_TRANSFER_DST_BIT,
     "a transfer destination"},
};

// The description on its own: sizes, format, usage, layers and view type.
void validate_desc(const ImageDesc& d, const std::string& what) {
  if (d.width == 0 || d.height == 0) throw std::invalid_argument(what + "width or height is 0");
  if (d.format == VK_FORMAT_UNDEFINED) throw std::invalid_argument(what + "no format");
  if (d.usage == 0) throw std::invalid_argument(what + "no usage");
  if (d.mip_levels == 0 || d.array_layers == 0) {
    throw std::invalid_argument(what + "mip_levels and array_layers must be at least 1");
  }
  if (is_cube(d.view_type) && (d.array_layers % 6 != 0 || d.width != d.height)) {
    throw std::invalid_argument(what + "a cube needs square faces and 6·n layers");
  }
  if (d.view_type == VK_IMAGE_VIEW_TYPE_2D && d.array_layers != 1) {
    throw std::invalid_argument(what + "several layers need VK_IMAGE_VIEW_TYPE_2D_ARRAY");
  }
}

// The device's limits on image sides and layers.
void validate_limits(const Context& context, const ImageDesc& d, const std::string& what) {
  const VkPhysicalDeviceLimits& limits = context.info().limits;
  const uint32_t max_side =
      is_cube(d.view_type) ? limits.maxImageDimensionCube : limits.maxImageDimension2D;
  if (d.width > max_side || d.height > max_side) {
    throw VulkanError(VK_ERROR_FORMAT_NOT_SUPPORTED,
                      what + std::to_string(d.width) + "x" + std::to_string(d.height) +
                          " exceeds " +
                          (is_cube(d.view_type) ? "maxImageDimensionCube (" :
                                                  "maxImageDimension2D (") +
                          std::to_string(max_side) + ") of " + context.info().name);
  }
  if (d.array_layers > limits.maxImageArrayLayers) {
    throw VulkanError(VK_ERROR_FORMAT_NOT_SUPPORTED,
                      what + std::to_string(d.array_layers) + " layers exceed maxImageArrayLayers (" +
                          std::to_string(limits.maxImageArrayLayers) + ") of " +
                          context.info().name);
  }
}

void validate(const Context& context, const ImageDesc& d) {
  const std::string what = "Image \"" + d.name + "\": ";
  validate_desc(d, what);
  validate_limits(context, d, what);
  // The format's features for optimal tiling first: a missing one is named (and the
  // query below is then not made: best practices reports every error result).
  VkFormatProperties format_props{};
  vkGetPhysicalDeviceFormatProperties(context.physical_device(), d.format, &format_props);
  for (const auto& [usage, feature, usage_name] : kUsageFeatures) {
    if ((d.usage & usage) && !(format_props.optimalTilingFeatures & feature)) {
      throw VulkanError(VK_ERROR_FORMAT_NOT_SUPPORTED,
                        what + format_name(d.format) + " cannot be used as " + usage_name +
                            " (optimal tiling) on " + context.info().name);
    }
  }

  VkImageFormatProperties props{};
  const VkResult supported = vkGetPhysicalDeviceImageFormatProperties(
      context.physical_device(), d.format, VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL, d.usage,
      is_cube(d.view_type) ? VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT : 0, &props);
  if (supported == VK_ERROR_FORMAT_NOT_SUPPORTED) {
    throw VulkanError(supported, what + format_name(d.format) + " with usage flags " +
                                     std::to_string(d.usage) + " is not supported by " +
                                     context.info().name);
  }
  VK_CHECK(supported);
  if (d.width > props.maxExtent.width || d.height > props.maxExtent.height ||
      d.mip_levels > props.maxMipLevels || d.array_layers > props.maxArrayLayers ||
      (props.sampleCounts & d.samples) == 0) {
    throw VulkanError(VK_ERROR_FORMAT_NOT_SUPPORTED,
                      what + std::to_string(d.width) + "x" + std::to_string(d.height) + ", " +
                          std::to_string(d.mip_levels) + " mips, " +
                          std::to_string(d.array_layers) + " layers, " + std::to_string(d.samples) +
                          " samples of " + format_name(d.format) + " exceed the limits of " +
                          context.info().name + " (max " + std::to_string(props.maxExtent.width) +
                          "x" + std::to_string(props.maxExtent.height) + ")");
  }
}

}  // namespace

Image::Image(const Context& context, const ImageDesc& desc)
    : desc_(desc), aspect_(aspect_of(desc.format)) {
  validate(context, desc);
  const VkDevice device = context.device();

  VkImageCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
  info.flags = is_cube(desc.view_type) ? VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT : 0;
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = desc.format;
  info.extent = {desc.width, desc.height, 1};
  info.mipLevels = desc.mip_levels;
  info.arrayLayers = desc.array_layers;
  info.samples = desc.samples;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = desc.usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImage image = VK_NULL_HANDLE;
  VK_CHECK(vkCreateImage(device, &info, nullptr, &image));
  image_ = ImageHandle(device, image);

  VkMemoryRequirements requirements{};
  vkGetImageMemoryRequirements(device, image, &requirements);
  Allocation allocation =
      allocate_memory(context, requirements, desc.memory, VK_NULL_HANDLE, image);
  memory_ = std::move(allocation.memory);
  bytes_ = requirements.size;
  VK_CHECK(vkBindImageMemory(device, image, memory_.get(), 0));

  view_ = make_view(desc.view_type, 0, desc.mip_levels, 0, desc.array_layers);
  if (!desc.name.empty()) {
    context.set_object_name(VK_OBJECT_TYPE_IMAGE, image, desc.name);
    context.set_object_name(VK_OBJECT_TYPE_IMAGE_VIEW, view_.get(), desc.name);
    context.set_object_name(VK_OBJECT_TYPE_DEVICE_MEMORY, memory_.get(), desc.name);
  }
}

Image::Image(Image&& other) noexcept
    : memory_(std::move(other.memory_)),
      image_(std::move(other.image_)),
      view_(std::move(other.view_)),
      desc_(std::exchange(other.desc_, {})),
      aspect_(std::exchange(other.aspect_, 0)),
      bytes_(std::exchange(other.bytes_, 0)) {}

Image& Image::operator=(Image&& other) noexcept {
  if (this != &other) {
    view_ = std::move(other.view_);  // view, image, memory: reverse order of creation
    image_ = std::move(other.image_);
    memory_ = std::move(other.memory_);
    desc_ = std::exchange(other.desc_, {});
    aspect_ = std::exchange(other.aspect_, 0);
    bytes_ = std::exchange(other.bytes_, 0);
  }
  return *this;
}

VkImageSubresourceRange Image::full_range() const {
  return {aspect_, 0, desc_.mip_levels, 0, desc_.array_layers};
}

VkImageSubresourceLayers Image::subresource_layers(uint32_t mip) const {
  return {aspect_, mip, 0, desc_.array_layers};
}

ImageViewHandle Image::create_view(uint32_t layer, uint32_t mip) const {
  if (layer >= desc_.array_layers || mip >= desc_.mip_levels) {
    throw std::out_of_range("Image \"" + desc_.name + "\": no layer " + std::to_string(layer) +
                            ", mip " + std::to_string(mip));
  }
  return make_view(VK_IMAGE_VIEW_TYPE_2D, mip, 1, layer, 1);
}

ImageViewHandle Image::make_view(VkImageViewType type, uint32_t base_mip, uint32_t mips,
                                 uint32_t base_layer, uint32_t layers) const {
  VkImageViewCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
  info.image = image_.get();
  info.viewType = type;
  info.format = desc_.format;
  // Depth-stencil views for sampling and attachments show the depth aspect.
  VkImageAspectFlags view_aspect = aspect_;
  if (aspect_ & VK_IMAGE_ASPECT_DEPTH_BIT) view_aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
  info.subresourceRange = {view_aspect, base_mip, mips, base_layer, layers};
  VkImageView view = VK_NULL_HANDLE;
  VK_CHECK(vkCreateImageView(image_.device(), &info, nullptr, &view));
  return ImageViewHandle(image_.device(), view);
}

}  // namespace sss::vk
