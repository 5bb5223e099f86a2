#include "renderer/vk/ValidationLog.h"

#include <cstdio>
#include <string_view>
#include <vector>
#include <utility>

namespace sss::vk {

namespace {

// "A|B|C" -> {"A", "B", "C"}.
std::vector<std::string_view> split_bits(std::string_view text) {
  std::vector<std::string_view> bits;
  while (!text.empty()) {
    const std::size_t bar = text.find('|');
    bits.push_back(text.substr(0, bar));
    if (bar == std::string_view::npos) break;
    text.remove_prefix(bar + 1);
  }
  return bits;
}

// Layer 1.3.239's ImageBarrierAccessLayout table predates synchronization2 and does not
// know that VK_ACCESS_2_SHADER_SAMPLED_READ_BIT / _STORAGE_READ_BIT are parts of
// VK_ACCESS_2_SHADER_READ_BIT (KhronosGroup/Vulkan-ValidationLayers#5429, reported
// against 1.3.239). True when every access the message names is allowed or is such a
// part of an allowed SHADER_READ; any other access (MEMORY_WRITE into a read-only
// layout, say) is still reported. The text reads "<bits>: accessMask is <call>, but for
// layout <layout> expected accessMask are <bits>."
bool only_sync2_shader_read_parts(std::string_view text) {
  const std::size_t colon = text.find(": accessMask is ");
  const std::size_t expected_at = text.find("expected accessMask are ");
  if (colon == std::string_view::npos || expected_at == std::string_view::npos) return false;
  std::size_t start = text.rfind("| ", colon);
  start = start == std::string_view::npos ? 0 : start + 2;
  std::string_view allowed = text.substr(expected_at + 24);
  if (const std::size_t dot = allowed.find('.'); dot != std::string_view::npos) {
    allowed = allowed.substr(0, dot);
  }
  const std::vector<std::string_view> allowed_bits = split_bits(allowed);
  const auto is_allowed = [&](std::string_view bit) {
    for (std::string_view a : allowed_bits) {
      if (a == bit) return true;
    }
    return false;
  };
  for (std::string_view bit : split_bits(text.substr(start, colon - start))) {
    const bool shader_read_part = bit == "VK_ACCESS_2_SHADER_SAMPLED_READ_BIT" ||
                                  bit == "VK_ACCESS_2_SHADER_STORAGE_READ_BIT";
    if (!is_allowed(bit) && !(shader_read_part && is_allowed("VK_ACCESS_2_SHADER_READ_BIT"))) {
      return false;
    }
  }
  return true;
}

}  // namespace

// Best-practices messages that are not defects of this renderer, by exact message ID
// (found on lavapipe with layer 1.3.239, SSS_VALIDATION_CHECKS=best-practices; see
// scripts/test-validation.sh), with a condition on the text where only some of an ID's
// messages are false. Everything else the layer says is kept and fails tests.
const std::array<IgnoredMessage, 5> kIgnoredMessages = {{
    {"UNASSIGNED-BestPractices-vkCreateInstance-specialuse-extension-debugging",
     "VK_EXT_debug_utils is enabled only to receive these messages and name objects", nullptr},
    {"UNASSIGNED-BestPractices-vkAllocateMemory-small-allocation",
     "design: one dedicated block per resource, no sub-allocator (renderer/vk/Memory.h)",
     nullptr},
    {"UNASSIGNED-BestPractices-vkBindMemory-small-dedicated-allocation",
     "the same design choice, reported again when the small block is bound", nullptr},
    {"UNASSIGNED-BestPractices-pipeline-stage-flags",
     "ALL_COMMANDS is deliberate in one-shot copies and at the start of a frame (renderer/vk/"
     "Barrier.h kAllCommands); precise stages would only help a real GPU",
     nullptr},
    {"UNASSIGNED-BestPractices-ImageBarrierAccessLayout",
     "only when every access named is allowed in the layout or is a synchronization2 part of "
     "an allowed SHADER_READ (layer bug, Vulkan-ValidationLayers#5429)",
     &only_sync2_shader_read_parts},
}};

bool is_ignored(std::string_view id_name, std::string_view text) {
  for (const IgnoredMessage& m : kIgnoredMessages) {
    if (id_name == m.id_name && (m.applies == nullptr || m.applies(text))) return true;
  }
  return false;
}

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
    if (is_ignored(message.id_name, data->pMessage != nullptr ? data->pMessage : "")) {
      log->ignored_.fetch_add(1);
      return VK_FALSE;
    }
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
