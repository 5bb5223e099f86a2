// The Vulkan instance, the chosen physical device, the logical device and its one queue
// (graphics + compute, and present when there is a surface). Everything else in
// renderer/vk is created from a Context and must be destroyed before it.
//
// Headless use needs no extension. The viewer adds its window-system instance extensions,
// VK_KHR_swapchain, and a create_surface callback (the queue is then chosen to present).
//
// Validation: with enable_validation and the Khronos layer installed, the layer is loaded
// with the requested extra checks, and every warning and error it reports is kept in a
// thread-safe list (validation_messages()) and printed to stderr. Without the layer the
// Context says so once on stderr and runs without it (validation_enabled() is false),
// except in a validation run: when SSS_VALIDATION_CHECKS is set (Environment.h) the
// checks it names replace sync_validation / best_practices, and a missing layer is an
// error (VK_ERROR_LAYER_NOT_PRESENT), so that such a run cannot pass without checking.
//
// Allocation failures can be simulated (ContextOptions::fail_allocation_after, or
// SSS_FAIL_ALLOCATION_AFTER): allocate_memory (Memory.cpp) asks the Context before each
// vkAllocateMemory and counts the successful ones here.
#pragma once

#include "renderer/vk/DeviceSelection.h"
#include "renderer/vk/Environment.h"
#include "renderer/vk/ValidationLog.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sss::vk {

struct ContextOptions {
  bool enable_validation = false;  // load VK_LAYER_KHRONOS_validation if installed
  bool sync_validation = false;    // + synchronization validation (hazards, layouts)
  bool best_practices = false;     // + best-practices warnings (noisy on lavapipe)
  bool print_validation = true;    // echo each message on stderr as it arrives
  // Where messages go; the Context makes its own when null. A caller that keeps the log
  // also sees what the layer reports while the Context is destroyed (leaked objects).
  std::shared_ptr<ValidationLog> validation_log;
  std::string device_name;                       // case-insensitive substring (`--device NAME`)
  std::vector<std::string> instance_extensions;  // e.g. from glfwGetRequiredInstanceExtensions
  std::vector<std::string> device_extensions;    // e.g. VK_KHR_swapchain
  // Called once the instance exists; the returned surface is owned by the Context.
  std::function<VkSurfaceKHR(VkInstance)> create_surface;
  std::string application_name = "sss";
  // After this many successful device-memory allocations every further one fails with
  // VK_ERROR_OUT_OF_DEVICE_MEMORY (a simulated failure, said so in the error). Unset:
  // SSS_FAIL_ALLOCATION_AFTER decides (no limit when that is unset too).
  std::optional<uint64_t> fail_allocation_after;
};

// What the renderer may need to know about the device it runs on.
struct DeviceInfo {
  std::string name;
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  uint32_t api_version = 0;
  uint32_t driver_version = 0;
  uint32_t vendor_id = 0;
  uint32_t device_id = 0;
  VkPhysicalDeviceLimits limits{};
  float timestamp_period = 0.0f;      // nanoseconds per timestamp tick
  uint32_t timestamp_valid_bits = 0;  // of the queue's family; 0: no timestamps
  VkDeviceSize max_memory_allocation_size = 0;
  VkDeviceSize max_buffer_size = 0;
  VkPhysicalDeviceMemoryProperties memory{};
  // Optional features, enabled when the device has them.
  bool sampler_anisotropy = false;
  bool storage_image_write_without_format = false;
};

class Context {
 public:
  explicit Context(const ContextOptions& options = {});
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  Context(Context&&) = delete;
  Context& operator=(Context&&) = delete;

  VkInstance instance() const { return core_.instance; }
  VkPhysicalDevice physical_device() const { return physical_device_; }
  VkDevice device() const { return core_.device; }
  VkQueue queue() const { return queue_; }
  uint32_t queue_family() const { return queue_family_; }
  VkSurfaceKHR surface() const { return core_.surface; }
  const DeviceInfo& info() const { return info_; }

  // True when the validation layer is loaded and reporting into this Context.
  bool validation_enabled() const { return validation_enabled_; }
  // The checks requested of the layer (what SSS_VALIDATION_CHECKS or the options asked
  // for; meaningful when validation_enabled()).
  ValidationChecks validation_checks() const { return validation_checks_; }

  // Simulated allocation failure (see ContextOptions::fail_allocation_after). Only
  // allocate_memory calls the last two.
  std::optional<uint64_t> fail_allocation_after() const { return fail_allocation_after_; }
  uint64_t successful_allocations() const { return successful_allocations_.load(); }
  bool allocation_must_fail() const {
    return fail_allocation_after_ && successful_allocations_.load() >= *fail_allocation_after_;
  }
  void count_successful_allocation() const { successful_allocations_.fetch_add(1); }
  std::vector<ValidationMessage> validation_messages() const { return log_->messages(); }
  std::size_t validation_message_count() const { return log_->size(); }
  void clear_validation_messages() { log_->clear(); }

  // vkQueueSubmit2 on the queue, serialised (a VkQueue is externally synchronised).
  void submit(std::span<const VkSubmitInfo2> submits, VkFence fence) const;
  void wait_idle() const;

  // Debug labels and names for tools (RenderDoc, validation messages); no-ops when
  // VK_EXT_debug_utils is not available.
  void begin_label(VkCommandBuffer cmd, std::string_view name) const;
  void end_label(VkCommandBuffer cmd) const;
  void set_object_name(VkObjectType type, uint64_t handle, std::string_view name) const;
  template <typename T>
  void set_object_name(VkObjectType type, T handle, std::string_view name) const {
    set_object_name(type, reinterpret_cast<uint64_t>(handle), name);
  }

 private:
  // Instance-level objects, destroyed in reverse order of creation even when the
  // constructor throws half-way.
  struct Core {
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    PFN_vkDestroyDebugUtilsMessengerEXT destroy_messenger = nullptr;
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    Core() = default;
    Core(const Core&) = delete;
    Core& operator=(const Core&) = delete;
    ~Core();
  };

  void create_instance(const ContextOptions& options);
  // The debug-utils entry points, and the validation messenger when the layer is used.
  void load_debug_utils(bool use_layer, VkDebugUtilsMessengerCreateInfoEXT& messenger_info);
  void create_device(const ContextOptions& options);

  std::shared_ptr<ValidationLog> log_;  // outlives core_: the layer reports until the end
  Core core_;
  VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queue_family_ = 0;
  DeviceInfo info_;
  bool validation_enabled_ = false;
  ValidationChecks validation_checks_ = ValidationChecks::Core;
  std::optional<uint64_t> fail_allocation_after_;
  mutable std::atomic<uint64_t> successful_allocations_{0};
  PFN_vkCmdBeginDebugUtilsLabelEXT cmd_begin_label_ = nullptr;
  PFN_vkCmdEndDebugUtilsLabelEXT cmd_end_label_ = nullptr;
  PFN_vkSetDebugUtilsObjectNameEXT set_object_name_ = nullptr;
  mutable std::mutex queue_mutex_;
};

}  // namespace sss::vk
