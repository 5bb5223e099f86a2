// CompositePass ("composite"): post-scatter albedo x scattered diffuse / pi + specular:
// L = albedo (1 - metallic) (1/pi)(R * E) + S, into targets.hdr (linear, what the EXR
// holds), and targets.display (exposure, filmic tonemap, sRGB encoding: the PNG); with
// RenderOptions::background_environment, the environment's radiance in the display image
// behind the geometry.
#pragma once

#include "renderer/Program.h"
#include "renderer/FrameResources.h"
#include "renderer/graph/FrameGraph.h"

namespace sss::renderer {

class CompositePass {
 public:
  static constexpr const char* kName = "composite";

  explicit CompositePass(const FrameResources& resources);
  void add_to(graph::FrameGraph& graph) const;
  // Points the sets at the current targets (after FrameTargets were recreated; none of
  // them may be in use by the GPU).
  void write_descriptors();
  // Whether it covers every pixel (the environment behind the geometry, FrameUniforms
  // flags.w) or only the geometry's rect; must agree with the frame's flag.
  void set_full_frame(bool full) { full_frame_ = full; }

 private:
  const FrameResources& r_;
  Program program_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  bool full_frame_ = false;
};

}  // namespace sss::renderer
