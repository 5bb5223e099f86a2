#include "renderer/vk/Commands.h"

#include "renderer/vk/Check.h"
#include "renderer/vk/Context.h"

namespace sss::vk {

CommandPoolHandle create_command_pool(const Context& context, VkCommandPoolCreateFlags flags) {
  VkCommandPoolCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  info.flags = flags;
  info.queueFamilyIndex = context.queue_family();
  VkCommandPool pool = VK_NULL_HANDLE;
  VK_CHECK(vkCreateCommandPool(context.device(), &info, nullptr, &pool));
  return CommandPoolHandle(context.device(), pool);
}

VkCommandBuffer allocate_command_buffer(const Context& context, VkCommandPool pool) {
  VkCommandBufferAllocateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  info.commandPool = pool;
  info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  info.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VK_CHECK(vkAllocateCommandBuffers(context.device(), &info, &cmd));
  return cmd;
}

FenceHandle create_fence(const Context& context, bool signaled) {
  VkFenceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  info.flags = signaled ? VK_FENCE_CREATE_SIGNALED_BIT : 0;
  VkFence fence = VK_NULL_HANDLE;
  VK_CHECK(vkCreateFence(context.device(), &info, nullptr, &fence));
  return FenceHandle(context.device(), fence);
}

SemaphoreHandle create_semaphore(const Context& context) {
  VkSemaphoreCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO;
  VkSemaphore semaphore = VK_NULL_HANDLE;
  VK_CHECK(vkCreateSemaphore(context.device(), &info, nullptr, &semaphore));
  return SemaphoreHandle(context.device(), semaphore);
}

void wait_for_fence(const Context& context, VkFence fence, std::chrono::nanoseconds timeout) {
  const VkResult result = VK_CHECK(vkWaitForFences(context.device(), 1, &fence, VK_TRUE,
                                                   static_cast<uint64_t>(timeout.count())));
  if (result == VK_TIMEOUT) {
    throw VulkanError(VK_TIMEOUT, "a fence was not signalled within " +
                                      std::to_string(timeout.count() / 1000000) + " ms");
  }
}

void record_and_submit(const Context& context, VkCommandBuffer cmd, VkFence fence,
                       const std::function<void(VkCommandBuffer)>& record,
                       const VkSemaphoreSubmitInfo* wait, const VkSemaphoreSubmitInfo* signal) {
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
  record(cmd);
  VK_CHECK(vkEndCommandBuffer(cmd));

  VkCommandBufferSubmitInfo cmd_info{};
  cmd_info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO;
  cmd_info.commandBuffer = cmd;
  VkSubmitInfo2 submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2;
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cmd_info;
  submit.waitSemaphoreInfoCount = wait != nullptr ? 1 : 0;
  submit.pWaitSemaphoreInfos = wait;
  submit.signalSemaphoreInfoCount = signal != nullptr ? 1 : 0;
  submit.pSignalSemaphoreInfos = signal;
  context.submit({&submit, 1}, fence);
}

void submit_once(const Context& context, const std::function<void(VkCommandBuffer)>& record) {
  // A pool per call keeps this free of shared state (it may be called from any thread);
  // setup work is rare enough that the cost does not matter.
  const CommandPoolHandle pool = create_command_pool(context, VK_COMMAND_POOL_CREATE_TRANSIENT_BIT);
  const VkCommandBuffer cmd = allocate_command_buffer(context, pool.get());
  const FenceHandle fence = create_fence(context);

  record_and_submit(context, cmd, fence.get(), record);
  // If the wait throws, the pool and fence would be destroyed while the GPU may still
  // use them; wait for the device before unwinding.
  try {
    wait_for_fence(context, fence.get());
  } catch (...) {
    vkDeviceWaitIdle(context.device());
    throw;
  }
}

}  // namespace sss::vk
