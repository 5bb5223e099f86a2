#include "scene/Mesh.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <numeric>

namespace sss::scene {

namespace {

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

std::vector<glm::vec3> area_weighted_normals(const std::vector<glm::vec3>& positions,
                                             const std::vector<std::uint32_t>& indices) {
  // Accumulate in double: thin slivers next to large faces would lose bits in float.
  std::vector<glm::dvec3> sum(positions.size(), glm::dvec3(0.0));
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const std::uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
    if (a >= positions.size() || b >= positions.size() || c >= positions.size()) continue;
    const glm::dvec3 pa(positions[a]), pb(positions[b]), pc(positions[c]);
    const glm::dvec3 n = glm::cross(pb - pa, pc - pa);  // length = 2 x area
    sum[a] += n;
    sum[b] += n;
    sum[c] += n;
  }
  std::vector<glm::vec3> normals(positions.size());
  for (std::size_t v = 0; v < positions.size(); ++v) {
    const double len = glm::length(sum[v]);
    normals[v] = (len > 0.0 && std::isfinite(len)) ? glm::vec3(sum[v] / len)
                                                    : glm::vec3(0.0f, 1.0f, 0.0f);
  }
  return normals;
}

std::size_t repair_normals(Mesh& mesh) {
  if (mesh.normals.size() != mesh.positions.size()) {
    mesh.normals = area_weighted_normals(mesh.positions, mesh.indices);
    return 0;
  }
  std::vector<glm::vec3> generated;
  std::size_t replaced = 0;
  for (std::size_t v = 0; v < mesh.normals.size(); ++v) {
    glm::vec3& n = mesh.normals[v];
    const float len = finite(n) ? glm::length(n) : 0.0f;
    if (len > 1e-6f && std::isfinite(len)) {
      n /= len;
      continue;
    }
    if (generated.empty()) generated = area_weighted_normals(mesh.positions, mesh.indices);
    n = generated[v];
    ++replaced;
  }
  return replaced;
}

std::vector<std::uint32_t> sequential_indices(std::uint32_t count) {
  std::vector<std::uint32_t> idx(count);
  std::iota(idx.begin(), idx.end(), 0u);
  return idx;
}

void compute_bounds(Mesh& mesh) {
  mesh.bounds = Bounds{};
  for (const glm::vec3& p : mesh.positions) mesh.bounds.extend(p);
}

std::optional<std::string> check_mesh(const Mesh& mesh) {
  const std::size_t n = mesh.positions.size();
  if (n == 0) return "has no vertices";
  if (mesh.normals.size() != n) return "normals: count differs from positions";
  if (!mesh.uv0.empty() && mesh.uv0.size() != n) return "uv0: count differs from positions";
  if (!mesh.tangents.empty() && mesh.tangents.size() != n)
    return "tangents: count differs from positions";
  if (!mesh.uv_atlas.empty() && mesh.uv_atlas.size() != n)
    return "uv_atlas: count differs from positions";
  if (mesh.indices.empty() || mesh.indices.size() % 3 != 0)
    return "indices: count must be a positive multiple of 3";
  for (std::uint32_t i : mesh.indices)
    if (i >= n) return "indices: value " + std::to_string(i) + " >= vertex count " + std::to_string(n);
  for (const glm::vec3& p : mesh.positions)
    if (!finite(p)) return "positions: not finite";
  for (const glm::vec3& nrm : mesh.normals)
    if (!finite(nrm) || std::fabs(glm::length(nrm) - 1.0f) > 1e-3f) return "normals: not unit";
  return std::nullopt;
}

}  // namespace sss::scene
