#include "scene/Camera.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>

namespace sss::scene {

glm::vec3 Camera::forward() const { return glm::normalize(-glm::vec3(world[2])); }
glm::vec3 Camera::up() const { return glm::normalize(glm::vec3(world[1])); }
glm::mat4 Camera::view() const { return glm::inverse(world); }

glm::mat4 clip_from_view(const Camera& camera, std::uint32_t width, std::uint32_t height, bool reversed_depth) {
  const float aspect = float(width) / float(height);
  glm::mat4 proj;
  // Swapping the planes maps the near one to depth 1 and the far one to 0 (glm's _ZO
  // forms are linear in 1/z or z between the two planes it is given).
  if (camera.projection == Projection::Orthographic) {
    const glm::vec2 half = camera.ortho_half_extent(aspect);
    const float n = reversed_depth ? camera.zfar : camera.znear, f = reversed_depth ? camera.znear : camera.zfar;
    proj = glm::orthoRH_ZO(-half.x, half.x, -half.y, half.y, n, f);
  } else {
    const float a = camera.aspect > 0.0f ? camera.aspect : aspect;
    const float zfar = camera.zfar > 0.0f ? camera.zfar : camera.znear * 1.0e5f;
    proj = reversed_depth ? glm::perspectiveRH_ZO(camera.yfov, a, zfar, camera.znear)
                          : glm::perspectiveRH_ZO(camera.yfov, a, camera.znear, zfar);
  }
  proj[1][1] = -proj[1][1];  // Vulkan: image y points down
  return proj;
}

glm::mat4 look_at_world(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up) {
  const glm::vec3 back = glm::normalize(eye - target);  // local +Z
  const glm::vec3 right = glm::normalize(glm::cross(up, back));
  const glm::vec3 true_up = glm::cross(back, right);
  glm::mat4 m(1.0f);
  m[0] = glm::vec4(right, 0.0f);
  m[1] = glm::vec4(true_up, 0.0f);
  m[2] = glm::vec4(back, 0.0f);
  m[3] = glm::vec4(eye, 1.0f);
  return m;
}

Camera frame_bounds(const Bounds& bounds, const glm::vec3& direction, float yfov, float margin) {
  Camera cam;
  cam.name = "framed";
  cam.projection = Projection::Perspective;
  cam.yfov = yfov;
  const glm::vec3 center = bounds.empty() ? glm::vec3(0.0f) : bounds.center();
  const float radius = std::max(bounds.radius(), 1e-3f);
  const float distance = margin * radius / std::sin(0.5f * yfov);
  const glm::vec3 dir = glm::normalize(direction);
  const glm::vec3 up = std::fabs(dir.y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
  cam.world = look_at_world(center - dir * distance, center, up);
  cam.znear = std::max(distance - 2.0f * radius, 0.01f * radius);
  cam.zfar = distance + 2.0f * radius;
  return cam;
}

}  // namespace sss::scene
