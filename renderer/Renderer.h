// Renderer: the real-time frame of DESIGN.md §5 for one scene at one output size. It owns
// the targets, the buffers and one object per pass, and orders them:
//
//   shadow -> gbuffer -> lighting -> [sss separable | sss gaussians] -> composite
//
// Headless and windowed use are the same Renderer (the window only presents `display`).
// render_frame() records one command buffer, submits it and waits for its fence, so
// one frame is in flight; GPU times per pass (GpuTimer, named after the pass) and the CPU
// frame time are in stats().
#pragma once

#include "renderer/FrameResources.h"
#include "renderer/FrameTargets.h"
#include "renderer/GpuScene.h"
#include "renderer/LightSetup.h"
#include "renderer/MaterialTable.h"
#include "renderer/RenderOptions.h"
#include "renderer/image/Image.h"
#include "renderer/scene/Scene.h"
#include "renderer/vk/Buffer.h"
#include "renderer/vk/GpuTimer.h"

#include <memory>
#include <string>
#include <vector>

namespace sss::vk {
class Context;
}

namespace sss::renderer {

class ShadowPass;
class GBufferPass;
class LightingPass;
class SssSeparablePass;
class SssGaussiansPass;
class CompositePass;

struct FrameStats {
  std::vector<vk::PassTime> passes;  // GPU ms per pass, in frame order
  double gpu_ms = 0.0;               // sum of the passes
  double cpu_ms = 0.0;               // record + submit + wait, wall clock
};

class Renderer {
 public:
  // Throws std::invalid_argument for an unusable scene or options (no camera, zero size,
  // too many materials), VulkanError for device failures.
  Renderer(const vk::Context& context, const scene::Scene& scene, const RenderOptions& options);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  void render_frame();
  const FrameStats& stats() const { return stats_; }

  // The last frame: linear radiance L (rgb; alpha 1 on geometry, 0 on background) and
  // the display image (tonemapped, sRGB-encoded, codes / 255).
  image::Image read_hdr() const;
  image::Image read_display() const;

  const MaterialData& materials() const { return materials_.data(); }
  const std::vector<std::string>& warnings() const { return warnings_; }
  const RenderOptions& options() const { return options_; }

 private:
  void record(VkCommandBuffer cmd);
  image::Image read(const vk::Image& image, bool eight_bit) const;

  const vk::Context& context_;
  RenderOptions options_;
  std::vector<std::string> warnings_;
  LightSetup lights_;
  MaterialTable materials_;
  GpuScene scene_;
  FrameTargets targets_;
  vk::Buffer frame_uniforms_;
  vk::Buffer light_buffer_;
  Samplers samplers_;
  FrameResources resources_;
  std::unique_ptr<ShadowPass> shadow_;
  std::unique_ptr<GBufferPass> gbuffer_;
  std::unique_ptr<LightingPass> lighting_;
  std::unique_ptr<SssSeparablePass> separable_;
  std::unique_ptr<SssGaussiansPass> gaussians_;
  std::unique_ptr<CompositePass> composite_;
  vk::CommandPoolHandle pool_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  vk::FenceHandle fence_;
  vk::GpuTimer timer_;
  FrameStats stats_;
  bool rendered_ = false;
};

}  // namespace sss::renderer
