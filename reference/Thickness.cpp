#include "reference/Thickness.h"

#include "reference/RayScene.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace sss::reference {

std::vector<float> inward_thickness(const scene::Mesh& mesh) {
  if (mesh.triangle_count() == 0 || mesh.normals.size() != mesh.positions.size()) return {};
  // The mesh alone, in its own units (mm_per_unit 1: RayScene's "mm" are mesh units).
  scene::Scene alone;
  alone.mm_per_unit = 1.0;
  alone.meshes.push_back(mesh);
  alone.meshes.back().uv_atlas_gutter = {};
  alone.instances.push_back({});
  const RayScene rays(alone);
  scene::Bounds box;
  for (const glm::vec3& p : mesh.positions) box.extend(p);
  const float start = 1e-4f * glm::length(box.extent());
  // Each ray starts a thousandth of the way from its vertex to the mean centroid of the
  // triangles around it: a ray from a box's corner runs exactly along the edges of the
  // side faces and reaches the opposite face at a corner, where even a watertight
  // traversal may slip between triangles; moved into its own face, it runs parallel to
  // the sides and meets the opposite face inside.
  const std::vector<glm::vec3> centroid = fan_centroids(mesh.positions, mesh.indices);
  std::vector<float> out(mesh.positions.size(), -1.0f);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const glm::vec3 n = mesh.normals[i];
    const float len = glm::length(n);
    if (!(len > 0.0f) || !std::isfinite(len)) continue;
    const glm::vec3 origin = mesh.positions[i] + 1e-3f * (centroid[i] - mesh.positions[i]);
    if (const auto hit = rays.intersect(origin, -n / len, start)) out[i] = hit->t;
  }
  return out;
}

std::vector<glm::vec3> fan_centroids(const std::vector<glm::vec3>& positions,
                                     const std::vector<std::uint32_t>& indices) {
  std::vector<glm::vec3> sum(positions.size(), glm::vec3(0.0f));
  std::vector<int> around(positions.size(), 0);
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const glm::vec3 c = (positions[indices[t]] + positions[indices[t + 1]] + positions[indices[t + 2]]) / 3.0f;
    for (int k = 0; k < 3; ++k) {
      sum[indices[t + k]] += c;
      ++around[indices[t + k]];
    }
  }
  for (std::size_t v = 0; v < positions.size(); ++v) sum[v] = around[v] > 0 ? sum[v] / float(around[v]) : positions[v];
  return sum;
}

}  // namespace sss::reference
