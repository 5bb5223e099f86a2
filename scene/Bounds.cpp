#include "scene/Bounds.h"

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

namespace sss::scene {

void Bounds::extend(const glm::vec3& p) {
  min = glm::min(min, p);
  max = glm::max(max, p);
}

void Bounds::extend(const Bounds& b) {
  if (b.empty()) return;
  extend(b.min);
  extend(b.max);
}

float Bounds::radius() const { return empty() ? 0.0f : 0.5f * glm::length(extent()); }

Bounds Bounds::transformed(const glm::mat4& m) const {
  Bounds out;
  if (empty()) return out;
  for (int i = 0; i < 8; ++i) out.extend(glm::vec3(m * glm::vec4(corner(i), 1.0f)));
  return out;
}

}  // namespace sss::scene
