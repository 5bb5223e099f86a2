#include "Presenter.h"

#include "renderer/Renderer.h"
#include "renderer/vk/Barrier.h"
#include "renderer/vk/Check.h"
#include "renderer/vk/Context.h"
#include "renderer/vk/Image.h"

#include <imgui.h>
#include <imgui_impl_vulkan.h>

#include <algorithm>
#include <cmath>

namespace sss::app {

namespace {

// The blit stage: where the frame waits for the acquired image and writes it first.
constexpr vk::Scope kBlitWrite{VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT};
constexpr vk::Scope kBlitRead{VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT};
constexpr vk::Scope kBlitWait{VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_NONE};
constexpr vk::Scope kColorAttachment{
    VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
    VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT};

// The UI pass over the blitted image: LOAD, COLOR_ATTACHMENT_OPTIMAL -> PRESENT_SRC.
vk::Handle<VkRenderPass, vkDestroyRenderPass> create_ui_render_pass(const vk::Context& ctx, VkFormat format) {
  VkAttachmentDescription color{};
  color.format = format;
  color.samples = VK_SAMPLE_COUNT_1_BIT;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  color.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &ref;
  VkSubpassDependency deps[2]{};
  deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  deps[0].dstSubpass = 0;
  deps[0].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  deps[0].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  deps[1].srcSubpass = 0;
  deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  deps[1].dstStageMask = VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT;
  deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  deps[1].dstAccessMask = 0;
  VkRenderPassCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
  info.attachmentCount = 1;
  info.pAttachments = &color;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 2;
  info.pDependencies = deps;
  VkRenderPass pass = VK_NULL_HANDLE;
  VK_CHECK(vkCreateRenderPass(ctx.device(), &info, nullptr, &pass));
  return {ctx.device(), pass};
}

std::vector<vk::Handle<VkFramebuffer, vkDestroyFramebuffer>> create_framebuffers(const vk::Context& ctx, VkRenderPass pass,
                                                   const vk::Swapchain& sc) {
  std::vector<vk::Handle<VkFramebuffer, vkDestroyFramebuffer>> out;
  for (uint32_t i = 0; i < sc.image_count(); ++i) {
    VkImageView view = sc.view(i);
    VkFramebufferCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
    info.renderPass = pass;
    info.attachmentCount = 1;
    info.pAttachments = &view;
    info.width = sc.extent().width;
    info.height = sc.extent().height;
    info.layers = 1;
    VkFramebuffer fb = VK_NULL_HANDLE;
    VK_CHECK(vkCreateFramebuffer(ctx.device(), &info, nullptr, &fb));
    out.emplace_back(ctx.device(), fb);
  }
  return out;
}

vk::DescriptorPoolHandle create_imgui_pool(const vk::Context& ctx) {
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16};
  VkDescriptorPoolCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  info.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  info.maxSets = 16;
  info.poolSizeCount = 1;
  info.pPoolSizes = &size;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VK_CHECK(vkCreateDescriptorPool(ctx.device(), &info, nullptr, &pool));
  return vk::DescriptorPoolHandle(ctx.device(), pool);
}

void check_imgui_vk(VkResult r) {
  if (r < 0) throw vk::VulkanError(r, "Dear ImGui's Vulkan backend");
}

}  // namespace

Presenter::Presenter(const vk::Context& ctx, VkExtent2D framebuffer_size, bool vsync)
    : ctx_(ctx),
      sc_(ctx, framebuffer_size, vsync),
      made_for_(framebuffer_size),
      ui_pass_(create_ui_render_pass(ctx, sc_.format())),
      framebuffers_(create_framebuffers(ctx, ui_pass_.get(), sc_)),
      imgui_pool_(create_imgui_pool(ctx)),
      pool_(vk::create_command_pool(ctx, 0)),
      cmd_(vk::allocate_command_buffer(ctx, pool_.get())),
      fence_(vk::create_fence(ctx, true)),
      acquired_(vk::create_semaphore(ctx)) {
  while (rendered_.size() < sc_.image_count()) rendered_.push_back(vk::create_semaphore(ctx));
}

Presenter::~Presenter() = default;

