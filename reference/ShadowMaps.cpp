#include "reference/ShadowMaps.h"

#include "shaders/shared/frame.h"

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace sss::reference {

namespace {

glm::vec3 project(const glm::mat4& m, const glm::vec3& p) {
  const glm::vec4 c = m * glm::vec4(p, 1.0f);
  return glm::vec3(c) / c.w;
}

}  // namespace

ShadowMaps::ShadowMaps(const scene::Scene& s, const RayScene& rays, std::uint32_t size)
    : size_(size), mm_per_unit_(float(s.mm_per_unit)) {
  if (size < 1 || size > 16384)
    throw std::invalid_argument("shadow map size: must be 1..16384, got " + std::to_string(size));
  const scene::Bounds bounds = s.bounds();
  const std::size_t shaded = std::min<std::size_t>(s.lights.size(), shader::kMaxLights);
  maps_.resize(shaded);
  const float n = float(size);
  for (std::size_t l = 0; l < shaded; ++l) {
    Map& map = maps_[l];
    map.frustum = scene::shadow_frustum(s.lights[l], bounds, size);
    if (!map.frustum.shadowed) continue;
    map.depth.assign(std::size_t(size) * size, 1.0f);
    map.raw.assign(std::size_t(size) * size, 1.0f);
    const glm::mat4& inv = map.frustum.inverse;
    const glm::mat4& vp = map.frustum.view_proj;
    const float mm = mm_per_unit_;
    tbb::parallel_for(std::uint32_t(0), size, [&](std::uint32_t y) {
      for (std::uint32_t x = 0; x < size; ++x) {
        // The texel centre's line of sight through the frustum, near plane to far plane.
        const float nx = (float(x) + 0.5f) / n * 2.0f - 1.0f, ny = (float(y) + 0.5f) / n * 2.0f - 1.0f;
        const glm::vec3 a = project(inv, {nx, ny, 0.0f}) * mm, b = project(inv, {nx, ny, 1.0f}) * mm;
        const float length = glm::length(b - a);
        if (!(length > 0.0f)) continue;
        const glm::vec3 dir = (b - a) / length;
        const std::optional<Hit> hit = rays.intersect(a, dir, 0.0f, length);
        if (!hit) continue;
        const glm::vec3 p = (a + dir * hit->t) / mm;
        const float z = project(vp, p).z;
        if (!(z >= 0.0f && z <= 1.0f)) continue;  // clipped, as the rasterizer clips it
        // The triangle's depth slope per texel in window coordinates (depth is affine in
        // window x, y for orthographic and perspective projections alike).
        const std::vector<glm::vec3>& world = rays.world_positions(hit->instance);
        const scene::Mesh& mesh = s.meshes[s.instances[hit->instance].mesh];
        glm::vec3 w[3];
        for (int k = 0; k < 3; ++k) {
          const glm::vec3 q = project(vp, world[mesh.indices[3 * hit->triangle + k]] / mm);
          w[k] = {(q.x * 0.5f + 0.5f) * n, (q.y * 0.5f + 0.5f) * n, q.z};
        }
        const glm::vec3 normal = glm::cross(w[1] - w[0], w[2] - w[0]);
        float slope = 0.0f;
        if (std::fabs(normal.z) > 1e-12f)
          slope = std::max(std::fabs(normal.x / normal.z), std::fabs(normal.y / normal.z));
        map.depth[std::size_t(y) * size + x] = z + scene::kShadowSlopeBias * slope;
        map.raw[std::size_t(y) * size + x] = z;
      }
    });
  }
}

double ShadowMaps::thickness_mm(std::size_t index, const glm::vec3& p_mm) const {
  if (index >= maps_.size() || maps_[index].raw.empty()) return -1.0;
  const Map& m = maps_[index];
  const glm::vec3 p = p_mm / mm_per_unit_;
  const glm::vec3 s = project(m.frustum.view_proj, p);
  const float u = s.x * 0.5f + 0.5f, v = s.y * 0.5f + 0.5f;
  if (u < 0.0f || v < 0.0f || u > 1.0f || v > 1.0f || s.z > 1.0f || s.z < 0.0f) return -1.0;
  const int last = int(size_) - 1;
  const auto at = [&](int x, int y) {
    return m.raw[std::size_t(std::clamp(y, 0, last)) * size_ + std::size_t(std::clamp(x, 0, last))];
  };
  const float fx = u * float(size_), fy = v * float(size_);
  const int tx = std::clamp(int(fx), 0, last), ty = std::clamp(int(fy), 0, last);
  const float d = at(tx, ty);
  // The depth step to the neighbour on the side where it is smaller (the other side may
  // lie on another triangle, or on the background at a silhouette).
  const auto step = [&](int ax, int ay) {
    const float back = d - at(tx - ax, ty - ay), ahead = at(tx + ax, ty + ay) - d;
    return std::fabs(back) < std::fabs(ahead) ? back : ahead;
  };
  float z = 1.0f;
  if (d < 1.0f) z = d + step(1, 0) * (fx - (float(tx) + 0.5f)) + step(0, 1) * (fy - (float(ty) + 0.5f));
  if (z >= s.z) {
    // No surface on p's texel nearer the light than p: the middle of 0 and p's distance to
    // the nearest surface on the texels around it (0 for a lit surface).
    float nearest = 1.0f;
    for (int j = -1; j <= 1; ++j)
      for (int i = -1; i <= 1; ++i) nearest = std::min(nearest, at(tx + i, ty + j));
    if (nearest >= s.z) return 0.0;
    z = 0.5f * (nearest + s.z);
  }
  const glm::vec3 q = project(m.frustum.inverse, {s.x, s.y, std::max(z, 0.0f)});
  return double(glm::length(p - q)) * double(mm_per_unit_);
}

float ShadowMaps::depth(std::size_t index, std::uint32_t x, std::uint32_t y) const {
  const Map& m = maps_.at(index);
  if (m.depth.empty() || x >= size_ || y >= size_) return 1.0f;
  return m.depth[std::size_t(y) * size_ + x];
}

double ShadowMaps::visibility(std::size_t index, const glm::vec3& p_mm, const glm::vec3& n) const {
  if (index >= maps_.size()) return 0.0;  // not shaded at all
  const Map& m = maps_[index];
  if (m.depth.empty()) return 1.0;
  const glm::vec3 p = p_mm / mm_per_unit_ + n * m.frustum.normal_offset;
  const glm::vec3 s = project(m.frustum.view_proj, p);
  const float u = s.x * 0.5f + 0.5f, v = s.y * 0.5f + 0.5f;
  if (u < 0.0f || v < 0.0f || u > 1.0f || v > 1.0f || s.z > 1.0f) return 1.0;
  const float ref = s.z - m.frustum.depth_bias;
  const float tx = u * float(size_) - 0.5f, ty = v * float(size_) - 0.5f;
  const float ix = std::floor(tx), iy = std::floor(ty);
  const float fx = tx - ix, fy = ty - iy;
  const float wx[4] = {1.0f - fx, 1.0f, 1.0f, fx}, wy[4] = {1.0f - fy, 1.0f, 1.0f, fy};
  const int last = int(size_) - 1;
  double sum = 0.0;
  for (int b = 0; b < 4; ++b) {
    const int y = std::clamp(int(iy) - 1 + b, 0, last);
    for (int a = 0; a < 4; ++a) {
      const int x = std::clamp(int(ix) - 1 + a, 0, last);
      if (ref <= m.depth[std::size_t(y) * size_ + std::size_t(x)]) sum += double(wx[a]) * wy[b];
    }
  }
  return sum / 9.0;
}

}  // namespace sss::reference
