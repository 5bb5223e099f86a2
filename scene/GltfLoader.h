// load_gltf: a glTF 2.0 file (.gltf text or .glb binary) into a Scene, treating the
// file as hostile (DESIGN.md §8, §9). Everything is checked before use; a malformed file
// gives a LoadError naming the file, the object and the field, never a crash.
//
// Read: meshes (TRIANGLES; strips and fans become triangles; points and lines are
// skipped with a warning), POSITION / NORMAL / TEXCOORD_0 / TANGENT, indexed and
// non-indexed; metallic-roughness materials, base-colour and normal textures;
// materials[i].extras.sss; the default scene's node hierarchy; cameras;
// KHR_lights_punctual. Not read (warned): skins, morph targets, other texture sets.
// Refused: sparse accessors, accessors without a buffer view, quantized attributes,
// required extensions other than KHR_lights_punctual.
#pragma once

#include "scene/LoadError.h"
#include "scene/Scene.h"
#include "scene/Texture.h"

#include <cstdint>
#include <string>
#include <variant>

namespace sss::scene {

struct LoadOptions {
  std::uint64_t max_file_bytes = 512ull << 20;     // the glTF/GLB, and each file it names
  std::uint64_t max_json_bytes = 64ull << 20;      // the JSON text (.gltf, or a GLB's chunk 0)
  std::uint64_t max_external_bytes = 1ull << 30;   // all external files together
  std::uint64_t max_scene_bytes = 2ull << 30;      // decoded geometry, pixels, instances (about)
  std::uint32_t max_nodes = 1u << 20;
  ImageLimits image_limits;
  double mm_per_unit = 1000.0;  // glTF is in metres
  bool add_camera_if_missing = true;  // frame_bounds() when the scene has no camera
  bool add_light_if_missing = true;   // a key light when it has none
};

std::variant<Scene, LoadError> load_gltf(const std::string& path, const LoadOptions& options = {});

}  // namespace sss::scene
