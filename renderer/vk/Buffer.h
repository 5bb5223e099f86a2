// A VkBuffer with its own memory block (renderer/vk/Memory.h).
//
// Host-visible buffers (Upload, Readback, Dynamic) stay mapped for their whole life;
// write() and read() copy through the mapping and flush or invalidate it when the memory
// is not host-coherent, with ranges widened to the device's nonCoherentAtomSize. A
// DeviceLocal buffer is filled through a staging buffer (renderer/vk/Transfer.h).
#pragma once

#include "renderer/vk/Handle.h"
#include "renderer/vk/Memory.h"

#include <vulkan/vulkan.h>

#include <cstddef>
#include <string>
#include <utility>

namespace sss::vk {

class Context;

// Buffer(ctx, {size, usage}) or Buffer(ctx, {size, usage, MemoryUsage::Upload, "name"}).
struct BufferDesc {
  BufferDesc(VkDeviceSize size_bytes, VkBufferUsageFlags usage_flags,
             MemoryUsage memory_usage = MemoryUsage::DeviceLocal, std::string debug_name = {})
      : size(size_bytes), usage(usage_flags), memory(memory_usage), name(std::move(debug_name)) {}

  VkDeviceSize size;  // bytes, > 0
  VkBufferUsageFlags usage;
  MemoryUsage memory;
  std::string name;  // debug name for tools and validation messages
};

class Buffer {
 public:
  Buffer() = default;  // empty
  // Throws std::invalid_argument for a zero size or no usage, VulkanError otherwise.
  Buffer(const Context& context, const BufferDesc& desc);

  // Moving leaves the source empty (no handle, size 0, not mapped).
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;

  VkBuffer handle() const { return buffer_.get(); }
  VkDeviceSize size() const { return size_; }
  VkBufferUsageFlags usage() const { return usage_; }
  VkMemoryPropertyFlags memory_properties() const { return properties_; }
  bool host_visible() const { return mapped_ != nullptr; }
  explicit operator bool() const { return static_cast<bool>(buffer_); }

  // The persistent mapping; nullptr unless host-visible.
  std::byte* mapped() const { return mapped_; }

  // Copies bytes into / out of a host-visible buffer. write() makes the bytes available
  // to the device (flush); read() makes the device's writes visible (invalidate) first.
  // The caller orders them against GPU work (fences, barriers with HOST stages).
  void write(const void* data, VkDeviceSize size, VkDeviceSize offset = 0);
  void read(void* data, VkDeviceSize size, VkDeviceSize offset = 0) const;
  void flush(VkDeviceSize offset = 0, VkDeviceSize size = VK_WHOLE_SIZE);
  void invalidate(VkDeviceSize offset = 0, VkDeviceSize size = VK_WHOLE_SIZE) const;

  VkDescriptorBufferInfo descriptor(VkDeviceSize offset = 0,
                                    VkDeviceSize range = VK_WHOLE_SIZE) const {
    return {buffer_.get(), offset, range};
  }

 private:
  void check_host_range(VkDeviceSize offset, VkDeviceSize size, const char* what) const;
  VkMappedMemoryRange atom_range(VkDeviceSize offset, VkDeviceSize size) const;

  // Declared before buffer_ so that the buffer is destroyed before its memory is freed.
  MemoryHandle memory_;
  BufferHandle buffer_;
  VkDeviceSize size_ = 0;
  VkDeviceSize allocation_size_ = 0;
  VkDeviceSize atom_size_ = 1;  // nonCoherentAtomSize
  VkBufferUsageFlags usage_ = 0;
  VkMemoryPropertyFlags properties_ = 0;
  std::byte* mapped_ = nullptr;
};

}  // namespace sss::vk
