// Choosing the physical device: a discrete GPU over an integrated one over a virtual one
// over a CPU implementation (lavapipe), unless the user names one (`--device NAME`, a
// case-insensitive substring of the device name).
//
// Every device is examined against the same requirements: Vulkan 1.3, the features
// dynamicRendering and synchronization2, the requested device extensions, and one queue
// family with graphics and compute (and presentation, when there is a surface). A device
// that fails says why, so that the error for "--device X" names the missing feature, and
// the error for a name that matches nothing lists every device.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sss::vk {

struct DeviceRequirements {
  std::vector<std::string> extensions;    // device extensions (VK_KHR_swapchain, ...)
  VkSurfaceKHR surface = VK_NULL_HANDLE;  // if set, the queue must present to it
};

struct DeviceCandidate {
  VkPhysicalDevice handle = VK_NULL_HANDLE;
  std::string name;
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  uint32_t api_version = 0;
  uint32_t queue_family = UINT32_MAX;  // graphics + compute (+ present), when usable
  std::string unsuitable;              // empty when usable, otherwise the reason

  bool usable() const { return unsuitable.empty(); }
};

// "discrete GPU", "integrated GPU", "virtual GPU", "CPU", "other".
std::string_view device_type_name(VkPhysicalDeviceType type);
// Higher is preferred: discrete 4, integrated 3, virtual 2, CPU 1, other 0.
int device_type_rank(VkPhysicalDeviceType type);
// Case-insensitive substring match; an empty pattern matches every name.
bool name_matches(std::string_view device_name, std::string_view pattern);
// "llvmpipe (LLVM 15.0.6, 256 bits) [CPU, Vulkan 1.3.230]", plus the reason if unusable.
std::string describe(const DeviceCandidate& candidate);

// All devices the loader reports, in its order, each examined against the requirements.
std::vector<DeviceCandidate> examine_devices(VkInstance instance,
                                             const DeviceRequirements& requirements);

// The best usable device whose name matches `name` (any device when empty). Throws
// VulkanError (VK_ERROR_INITIALIZATION_FAILED) when there is none: the message lists
// every device with its type and, for unusable ones, the reason.
const DeviceCandidate& choose_device(const std::vector<DeviceCandidate>& candidates,
                                     std::string_view name);

}  // namespace sss::vk
