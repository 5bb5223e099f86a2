// Error handling for Vulkan calls (DESIGN.md §8, "Errors"): VK_CHECK(expr) evaluates a
// call returning VkResult and throws VulkanError when the result is negative (an error
// code). The error carries the expression text, the file and line of the call, and the
// result's name, so a failure in a test log points at one line of code.
//
// Positive results (VK_SUBOPTIMAL_KHR, VK_TIMEOUT, VK_NOT_READY, VK_INCOMPLETE) are
// successes with a message; they are returned, not thrown. Code that must treat them
// (a swapchain that is OUT_OF_DATE or SUBOPTIMAL) calls the function directly and
// inspects the result, or catches VulkanError and reads result().
#pragma once

#include <vulkan/vulkan.h>

#include <stdexcept>
#include <string>
#include <string_view>

namespace sss::vk {

// "VK_ERROR_DEVICE_LOST" for VK_ERROR_DEVICE_LOST; "VkResult(-123)" for unknown codes.
std::string result_name(VkResult result);

class VulkanError : public std::runtime_error {
 public:
  // what() reads "vkCreateBuffer(...) failed with VK_ERROR_OUT_OF_DEVICE_MEMORY at
  // renderer/vk/Buffer.cpp:42".
  VulkanError(VkResult result, std::string_view expression, std::string_view file, int line);
  // An error that is not the result of one call (no suitable device, missing feature).
  VulkanError(VkResult result, const std::string& message);

  VkResult result() const noexcept { return result_; }
  const std::string& expression() const noexcept { return expression_; }
  const std::string& file() const noexcept { return file_; }
  int line() const noexcept { return line_; }

 private:
  VkResult result_;
  std::string expression_;
  std::string file_;
  int line_ = 0;
};

// Throws VulkanError for a negative result; returns the result otherwise.
VkResult check_result(VkResult result, const char* expression, const char* file, int line);

}  // namespace sss::vk

// Evaluates expr once; throws sss::vk::VulkanError if it returned an error code and
// yields the VkResult otherwise (so `if (VK_CHECK(f()) == VK_INCOMPLETE)` works).
#define VK_CHECK(expr) ::sss::vk::check_result((expr), #expr, __FILE__, __LINE__)
