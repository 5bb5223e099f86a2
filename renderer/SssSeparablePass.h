// SssSeparablePass ("sss separable"): Jimenez et al. 2015. Each SSS material's 1D kernel
// (profiles::make_separable_kernel: offsets in mm, RGB weights summing to 1) is applied
// horizontally to the irradiance (-> blur_temp), then vertically (-> blur_a), with the
// kernel's mm turned into pixels from the depth and the projection and follow-surface
// fallback (sss.glsl). Composite multiplies blur_a by the total reflectance.
#pragma once

#include "renderer/ComputeProgram.h"
#include "renderer/FrameResources.h"
#include "renderer/vk/GpuTimer.h"

namespace sss::renderer {

class SssSeparablePass {
 public:
  static constexpr const char* kName = "sss separable";

  explicit SssSeparablePass(const FrameResources& resources);
  void record(VkCommandBuffer cmd, vk::GpuTimer& timer) const;
  // Points the sets at the current targets (after FrameTargets were recreated; none of
  // them may be in use by the GPU).
  void write_descriptors();

 private:
  const FrameResources& r_;
  ComputeProgram program_;
  VkDescriptorSet horizontal_ = VK_NULL_HANDLE;
  VkDescriptorSet vertical_ = VK_NULL_HANDLE;
};

}  // namespace sss::renderer
