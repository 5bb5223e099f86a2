// Plane-triangle geometry shared by check_uvs (UvCheck.cpp) and the atlas builder
// (UvAtlas.cpp): exact separating-axis overlap tests, a uniform grid over triangles, and
// the box projection's axis bases. Internal to scene.
#pragma once

#include "scene/UvAtlas.h"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

namespace sss::scene::uv_detail {

using Tri2 = std::array<glm::dvec2, 3>;

inline double cross2(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }
inline double signed_area(const Tri2& t) { return 0.5 * cross2(t[1] - t[0], t[2] - t[0]); }

inline double area3(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::dvec3 e1 = glm::dvec3(b) - glm::dvec3(a);
  const glm::dvec3 e2 = glm::dvec3(c) - glm::dvec3(a);
  return 0.5 * glm::length(glm::cross(e1, e2));
}

// True when the triangles overlap by more than `tol` along each of their 6 edge normals.
// Triangles that share an edge or a vertex (and do not fold over each other) have depth
// exactly 0 along the shared edge's normal, since the shared corners project identically.
inline bool overlaps(const Tri2& a, const Tri2& b, double tol) {
  for (const Tri2* t : {&a, &b}) {
    for (int e = 0; e < 3; ++e) {
      const glm::dvec2 d = (*t)[(e + 1) % 3] - (*t)[e];
      const glm::dvec2 n(-d.y, d.x);
      const double len = glm::length(n);
      if (!(len > 0.0)) continue;
      double amin = std::numeric_limits<double>::infinity(), amax = -amin;
      double bmin = amin, bmax = -amin;
      for (int i = 0; i < 3; ++i) {
        const double pa = glm::dot(a[i], n) / len, pb = glm::dot(b[i], n) / len;
        amin = std::min(amin, pa), amax = std::max(amax, pa);
        bmin = std::min(bmin, pb), bmax = std::max(bmax, pb);
      }
      if (std::min(amax, bmax) - std::max(amin, bmin) <= tol) return false;
    }
  }
  return true;
}

// Sparse uniform grid of triangle ids, for the overlap searches. A triangle whose box
// would cover more than kMaxCells cells (a huge triangle among small ones, or coordinates
// so large that the cell index would not fit an int64: both came from fuzzing hostile
// glTF files, fuzz/regressions/gltf/atlas_*) goes into one list that every visit scans,
// so the search stays exact and the grid's work per triangle stays bounded. Such a triangle
// has an edge longer than 64 cells, and cells are two mean edges wide, so there are few.
class TriGrid {
 public:
  explicit TriGrid(double cell) : inv_cell_(1.0 / cell) {}
  template <class F>  // f(id) for every id in a cell the box touches; returns cells visited
  std::size_t visit(const Tri2& t, F&& f) const {
    std::size_t visited = 0;
    for (std::uint32_t id : oversized_) f(id);
    if (!for_cells(t, [&](std::int64_t key) {
          ++visited;
          const auto it = cells_.find(key);
          if (it != cells_.end())
            for (std::uint32_t id : it->second) f(id);
        })) {
      for (const auto& [key, ids] : cells_)  // an oversized query meets every cell
        for (std::uint32_t id : ids) f(id);
      visited += cells_.size();
    }
    return visited + oversized_.size();
  }
  void insert(const Tri2& t, std::uint32_t id) {
    if (!for_cells(t, [&](std::int64_t key) { cells_[key].push_back(id); })) oversized_.push_back(id);
  }
  void clear() {
    cells_.clear();
    oversized_.clear();
  }

 private:
  static constexpr double kMaxCells = 4096.0;
  // Calls f for each cell of the box; false (and no call) when the box is oversized or
  // not finite.
  template <class F>
  bool for_cells(const Tri2& t, F&& f) const {
    const glm::dvec2 lo = glm::min(glm::min(t[0], t[1]), t[2]) * inv_cell_;
    const glm::dvec2 hi = glm::max(glm::max(t[0], t[1]), t[2]) * inv_cell_;
    constexpr double kMaxIndex = 1e15;  // well inside int64 and exact in a double
    if (!(std::abs(lo.x) < kMaxIndex && std::abs(lo.y) < kMaxIndex && std::abs(hi.x) < kMaxIndex &&
          std::abs(hi.y) < kMaxIndex))
      return false;
    const double fx0 = std::floor(lo.x), fx1 = std::floor(hi.x);
    const double fy0 = std::floor(lo.y), fy1 = std::floor(hi.y);
    if ((fx1 - fx0 + 1.0) * (fy1 - fy0 + 1.0) > kMaxCells) return false;
    const auto x0 = std::int64_t(fx0), x1 = std::int64_t(fx1);
    const auto y0 = std::int64_t(fy0), y1 = std::int64_t(fy1);
    for (std::int64_t y = y0; y <= y1; ++y)
      for (std::int64_t x = x0; x <= x1; ++x) f((y << 32) ^ (x & 0xffffffff));
    return true;
  }
  double inv_cell_;
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> cells_;
  std::vector<std::uint32_t> oversized_;
};

inline bool finite(const glm::vec2& v) { return std::isfinite(v.x) && std::isfinite(v.y); }

inline std::string count(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + (n == 1 ? " triangle " + std::string(one) : " triangles " + std::string(many));
}

// 0..5 = +x, -x, +y, -y, +z, -z. The plane basis (u, v) has u × v = the axis, so a face
// wound CCW around a normal near the axis stays CCW in the projection.
inline void axis_basis(int axis, glm::dvec3& u, glm::dvec3& v) {
  const int i = axis / 2;
  const double sign = axis % 2 == 0 ? 1.0 : -1.0;
  u = glm::dvec3(0.0), v = glm::dvec3(0.0);
  u[(i + 1) % 3] = sign;
  v[(i + 2) % 3] = 1.0;
}

}  // namespace sss::scene::uv_detail
