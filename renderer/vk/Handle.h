// Move-only owners of Vulkan device objects (DESIGN.md §8, "Vulkan objects").
//
// Handle<T, Destroy> owns one object T created from a VkDevice and destroys it with
// Destroy(device, object, nullptr) when it goes out of scope or is reset. Moving leaves
// the source empty. A Handle never outlives its device by itself: the Context must be
// destroyed last. There is one frame in flight (Renderer::render_frame waits for its
// fence), so an object the GPU may still use is one a window's blit reads; the owner
// calls Context::wait_idle before replacing it (Renderer's resize, set_options).
//
// Objects that are freed with their parent (command buffers with their pool, descriptor
// sets with their pool) have no Handle. Instance-level objects (instance, surface,
// debug messenger, device) are owned by Context, and the swapchain by vk::Swapchain.
//
// Live counts (the soak's leak check, sss-viewer --soak): every Handle that owns an
// object counts it in a per-type counter, from construction to reset()/release()/
// destruction (a move keeps the count). live_objects() lists the types seen so far and
// live_object_count() their total: every device object this code base creates, except
// the ones named above that have no Handle (and whatever Dear ImGui's Vulkan backend
// creates for itself in the window). A count that keeps rising while the same work is
// repeated is a leak; release() hands the object to the caller, so it leaves the count.
#pragma once

#include <vulkan/vulkan.h>

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string_view>
#include <utility>
#include <vector>

namespace sss::vk {

struct LiveCount {
  std::string_view type;  // "VkBuffer", ...
  std::int64_t live = 0;
};

namespace detail {

// One per Handle type, registered in a list at its first construction.
struct LiveCounter {
  const char* type;
  std::atomic<std::int64_t> live{0};
  LiveCounter* next = nullptr;
};
inline std::mutex live_counters_mutex;
inline LiveCounter* live_counters = nullptr;

inline LiveCounter* register_live_counter(LiveCounter* counter) {
  std::lock_guard lock(live_counters_mutex);
  counter->next = live_counters;
  live_counters = counter;
  return counter;
}

// The type's name for the report. On 64-bit targets every Vulkan handle is a distinct
// pointer type (vulkan_core.h, VK_USE_64_BIT_PTR_DEFINES); elsewhere the non-dispatchable
// ones are all uint64_t and share one name.
template <typename T>
inline constexpr const char* kVkTypeName = "VkObject";
#if VK_USE_64_BIT_PTR_DEFINES == 1
template <> inline constexpr const char* kVkTypeName<VkBuffer> = "VkBuffer";
template <> inline constexpr const char* kVkTypeName<VkDeviceMemory> = "VkDeviceMemory";
template <> inline constexpr const char* kVkTypeName<VkImage> = "VkImage";
template <> inline constexpr const char* kVkTypeName<VkImageView> = "VkImageView";
template <> inline constexpr const char* kVkTypeName<VkSampler> = "VkSampler";
template <> inline constexpr const char* kVkTypeName<VkShaderModule> = "VkShaderModule";
template <> inline constexpr const char* kVkTypeName<VkPipeline> = "VkPipeline";
template <> inline constexpr const char* kVkTypeName<VkPipelineLayout> = "VkPipelineLayout";
template <> inline constexpr const char* kVkTypeName<VkDescriptorSetLayout> = "VkDescriptorSetLayout";
template <> inline constexpr const char* kVkTypeName<VkDescriptorPool> = "VkDescriptorPool";
template <> inline constexpr const char* kVkTypeName<VkCommandPool> = "VkCommandPool";
template <> inline constexpr const char* kVkTypeName<VkFence> = "VkFence";
template <> inline constexpr const char* kVkTypeName<VkSemaphore> = "VkSemaphore";
template <> inline constexpr const char* kVkTypeName<VkQueryPool> = "VkQueryPool";
template <> inline constexpr const char* kVkTypeName<VkRenderPass> = "VkRenderPass";
template <> inline constexpr const char* kVkTypeName<VkFramebuffer> = "VkFramebuffer";
#endif

}  // namespace detail

// The live count of every Handle type constructed so far in this process (types whose
// count went back to 0 included), in no particular order.
inline std::vector<LiveCount> live_objects() {
  std::lock_guard lock(detail::live_counters_mutex);
  std::vector<LiveCount> out;
  for (const detail::LiveCounter* c = detail::live_counters; c != nullptr; c = c->next)
    out.push_back({c->type, c->live.load()});
  return out;
}

// The Vulkan objects owned by Handles now, all types together.
inline std::int64_t live_object_count() {
  std::int64_t total = 0;
  for (const LiveCount& c : live_objects()) total += c.live;
  return total;
}

template <typename T, void(VKAPI_PTR* Destroy)(VkDevice, T, const VkAllocationCallbacks*)>
class Handle {
 public:
  Handle() noexcept = default;
  Handle(VkDevice device, T object) noexcept : device_(device), object_(object) {
    if (object_ != T{VK_NULL_HANDLE}) counter().live.fetch_add(1, std::memory_order_relaxed);
  }
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
    if (object_ != T{VK_NULL_HANDLE}) {
      Destroy(device_, object_, nullptr);
      counter().live.fetch_sub(1, std::memory_order_relaxed);
    }
    object_ = T{VK_NULL_HANDLE};
  }
  // Gives up ownership without destroying; the caller must destroy the object (it is no
  // longer counted in live_objects()).
  [[nodiscard]] T release() noexcept {
    if (object_ != T{VK_NULL_HANDLE}) counter().live.fetch_sub(1, std::memory_order_relaxed);
    return std::exchange(object_, T{VK_NULL_HANDLE});
  }

 private:
  static detail::LiveCounter& counter() noexcept {
    static detail::LiveCounter c{detail::kVkTypeName<T>};
    static const detail::LiveCounter* registered = detail::register_live_counter(&c);
    (void)registered;
    return c;
  }

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
