#include "renderer/AntialiasPass.h"

#include "renderer/vk/Barrier.h"
#include "shaders/antialias.comp.h"

namespace sss::renderer {

namespace {
vk::DescriptorSetLayoutBuilder bindings() {
  const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
  vk::DescriptorSetLayoutBuilder b;
  b.add(0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, cs).add(1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cs);
  return b;
}
}  // namespace

AntialiasPass::AntialiasPass(const FrameResources& resources)
    : r_(resources), program_(r_.context, bindings(), sss_spv_antialias_comp, 0, 1, kName) {
  set_ = program_.allocate();
  write_descriptors();
}

void AntialiasPass::write_descriptors() {
  const FrameTargets& t = r_.targets;
  vk::DescriptorWriter(set_)
      .combined_image(0, t.display_source, r_.samplers.linear.get())
      .storage_image(1, t.display)
      .update(r_.context);
}

void AntialiasPass::record(VkCommandBuffer cmd, vk::GpuTimer& timer) const {
  auto scope = timer.scope(cmd, kName);
  const FrameTargets& t = r_.targets;
  // Composite's (or the separable pass's) writes to display before the copy reads it;
  // the source's last frame's reads before the copy overwrites it (UNDEFINED: its old
  // contents are not needed).
  const VkImageLayout general = VK_IMAGE_LAYOUT_GENERAL, src = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                      dst = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                      read = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  const vk::Scope sampled{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
  const vk::Scope copy_write{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT};
  vk::pipeline_barrier(
      cmd, {vk::image_barrier(t.display, general, src, vk::kComputeWrite, vk::kTransferRead),
            vk::image_barrier(t.display_source, VK_IMAGE_LAYOUT_UNDEFINED, dst, sampled, copy_write)});
  VkImageCopy region{};
  region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.extent = {t.width, t.height, 1};
  vkCmdCopyImage(cmd, t.display.handle(), src, t.display_source.handle(), dst, 1, &region);
  // The copy's write before the pass samples the source; its read of display before the
  // pass overwrites display.
  vk::pipeline_barrier(
      cmd, {vk::image_barrier(t.display, src, general, vk::kTransferRead, vk::kComputeWrite),
            vk::image_barrier(t.display_source, dst, read, copy_write, sampled)});
  program_.bind(cmd, set_);
  ComputeProgram::dispatch(cmd, t.width, t.height);
}

}  // namespace sss::renderer
