// The SCENE argument of sss-viewer and sss-reference, loaded as both tools load it.
#pragma once

#include "EnvironmentArgs.h"
#include "MaterialOverrides.h"

#include "scene/Scene.h"

#include <cstdint>
#include <string>
#include <variant>

namespace sss::app {

// load_scene(name) with a camera and a light where the scene has none, the material
// overrides and the environment applied, and the material warnings (for a frame `height`
// pixels tall) printed as "TOOL: warning: ...". Where it cannot be had: the message
// (naming the file and field, or the option) is printed and the exit status returned, 2.
std::variant<scene::Scene, int> load_cli_scene(const std::string& tool, const std::string& name,
                                               const MaterialOverrideArgs& material,
                                               const EnvironmentArgs& environment, std::uint32_t height);

}  // namespace sss::app
