// GBufferPass ("gbuffer"): depth (D32), normal + inward thickness (rgba16f) and albedo +
// material id (rgba8) with dynamic rendering. Leaves normal and albedo
// SHADER_READ_ONLY_OPTIMAL, depth kDepthReadLayout.
#pragma once

#include "renderer/FrameResources.h"
#include "renderer/Program.h"
#include "renderer/graph/FrameGraph.h"

namespace sss::renderer {

// The set the passes that draw the scene's surfaces with surface.glsl bind (the G-buffer,
// the texture path's atlas raster): 0 the frame uniforms, 1 the material textures, 2 the
// lights (the environment's harmonics, for the sky variants' sky_blocked).
vk::DescriptorSetLayoutBuilder surface_set_bindings();
void write_surface_set(VkDescriptorSet set, const FrameResources& resources);

class GBufferPass {
 public:
  static constexpr const char* kName = "gbuffer";

  explicit GBufferPass(const FrameResources& resources);
  // Expects the colour targets in COLOR_ATTACHMENT_OPTIMAL, depth in DEPTH_ATTACHMENT_OPTIMAL.
  void add_to(graph::FrameGraph& graph) const;
  // The uv-stretch debug view: draw with gbuffer_uv_stretch.frag, which also writes
  // targets.uv_stretch (its pipeline is built on first use). Off: the frame's pipeline,
  // uv_stretch is only moved to SHADER_READ_ONLY_OPTIMAL.
  void set_uv_stretch(bool on);
  // With an environment (FrameTargets::Use::sky_blocked; the scene's sky occlusion baked):
  // draw with gbuffer_sky.vert/.frag, which also write targets.sky_blocked (built on first
  // use). The uv-stretch view wins when both are on.
  void set_sky(bool on);

 private:
  const FrameResources& r_;
  Program program_;
  vk::PipelineHandle uv_stretch_pipeline_;  // on program_'s layout, built by set_uv_stretch(true)
  vk::PipelineHandle sky_pipeline_;         // on program_'s layout, built by set_sky(true)
  bool uv_stretch_ = false;
  bool sky_ = false;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace sss::renderer
