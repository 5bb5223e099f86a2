// Device memory: choosing a memory type for what a resource is for, and allocating one
// block per resource (no sub-allocation: the renderer's resources are few and large).
//
// The chooser takes the memory types the resource allows (VkMemoryRequirements::
// memoryTypeBits), the properties it cannot do without, those it would like and those
// it would rather avoid, and picks the allowed type with all required properties and the
// best score. Allocation checks the device limits first (maxMemoryAllocationSize, the
// heap's size) so that an oversized request fails with a message instead of undefined
// behaviour, and marks the block as dedicated to its resource.
#pragma once

#include "renderer/vk/Handle.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string_view>

namespace sss::vk {

class Context;

enum class MemoryUsage {
  DeviceLocal,  // written and read by the GPU only (render targets, static meshes)
  Upload,       // written once by the CPU, read by the GPU (staging for uploads)
  Readback,     // written by the GPU, read by the CPU (staging for downloads)
  Dynamic,      // rewritten by the CPU every frame, read by the GPU (uniform buffers)
};

struct MemoryPreference {
  VkMemoryPropertyFlags required = 0;
  VkMemoryPropertyFlags preferred = 0;
  VkMemoryPropertyFlags avoided = 0;
};

std::string_view memory_usage_name(MemoryUsage usage);
MemoryPreference memory_preference(MemoryUsage usage);

// The index of the best memory type, or UINT32_MAX when no allowed type has the required
// properties.
uint32_t find_memory_type(const VkPhysicalDeviceMemoryProperties& memory, uint32_t allowed_types,
                          const MemoryPreference& preference);

// Rounds value up to a multiple of alignment (a power of two, or 0 / 1 for none).
constexpr VkDeviceSize align_up(VkDeviceSize value, VkDeviceSize alignment) {
  return alignment <= 1 ? value : (value + alignment - 1) / alignment * alignment;
}

// One block of memory for one resource.
struct Allocation {
  MemoryHandle memory;
  VkMemoryPropertyFlags properties = 0;
  VkDeviceSize size = 0;
};

// Allocates requirements.size bytes for the buffer or the image named (the other is
// VK_NULL_HANDLE), marked as dedicated to it (VkMemoryDedicatedAllocateInfo). Throws
// VulkanError naming the limit that a request exceeds, or the usage for which no memory
// type exists.
Allocation allocate_memory(const Context& context, const VkMemoryRequirements& requirements,
                           MemoryUsage usage, VkBuffer dedicated_buffer, VkImage dedicated_image);

}  // namespace sss::vk
