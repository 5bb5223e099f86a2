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
  std::vector<glm::vec3> centroid_sum(mesh.positions.size(), glm::vec3(0.0f));
  std::vector<int> around(mesh.positions.size(), 0);
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::vec3 c = (mesh.positions[mesh.indices[t]] + mesh.positions[mesh.indices[t + 1]] +
                         mesh.positions[mesh.indices[t + 2]]) / 3.0f;
    for (int k = 0; k < 3; ++k) {
      centroid_sum[mesh.indices[t + k]] += c;
      ++around[mesh.indices[t + k]];
    }
  }
  std::vector<float> out(mesh.positions.size(), -1.0f);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const glm::vec3 n = mesh.normals[i];
    const float len = glm::length(n);
    if (!(len > 0.0f) || !std::isfinite(len)) continue;
    glm::vec3 origin = mesh.positions[i];
    if (around[i] > 0) origin += 1e-3f * (centroid_sum[i] / float(around[i]) - origin);
    if (const auto hit = rays.intersect(origin, -n / len, start)) out[i] = hit->t;
  }
  return out;
}

}  // namespace sss::reference
