#include "renderer/vk/Buffer.h"

#include "renderer/vk/Check.h"
#include "renderer/vk/Context.h"

#include <cstring>
#include <stdexcept>
#include <utility>

namespace sss::vk {

Buffer::Buffer(const Context& context, const BufferDesc& desc)
    : size_(desc.size), atom_size_(context.info().limits.nonCoherentAtomSize), usage_(desc.usage) {
  if (desc.size == 0) throw std::invalid_argument("Buffer \"" + desc.name + "\": size is 0");
  if (desc.usage == 0) throw std::invalid_argument("Buffer \"" + desc.name + "\": no usage");
  const VkDeviceSize max_size = context.info().max_buffer_size;
  if (max_size != 0 && desc.size > max_size) {
    throw VulkanError(VK_ERROR_OUT_OF_DEVICE_MEMORY,
                      "Buffer \"" + desc.name + "\": " + std::to_string(desc.size) +
                          " bytes exceed maxBufferSize (" + std::to_string(max_size) + ") of " +
                          context.info().name);
  }
  const VkDevice device = context.device();

  VkBufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  info.size = desc.size;
  info.usage = desc.usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer buffer = VK_NULL_HANDLE;
  VK_CHECK(vkCreateBuffer(device, &info, nullptr, &buffer));
  buffer_ = BufferHandle(device, buffer);

  VkMemoryRequirements requirements{};
  vkGetBufferMemoryRequirements(device, buffer, &requirements);
  Allocation allocation =
      allocate_memory(context, requirements, desc.memory, buffer, VK_NULL_HANDLE);
  memory_ = std::move(allocation.memory);
  properties_ = allocation.properties;
  allocation_size_ = allocation.size;
  VK_CHECK(vkBindBufferMemory(device, buffer, memory_.get(), 0));

  if (properties_ & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
    void* pointer = nullptr;
    VK_CHECK(vkMapMemory(device, memory_.get(), 0, VK_WHOLE_SIZE, 0, &pointer));
    mapped_ = static_cast<std::byte*>(pointer);
  }
  if (!desc.name.empty()) {
    context.set_object_name(VK_OBJECT_TYPE_BUFFER, buffer, desc.name);
    context.set_object_name(VK_OBJECT_TYPE_DEVICE_MEMORY, memory_.get(), desc.name);
  }
}

Buffer::Buffer(Buffer&& other) noexcept
    : memory_(std::move(other.memory_)),
      buffer_(std::move(other.buffer_)),
      size_(std::exchange(other.size_, 0)),
      allocation_size_(std::exchange(other.allocation_size_, 0)),
      atom_size_(other.atom_size_),
      usage_(std::exchange(other.usage_, 0)),
      properties_(std::exchange(other.properties_, 0)),
      mapped_(std::exchange(other.mapped_, nullptr)) {}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    buffer_ = std::move(other.buffer_);  // the buffer goes before its memory
    memory_ = std::move(other.memory_);
    size_ = std::exchange(other.size_, 0);
    allocation_size_ = std::exchange(other.allocation_size_, 0);
    atom_size_ = other.atom_size_;
    usage_ = std::exchange(other.usage_, 0);
    properties_ = std::exchange(other.properties_, 0);
    mapped_ = std::exchange(other.mapped_, nullptr);
  }
  return *this;
}

void Buffer::check_host_range(VkDeviceSize offset, VkDeviceSize size, const char* what) const {
  if (mapped_ == nullptr) {
    throw std::logic_error(std::string("Buffer::") + what + ": the buffer is not host-visible");
  }
  if (offset > size_ || size > size_ - offset) {
    throw std::out_of_range(std::string("Buffer::") + what + ": range [" + std::to_string(offset) +
                            ", +" + std::to_string(size) + ") exceeds the size " +
                            std::to_string(size_));
  }
}

// [offset, offset + size) widened to whole atoms and clamped to the allocation, as
// vkFlushMappedMemoryRanges requires for non-coherent memory.
VkMappedMemoryRange Buffer::atom_range(VkDeviceSize offset, VkDeviceSize size) const {
  if (size == VK_WHOLE_SIZE) size = size_ - offset;
  const VkDeviceSize atom = atom_size_ == 0 ? 1 : atom_size_;
  const VkDeviceSize begin = offset / atom * atom;
  VkDeviceSize end = align_up(offset + size, atom);
  if (end > allocation_size_) end = allocation_size_;
  VkMappedMemoryRange range{};
  range.sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE;
  range.memory = memory_.get();
  range.offset = begin;
  range.size = end == allocation_size_ ? VK_WHOLE_SIZE : end - begin;
  return range;
}

void Buffer::flush(VkDeviceSize offset, VkDeviceSize size) {
  if (mapped_ == nullptr || (properties_ & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT)) return;
  const VkMappedMemoryRange range = atom_range(offset, size);
  VK_CHECK(vkFlushMappedMemoryRanges(memory_.device(), 1, &range));
}

void Buffer::invalidate(VkDeviceSize offset, VkDeviceSize size) const {
  if (mapped_ == nullptr || (properties_ & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT)) return;
  const VkMappedMemoryRange range = atom_range(offset, size);
  VK_CHECK(vkInvalidateMappedMemoryRanges(memory_.device(), 1, &range));
}

void Buffer::write(const void* data, VkDeviceSize size, VkDeviceSize offset) {
  check_host_range(offset, size, "write");
  if (size == 0) return;
  std::memcpy(mapped_ + offset, data, static_cast<std::size_t>(size));
  flush(offset, size);
}

void Buffer::read(void* data, VkDeviceSize size, VkDeviceSize offset) const {
  check_host_range(offset, size, "read");
  if (size == 0) return;
  invalidate(offset, size);
  std::memcpy(data, mapped_ + offset, static_cast<std::size_t>(size));
}

}  // namespace sss::vk
