// synchronization2 barriers, spelled out at the point of use. Each helper fills one
// barrier struct (no queue-family transfer: the renderer uses one queue), and
// pipeline_barrier() records any mix of them in one vkCmdPipelineBarrier2.
//
//   pipeline_barrier(cmd, {image_barrier(gbuffer_albedo,
//       VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
//       {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT},
//       {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT})});
#pragma once

#include <vulkan/vulkan.h>

#include <initializer_list>
#include <span>

namespace sss::vk {

class Buffer;
class Image;

// One side of a dependency: the stages and the accesses in them.
struct Scope {
  VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = VK_ACCESS_2_NONE;
};

// Common scopes.
inline constexpr Scope kNothing{VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE};
inline constexpr Scope kTransferWrite{VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT,
                                      VK_ACCESS_2_TRANSFER_WRITE_BIT};
inline constexpr Scope kTransferRead{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT};
inline constexpr Scope kComputeWrite{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                     VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
inline constexpr Scope kComputeRead{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                    VK_ACCESS_2_SHADER_SAMPLED_READ_BIT |
                                        VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                                        VK_ACCESS_2_UNIFORM_READ_BIT};
inline constexpr Scope kHostRead{VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT};
// Everything before / after: coarse, for setup code and the ends of one-shot work.
inline constexpr Scope kAllCommands{VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                    VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT};

VkMemoryBarrier2 memory_barrier(Scope src, Scope dst);
VkBufferMemoryBarrier2 buffer_barrier(const Buffer& buffer, Scope src, Scope dst,
                                      VkDeviceSize offset = 0, VkDeviceSize size = VK_WHOLE_SIZE);
// A layout transition (or, with old == new, a plain dependency) of every mip and layer.
VkImageMemoryBarrier2 image_barrier(const Image& image, VkImageLayout old_layout,
                                    VkImageLayout new_layout, Scope src, Scope dst);
// The same for a subresource range of a raw image (swapchain images).
VkImageMemoryBarrier2 image_barrier(VkImage image, const VkImageSubresourceRange& range,
                                    VkImageLayout old_layout, VkImageLayout new_layout, Scope src,
                                    Scope dst);

void pipeline_barrier(VkCommandBuffer cmd, std::span<const VkImageMemoryBarrier2> images,
                      std::span<const VkBufferMemoryBarrier2> buffers = {},
                      std::span<const VkMemoryBarrier2> memory = {});
inline void pipeline_barrier(VkCommandBuffer cmd,
                             std::initializer_list<VkImageMemoryBarrier2> images) {
  pipeline_barrier(cmd, std::span<const VkImageMemoryBarrier2>(images.begin(), images.size()));
}

}  // namespace sss::vk
