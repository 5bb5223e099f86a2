// DebugViewPass ("debug view"): RenderOptions::debug_view. After composite, overwrites the
// display image with one intermediate of the frame (debug_view.comp; renderer/README.md
// "Debug views"); the HDR image keeps the shaded frame. The Renderer creates it only while
// a view is asked for, so the frame without one records nothing more.
#pragma once

#include "renderer/Program.h"
#include "renderer/FrameResources.h"
#include "renderer/RenderOptions.h"
#include "renderer/graph/FrameGraph.h"

#include <array>

namespace sss::renderer {

class DebugViewPass {
 public:
  static constexpr const char* kName = "debug view";
  explicit DebugViewPass(const FrameResources& resources);
  void add_to(graph::FrameGraph& graph) const;
  void write_descriptors();
  // The view and its heat map's [lo, hi] (Renderer::debug_range()), set before each frame.
  void set_view(DebugView view, const std::array<float, 2>& range);

 private:
  const FrameResources& r_;
  Program program_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  DebugView view_ = DebugView::None;
  std::array<float, 2> range_{0.0f, 1.0f};
};

}  // namespace sss::renderer
