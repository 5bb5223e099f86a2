// check_uvs: is a UV set usable for texture-space diffusion (exact separating-axis
// overlap tests on a uniform grid), and uv_islands, its connected pieces.
#include "scene/UvAtlas.h"
#include "scene/UvGeometry.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <cstdint>
#include <deque>
#include <exception>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <vector>

namespace sss::scene {

using namespace uv_detail;

UvCheck check_uvs(const Mesh& mesh, const UvCheckOptions& options) {
  return check_uvs(mesh, mesh.uv0, options);
}

namespace {

// The squared diagonal of the mesh's bounds, measured here when they were not computed.
double diagonal2(const Mesh& mesh) {
  const glm::vec3 ext = mesh.bounds.empty() ? glm::vec3(0.0f) : mesh.bounds.max - mesh.bounds.min;
  double diag2 = glm::dot(glm::dvec3(ext), glm::dvec3(ext));
  if (!(diag2 > 0.0)) {  // bounds not computed: measure them here
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    for (const glm::vec3& p : mesh.positions) lo = glm::min(lo, glm::dvec3(p)), hi = glm::max(hi, glm::dvec3(p));
    diag2 = mesh.positions.empty() ? 0.0 : glm::dot(hi - lo, hi - lo);
  }
  return diag2;
}

// Each triangle's UV corners (tri), and the triangles worth testing for overlaps: inside
// [0,1]^2 (within the tolerance) and finite, with 3-D area, and with a UV area not below
// min_relative_area of the mesh's mean UV density. Counts the others into r.
std::vector<std::uint32_t> live_triangles(const Mesh& mesh, const std::vector<glm::vec2>& uv,
                                          const UvCheckOptions& options, std::vector<Tri2>& tri, UvCheck& r) {
  const std::size_t n = mesh.triangle_count();
  const double min_area3 = 1e-12 * diagonal2(mesh);
  tri.assign(n, Tri2{});
  std::vector<double> a3(n), auv(n);
  std::vector<std::uint8_t> skip(n, 0);  // 1 outside/non-finite, 2 no 3D area
  double total3 = 0.0, total_uv = 0.0;
  const double lo = -options.outside_tolerance, hi = 1.0 + options.outside_tolerance;
  for (std::size_t t = 0; t < n; ++t) {
    const std::uint32_t* idx = &mesh.indices[3 * t];
    bool out = false;
    for (int k = 0; k < 3; ++k) {
      const glm::vec2 w = uv[idx[k]];
      if (!finite(w) || w.x < lo || w.y < lo || w.x > hi || w.y > hi) out = true;
      tri[t][k] = glm::dvec2(w);
    }
    a3[t] = area3(mesh.positions[idx[0]], mesh.positions[idx[1]], mesh.positions[idx[2]]);
    if (out) {
      ++r.outside;
      skip[t] = 1;
      continue;
    }
    auv[t] = std::abs(signed_area(tri[t]));
    if (!(a3[t] > min_area3)) {
      skip[t] = 2;
      continue;
    }
    total3 += a3[t];
    total_uv += auv[t];
  }
  const double density = total3 > 0.0 ? total_uv / total3 : 0.0;
  std::vector<std::uint32_t> live;
  for (std::size_t t = 0; t < n; ++t) {
    if (skip[t]) continue;
    if (!(auv[t] > 1e-12) || auv[t] < options.min_relative_area * density * a3[t]) {
      ++r.degenerate;
      continue;
    }
    live.push_back(std::uint32_t(t));
  }
  return live;
}

// Overlaps: insert the triangles one by one into a grid over [0,1]^2 and test each against
// the earlier ones sharing a cell (each pair once, thanks to the stamps). Past a work
// budget the count is a lower bound.
void count_overlaps(const std::vector<Tri2>& tri, const std::vector<std::uint32_t>& live,
                    const UvCheckOptions& options, UvCheck& r) {
  if (live.empty()) return;
  const std::size_t n = tri.size();
  const double cells = std::clamp(std::ceil(std::sqrt(double(live.size()))), 1.0, 2048.0);
  TriGrid grid(1.0 / cells);
  std::vector<std::uint32_t> stamp(n, std::numeric_limits<std::uint32_t>::max());
  std::vector<std::uint8_t> flagged(n, 0);
  const std::size_t budget = 256 * live.size() + 1000000;
  std::size_t work = 0;
  for (std::uint32_t t : live) {
    work += grid.visit(tri[t], [&](std::uint32_t o) {
      if (stamp[o] == t) return;
      stamp[o] = t;
      ++work;
      if (overlaps(tri[t], tri[o], options.overlap_tolerance)) flagged[t] = flagged[o] = 1;
    });
    grid.insert(tri[t], t);
    if (work > budget) {
      r.overlap_count_is_lower_bound = true;
      break;
    }
  }
  for (std::uint8_t f : flagged) r.overlapping += f;
}

}  // namespace

UvCheck check_uvs(const Mesh& mesh, const std::vector<glm::vec2>& uv,
                  const UvCheckOptions& options) {
  UvCheck r;
  if (uv.empty()) {
    r.reason = "no UVs";
    return r;
  }
  if (uv.size() != mesh.positions.size()) {
    r.reason = "UV count (" + std::to_string(uv.size()) + ") differs from positions (" +
               std::to_string(mesh.positions.size()) + ")";
    return r;
  }
  std::vector<Tri2> tri;
  const std::vector<std::uint32_t> live = live_triangles(mesh, uv, options, tri, r);
  count_overlaps(tri, live, options, r);

  std::string reason;
  auto add = [&](const std::string& s) { reason += (reason.empty() ? "" : "; ") + s; };
  if (r.overlapping)
    add((r.overlap_count_is_lower_bound ? "at least " : "") + count(r.overlapping, "overlaps in UV", "overlap in UV"));
  if (r.degenerate) add(count(r.degenerate, "is degenerate in UV", "are degenerate in UV"));
  if (r.outside) add(count(r.outside, "lies outside [0,1]^2", "lie outside [0,1]^2"));
  r.usable = reason.empty();
  r.reason = reason;
  return r;
}

UvIslands uv_islands(const std::vector<glm::vec2>& uv, const std::vector<std::uint32_t>& indices) {
  const std::size_t n = uv.size();
  std::vector<std::uint32_t> parent(n);
  for (std::size_t i = 0; i < n; ++i) parent[i] = static_cast<std::uint32_t>(i);
  const auto find = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];  // path halving
    return v;
  };
  const auto join = [&](std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  };
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    if (indices[t] >= n || indices[t + 1] >= n || indices[t + 2] >= n) continue;
    join(indices[t], indices[t + 1]);
    join(indices[t], indices[t + 2]);
  }
  std::unordered_map<std::uint64_t, std::uint32_t> at_uv;  // quantized UV -> first vertex
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(uv[i].x) || !std::isfinite(uv[i].y)) continue;
    const auto q = [](float c) {
      return static_cast<std::uint64_t>(static_cast<std::uint32_t>(
          static_cast<std::int64_t>(std::llround(double(c) * 1048576.0))));
    };
    const std::uint64_t key = q(uv[i].x) << 32 | q(uv[i].y);
    const auto [it, fresh] = at_uv.emplace(key, static_cast<std::uint32_t>(i));
    if (!fresh) join(it->second, static_cast<std::uint32_t>(i));
  }
  UvIslands out;
  out.vertex_island.assign(n, 0);
  std::vector<bool> used(n, false);
  for (std::uint32_t v : indices)
    if (v < n) used[v] = true;
  std::vector<std::uint32_t> id_of_root(n, std::numeric_limits<std::uint32_t>::max());
  for (std::size_t i = 0; i < n; ++i) {
    if (!used[i]) continue;
    std::uint32_t& id = id_of_root[find(static_cast<std::uint32_t>(i))];
    if (id == std::numeric_limits<std::uint32_t>::max()) id = out.count++;
    out.vertex_island[i] = id;
  }
  return out;
}

}  // namespace sss::scene
