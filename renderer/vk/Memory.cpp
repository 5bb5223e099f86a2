#include "renderer/vk/Memory.h"

#include "renderer/vk/Check.h"
#include "renderer/vk/Context.h"

#include <bit>
#include <bitset>
#include <cstdio>
#include <string>

namespace sss::vk {

namespace {
std::string hex(uint32_t value) {
  char text[9];
  std::snprintf(text, sizeof text, "%x", value);
  return text;
}
}  // namespace

std::string_view memory_usage_name(MemoryUsage usage) {
  switch (usage) {
    case MemoryUsage::DeviceLocal: return "device-local";
    case MemoryUsage::Upload: return "upload";
    case MemoryUsage::Readback: return "readback";
    case MemoryUsage::Dynamic: return "dynamic";
  }
  return "unknown";
}

MemoryPreference memory_preference(MemoryUsage usage) {
  constexpr VkMemoryPropertyFlags kDevice = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
  constexpr VkMemoryPropertyFlags kVisible = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
  constexpr VkMemoryPropertyFlags kCoherent = VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  constexpr VkMemoryPropertyFlags kCached = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
  switch (usage) {
    case MemoryUsage::DeviceLocal:
      // On a discrete GPU the host-visible device-local window (BAR) is small: keep out.
      return {kDevice, 0, kVisible};
    case MemoryUsage::Upload:
      // System memory, write-combined (uncached) is fine for sequential writes.
      return {kVisible, kCoherent, kDevice | kCached};
    case MemoryUsage::Readback:
      // Reading uncached memory from the CPU is very slow.
      return {kVisible, kCached | kCoherent, 0};
    case MemoryUsage::Dynamic:
      // Device-local and host-visible when the device has it (BAR, unified memory).
      return {kVisible, kDevice | kCoherent, kCached};
  }
  return {};
}

uint32_t find_memory_type(const VkPhysicalDeviceMemoryProperties& memory, uint32_t allowed_types,
                          const MemoryPreference& preference) {
  uint32_t best = UINT32_MAX;
  int best_score = 0;
  for (uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
    if ((allowed_types & (1u << i)) == 0) continue;
    const VkMemoryPropertyFlags flags = memory.memoryTypes[i].propertyFlags;
    if ((flags & preference.required) != preference.required) continue;
    // Lazily allocated and protected memory are for special uses only.
    if (flags & (VK_MEMORY_PROPERTY_LAZILY_ALLOCATED_BIT | VK_MEMORY_PROPERTY_PROTECTED_BIT)) {
      continue;
    }
    const int score =
        std::popcount(flags & preference.preferred) - std::popcount(flags & preference.avoided);
    if (best == UINT32_MAX || score > best_score) {  // ties: the lower index
      best = i;
      best_score = score;
    }
  }
  return best;
}

namespace {

// The memory type for the requirements and usage, checked against the device's largest
// allocation and the type's heap; a VulkanError that says which limit otherwise.
uint32_t checked_memory_type(const DeviceInfo& info, const VkMemoryRequirements& requirements, MemoryUsage usage) {
  const uint32_t type =
      find_memory_type(info.memory, requirements.memoryTypeBits, memory_preference(usage));
  if (type == UINT32_MAX) {
    throw VulkanError(VK_ERROR_OUT_OF_DEVICE_MEMORY,
                      "no memory type of " + info.name + " suits " +
                          std::string(memory_usage_name(usage)) + " memory (allowed types " +
                          std::bitset<32>(requirements.memoryTypeBits).to_string() + ")");
  }
  if (info.max_memory_allocation_size != 0 && requirements.size > info.max_memory_allocation_size) {
    throw VulkanError(VK_ERROR_OUT_OF_DEVICE_MEMORY,
                      "allocation of " + std::to_string(requirements.size) +
                          " bytes exceeds maxMemoryAllocationSize (" +
                          std::to_string(info.max_memory_allocation_size) + ") of " + info.name);
  }
  const VkMemoryHeap& heap = info.memory.memoryHeaps[info.memory.memoryTypes[type].heapIndex];
  if (requirements.size > heap.size) {
    throw VulkanError(VK_ERROR_OUT_OF_DEVICE_MEMORY,
                      "allocation of " + std::to_string(requirements.size) +
                          " bytes exceeds the size of memory heap (" + std::to_string(heap.size) +
                          " bytes) of " + info.name);
  }
  return type;
}

// What a failed vkAllocateMemory says: the size, usage, type, heap and flags, and the
// result (or that the failure was simulated).
std::string allocation_failure(const Context& context, VkDeviceSize size, MemoryUsage usage, uint32_t type,
                               bool simulated, VkResult allocated) {
  const DeviceInfo& info = context.info();
  const VkMemoryType& memory_type = info.memory.memoryTypes[type];
  std::string message;
  if (simulated) {
    message = "simulated allocation failure (fail after " + std::to_string(*context.fail_allocation_after()) +
              " allocations, SSS_FAIL_ALLOCATION_AFTER): ";
  }
  message += "vkAllocateMemory of " + std::to_string(size) + " bytes of " + std::string(memory_usage_name(usage)) +
             " memory (memory type " + std::to_string(type) + ", heap " + std::to_string(memory_type.heapIndex) +
             ", property flags 0x" + hex(memory_type.propertyFlags) + ") on " + info.name + " failed with " +
             result_name(allocated);
  return message;
}

}  // namespace

Allocation allocate_memory(const Context& context, const VkMemoryRequirements& requirements,
                           MemoryUsage usage, VkBuffer dedicated_buffer, VkImage dedicated_image) {
  const DeviceInfo& info = context.info();
  const uint32_t type = checked_memory_type(info, requirements, usage);
  VkMemoryDedicatedAllocateInfo dedicated{};
  dedicated.sType = VK_STRUCTURE_TYPE_MEMORY_DEDICATED_ALLOCATE_INFO;
  dedicated.buffer = dedicated_buffer;
  dedicated.image = dedicated_image;
  VkMemoryAllocateInfo allocate{};
  allocate.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  allocate.pNext = &dedicated;
  allocate.allocationSize = requirements.size;
  allocate.memoryTypeIndex = type;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  // The renderer's one call of vkAllocateMemory. A simulated failure (SSS_FAIL_ALLOCATION_
  // AFTER, ContextOptions::fail_allocation_after) takes the same path as a real one.
  const bool simulated = context.allocation_must_fail();
  const VkResult allocated = simulated
                              ? VK_ERROR_OUT_OF_DEVICE_MEMORY
                              : vkAllocateMemory(context.device(), &allocate, nullptr, &memory);
  if (allocated < 0)
    throw VulkanError(allocated, allocation_failure(context, requirements.size, usage, type, simulated, allocated));
  context.count_successful_allocation();

  Allocation result;
  result.memory = MemoryHandle(context.device(), memory);
  result.properties = info.memory.memoryTypes[type].propertyFlags;
  result.size = requirements.size;
  return result;
}

}  // namespace sss::vk
