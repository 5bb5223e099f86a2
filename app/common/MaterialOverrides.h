// The material options shared by sss-viewer and sss-reference (DESIGN.md §4): --model,
// --gaussians, --albedo and the MEDIUM flags, which override every SSS material of a
// loaded scene, so that both renderers see the same materials for the same command line.
#pragma once

#include "ExitCodes.h"
#include "MediumArgs.h"

#include "renderer/scene/Scene.h"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <variant>

namespace sss::app {

struct MaterialOverrideArgs {
  std::string model;
  std::optional<int> gaussians;
  std::string albedo;  // post-scatter | pre-post
  MediumArgs medium;
  std::string layers;  // --layers FILE.json: a stack for every SSS material (issue 19)
};

// Adds --model, --gaussians, --albedo, --layers and the MEDIUM options to `app`.
void add_material_override_options(CLI::App& app, MaterialOverrideArgs& args);

// Applies the overrides to every SSS material of the scene. Returns the number of
// materials changed, or the error (which names the option).
std::variant<int, FieldError> apply_material_overrides(scene::Scene& scene,
                                                       const MaterialOverrideArgs& args);

}  // namespace sss::app
