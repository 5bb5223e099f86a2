#include "scene/Scene.h"

namespace sss::scene {

Bounds Scene::bounds() const {
  Bounds b;
  for (const Instance& inst : instances)
    if (inst.mesh < meshes.size()) b.extend(meshes[inst.mesh].bounds.transformed(inst.world));
  return b;
}

std::size_t Scene::triangle_count() const {
  std::size_t n = 0;
  for (const Instance& inst : instances)
    if (inst.mesh < meshes.size()) n += meshes[inst.mesh].triangle_count();
  return n;
}

void add_camera_if_missing(Scene& scene) {
  if (scene.cameras.empty()) scene.cameras.push_back(frame_bounds(scene.bounds()));
}

void add_light_if_missing(Scene& scene) {
  if (scene.lights.empty())
    scene.lights.push_back(directional_light("default key", {0.5f, -0.7f, -0.5f}, 3.0f));
}

}  // namespace sss::scene
