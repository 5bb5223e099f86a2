// What every pass reads besides its own pipeline: the Context, the frame's targets, the
// uniform and storage buffers, the samplers and the scene's geometry. Owned by Renderer.
#pragma once

#include "renderer/CameraSetup.h"
#include "renderer/EnvironmentMaps.h"
#include "renderer/FrameTargets.h"
#include "renderer/GpuScene.h"
#include "renderer/vk/Buffer.h"
#include "renderer/vk/Handle.h"

namespace sss::vk {
class Context;
}

namespace sss::renderer {

struct Samplers {
  vk::SamplerHandle nearest;  // G-buffer fetches
  vk::SamplerHandle linear;   // bilinear taps of the SSS kernels
  vk::SamplerHandle shadow;   // depth comparison (sampler2DArrayShadow)
};

struct FrameResources {
  const vk::Context& context;
  const FrameTargets& targets;
  const vk::Buffer& frame_uniforms;  // FrameUniforms
  const vk::Buffer& lights;          // LightBlock
  const vk::Buffer& materials;       // GpuMaterial[]
  const Samplers& samplers;
  const GpuScene& scene;
  const EnvironmentMaps& environment;  // the environment's specular tables (lighting)
  // The rect the screen passes dispatch over (geometry_rect; FrameUniforms::rect).
  const PixelRect& rect;
};

}  // namespace sss::renderer
