// The builtin sphere inside a closed box whose faces look inward (normals and winding
// turned), camera inside too, under a uniform sky: every direction from every vertex of
// the sphere and of the box meets the box, so the sky occlusion's bake
// (reference/SkyOcclusion.h) blocks the whole sky, each sample adding the same Y_00:
// E_blocked = E_open exactly. The box has a second material, without subsurface
// scattering. Shared by the GPU's and the reference's sky-occlusion tests.
#pragma once

#include "scene/BuiltinScenes.h"
#include "scene/Environment.h"
#include "scene/Shapes.h"

#include <utility>

namespace sss::testing {

inline scene::Scene boxed_sphere(const glm::vec3& sky) {
  scene::Scene s = scene::sphere_scene();
  const scene::Bounds b = s.bounds();
  const glm::vec3 c = b.center(), half(10.0f * b.radius());
  scene::Mesh box = scene::make_box(c - half, c + half, 1);
  for (glm::vec3& n : box.normals) n = -n;
  for (std::size_t t = 0; t + 2 < box.indices.size(); t += 3) std::swap(box.indices[t + 1], box.indices[t + 2]);
  box.tangents.clear();
  box.name = "box";
  scene::Material wall = s.materials[0];
  wall.name = "wall";
  wall.sss.enabled = false;
  s.materials.push_back(wall);
  s.meshes.push_back(box);
  s.instances.push_back({std::uint32_t(s.meshes.size() - 1), glm::mat4(1.0f), "box"});
  s.environment = scene::uniform_environment(sky);
  s.cameras[0].zfar = 0.0f;  // infinite: the box's far walls are beyond the sphere's frame
  return s;
}

}  // namespace sss::testing
