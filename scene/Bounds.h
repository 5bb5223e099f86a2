// Bounds: an axis-aligned box in the units of the points put into it (metres for a
// scene). An empty box has min > max; extending it with a point makes it that point.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <limits>

namespace sss::scene {

struct Bounds {
  glm::vec3 min{std::numeric_limits<float>::infinity()};
  glm::vec3 max{-std::numeric_limits<float>::infinity()};

  bool empty() const { return !(min.x <= max.x && min.y <= max.y && min.z <= max.z); }
  void extend(const glm::vec3& p);
  void extend(const Bounds& b);
  glm::vec3 center() const { return 0.5f * (min + max); }
  glm::vec3 extent() const { return max - min; }
  // Radius of the sphere around center() that holds the box.
  float radius() const;
  // The box around the eight transformed corners (exact for translations and axis
  // permutations, conservative under rotation).
  Bounds transformed(const glm::mat4& m) const;
  // Corner i of 8: bit 0 picks max.x, bit 1 max.y, bit 2 max.z.
  glm::vec3 corner(int i) const {
    return {(i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z};
  }
};

}  // namespace sss::scene
