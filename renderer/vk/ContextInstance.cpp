// Context, part 1: the instance, the validation layer and the debug messenger.
#include "renderer/vk/Context.h"

#include "renderer/vk/Check.h"

#include <algorithm>
#include <cstdio>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace sss::vk {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool layer_installed(const char* name) {
  uint32_t count = 0;
  VK_CHECK(vkEnumerateInstanceLayerProperties(&count, nullptr));
  std::vector<VkLayerProperties> layers(count);
  VK_CHECK(vkEnumerateInstanceLayerProperties(&count, layers.data()));
  return std::any_of(layers.begin(), layers.begin() + count, [&](const VkLayerProperties& l) {
    return std::string_view(l.layerName) == name;
  });
}

// Instance extensions of the implementation and implicit layers (layer == nullptr), or
// those that one explicit layer adds.
std::vector<std::string> instance_extensions(const char* layer) {
  uint32_t count = 0;
  VK_CHECK(vkEnumerateInstanceExtensionProperties(layer, &count, nullptr));
  std::vector<VkExtensionProperties> props(count);
  VK_CHECK(vkEnumerateInstanceExtensionProperties(layer, &count, props.data()));
  std::vector<std::string> names;
  for (uint32_t i = 0; i < count; ++i) names.emplace_back(props[i].extensionName);
  return names;
}

