#include "scene/Light.h"

#include "scene/Camera.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace sss::scene {

glm::vec3 Light::direction() const { return glm::normalize(-glm::vec3(world[2])); }

bool Light::reaches(const glm::vec3& p) const {
  return !mask || glm::dot(glm::vec3(*mask), p) + mask->w < 0.0f;
}

Light directional_light(const std::string& name, const glm::vec3& direction, float irradiance,
                        const glm::vec3& color) {
  Light l;
  l.name = name;
  l.type = LightType::Directional;
  l.color = color;
  l.intensity = irradiance;
  const glm::vec3 d = glm::normalize(direction);
  const glm::vec3 up = std::fabs(d.y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
  // Placed one unit up-stream of the origin; only the orientation matters.
  l.world = look_at_world(-d, glm::vec3(0.0f), up);
  return l;
}

}  // namespace sss::scene
