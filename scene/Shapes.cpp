#include "scene/Shapes.h"

#include <glm/geometric.hpp>

#include <array>
#include <cmath>
#include <numbers>

namespace sss::scene {

Mesh make_uv_sphere(float radius, std::uint32_t segments, std::uint32_t rings,
                    std::uint32_t material) {
  Mesh m;
  m.name = "sphere";
  m.material = material;
  const float pi = std::numbers::pi_v<float>;
  for (std::uint32_t i = 0; i <= rings; ++i) {
    const float theta = pi * float(i) / float(rings);  // from +Y
    for (std::uint32_t j = 0; j <= segments; ++j) {
      const float phi = 2.0f * pi * float(j) / float(segments);
      const glm::vec3 n(std::sin(theta) * std::sin(phi), std::cos(theta),
                        std::sin(theta) * std::cos(phi));
      m.positions.push_back(radius * n);
      m.normals.push_back(n);
      m.uv0.emplace_back(float(j) / float(segments), float(i) / float(rings));
      m.tangents.emplace_back(std::cos(phi), 0.0f, -std::sin(phi), 1.0f);  // d/dphi
    }
  }
  const std::uint32_t row = segments + 1;
  for (std::uint32_t i = 0; i < rings; ++i) {
    for (std::uint32_t j = 0; j < segments; ++j) {
      const std::uint32_t a = i * row + j, b = a + row;  // b: one ring further south
      if (i != 0) m.indices.insert(m.indices.end(), {a, b, a + 1});
      if (i + 1 != rings) m.indices.insert(m.indices.end(), {a + 1, b, b + 1});
    }
  }
  compute_bounds(m);
  return m;
}

Mesh make_box(const glm::vec3& lo, const glm::vec3& hi, std::uint32_t material) {
  Mesh m;
  m.name = "box";
  m.material = material;
  // For each face: normal, then the tangent (u direction) and bitangent (v direction).
  const std::array<std::array<glm::vec3, 3>, 6> faces = {{
      {glm::vec3(1, 0, 0), glm::vec3(0, 0, -1), glm::vec3(0, 1, 0)},
      {glm::vec3(-1, 0, 0), glm::vec3(0, 0, 1), glm::vec3(0, 1, 0)},
      {glm::vec3(0, 1, 0), glm::vec3(1, 0, 0), glm::vec3(0, 0, -1)},
      {glm::vec3(0, -1, 0), glm::vec3(1, 0, 0), glm::vec3(0, 0, 1)},
      {glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)},
      {glm::vec3(0, 0, -1), glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0)},
  }};
  const glm::vec3 center = 0.5f * (lo + hi), half = 0.5f * (hi - lo);
  for (const auto& [n, t, b] : faces) {
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    for (int k = 0; k < 4; ++k) {
      const float su = (k == 1 || k == 2) ? 1.0f : -1.0f, sv = (k >= 2) ? 1.0f : -1.0f;
      m.positions.push_back(center + half * (n + su * t + sv * b));
      m.normals.push_back(n);
      m.uv0.emplace_back(0.5f * (su + 1.0f), 0.5f * (1.0f - sv));
      m.tangents.emplace_back(t, 1.0f);
    }
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }
  compute_bounds(m);
  return m;
}

}  // namespace sss::scene
