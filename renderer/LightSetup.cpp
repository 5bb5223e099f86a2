#include "renderer/LightSetup.h"

#include "renderer/CameraSetup.h"
#include "scene/ShadowFrustum.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace sss::renderer {

LightSetup make_light_setup(const scene::Scene& scene, std::uint32_t shadow_map_size) {
  return make_light_setup(scene.lights, scene.bounds(), shadow_map_size);
}

LightSetup make_light_setup(const std::vector<scene::Light>& lights, const scene::Bounds& bounds,
                            std::uint32_t shadow_map_size) {
  LightSetup out;
  for (const scene::Light& light : lights) {
    if (out.count == shader::kMaxLights) {
      out.warnings.push_back("light '" + light.name + "' ignored: at most " +
                             std::to_string(shader::kMaxLights) + " lights are shaded");
      continue;
    }
    shader::GpuLight& g = out.block.lights[out.count];
    const glm::vec3 c = light.color * light.intensity;
    const glm::vec3 d = light.direction();
    const glm::vec3 p = light.position();
    int type = SSS_LIGHT_DIRECTIONAL;
    if (light.type == scene::LightType::Point) type = SSS_LIGHT_POINT;
    if (light.type == scene::LightType::Spot) type = SSS_LIGHT_SPOT;
    g.color = {c.r, c.g, c.b, float(type)};
    g.direction = {d.x, d.y, d.z, std::cos(light.outer_cone)};
    g.position = {p.x, p.y, p.z, std::cos(light.inner_cone)};
    if (light.mask) g.mask = {light.mask->x, light.mask->y, light.mask->z, light.mask->w};
    g.shadow = {light.mask ? 1.0f : 0.0f, 0.0f, 0.0f, 0.0f};
    const scene::ShadowFrustum f = scene::shadow_frustum(light, bounds, shadow_map_size);
    const bool shadowed = f.shadowed;
    if (shadowed) {
      g.shadow_matrix = to_shader(f.view_proj);
      g.shadow_inverse = to_shader(f.inverse);
      g.shadow.z = f.normal_offset;
      g.shadow.w = f.depth_bias;
    }
    g.shadow.y = shadowed ? 1.0f : 0.0f;
    out.shadowed.push_back(shadowed);
    ++out.count;
  }
  return out;
}

}  // namespace sss::renderer
