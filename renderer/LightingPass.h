// LightingPass ("lighting"): per pixel, diffuse irradiance E before albedo (Lambert cosine
// x light x shadow visibility x the light's half-space mask) and GGX specular radiance,
// into targets.irradiance and targets.specular (GENERAL).
#pragma once

#include "renderer/Program.h"
#include "renderer/FrameResources.h"
#include "renderer/graph/FrameGraph.h"

namespace sss::renderer {

class LightingPass {
 public:
  static constexpr const char* kName = "lighting";

  explicit LightingPass(const FrameResources& resources);
  void add_to(graph::FrameGraph& graph) const;
  // Points the sets at the current targets (after FrameTargets were recreated; none of
  // them may be in use by the GPU).
  void write_descriptors();

 private:
  const FrameResources& r_;
  Program program_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace sss::renderer
