// builtin:sphere and builtin:materials: SSS objects of a few centimetres (glTF metres),
// lit by one key light from the upper left front and seen by a framing camera.
#include "scene/BuiltinScenes.h"

#include "scene/Shapes.h"

#include "profiles/Presets.h"

#include <stdexcept>

namespace sss::scene {

namespace {

Material sss_material(const std::string& preset, float roughness) {
  Material m;
  m.name = preset;
  m.metallic = 0.0f;
  m.roughness = roughness;
  m.sss = preset_sss_material(preset);
  return m;
}

const glm::vec3 kKeyDirection{0.6f, -0.55f, -0.6f};  // from the upper left front

}  // namespace

Scene sphere_scene() {
  Scene s;
  s.name = "builtin:sphere";
  s.materials.push_back(sss_material("skin1", 0.45f));
  s.meshes.push_back(make_uv_sphere(0.030f, 96, 48, 0));  // radius 30 mm
  s.instances.push_back({0, glm::mat4(1.0f), "sphere"});
  s.lights.push_back(directional_light("key", kKeyDirection, 3.0f));
  s.cameras.push_back(frame_bounds(s.bounds(), {0.0f, -0.2f, -1.0f}));
  return s;
}

Scene materials_scene() {
  Scene s;
  s.name = "builtin:materials";
  const float radius = 0.015f, pitch = 0.040f;  // 15 mm spheres, 40 mm apart
  const std::uint32_t columns = 6;
  for (const profiles::Preset& p : profiles::presets()) {
    Material m;
    try {
      m = sss_material(std::string(p.name), 0.4f);
    } catch (const std::invalid_argument&) {
      continue;  // spectralon: albedo 1, no finite profile
    }
    const auto index = static_cast<std::uint32_t>(s.materials.size());
    s.materials.push_back(m);
    Mesh sphere = make_uv_sphere(radius, 48, 24, index);
    sphere.name = m.name + " sphere";
    s.meshes.push_back(std::move(sphere));
    const float x = (float(index % columns) - 0.5f * float(columns - 1)) * pitch;
    const float y = -float(index / columns) * pitch;
    glm::mat4 world(1.0f);
    world[3] = glm::vec4(x, y, 0.0f, 1.0f);
    s.instances.push_back({index, world, m.name});
  }
  s.lights.push_back(directional_light("key", kKeyDirection, 3.0f));
  s.cameras.push_back(frame_bounds(s.bounds(), {0.0f, -0.15f, -1.0f}, 0.5f));
  return s;
}

}  // namespace sss::scene
