#include "reference/SkyOcclusion.h"

#include "profiles/Random.h"
#include "reference/RayScene.h"
#include "reference/Thickness.h"
#include "scene/Environment.h"

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace sss::reference {

namespace {

constexpr double kPi = 3.14159265358979323846;
// 1 / A_l per coefficient (Y_00; Y_1m x 3; Y_2m x 5).
constexpr std::array<double, 9> kInverseA = {1.0 / kPi,         3.0 / (2.0 * kPi), 3.0 / (2.0 * kPi),
                                             3.0 / (2.0 * kPi), 4.0 / kPi,         4.0 / kPi,
                                             4.0 / kPi,         4.0 / kPi,         4.0 / kPi};

// The seed of a vertex's directions: its position's and normal's bits, so that copies of
// one vertex (UV seams, split normals, an atlas's re-indexing) get the same estimate.
std::uint64_t seed_of(const glm::vec3& p, const glm::vec3& n) {
  std::uint64_t h = 0x5C0CC1u;
  for (const float v : {p.x, p.y, p.z, n.x, n.y, n.z}) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &v, sizeof(bits));
    h = profiles::SplitMix64(h ^ bits).next();
  }
  return h;
}

// `origin`: the vertex lifted off its surface (see sky_occlusion).
SkyTransfer vertex_transfer(const RayScene& rays, const glm::vec3& origin, const glm::vec3& n,
                            std::uint64_t seed) {
  SkyTransfer out{};
  const glm::vec3 a = std::fabs(n.x) > 0.9f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
  const glm::vec3 b1 = glm::normalize(glm::cross(a, n));
  const glm::vec3 b2 = glm::cross(n, b1);
  profiles::Xoshiro256ss rng(seed);
  const int k = kSkyOcclusionStrata;
  std::array<double, 9> sum{};
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      // Density cos / pi: cos = sqrt(1 - u1), azimuth 2 pi u2 (as the references sample).
      const double u1 = (i + rng.uniform()) / k, u2 = (j + rng.uniform()) / k;
      const double c = std::sqrt(std::max(0.0, 1.0 - u1)), s = std::sqrt(std::max(0.0, u1));
      const double phi = 2.0 * kPi * u2;
      const glm::vec3 w = glm::normalize(b1 * float(s * std::cos(phi)) + b2 * float(s * std::sin(phi)) +
                                         n * float(c));
      if (!rays.occluded(origin, w, 0.0f, std::numeric_limits<float>::infinity())) continue;
      const std::array<float, 9> y = scene::sh_basis(w);
      for (int m = 0; m < 9; ++m) sum[m] += y[m];
    }
  for (int m = 0; m < 9; ++m) out[m] = float(sum[m] * kPi / double(k * k) * kInverseA[m]);
  return out;
}

}  // namespace

std::vector<std::vector<SkyTransfer>> sky_occlusion(const scene::Scene& scene,
                                                   const std::atomic<bool>* cancel) {
  bool any = false;
  for (const scene::Instance& instance : scene.instances)
    any = any || (instance.mesh < scene.meshes.size() && scene.meshes[instance.mesh].triangle_count() > 0);
  if (!any) return std::vector<std::vector<SkyTransfer>>(scene.instances.size());
  return sky_occlusion(scene, RayScene(scene), cancel);
}

std::vector<std::vector<SkyTransfer>> sky_occlusion(const scene::Scene& scene, const RayScene& rays,
                                                   const std::atomic<bool>* cancel) {
  std::vector<std::vector<SkyTransfer>> out(scene.instances.size());
  scene::Bounds box;
  for (std::uint32_t i = 0; i < scene.instances.size(); ++i)
    for (const glm::vec3& p : rays.world_positions(i)) box.extend(p);
  const float offset = 1e-4f * glm::length(box.extent());
  for (std::uint32_t i = 0; i < scene.instances.size(); ++i) {
    const std::uint32_t m = scene.instances[i].mesh;
    if (m >= scene.meshes.size() || scene.meshes[m].triangle_count() == 0) continue;
    const scene::Mesh& mesh = scene.meshes[m];
    const std::vector<glm::vec3>& world = rays.world_positions(i);
    const glm::mat3& normal_matrix = rays.normal_matrix(i);
    std::vector<SkyTransfer>& transfers = out[i];
    transfers.assign(mesh.positions.size(), SkyTransfer{});
    if (mesh.normals.size() != mesh.positions.size()) continue;
    // A thousandth of the way toward the vertex's own triangles (fan_centroids): at a
    // concave crease with split normals (a box's inside corner, a floor against a wall)
    // the lifted vertex would lie in the next face's plane, where a ray into that face
    // hits at t = 0 or not at all by rounding.
    const std::vector<glm::vec3> centroid = fan_centroids(world, mesh.indices);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, transfers.size(), 256),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        if (cancel && cancel->load()) return;
                        for (std::size_t v = r.begin(); v != r.end(); ++v) {
                          const glm::vec3 n = normal_matrix * mesh.normals[v];
                          const float len = glm::length(n);
                          if (!(len > 0.0f) || !std::isfinite(len)) continue;
                          const glm::vec3 origin =
                              world[v] + 1e-3f * (centroid[v] - world[v]) + n / len * offset;
                          transfers[v] = vertex_transfer(rays, origin, n / len, seed_of(world[v], n / len));
                        }
                      });
  }
  return out;
}

glm::vec3 blocked_irradiance(const std::array<glm::vec3, 9>& sh, const SkyTransfer& t) {
  glm::vec3 e(0.0f);
  for (int k = 0; k < 9; ++k) e += sh[k] * t[k];
  return e;
}

}  // namespace sss::reference
