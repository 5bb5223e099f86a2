// The window's presenting: its swapchain, and what is drawn into the acquired image each
// frame: the renderer's display image blitted over it (the Compare view's overlay over
// the columns left of its split), then Dear ImGui's draw data in a render pass on top.
// One frame in flight: wait() before the renderer's resources or the panels change.
#pragma once

#include "Tools.h"

#include "renderer/vk/Commands.h"
#include "renderer/vk/Handle.h"
#include "renderer/vk/Swapchain.h"

#include <vulkan/vulkan.h>

#include <optional>
#include <vector>

namespace sss::vk {
class Context;
class Image;
}  // namespace sss::vk

namespace sss::app {

class Presenter {
 public:
  Presenter(const vk::Context& ctx, VkExtent2D framebuffer_size, bool vsync);
  ~Presenter();
  Presenter(const Presenter&) = delete;
  Presenter& operator=(const Presenter&) = delete;

  // Starts Dear ImGui's Vulkan backend on this swapchain's render pass (the context and
  // the GLFW backend exist); true when it did.
  bool init_imgui() const;

  // The swapchain at `size`, recreated where it differs or was lost; false while there
  // can be none (a side of 0).
  bool fit(VkExtent2D size);
  // Waits for the frame in flight.
  void wait() const;
  // Records, submits and presents one frame: `display` (in Renderer::display_layout())
  // scaled to the swapchain, `overlay` over it, and ImGui's draw data. False when the
  // swapchain was out of date at acquire (it is recreated at `size`; nothing was shown).
  bool present(const vk::Image& display, const std::optional<ViewerTools::Overlay>& overlay,
               VkExtent2D size);

  VkExtent2D extent() const { return sc_.extent(); }
  VkPresentModeKHR present_mode() const { return sc_.present_mode(); }

 private:
  using RenderPassHandle = vk::Handle<VkRenderPass, vkDestroyRenderPass>;
  using FramebufferHandle = vk::Handle<VkFramebuffer, vkDestroyFramebuffer>;
  void recreate(VkExtent2D size);
  void record(VkCommandBuffer cmd, const vk::Image& display,
              const std::optional<ViewerTools::Overlay>& overlay, std::uint32_t index) const;

  const vk::Context& ctx_;
  vk::Swapchain sc_;
  VkExtent2D made_for_{};  // the framebuffer size sc_ was made for
  RenderPassHandle ui_pass_;
  std::vector<FramebufferHandle> framebuffers_;
  vk::DescriptorPoolHandle imgui_pool_;
  // One buffer in its own pool, reset as a pool each frame (best practices: cheaper than
  // per-buffer resets, which need VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT).
  vk::CommandPoolHandle pool_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  vk::FenceHandle fence_;
  vk::SemaphoreHandle acquired_;
  std::vector<vk::SemaphoreHandle> rendered_;  // one per swapchain image
};

}  // namespace sss::app
