#include "renderer/vk/Transfer.h"

#include "renderer/vk/Barrier.h"
#include "renderer/vk/Buffer.h"
#include "renderer/vk/Commands.h"
#include "renderer/vk/Context.h"
#include "renderer/vk/Format.h"
#include "renderer/vk/Image.h"

#include <stdexcept>
#include <string>

namespace sss::vk {

namespace {

// Source and destination of every layout transition in this file.
constexpr Scope kCopyStage{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE};
constexpr Scope kTransferWriteOnly{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT};

// Every use an image may have in `layout`, for the coarse dependencies of one-shot copies
// with whatever came before or comes after: all stages, but only the accesses that the
// layout allows (best practices, ImageBarrierAccessLayout: MEMORY_READ|MEMORY_WRITE into
// SHADER_READ_ONLY_OPTIMAL names accesses that cannot happen in that layout).
Scope uses_in(VkImageLayout layout) {
  constexpr VkPipelineStageFlags2 kAll = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  switch (layout) {
    case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL:
      return {kAll, VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_INPUT_ATTACHMENT_READ_BIT};
    case VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL:
    case VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL:
      return {kAll, VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_INPUT_ATTACHMENT_READ_BIT |
                        VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT};
    case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL: return {kAll, VK_ACCESS_2_TRANSFER_READ_BIT};
    case VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL: return {kAll, VK_ACCESS_2_TRANSFER_WRITE_BIT};
    case VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL:
      return {kAll, VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT};
    case VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL:
    case VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL:
      return {kAll, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                        VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT};
    default: return kAllCommands;  // GENERAL and the rest
  }
}

VkDeviceSize image_bytes(const Image& image) {
  if (image.desc().samples != VK_SAMPLE_COUNT_1_BIT) {
    throw std::invalid_argument("Image \"" + image.desc().name +
                                "\": multisampled images cannot be copied");
  }
  if (is_depth_format(image.format()) && has_stencil(image.format())) {
    throw std::invalid_argument("Image \"" + image.desc().name +
                                "\": depth-stencil formats are not supported by upload/download");
  }
  const uint32_t texel = texel_size(image.format());
  if (texel == 0) {
    throw std::invalid_argument("Image \"" + image.desc().name + "\": unknown texel size of " +
                                format_name(image.format()));
  }
  return VkDeviceSize{image.width()} * image.height() * image.desc().array_layers * texel;
}

VkBufferImageCopy whole_mip0(const Image& image) {
  VkBufferImageCopy region{};
  region.bufferOffset = 0;
  region.bufferRowLength = 0;  // tightly packed
  region.bufferImageHeight = 0;
  region.imageSubresource = image.subresource_layers(0);
  region.imageExtent = {image.width(), image.height(), 1};
  return region;
}

}  // namespace

void upload_buffer(const Context& context, const Buffer& dst, std::span<const std::byte> data,
                   VkDeviceSize offset) {
  if (data.empty()) return;
  if (offset > dst.size() || data.size() > dst.size() - offset) {
    throw std::out_of_range("upload_buffer: " + std::to_string(data.size()) + " bytes at offset " +
                            std::to_string(offset) + " exceed the buffer size " +
                            std::to_string(dst.size()));
  }
  Buffer staging(context, {data.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload,
                           "staging (upload)"});
  staging.write(data.data(), data.size());
  submit_once(context, [&](VkCommandBuffer cmd) {
    const VkBufferMemoryBarrier2 before[] = {buffer_barrier(dst, kAllCommands, kTransferWrite)};
    pipeline_barrier(cmd, {}, before);
    const VkBufferCopy region{0, offset, data.size()};
    vkCmdCopyBuffer(cmd, staging.handle(), dst.handle(), 1, &region);
    const VkBufferMemoryBarrier2 after[] = {buffer_barrier(dst, kTransferWrite, kAllCommands)};
    pipeline_barrier(cmd, {}, after);
  });
}

std::vector<std::byte> download_buffer(const Context& context, const Buffer& src,
                                       VkDeviceSize offset, VkDeviceSize size) {
  if (offset > src.size()) throw std::out_of_range("download_buffer: offset past the end");
  if (size == VK_WHOLE_SIZE) size = src.size() - offset;
  if (size > src.size() - offset) throw std::out_of_range("download_buffer: range past the end");
  std::vector<std::byte> bytes(static_cast<std::size_t>(size));
  if (size == 0) return bytes;
  Buffer staging(context, {size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::Readback,
                           "staging (download)"});
  submit_once(context, [&](VkCommandBuffer cmd) {
    const VkBufferMemoryBarrier2 before[] = {buffer_barrier(src, kAllCommands, kTransferRead)};
    pipeline_barrier(cmd, {}, before);
    const VkBufferCopy region{offset, 0, size};
    vkCmdCopyBuffer(cmd, src.handle(), staging.handle(), 1, &region);
    const VkBufferMemoryBarrier2 after[] = {buffer_barrier(staging, kTransferWrite, kHostRead)};
    pipeline_barrier(cmd, {}, after);
  });
  staging.read(bytes.data(), size);
  return bytes;
}

void upload_image(const Context& context, const Image& dst, std::span<const std::byte> texels,
                  VkImageLayout final_layout) {
  const VkDeviceSize expected = image_bytes(dst);
  if (texels.size() != expected) {
    throw std::invalid_argument("upload_image \"" + dst.desc().name + "\": got " +
                                std::to_string(texels.size()) + " bytes, expected " +
                                std::to_string(expected));
  }
  Buffer staging(context, {expected, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload,
                           "staging (image upload)"});
  staging.write(texels.data(), expected);
  submit_once(context, [&](VkCommandBuffer cmd) {
    pipeline_barrier(
        cmd, {image_barrier(dst, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                            kAllCommands, kTransferWriteOnly)});
    const VkBufferImageCopy region = whole_mip0(dst);
    vkCmdCopyBufferToImage(cmd, staging.handle(), dst.handle(),
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    if (final_layout != VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL) {
      pipeline_barrier(cmd, {image_barrier(dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, final_layout,
                                           kTransferWriteOnly, uses_in(final_layout))});
    } else {
      pipeline_barrier(
          cmd, {image_barrier(dst, final_layout, final_layout, kTransferWriteOnly,
                              uses_in(final_layout))});
    }
  });
}

std::vector<std::byte> download_image(const Context& context, const Image& src,
                                      VkImageLayout layout) {
  if (layout == VK_IMAGE_LAYOUT_UNDEFINED || layout == VK_IMAGE_LAYOUT_PREINITIALIZED) {
    throw std::invalid_argument("download_image \"" + src.desc().name +
                                "\": the image has no defined contents in layout UNDEFINED");
  }
  const VkDeviceSize size = image_bytes(src);
  Buffer staging(context, {size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::Readback,
                           "staging (image download)"});
  submit_once(context, [&](VkCommandBuffer cmd) {
    const VkImageLayout copy_layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    pipeline_barrier(cmd,
                     {image_barrier(src, layout, copy_layout, uses_in(layout), kTransferRead)});
    const VkBufferImageCopy region = whole_mip0(src);
    vkCmdCopyImageToBuffer(cmd, src.handle(), copy_layout, staging.handle(), 1, &region);
    const VkImageMemoryBarrier2 restore[] = {
        image_barrier(src, copy_layout, layout, kCopyStage, uses_in(layout))};
    const VkBufferMemoryBarrier2 to_host[] = {buffer_barrier(staging, kTransferWrite, kHostRead)};
    pipeline_barrier(cmd, restore, to_host);
  });
  std::vector<std::byte> bytes(static_cast<std::size_t>(size));
  staging.read(bytes.data(), size);
  return bytes;
}

}  // namespace sss::vk
