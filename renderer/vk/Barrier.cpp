#include "renderer/vk/Barrier.h"

#include "renderer/vk/Buffer.h"
#include "renderer/vk/Image.h"

namespace sss::vk {

VkMemoryBarrier2 memory_barrier(Scope src, Scope dst) {
  VkMemoryBarrier2 b{};
  b.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2;
  b.srcStageMask = src.stages;
  b.srcAccessMask = src.access;
  b.dstStageMask = dst.stages;
  b.dstAccessMask = dst.access;
  return b;
}

VkBufferMemoryBarrier2 buffer_barrier(const Buffer& buffer, Scope src, Scope dst,
                                      VkDeviceSize offset, VkDeviceSize size) {
  VkBufferMemoryBarrier2 b{};
  b.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2;
  b.srcStageMask = src.stages;
  b.srcAccessMask = src.access;
  b.dstStageMask = dst.stages;
  b.dstAccessMask = dst.access;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.buffer = buffer.handle();
  b.offset = offset;
  b.size = size;
  return b;
}

VkImageMemoryBarrier2 image_barrier(VkImage image, const VkImageSubresourceRange& range,
                                    VkImageLayout old_layout, VkImageLayout new_layout, Scope src,
                                    Scope dst) {
  VkImageMemoryBarrier2 b{};
  b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2;
  b.srcStageMask = src.stages;
  b.srcAccessMask = src.access;
  b.dstStageMask = dst.stages;
  b.dstAccessMask = dst.access;
  b.oldLayout = old_layout;
  b.newLayout = new_layout;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = range;
  return b;
}

VkImageMemoryBarrier2 image_barrier(const Image& image, VkImageLayout old_layout,
                                    VkImageLayout new_layout, Scope src, Scope dst) {
  return image_barrier(image.handle(), image.full_range(), old_layout, new_layout, src, dst);
}

void pipeline_barrier(VkCommandBuffer cmd, std::span<const VkImageMemoryBarrier2> images,
                      std::span<const VkBufferMemoryBarrier2> buffers,
                      std::span<const VkMemoryBarrier2> memory) {
  VkDependencyInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
  info.memoryBarrierCount = static_cast<uint32_t>(memory.size());
  info.pMemoryBarriers = memory.data();
  info.bufferMemoryBarrierCount = static_cast<uint32_t>(buffers.size());
  info.pBufferMemoryBarriers = buffers.data();
  info.imageMemoryBarrierCount = static_cast<uint32_t>(images.size());
  info.pImageMemoryBarriers = images.data();
  vkCmdPipelineBarrier2(cmd, &info);
}

}  // namespace sss::vk
