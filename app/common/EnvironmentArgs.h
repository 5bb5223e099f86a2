// --environment and --environment-intensity, shared by sss-viewer and sss-reference so
// that both renderers light a scene alike (scene/Environment.h; README "Environment
// light").
#pragma once

#include "scene/Scene.h"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace sss::app {

struct EnvironmentArgs {
  std::string environment = "none";  // none | R,G,B | FILE.exr
  float intensity = 1.0f;
};

void add_environment_options(CLI::App& app, EnvironmentArgs& args);

// What apply_environment refused: the message names the option and the value or file;
// `file` is true when the file could not be read or holds no environment (an input error,
// not a usage one).
struct EnvironmentError {
  std::string message;
  bool file = false;
};

// Sets scene.environment from the options (none: leaves it empty).
std::optional<EnvironmentError> apply_environment(scene::Scene& scene, const EnvironmentArgs& args);

}  // namespace sss::app
