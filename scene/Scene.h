// Scene: everything both renderers read (DESIGN.md §1): meshes (one per glTF primitive),
// materials, textures, the node hierarchy flattened to instances, cameras and lights in
// world space. Positions are in scene units; mm_per_unit converts them to the mm of the
// optical coefficients (glTF is in metres: 1000).
#pragma once

#include "scene/Bounds.h"
#include "scene/Camera.h"
#include "scene/Environment.h"
#include "scene/Light.h"
#include "scene/Material.h"
#include "scene/Mesh.h"
#include "scene/Texture.h"

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sss::scene {

struct Instance {
  std::uint32_t mesh = 0;  // Scene::meshes
  glm::mat4 world{1.0f};   // mesh space -> world, composed down the node hierarchy
  std::string node;        // the glTF node's name, or "nodes[i]"
};

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;
  std::vector<Material> materials;  // every Mesh::material indexes this
  std::vector<Texture> textures;    // every Material texture index indexes this
  std::vector<Instance> instances;
  std::vector<Camera> cameras;      // cameras[0] is the one to render from
  std::vector<Light> lights;
  // Light from every direction (Environment.h): none unless a tool's --environment sets one.
  std::optional<Environment> environment;
  double mm_per_unit = 1000.0;
  std::vector<std::string> warnings;  // what was skipped or repaired, for the user
  // What only texture-space SSS (--sss texture) is concerned with: a generated UV atlas
  // and why the file's UVs did not serve. Printed where that mode runs, as notes.
  std::vector<std::string> texture_notes;

  // World-space bounds of every instance (empty box for an empty scene).
  Bounds bounds() const;
  std::size_t triangle_count() const;  // over instances
};

// A perspective camera framing the scene's bounds, added when it has none.
void add_camera_if_missing(Scene& scene);

// A white directional key light from the upper left front (E = 3), added when the scene
// has no light, so that a file without lights is not rendered black.
void add_light_if_missing(Scene& scene);

}  // namespace sss::scene