bool Presenter::init_imgui() const {
  ImGui_ImplVulkan_InitInfo init{};
  init.Instance = ctx_.instance();
  init.PhysicalDevice = ctx_.physical_device();
  init.Device = ctx_.device();
  init.QueueFamily = ctx_.queue_family();
  init.Queue = ctx_.queue();
  init.DescriptorPool = imgui_pool_.get();
  init.MinImageCount = std::max(sc_.min_image_count(), 2u);
  init.ImageCount = std::max(sc_.image_count(), init.MinImageCount);
  init.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  init.CheckVkResultFn = check_imgui_vk;
  if (!ImGui_ImplVulkan_Init(&init, ui_pass_.get())) return false;
  vk::submit_once(ctx_, [](VkCommandBuffer c) { ImGui_ImplVulkan_CreateFontsTexture(c); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
  return true;
}

void Presenter::wait() const { vk::wait_for_fence(ctx_, fence_.get()); }

void Presenter::recreate(VkExtent2D size) {
  wait();  // the last frame's UI pass uses the framebuffers
  framebuffers_.clear();
  sc_.recreate(size);
  made_for_ = size;
  if (!sc_.valid()) return;
  framebuffers_ = create_framebuffers(ctx_, ui_pass_.get(), sc_);
  while (rendered_.size() < sc_.image_count()) rendered_.push_back(vk::create_semaphore(ctx_));
  ImGui_ImplVulkan_SetMinImageCount(std::max(sc_.min_image_count(), 2u));
}

bool Presenter::fit(VkExtent2D size) {
  if (!sc_.valid() || size.width != made_for_.width || size.height != made_for_.height) recreate(size);
  return sc_.valid();
}

bool Presenter::present(const vk::Image& display, const std::optional<ViewerTools::Overlay>& overlay,
                        VkExtent2D size) {
  uint32_t index = 0;
  if (!sc_.acquire(acquired_.get(), index)) {
    recreate(size);
    return false;
  }
  VkFence frame_fence = fence_.get();
  VK_CHECK(vkResetFences(ctx_.device(), 1, &frame_fence));
  VK_CHECK(vkResetCommandPool(ctx_.device(), pool_.get(), 0));
  VkSemaphoreSubmitInfo wait{};
  wait.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO;
  wait.semaphore = acquired_.get();
  wait.stageMask = VK_PIPELINE_STAGE_2_BLIT_BIT;
  VkSemaphoreSubmitInfo signal{};
  signal.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO;
  signal.semaphore = rendered_[index].get();
  signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  vk::record_and_submit(
      ctx_, cmd_, fence_.get(), [&](VkCommandBuffer cmd) { record(cmd, display, overlay, index); }, &wait,
      &signal);
  if (!sc_.present(index, rendered_[index].get())) recreate(size);
  return true;
}

void Presenter::record(VkCommandBuffer cmd, const vk::Image& display,
                       const std::optional<ViewerTools::Overlay>& overlay, std::uint32_t index) const {
  ctx_.begin_label(cmd, "present");
  const VkImageSubresourceRange color_range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  VkImage target = sc_.image(index);
  vk::pipeline_barrier(
      cmd, {vk::image_barrier(display, renderer::Renderer::display_layout(),
                              VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, vk::kComputeWrite, kBlitRead),
            vk::image_barrier(target, color_range, VK_IMAGE_LAYOUT_UNDEFINED,
                              VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kBlitWait, kBlitWrite)});
  VkImageBlit blit{};
  blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.srcOffsets[1] = {int32_t(display.width()), int32_t(display.height()), 1};
  blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.dstOffsets[1] = {int32_t(sc_.extent().width), int32_t(sc_.extent().height), 1};
  const bool same = display.width() == sc_.extent().width && display.height() == sc_.extent().height;
  vkCmdBlitImage(cmd, display.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit,
                 same ? VK_FILTER_NEAREST : VK_FILTER_LINEAR);
  if (overlay) {
    // The compare view: the reference or the heat map over the columns left of the
    // split (both stay in TRANSFER_SRC_OPTIMAL from their upload).
    const vk::Image& over = *overlay->image;
    const int32_t src_w = int32_t(std::lround(overlay->split * float(over.width())));
    const int32_t dst_w = int32_t(std::lround(overlay->split * float(sc_.extent().width)));
    if (src_w > 0 && dst_w > 0) {
      vk::pipeline_barrier(cmd, {vk::image_barrier(target, color_range,
                                                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                                   kBlitWrite, kBlitWrite)});
      VkImageBlit part = blit;
      part.srcOffsets[1] = {src_w, int32_t(over.height()), 1};
      part.dstOffsets[1] = {dst_w, int32_t(sc_.extent().height), 1};
      vkCmdBlitImage(cmd, over.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &part,
                     same ? VK_FILTER_NEAREST : VK_FILTER_LINEAR);
    }
  }
  vk::pipeline_barrier(
      cmd, {vk::image_barrier(display, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                              renderer::Renderer::display_layout(), kBlitRead, vk::kAllCommands),
            vk::image_barrier(target, color_range, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                              VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, kBlitWrite,
                              kColorAttachment)});
  VkRenderPassBeginInfo rp{};
  rp.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
  rp.renderPass = ui_pass_.get();
  rp.framebuffer = framebuffers_[index].get();
  rp.renderArea = {{0, 0}, sc_.extent()};
  vkCmdBeginRenderPass(cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
  vkCmdEndRenderPass(cmd);
  ctx_.end_label(cmd);
}

}  // namespace sss::app
