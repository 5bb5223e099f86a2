// ShadowPass ("shadow"): one depth layer per light (LightSetup's matrices), slope-scaled
// depth bias in the rasterizer plus the normal offset and constant bias of the lookup
// (lighting.comp). Writes targets.shadow, and the same depths without the bias to
// targets.light_depth (thickness); leaves both SHADER_READ_ONLY_OPTIMAL.
#pragma once

#include "renderer/FrameResources.h"
#include "renderer/Program.h"
#include "renderer/graph/FrameGraph.h"

#include <utility>
#include <vector>

namespace sss::renderer {

class ShadowPass {
 public:
  static constexpr const char* kName = "shadow";

  ShadowPass(const FrameResources& resources, std::vector<bool> shadowed);
  // Expects targets.shadow and targets.light_depth in DEPTH_ATTACHMENT_OPTIMAL. Draws
  // light_depth only when `light_depth` (transmission or the thickness view reads it);
  // otherwise it is left undefined, unread.
  void add_to(graph::FrameGraph& graph, bool light_depth) const;
  // Which layers to draw from now on (LightSetup::shadowed, after the lights changed).
  void set_shadowed(std::vector<bool> shadowed) { shadowed_ = std::move(shadowed); }

 private:
  const FrameResources& r_;
  std::vector<bool> shadowed_;
  Program program_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace sss::renderer
