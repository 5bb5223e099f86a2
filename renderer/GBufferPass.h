// GBufferPass ("gbuffer"): depth (D32), normal + roughness (rgba16f) and albedo +
// material id (rgba8) with dynamic rendering. Leaves the three SHADER_READ_ONLY_OPTIMAL.
#pragma once

#include "renderer/FrameResources.h"
#include "renderer/vk/Descriptors.h"
#include "renderer/vk/GpuTimer.h"

namespace sss::renderer {

class GBufferPass {
 public:
  static constexpr const char* kName = "gbuffer";

  explicit GBufferPass(const FrameResources& resources);
  // Expects the colour targets in COLOR_ATTACHMENT_OPTIMAL, depth in DEPTH_ATTACHMENT_OPTIMAL.
  void record(VkCommandBuffer cmd, vk::GpuTimer& timer) const;

 private:
  const FrameResources& r_;
  vk::DescriptorSetLayoutHandle set_layout_;
  vk::PipelineLayoutHandle layout_;
  vk::PipelineHandle pipeline_;
  vk::DescriptorPool pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace sss::renderer
