#include "renderer/vk/Context.h"

#include "renderer/vk/Check.h"

#include <string>
#include <vector>

namespace sss::vk {

namespace {
std::vector<const char*> c_strings(const std::vector<std::string>& names) {
  std::vector<const char*> out;
  for (const std::string& n : names) out.push_back(n.c_str());
  return out;
}
}  // namespace

Context::Core::~Core() {
  if (device != VK_NULL_HANDLE) vkDestroyDevice(device, nullptr);
  if (surface != VK_NULL_HANDLE) vkDestroySurfaceKHR(instance, surface, nullptr);
  if (messenger != VK_NULL_HANDLE) destroy_messenger(instance, messenger, nullptr);
  if (instance != VK_NULL_HANDLE) vkDestroyInstance(instance, nullptr);
}

Context::Context(const ContextOptions& options)
    : log_(options.validation_log ? options.validation_log
                                  : std::make_shared<ValidationLog>(options.print_validation)),
      fail_allocation_after_(options.fail_allocation_after
                                 ? options.fail_allocation_after
                                 : fail_allocation_after_from_environment()) {
  create_instance(options);
  if (options.create_surface) {
    core_.surface = options.create_surface(core_.instance);
    if (core_.surface == VK_NULL_HANDLE) {
      throw VulkanError(VK_ERROR_INITIALIZATION_FAILED, "create_surface returned no surface");
    }
  }
  create_device(options);
}

Context::~Context() {
  // Nothing may be executing when the device goes; Core's destructor does the rest.
  if (core_.device != VK_NULL_HANDLE) vkDeviceWaitIdle(core_.device);
}

void Context::create_device(const ContextOptions& options) {
  DeviceRequirements requirements;
  requirements.extensions = options.device_extensions;
  requirements.surface = core_.surface;
  const std::vector<DeviceCandidate> candidates = examine_devices(core_.instance, requirements);
  const DeviceCandidate& chosen = choose_device(candidates, options.device_name);
  physical_device_ = chosen.handle;
  queue_family_ = chosen.queue_family;

  VkPhysicalDeviceVulkan13Properties props13{};
  props13.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_PROPERTIES;
  VkPhysicalDeviceVulkan11Properties props11{};
  props11.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES;
  props11.pNext = &props13;
  VkPhysicalDeviceProperties2 props{};
  props.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
  props.pNext = &props11;
  vkGetPhysicalDeviceProperties2(physical_device_, &props);
  uint32_t family_count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &family_count, nullptr);
  std::vector<VkQueueFamilyProperties> families(family_count);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &family_count, families.data());
  VkPhysicalDeviceFeatures supported{};
  vkGetPhysicalDeviceFeatures(physical_device_, &supported);

  info_.name = props.properties.deviceName;
  info_.type = props.properties.deviceType;
  info_.api_version = props.properties.apiVersion;
  info_.driver_version = props.properties.driverVersion;
  info_.vendor_id = props.properties.vendorID;
  info_.device_id = props.properties.deviceID;
  info_.limits = props.properties.limits;
  info_.timestamp_period = props.properties.limits.timestampPeriod;
  info_.timestamp_valid_bits = families[queue_family_].timestampValidBits;
  info_.max_memory_allocation_size = props11.maxMemoryAllocationSize;
  info_.max_buffer_size = props13.maxBufferSize;
  vkGetPhysicalDeviceMemoryProperties(physical_device_, &info_.memory);
  info_.sampler_anisotropy = supported.samplerAnisotropy == VK_TRUE;
  info_.storage_image_write_without_format =
      supported.shaderStorageImageWriteWithoutFormat == VK_TRUE;

  VkPhysicalDeviceVulkan13Features features13{};
  features13.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES;
  features13.dynamicRendering = VK_TRUE;
  features13.synchronization2 = VK_TRUE;
  features13.maintenance4 = VK_TRUE;  // LocalSizeId in glslang's SPIR-V 1.6
  VkPhysicalDeviceFeatures2 features{};
  features.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
  features.pNext = &features13;
  features.features.samplerAnisotropy = supported.samplerAnisotropy;
  features.features.shaderStorageImageWriteWithoutFormat =
      supported.shaderStorageImageWriteWithoutFormat;
  // Arrays of samplers indexed by a push constant (material textures, the texture path's
  // atlases): dynamically uniform indexing.
  features.features.shaderSampledImageArrayDynamicIndexing =
      supported.shaderSampledImageArrayDynamicIndexing;

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{};
  queue_info.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  queue_info.queueFamilyIndex = queue_family_;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;

  const std::vector<const char*> extension_names = c_strings(options.device_extensions);
  VkDeviceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  info.pNext = &features;
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue_info;
  info.enabledExtensionCount = static_cast<uint32_t>(extension_names.size());
  info.ppEnabledExtensionNames = extension_names.data();
  VK_CHECK(vkCreateDevice(physical_device_, &info, nullptr, &core_.device));
  vkGetDeviceQueue(core_.device, queue_family_, 0, &queue_);
  set_object_name(VK_OBJECT_TYPE_QUEUE, queue_, "main queue");
}

void Context::submit(std::span<const VkSubmitInfo2> submits, VkFence fence) const {
  std::lock_guard lock(queue_mutex_);
  VK_CHECK(vkQueueSubmit2(queue_, static_cast<uint32_t>(submits.size()), submits.data(), fence));
}

void Context::wait_idle() const {
  std::lock_guard lock(queue_mutex_);  // vkDeviceWaitIdle synchronises with the queue too
  VK_CHECK(vkDeviceWaitIdle(core_.device));
}

void Context::begin_label(VkCommandBuffer cmd, std::string_view name) const {
  if (cmd_begin_label_ == nullptr) return;
  const std::string text(name);
  VkDebugUtilsLabelEXT label{};
  label.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT;
  label.pLabelName = text.c_str();
  cmd_begin_label_(cmd, &label);
}

void Context::end_label(VkCommandBuffer cmd) const {
  if (cmd_end_label_ != nullptr) cmd_end_label_(cmd);
}

void Context::set_object_name(VkObjectType type, uint64_t handle, std::string_view name) const {
  if (set_object_name_ == nullptr || handle == 0) return;
  const std::string text(name);
  VkDebugUtilsObjectNameInfoEXT info{};
  info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT;
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = text.c_str();
  VK_CHECK(set_object_name_(core_.device, &info));
}

}  // namespace sss::vk
