// AntialiasPass ("antialias"): RenderOptions::antialias == Fxaa. After composite (and
// before a debug view, which is data and keeps hard edges), copies the display image to
// targets.display_source and runs antialias.comp from it back into display: FXAA over the
// sRGB-coded frame (renderer/README.md "Anti-aliasing"). The HDR image, which the EXR,
// the compare suite and the references read, is not touched. The Renderer creates it
// only while it is asked for.
#pragma once

#include "renderer/Program.h"
#include "renderer/FrameResources.h"
#include "renderer/graph/FrameGraph.h"

namespace sss::renderer {

class AntialiasPass {
 public:
  static constexpr const char* kName = "antialias";

  explicit AntialiasPass(const FrameResources& resources);
  void add_to(graph::FrameGraph& graph) const;
  void write_descriptors();

 private:
  const FrameResources& r_;
  Program program_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace sss::renderer
