#include "renderer/vk/ValidationLog.h"

#include <cstdio>
#include <utility>

namespace sss::vk {

std::string to_string(const ValidationMessage& message) {
  std::string s = "[vulkan ";
  if (message.type & VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT) {
    s += "performance ";
  } else if (message.type & VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT) {
    s += "validation ";
  }
  s += message.severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error] " : "warning] ";
  if (!message.id_name.empty()) s += message.id_name + ": ";
  s += message.text;
  return s;
}

void ValidationLog::record(ValidationMessage message) {
  if (print_) {
    // One fprintf per message so that lines from several threads do not interleave.
    std::fprintf(stderr, "%s\n", to_string(message).c_str());
  }
  std::lock_guard lock(mutex_);
  messages_.push_back(std::move(message));
}

std::vector<ValidationMessage> ValidationLog::messages() const {
  std::lock_guard lock(mutex_);
  return messages_;
}

std::size_t ValidationLog::size() const {
  std::lock_guard lock(mutex_);
  return messages_.size();
}

void ValidationLog::clear() {
  std::lock_guard lock(mutex_);
  messages_.clear();
}

VkDebugUtilsMessengerCreateInfoEXT ValidationLog::messenger_info(ValidationLog* log) {
  VkDebugUtilsMessengerCreateInfoEXT info{};
  info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                         VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = &ValidationLog::callback;
  info.pUserData = log;
  return info;
}

VKAPI_ATTR VkBool32 VKAPI_CALL ValidationLog::callback(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT type,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user_data) {
  auto* log = static_cast<ValidationLog*>(user_data);
  if (log == nullptr || data == nullptr) return VK_FALSE;
  // The callback must not throw into the layer: a failed allocation loses the message.
  try {
    ValidationMessage message;
    message.severity = severity;
    message.type = type;
    if (data->pMessageIdName != nullptr) message.id_name = data->pMessageIdName;
    message.id_number = data->messageIdNumber;
    if (data->pMessage != nullptr) message.text = data->pMessage;
    log->record(std::move(message));
  } catch (...) {
  }
  // VK_FALSE: the call that triggered the message proceeds (the spec reserves VK_TRUE
  // for layer development).
  return VK_FALSE;
}

}  // namespace sss::vk
