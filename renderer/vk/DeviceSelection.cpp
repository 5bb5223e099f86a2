#include "renderer/vk/DeviceSelection.h"

#include "renderer/vk/Check.h"

#include <algorithm>
#include <cctype>

namespace sss::vk {

namespace {

// The Vulkan 1.3 features the renderer cannot do without, by name. maintenance4 is
// required of every 1.3 device; it is listed because glslang's SPIR-V 1.6 output
// declares workgroup sizes with LocalSizeId, which needs it enabled.
struct RequiredFeature {
  const char* name;
  VkBool32 VkPhysicalDeviceVulkan13Features::*member;
};
constexpr RequiredFeature kRequiredFeatures[] = {
    {"dynamicRendering", &VkPhysicalDeviceVulkan13Features::dynamicRendering},
    {"synchronization2", &VkPhysicalDeviceVulkan13Features::synchronization2},
    {"maintenance4", &VkPhysicalDeviceVulkan13Features::maintenance4},
};

std::string version_string(uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
         "." + std::to_string(VK_API_VERSION_PATCH(v));
}

// Empty when the device meets the requirements; otherwise the first reason it does not.
std::string check(DeviceCandidate& c, const DeviceRequirements& req) {
  if (c.api_version < VK_API_VERSION_1_3) {
    return "supports Vulkan " + version_string(c.api_version) + ", the renderer needs 1.3";
  }

  uint32_t count = 0;
  VK_CHECK(vkEnumerateDeviceExtensionProperties(c.handle, nullptr, &count, nullptr));
  std::vector<VkExtensionProperties> extensions(count);
  VK_CHECK(vkEnumerateDeviceExtensionProperties(c.handle, nullptr, &count, extensions.data()));
  for (const std::string& wanted : req.extensions) {
    const bool found = std::any_of(extensions.begin(), extensions.end(),
                                   [&](const auto& e) { return wanted == e.extensionName; });
    if (!found) return "lacks the device extension " + wanted;
  }

  VkPhysicalDeviceVulkan13Features f13{};
  f13.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES;
  VkPhysicalDeviceFeatures2 features{};
  features.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
  features.pNext = &f13;
  vkGetPhysicalDeviceFeatures2(c.handle, &features);
  for (const RequiredFeature& feature : kRequiredFeatures) {
    if (f13.*feature.member != VK_TRUE) {
      return std::string("lacks the Vulkan 1.3 feature ") + feature.name;
    }
  }

  vkGetPhysicalDeviceQueueFamilyProperties(c.handle, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(c.handle, &count, families.data());
  constexpr VkQueueFlags kNeeded = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  bool any_graphics = false;
  for (uint32_t i = 0; i < count; ++i) {
    if ((families[i].queueFlags & kNeeded) != kNeeded || families[i].queueCount == 0) continue;
    any_graphics = true;
    if (req.surface != VK_NULL_HANDLE) {
      VkBool32 present = VK_FALSE;
      VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(c.handle, i, req.surface, &present));
      if (present != VK_TRUE) continue;
    }
    c.queue_family = i;
    return {};
  }
  return any_graphics ? "has no graphics and compute queue that can present to the surface"
                      : "has no queue family with both graphics and compute";
}

}  // namespace

std::string_view device_type_name(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
  }
}

int device_type_rank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
  }
}

bool name_matches(std::string_view device_name, std::string_view pattern) {
  const auto lower_equal = [](char a, char b) {
    return std::tolower(static_cast<unsigned char>(a)) ==
           std::tolower(static_cast<unsigned char>(b));
  };
  return std::search(device_name.begin(), device_name.end(), pattern.begin(), pattern.end(),
                     lower_equal) != device_name.end();
}

std::string describe(const DeviceCandidate& c) {
  std::string s = c.name + " [" + std::string(device_type_name(c.type)) + ", Vulkan " +
                  version_string(c.api_version) + "]";
  if (!c.usable()) s += ": " + c.unsuitable;
  return s;
}

std::vector<DeviceCandidate> examine_devices(VkInstance instance,
                                             const DeviceRequirements& requirements) {
  uint32_t count = 0;
  VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
  devices.resize(count);

  std::vector<DeviceCandidate> candidates;
  for (VkPhysicalDevice device : devices) {
    VkPhysicalDeviceProperties props{};
    vkGetPhysicalDeviceProperties(device, &props);
    DeviceCandidate c;
    c.handle = device;
    c.name = props.deviceName;
    c.type = props.deviceType;
    c.api_version = props.apiVersion;
    c.unsuitable = check(c, requirements);
    if (!c.usable()) c.queue_family = UINT32_MAX;
    candidates.push_back(std::move(c));
  }
  return candidates;
}

const DeviceCandidate& choose_device(const std::vector<DeviceCandidate>& candidates,
                                     std::string_view name) {
  const DeviceCandidate* best = nullptr;
  bool any_match = false;
  for (const DeviceCandidate& c : candidates) {
    if (!name_matches(c.name, name)) continue;
    any_match = true;
    // Strictly greater: among equals the loader's first device wins.
    if (c.usable() &&
        (best == nullptr || device_type_rank(c.type) > device_type_rank(best->type))) {
      best = &c;
    }
  }
  if (best != nullptr) return *best;

  std::string message;
  if (candidates.empty()) {
    message = "no Vulkan device found (is a Vulkan driver such as mesa-vulkan-drivers installed?)";
  } else {
    if (!any_match) {
      message = "no Vulkan device matches \"" + std::string(name) + "\"";
    } else if (name.empty()) {
      message = "no Vulkan device can run the renderer";
    } else {
      message = "no device matching \"" + std::string(name) + "\" can run the renderer";
    }
    message += "; available devices:";
    for (const DeviceCandidate& c : candidates) message += "\n  " + describe(c);
  }
  throw VulkanError(VK_ERROR_INITIALIZATION_FAILED, message);
}

}  // namespace sss::vk
