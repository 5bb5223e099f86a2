// LightSetup: the scene's lights as the frame shades them (LightBlock), with a shadow
// matrix per light: directional lights get an orthographic fit to the scene's bounding
// sphere, spot lights a perspective frustum of their outer cone; point lights are not
// shadowed yet (no cube maps). Lights beyond SSS_MAX_LIGHTS are dropped with a warning.
#pragma once

#include "scene/Scene.h"
#include "shaders/shared/frame.h"

#include <cstdint>
#include <string>
#include <vector>

namespace sss::renderer {

struct LightSetup {
  shader::LightBlock block{};
  std::uint32_t count = 0;         // lights in block
  std::vector<bool> shadowed;      // per light in block: has a shadow map layer
  std::vector<std::string> warnings;
};

LightSetup make_light_setup(const scene::Scene& scene, std::uint32_t shadow_map_size);
// The same for `lights` in a scene with these bounds (Renderer::set_lights).
LightSetup make_light_setup(const std::vector<scene::Light>& lights, const scene::Bounds& bounds,
                            std::uint32_t shadow_map_size);

}  // namespace sss::renderer
