#include "renderer/LightSetup.h"

#include "renderer/CameraSetup.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace sss::renderer {

namespace {

glm::vec3 any_up(const glm::vec3& d) {
  return std::fabs(d.y) > 0.99f ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
}

}  // namespace

LightSetup make_light_setup(const scene::Scene& scene, std::uint32_t shadow_map_size) {
  return make_light_setup(scene.lights, scene.bounds(), shadow_map_size);
}

LightSetup make_light_setup(const std::vector<scene::Light>& lights, const scene::Bounds& bounds,
                            std::uint32_t shadow_map_size) {
  LightSetup out;
  const glm::vec3 center = bounds.empty() ? glm::vec3(0.0f) : bounds.center();
  const float radius = bounds.empty() ? 1.0f : std::max(bounds.radius(), 1e-6f);
  const float size = float(std::max(shadow_map_size, 1u));
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
    bool shadowed = false;
    if (type == SSS_LIGHT_DIRECTIONAL) {
      // The bounding sphere seen along the light: depth covers [eye+0.5r, eye+3.5r].
      const glm::vec3 eye = center - d * (2.0f * radius);
      const glm::mat4 view = glm::lookAtRH(eye, center, any_up(d));
      const glm::mat4 proj =
          glm::orthoRH_ZO(-radius, radius, -radius, radius, 0.5f * radius, 3.5f * radius);
      g.shadow_matrix = to_shader(proj * view);
      g.shadow_inverse = to_shader(glm::inverse(proj * view));
      const float texel = 2.0f * radius / size;
      g.shadow.z = 1.5f * texel;          // normal offset, scene units
      g.shadow.w = 2.0f * texel / (3.0f * radius);  // depth bias, in depth units
      shadowed = true;
    } else if (type == SSS_LIGHT_SPOT) {
      const float dist = glm::length(center - p);
      const float fov = std::min(2.0f * light.outer_cone, 3.0f);
      const float znear = std::max(0.01f * radius, dist - 2.0f * radius > 0.0f
                                                       ? 0.5f * (dist - radius)
                                                       : 0.01f * radius);
      const float zfar = dist + 2.0f * radius;
      const glm::mat4 view = glm::lookAtRH(p, p + d, any_up(d));
      const glm::mat4 proj = glm::perspectiveRH_ZO(fov, 1.0f, znear, zfar);
      g.shadow_matrix = to_shader(proj * view);
      g.shadow_inverse = to_shader(glm::inverse(proj * view));
      const float texel = 2.0f * dist * std::tan(0.5f * fov) / size;
      g.shadow.z = 1.5f * texel;
      g.shadow.w = 1e-5f;
      shadowed = true;
    }
    g.shadow.y = shadowed ? 1.0f : 0.0f;
    out.shadowed.push_back(shadowed);
    ++out.count;
  }
  return out;
}

}  // namespace sss::renderer
