// The material options shared by sss-viewer and sss-reference (DESIGN.md §4): --model,
// --gaussians, --albedo, --scale and the MEDIUM flags, which override every SSS material
// of a loaded scene, and --sss-material, which gives subsurface scattering to chosen
// materials (any glTF material, with or without extras.sss), so that both renderers see
// the same materials for the same command line.
#pragma once

#include "ExitCodes.h"
#include "MediumArgs.h"

#include "scene/Scene.h"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace sss::app {

struct MaterialOverrideArgs {
  std::string model;
  std::optional<int> gaussians;
  std::string albedo;  // post-scatter | pre-post
  MediumArgs medium;
  std::string layers;  // --layers FILE.json: a stack for every SSS material (issue 19)
  std::optional<double> scale;  // --scale S: SssMaterial::scale of every SSS material
  // --sss-material TARGET=SPEC, repeatable (README "Subsurface scattering on any glTF").
  std::vector<std::string> sss_material;
};

// One --sss-material value, parsed. TARGET is a material name, its index in the file, or
// `all`; SPEC is `off`, a preset name, or `;`-separated key=value items whose keys are the
// MEDIUM options' names without the dashes (preset, sigma-a, sigma-s, color, mfp, g, eta,
// thickness, subsurface-color, subsurface-radius, subsurface-radius-scale, subsurface-scale,
// albedo-inversion) and model, gaussians, albedo, scale. A bare preset name may come first.
struct SssMaterialSpec {
  std::string text;    // as given, for messages
  std::string target;
  bool off = false;    // SPEC `off`: the material becomes opaque
  MediumArgs medium;
  std::string model, albedo;
  std::optional<int> gaussians;
  std::optional<double> scale;
};
std::variant<SssMaterialSpec, FieldError> parse_sss_material_spec(const std::string& text);

// "0 'skin' (subsurface), 1 'metal'": the scene's materials as --sss-material names them.
std::string material_list(const scene::Scene& scene);

// Adds --model, --gaussians, --albedo, --scale, --layers, --sss-material and the MEDIUM
// options to `app`.
void add_material_override_options(CLI::App& app, MaterialOverrideArgs& args);

// Applies --sss-material first: each names materials (an error, listing the scene's
// materials, when it names none) and sets them from its SPEC, its keys winning over the
// global options, which fill in the rest (then the material's own values, then the
// defaults). The global options then override every other SSS material; given to a scene
// with no SSS material they are an error naming the option and the materials there are.
// Meshes newly given subsurface scattering get a UV atlas as load_scene gives one, and a
// metallic material a warning (its subsurface light is scaled by 1 - metallic).
// Returns the number of materials changed, or the error (which names the option).
std::variant<int, FieldError> apply_material_overrides(scene::Scene& scene,
                                                       const MaterialOverrideArgs& args);

// For every SSS material, appended to scene.warnings: its model's warnings
// (SssMaterial::model_warnings: mc-table outside its tabulated g) and
// scene::scatter_scale_warning, seen by the scene's first camera in an image `height`
// pixels high. Each names the material.
void add_material_warnings(scene::Scene& scene, std::uint32_t height);

}  // namespace sss::app
