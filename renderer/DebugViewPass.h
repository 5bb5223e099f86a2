// DebugViewPass ("debug view"): RenderOptions::debug_view. After composite, overwrites the
// display image with one intermediate of the frame (debug_view.comp; renderer/README.md
// "Debug views"); the HDR image keeps the shaded frame. The Renderer creates it only while
// a view is asked for, so the frame without one records nothing more.
#pragma once

#include "renderer/ComputeProgram.h"
#include "renderer/FrameResources.h"
#include "renderer/RenderOptions.h"
#include "renderer/vk/GpuTimer.h"

namespace sss::renderer {

class DebugViewPass {
 public:
  static constexpr const char* kName = "debug view";
  // Heat-map tops: kernel radius 2^6 = 64 pixels; thickness the scene's bounding diameter;
  // uv stretch pi x that diameter (a UV sphere's u spans its circumference).
  static constexpr float kKernelRadiusTopLog2 = 6.0f;

  explicit DebugViewPass(const FrameResources& resources);
  void record(VkCommandBuffer cmd, vk::GpuTimer& timer) const;
  void write_descriptors();
  void set_view(DebugView view, float scene_diameter_mm);

 private:
  const FrameResources& r_;
  ComputeProgram program_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  DebugView view_ = DebugView::None;
  float scene_diameter_mm_ = 1.0f;
};

}  // namespace sss::renderer
