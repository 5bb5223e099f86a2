// Move-only owners of Vulkan device objects (DESIGN.md §8, "Vulkan objects").
//
// Handle<T, Destroy> owns one object T created from a VkDevice and destroys it with
// Destroy(device, object, nullptr) when it goes out of scope or is reset. Moving leaves
// the source empty. A Handle never outlives its device by itself: the Context must be
// destroyed last, and objects the GPU may still use go through a DeletionQueue rather
// than being destroyed on the spot.
//
// Objects that are freed with their parent (command buffers with their pool, descriptor
// sets with their pool) have no Handle. Instance-level objects (instance, surface,
// debug messenger, device) are owned by Context.
#pragma once

#include <vulkan/vulkan.h>

#include <utility>

namespace sss::vk {

template <typename T, void(VKAPI_PTR* Destroy)(VkDevice, T, const VkAllocationCallbacks*)>
class Handle {
 public:
  Handle() noexcept = default;
  Handle(VkDevice device, T object) noexcept : device_(device), object_(object) {}
  ~Handle() { reset(); }

  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept
      : device_(other.device_), object_(std::exchange(other.object_, T{VK_NULL_HANDLE})) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      device_ = other.device_;
      object_ = std::exchange(other.object_, T{VK_NULL_HANDLE});
    }
    return *this;
  }

  T get() const noexcept { return object_; }
  VkDevice device() const noexcept { return device_; }
  explicit operator bool() const noexcept { return object_ != T{VK_NULL_HANDLE}; }

  // Destroys the object now (if any); the handle is empty afterwards.
  void reset() noexcept {
    if (object_ != T{VK_NULL_HANDLE}) Destroy(device_, object_, nullptr);
    object_ = T{VK_NULL_HANDLE};
  }
  // Gives up ownership without destroying; the caller must destroy the object.
  [[nodiscard]] T release() noexcept { return std::exchange(object_, T{VK_NULL_HANDLE}); }

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  T object_ = T{VK_NULL_HANDLE};
};

using BufferHandle = Handle<VkBuffer, vkDestroyBuffer>;
using MemoryHandle = Handle<VkDeviceMemory, vkFreeMemory>;
using ImageHandle = Handle<VkImage, vkDestroyImage>;
using ImageViewHandle = Handle<VkImageView, vkDestroyImageView>;
using SamplerHandle = Handle<VkSampler, vkDestroySampler>;
using ShaderModuleHandle = Handle<VkShaderModule, vkDestroyShaderModule>;
using PipelineHandle = Handle<VkPipeline, vkDestroyPipeline>;
using PipelineLayoutHandle = Handle<VkPipelineLayout, vkDestroyPipelineLayout>;
using DescriptorSetLayoutHandle = Handle<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>;
using DescriptorPoolHandle = Handle<VkDescriptorPool, vkDestroyDescriptorPool>;
using CommandPoolHandle = Handle<VkCommandPool, vkDestroyCommandPool>;
using FenceHandle = Handle<VkFence, vkDestroyFence>;
using SemaphoreHandle = Handle<VkSemaphore, vkDestroySemaphore>;
using QueryPoolHandle = Handle<VkQueryPool, vkDestroyQueryPool>;

}  // namespace sss::vk
