#include "renderer/vk/Check.h"

#include <string>

namespace sss::vk {

std::string result_name(VkResult result) {
  switch (result) {
#define SSS_VK_RESULT_CASE(name) \
  case name: return #name;
    SSS_VK_RESULT_CASE(VK_SUCCESS)
    SSS_VK_RESULT_CASE(VK_NOT_READY)
    SSS_VK_RESULT_CASE(VK_TIMEOUT)
    SSS_VK_RESULT_CASE(VK_EVENT_SET)
    SSS_VK_RESULT_CASE(VK_EVENT_RESET)
    SSS_VK_RESULT_CASE(VK_INCOMPLETE)
    SSS_VK_RESULT_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    SSS_VK_RESULT_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    SSS_VK_RESULT_CASE(VK_ERROR_INITIALIZATION_FAILED)
    SSS_VK_RESULT_CASE(VK_ERROR_DEVICE_LOST)
    SSS_VK_RESULT_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    SSS_VK_RESULT_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    SSS_VK_RESULT_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    SSS_VK_RESULT_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    SSS_VK_RESULT_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    SSS_VK_RESULT_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    SSS_VK_RESULT_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    SSS_VK_RESULT_CASE(VK_ERROR_FRAGMENTED_POOL)
    SSS_VK_RESULT_CASE(VK_ERROR_UNKNOWN)
    SSS_VK_RESULT_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
    SSS_VK_RESULT_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE)
    SSS_VK_RESULT_CASE(VK_ERROR_FRAGMENTATION)
    SSS_VK_RESULT_CASE(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
    SSS_VK_RESULT_CASE(VK_PIPELINE_COMPILE_REQUIRED)
    SSS_VK_RESULT_CASE(VK_ERROR_SURFACE_LOST_KHR)
    SSS_VK_RESULT_CASE(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
    SSS_VK_RESULT_CASE(VK_SUBOPTIMAL_KHR)
    SSS_VK_RESULT_CASE(VK_ERROR_OUT_OF_DATE_KHR)
    SSS_VK_RESULT_CASE(VK_ERROR_INCOMPATIBLE_DISPLAY_KHR)
    SSS_VK_RESULT_CASE(VK_ERROR_VALIDATION_FAILED_EXT)
    SSS_VK_RESULT_CASE(VK_ERROR_INVALID_SHADER_NV)
    SSS_VK_RESULT_CASE(VK_ERROR_INVALID_DRM_FORMAT_MODIFIER_PLANE_LAYOUT_EXT)
    SSS_VK_RESULT_CASE(VK_ERROR_NOT_PERMITTED_KHR)
    SSS_VK_RESULT_CASE(VK_ERROR_FULL_SCREEN_EXCLUSIVE_MODE_LOST_EXT)
    SSS_VK_RESULT_CASE(VK_THREAD_IDLE_KHR)
    SSS_VK_RESULT_CASE(VK_THREAD_DONE_KHR)
    SSS_VK_RESULT_CASE(VK_OPERATION_DEFERRED_KHR)
    SSS_VK_RESULT_CASE(VK_OPERATION_NOT_DEFERRED_KHR)
    SSS_VK_RESULT_CASE(VK_ERROR_COMPRESSION_EXHAUSTED_EXT)
#undef SSS_VK_RESULT_CASE
    default: break;
  }
  // An unknown code (a driver newer than these headers): keep the number.
  return "VkResult(" + std::to_string(static_cast<int>(result)) + ")";
}

namespace {
std::string describe(VkResult result, std::string_view expression, std::string_view file,
                     int line) {
  std::string s;
  s.append(expression).append(" failed with ").append(result_name(result));
  s.append(" at ").append(file).append(":").append(std::to_string(line));
  return s;
}
}  // namespace

VulkanError::VulkanError(VkResult result, std::string_view expression, std::string_view file,
                         int line)
    : std::runtime_error(describe(result, expression, file, line)),
      result_(result),
      expression_(expression),
      file_(file),
      line_(line) {}

VulkanError::VulkanError(VkResult result, const std::string& message)
    : std::runtime_error(message), result_(result) {}

VkResult check_result(VkResult result, const char* expression, const char* file, int line) {
  if (result < 0) throw VulkanError(result, expression, file, line);
  return result;
}

}  // namespace sss::vk