bool contains(const std::vector<std::string>& names, std::string_view name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

void add_unique(std::vector<std::string>& names, std::string_view name) {
  if (!contains(names, name)) names.emplace_back(name);
}

std::vector<const char*> c_strings(const std::vector<std::string>& names) {
  std::vector<const char*> out;
  for (const std::string& n : names) out.push_back(n.c_str());
  return out;
}


// The loader must offer Vulkan 1.3.
void check_loader_version() {
  uint32_t loader_version = 0;
  VK_CHECK(vkEnumerateInstanceVersion(&loader_version));
  if (loader_version < VK_API_VERSION_1_3) {
    throw VulkanError(VK_ERROR_INCOMPATIBLE_DRIVER,
                      "the Vulkan loader supports version " +
                          std::to_string(VK_API_VERSION_MAJOR(loader_version)) + "." +
                          std::to_string(VK_API_VERSION_MINOR(loader_version)) +
                          "; the renderer needs 1.3");
  }
}

// Whether the validation layer is used: validation asked for and the layer installed. A
// validation run (SSS_VALIDATION_CHECKS) without the layer throws; otherwise its absence
// is warned about once.
bool use_validation_layer(const ContextOptions& options, const std::optional<ValidationChecks>& run_checks) {
  bool use_layer = false;
  if (options.enable_validation) {
    use_layer = layer_installed(kValidationLayer);
    if (!use_layer && run_checks) {
      throw VulkanError(VK_ERROR_LAYER_NOT_PRESENT,
                        std::string("SSS_VALIDATION_CHECKS=") +
                            std::string(validation_checks_name(*run_checks)) + " asks for " +
                            kValidationLayer +
                            ", which is not installed (Debian: vulkan-validationlayers)");
    }
    if (!use_layer) {
      static std::once_flag once;
      std::call_once(once, [] {
        std::fprintf(stderr,
                     "warning: validation requested but %s is not installed "
                     "(Debian: vulkan-validationlayers); running without it\n",
                     kValidationLayer);
      });
    }
  }
  return use_layer;
}

// The options' instance extensions (each one offered, else VulkanError), and debug utils
// when offered (*debug_utils_offered).
std::vector<std::string> instance_extension_list(const ContextOptions& options,
                                                 const std::vector<std::string>& available,
                                                 const std::vector<std::string>& from_layer,
                                                 bool* debug_utils_offered) {
  const auto offered = [&](std::string_view name) {
    return contains(available, name) || contains(from_layer, name);
  };
  std::vector<std::string> extensions;
  for (const std::string& name : options.instance_extensions) {
    if (!offered(name)) {
      throw VulkanError(VK_ERROR_EXTENSION_NOT_PRESENT,
                        "the Vulkan instance extension " + name + " is not available");
    }
    add_unique(extensions, name);
  }
  const bool debug_utils = offered(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (debug_utils) add_unique(extensions, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

  *debug_utils_offered = debug_utils;
  return extensions;
}

}  // namespace

void Context::create_instance(const ContextOptions& options) {
  check_loader_version();

  // A validation run (SSS_VALIDATION_CHECKS set) names the checks, replacing the
  // options' own, and must not run without the layer.
  const std::optional<ValidationChecks> run_checks =
      options.enable_validation ? validation_checks_from_environment() : std::nullopt;
  bool sync_validation = options.sync_validation;
  bool best_practices = options.best_practices;
  if (run_checks) {
    sync_validation = *run_checks == ValidationChecks::Sync;
    best_practices = *run_checks == ValidationChecks::BestPractices;
  }
  validation_checks_ = best_practices    ? ValidationChecks::BestPractices
                       : sync_validation ? ValidationChecks::Sync
                                         : ValidationChecks::Core;
  const bool use_layer = use_validation_layer(options, run_checks);
  const std::vector<std::string> available = instance_extensions(nullptr);
  const std::vector<std::string> from_layer =
      use_layer ? instance_extensions(kValidationLayer) : std::vector<std::string>{};
  bool debug_utils = false;
  std::vector<std::string> extensions = instance_extension_list(options, available, from_layer, &debug_utils);

  // Synchronization validation and best practices are off by default in the layer.
  // Layer 1.3.239 (Debian 12) takes them from VkValidationFeaturesEXT in the instance's
  // pNext chain, or from VK_LAYER_ENABLES=VK_VALIDATION_FEATURE_ENABLE_..._EXT in the
  // environment; VK_EXT_layer_settings and the VK_KHRONOS_VALIDATION_* variables came
  // later. Verified on lavapipe (tests/vk/ValidationTest.cpp): with the struct below, a
  // compute pass sampling an image that the previous pass wrote, with no barrier, is
  // reported as SYNC-HAZARD-READ-AFTER-WRITE; without the struct it is not; with
  // VK_LAYER_ENABLES set instead, it is. The struct belongs to VK_EXT_validation_features,
  // which the layer itself offers, so that extension is enabled with it.
  std::vector<VkValidationFeatureEnableEXT> enables;
  if (use_layer && sync_validation) {
    enables.push_back(VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT);
  }
  if (use_layer && best_practices) {
    enables.push_back(VK_VALIDATION_FEATURE_ENABLE_BEST_PRACTICES_EXT);
  }
  VkDebugUtilsMessengerCreateInfoEXT messenger_info = ValidationLog::messenger_info(log_.get());
  VkValidationFeaturesEXT features{};
  features.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT;
  features.enabledValidationFeatureCount = static_cast<uint32_t>(enables.size());
  features.pEnabledValidationFeatures = enables.data();

  const void* chain = nullptr;
  if (use_layer && debug_utils) {
    messenger_info.pNext = chain;  // reports during vkCreateInstance / vkDestroyInstance
    chain = &messenger_info;
  }
  if (!enables.empty() && contains(from_layer, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME)) {
    add_unique(extensions, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    features.pNext = chain;
    chain = &features;
  }

  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = options.application_name.c_str();
  app.applicationVersion = VK_MAKE_API_VERSION(0, 0, 1, 0);
  app.pEngineName = "sss";
  app.engineVersion = VK_MAKE_API_VERSION(0, 0, 1, 0);
  app.apiVersion = VK_API_VERSION_1_3;

  const std::vector<const char*> extension_names = c_strings(extensions);
  const char* layers[] = {kValidationLayer};
  VkInstanceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  info.pNext = chain;
  info.pApplicationInfo = &app;
  info.enabledLayerCount = use_layer ? 1u : 0u;
  info.ppEnabledLayerNames = layers;
  info.enabledExtensionCount = static_cast<uint32_t>(extension_names.size());
  info.ppEnabledExtensionNames = extension_names.data();
  VK_CHECK(vkCreateInstance(&info, nullptr, &core_.instance));

  if (debug_utils) load_debug_utils(use_layer, messenger_info);
}

void Context::load_debug_utils(bool use_layer, VkDebugUtilsMessengerCreateInfoEXT& messenger_info) {
  const auto load = [&](const char* name) { return vkGetInstanceProcAddr(core_.instance, name); };
  cmd_begin_label_ =
      reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(load("vkCmdBeginDebugUtilsLabelEXT"));
  cmd_end_label_ =
      reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(load("vkCmdEndDebugUtilsLabelEXT"));
  set_object_name_ =
      reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(load("vkSetDebugUtilsObjectNameEXT"));
  if (!use_layer) return;
  auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
      load("vkCreateDebugUtilsMessengerEXT"));
  core_.destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
      load("vkDestroyDebugUtilsMessengerEXT"));
  if (create != nullptr && core_.destroy_messenger != nullptr) {
    messenger_info.pNext = nullptr;
    VK_CHECK(create(core_.instance, &messenger_info, nullptr, &core_.messenger));
    validation_enabled_ = true;
  }
}

}  // namespace sss::vk
