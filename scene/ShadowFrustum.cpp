#include "scene/ShadowFrustum.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>

namespace sss::scene {

namespace {

glm::vec3 any_up(const glm::vec3& d) {
  return std::fabs(d.y) > 0.99f ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
}

}  // namespace

ShadowFrustum shadow_frustum(const Light& light, const Bounds& bounds, std::uint32_t shadow_map_size) {
  ShadowFrustum out;
  const glm::vec3 center = bounds.empty() ? glm::vec3(0.0f) : bounds.center();
  const float radius = bounds.empty() ? 1.0f : std::max(bounds.radius(), 1e-6f);
  const float size = float(std::max(shadow_map_size, 1u));
  const glm::vec3 d = light.direction();
  if (light.type == LightType::Directional) {
    // The bounding sphere seen along the light: depth covers [eye+0.5r, eye+3.5r].
    const glm::vec3 eye = center - d * (2.0f * radius);
    const glm::mat4 view = glm::lookAtRH(eye, center, any_up(d));
    const glm::mat4 proj = glm::orthoRH_ZO(-radius, radius, -radius, radius, 0.5f * radius, 3.5f * radius);
    out.view_proj = proj * view;
    const float texel = 2.0f * radius / size;
    out.normal_offset = 1.5f * texel;
    out.depth_bias = 2.0f * texel / (3.0f * radius);
    out.shadowed = true;
  } else if (light.type == LightType::Spot) {
    const glm::vec3 p = light.position();
    const float dist = glm::length(center - p);
    const float fov = std::min(2.0f * light.outer_cone, 3.0f);
    const float znear =
        std::max(0.01f * radius, dist - 2.0f * radius > 0.0f ? 0.5f * (dist - radius) : 0.01f * radius);
    const float zfar = dist + 2.0f * radius;
    const glm::mat4 view = glm::lookAtRH(p, p + d, any_up(d));
    const glm::mat4 proj = glm::perspectiveRH_ZO(fov, 1.0f, znear, zfar);
    out.view_proj = proj * view;
    const float texel = 2.0f * dist * std::tan(0.5f * fov) / size;
    out.normal_offset = 1.5f * texel;
    out.depth_bias = 1e-5f;
    out.shadowed = true;
  }
  out.inverse = glm::inverse(out.view_proj);
  return out;
}

}  // namespace sss::scene
