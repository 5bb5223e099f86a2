// The sss-viewer command line (DESIGN.md §4) as a plain struct, and what it changes in a
// loaded scene: --model, --gaussians and the MEDIUM flags override every SSS material.
#pragma once

#include "MediumArgs.h"

#include "renderer/RenderOptions.h"
#include "renderer/scene/Scene.h"

#include <optional>
#include <string>

namespace sss::app {

inline constexpr int kExitOk = 0, kExitRuntime = 1, kExitUsage = 2;

struct ViewerArgs {
  std::string scene = "builtin:bunny";
  bool headless = false;
  std::string out;
  std::string screenshot;
  int width = 640;
  int height = 360;
  int frames = 1;
  std::string sss = "screen";
  std::string mode = "separable";
  std::string model;
  std::optional<int> gaussians;
  std::string albedo;  // post-scatter | pre-post
  int taps = 17;
  float exposure = 1.0f;
  bool stats = false;
  std::string device;
  MediumArgs medium;
};

// Applies --model / --gaussians / --albedo / MEDIUM to every SSS material of the scene. Returns the
// number of materials changed, or the error (which names the option).
std::variant<int, FieldError> apply_material_overrides(scene::Scene& scene,
                                                       const ViewerArgs& args);

}  // namespace sss::app
