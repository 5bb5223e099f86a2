// The environment's specular tables on the GPU (scene/SplitSum.h): the prefiltered
// radiance (kSpecularLevels layers of kSpecularWidth x kSpecularHeight, rgba32f, 2D array)
// and the DFG table (kDfgSize², rg32f). Both are read with texelFetch (lighting.comp through
// shading.glsl), so they need no filtering support and go through the same arithmetic as the
// C++ lookups (in float, with the GPU's own atan and acos). Both stay in SHADER_READ_ONLY_OPTIMAL; without an environment the
// levels hold 0 (and the frame's flag keeps the shader from reading them).
#pragma once

#include "scene/Environment.h"
#include "renderer/vk/Image.h"

#include <optional>

namespace sss::vk {
class Context;
}

namespace sss::renderer {

class EnvironmentMaps {
 public:
  // The levels are undefined until the first upload(), which must come before the first
  // frame (Renderer's constructor makes it, with the scene's environment or none).
  explicit EnvironmentMaps(const vk::Context& context);
  // Uploads the levels of `environment` (zeros for none); waits for the copy, so no frame
  // may be in flight (Renderer::set_environment waits for the device first).
  void upload(const std::optional<scene::Environment>& environment);

  const vk::Image& specular() const { return specular_; }
  const vk::Image& dfg() const { return dfg_; }
  // The radiance itself for the display's background (RenderOptions::
  // background_environment): the environment's image at its own size (rgba32f, a 2D array
  // of one layer, read as the levels are), one texel of its colour when it is uniform, one
  // zero texel without one. upload() makes a new image when the size changes: descriptor
  // sets that hold it must be written again.
  const vk::Image& background() const { return background_; }

 private:
  const vk::Context& context_;
  vk::Image specular_;
  vk::Image dfg_;
  vk::Image background_;
  bool dfg_uploaded_ = false;  // the table, made at the first environment (zeros before)
};

}  // namespace sss::renderer
