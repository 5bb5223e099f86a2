// TextureGatherPass ("sss texture gather"): the texture path's final lookup. Draws each
// texture-space object again with gbuffer.vert and a LESS_OR_EQUAL test (no write) on the
// G-buffer's depth, pulled toward the camera by a small depth bias: the G-buffer's own
// fragments pass (the same vertex shader on the same vertices, up to rounding; nothing
// lies in front of the stored depth), reading the object's scattered irradiance
// (SssTexturePass) at the fragment's atlas UV into the frame's `accum` target (cleared to
// 0 first; alpha 1 where written). The composite then reads accum as in gaussians mode.
#pragma once

#include "renderer/FrameResources.h"
#include "renderer/Program.h"
#include "renderer/graph/FrameGraph.h"

namespace sss::renderer {

class SssTexturePass;

class TextureGatherPass {
 public:
  static constexpr const char* kName = "sss texture gather";

  explicit TextureGatherPass(const FrameResources& resources);
  // The objects and their scattered textures (after SssTexturePass::configure; none may be
  // in use by the GPU).
  void set_objects(const SssTexturePass& texture);
  // Expects depth in kDepthReadLayout and accum in GENERAL after the frame's first
  // barrier; leaves accum in GENERAL for compute reads.
  void add_to(graph::FrameGraph& graph) const;

 private:
  const FrameResources& r_;
  Program program_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  std::vector<std::pair<std::size_t, int>> draws_;  // (instance, object)
};

}  // namespace sss::renderer
