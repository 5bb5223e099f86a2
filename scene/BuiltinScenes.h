// Built-in scenes, named "builtin:NAME" wherever a SCENE is accepted (DESIGN.md §4).
//
//   builtin:edge       the end-to-end check (issue 3): a flat skin1 slab in y = 0, an
//                      orthographic camera straight down spanning x in [-20, 20] mm, a
//                      normal-incidence directional light of irradiance 1 masked to x < 0
//   builtin:sphere     a 30 mm skin1 sphere, a key light, a framing camera
//   builtin:materials  one 15 mm sphere per usable preset (11), each its own profile
//   builtin:slab       transmission (issue 6): a 30 x 30 x 2 mm skin2 slab (multipole,
//                      thickness 2 mm) lit from behind at normal incidence (E = 3), no
//                      fill, seen from the front slightly obliquely (SlabScene.cpp)
//   builtin:bunny      the default: the Stanford bunny (assets/bunny.glb, 150 mm, skin1 at
//                      scale 0.25), back-lit from behind so the ears glow, plus a fill light
#pragma once

#include "scene/LoadError.h"
#include "scene/Scene.h"

#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace sss::scene {

inline constexpr std::string_view kBuiltinPrefix = "builtin:";
inline constexpr std::string_view kDefaultScene = "builtin:bunny";

std::vector<std::string> builtin_scene_names();  // "builtin:bunny", "builtin:edge", ...

// "builtin:NAME" (or just NAME). An unknown name gives a LoadError listing the known ones.
std::variant<Scene, LoadError> builtin_scene(std::string_view name);

// A SCENE argument: a built-in name, else a glTF/GLB path (load_gltf with defaults).
// No UV atlas is built: texture-space SSS builds its own (GpuScene::ensure_sss_uvs).
std::variant<Scene, LoadError> load_scene(std::string_view scene);

struct EdgeOptions {
  std::string preset = "skin1";
  double half_width_mm = 20.0;  // the image spans x in [-half_width, +half_width] mm
  double irradiance = 1.0;      // E on the lit half (Light.h units)
};
// builtin:edge with another material or width: the scene the edge tests render.
Scene edge_scene(const EdgeOptions& options = {});

Scene sphere_scene();
Scene materials_scene();
Scene slab_scene();
std::variant<Scene, LoadError> bunny_scene();

}  // namespace sss::scene
