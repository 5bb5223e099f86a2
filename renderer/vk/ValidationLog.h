// The messages of the validation layer, collected for tests and printed for people.
//
// A VK_EXT_debug_utils messenger (created by Context when the layer is loaded) calls
// ValidationLog::callback for every warning and error. Each message is appended to a
// thread-safe list, because the layer may report from any thread that calls Vulkan, and
// printed to stderr. Tests assert that the list is empty at the end (DESIGN.md §7,
// "validation-clean runs"); the renderer can print its length with --stats.
#pragma once

#include <vulkan/vulkan.h>

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace sss::vk {

struct ValidationMessage {
  VkDebugUtilsMessageSeverityFlagBitsEXT severity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  VkDebugUtilsMessageTypeFlagsEXT type = 0;
  std::string id_name;  // "VUID-VkBufferCreateInfo-size-00912", "SYNC-HAZARD-WRITE-AFTER-WRITE"
  int32_t id_number = 0;
  std::string text;
};

// Messages that are dropped by exact ID (and, for one, a condition on the text), each
// with its reason (ValidationLog.cpp: a few best-practices warnings that are design
// choices or a bug of layer 1.3.239). Every other message is recorded.
struct IgnoredMessage {
  const char* id_name;
  const char* reason;
  bool (*applies)(std::string_view text);  // nullptr: every message with this ID
};
extern const std::array<IgnoredMessage, 5> kIgnoredMessages;
bool is_ignored(std::string_view id_name, std::string_view text);

// "[vulkan validation error] VUID-...: text" — one line per message.
std::string to_string(const ValidationMessage& message);

class ValidationLog {
 public:
  // print: also write each message to stderr as it arrives.
  explicit ValidationLog(bool print = true) : print_(print) {}

  void record(ValidationMessage message);
  std::vector<ValidationMessage> messages() const;
  std::size_t size() const;
  void clear();
  // How many messages were dropped because their ID is in kIgnoredMessages.
  std::size_t ignored() const { return ignored_.load(); }

  // Chain this into VkInstanceCreateInfo::pNext (so that instance creation and
  // destruction are covered) and pass it to vkCreateDebugUtilsMessengerEXT. It selects
  // warnings and errors of the general, validation and performance kinds.
  static VkDebugUtilsMessengerCreateInfoEXT messenger_info(ValidationLog* log);

  static VKAPI_ATTR VkBool32 VKAPI_CALL callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                 VkDebugUtilsMessageTypeFlagsEXT type,
                                                 const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                 void* user_data);

 private:
  bool print_;
  mutable std::mutex mutex_;
  std::vector<ValidationMessage> messages_;
  std::atomic<std::size_t> ignored_{0};
};

}  // namespace sss::vk
