// Command pools, command buffers, fences and semaphores, and the one-shot submission
// used for uploads, downloads and tests: record through a callback, submit, wait.
#pragma once

#include "renderer/vk/Handle.h"

#include <vulkan/vulkan.h>

#include <chrono>
#include <cstdint>
#include <functional>

namespace sss::vk {

class Context;

// A pool on the Context's queue family. flags: TRANSIENT for short-lived buffers,
// RESET_COMMAND_BUFFER to reset buffers one by one (otherwise reset the whole pool).
CommandPoolHandle create_command_pool(const Context& context, VkCommandPoolCreateFlags flags = 0);
// A primary command buffer; freed with its pool.
VkCommandBuffer allocate_command_buffer(const Context& context, VkCommandPool pool);

FenceHandle create_fence(const Context& context, bool signaled = false);
SemaphoreHandle create_semaphore(const Context& context);

// Waits for the fence; throws VulkanError(VK_TIMEOUT) after `timeout` (a GPU hang, or a
// fence that was never submitted) instead of blocking forever.
void wait_for_fence(const Context& context, VkFence fence,
                    std::chrono::nanoseconds timeout = std::chrono::seconds(60));

// Begins a command buffer (ONE_TIME_SUBMIT), lets `record` fill it, submits it on the
// Context's queue and waits for it to finish. For setup work, not for frames: it
// stalls the CPU until the GPU is done.
void submit_once(const Context& context, const std::function<void(VkCommandBuffer)>& record);

// Begins `cmd` for one-time submission, records it through `record`, ends it and submits
// it to the context's queue signalling `fence` (which must be unsignalled). Does not wait.
// The submission waits for `wait` and signals `signal` where given (the window's
// acquired and rendered semaphores). submit_once, the renderer's frame and the window's
// present all go through this.
void record_and_submit(const Context& context, VkCommandBuffer cmd, VkFence fence,
                       const std::function<void(VkCommandBuffer)>& record,
                       const VkSemaphoreSubmitInfo* wait = nullptr,
                       const VkSemaphoreSubmitInfo* signal = nullptr);

}  // namespace sss::vk
