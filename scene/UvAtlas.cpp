// The box-projection atlas (UvAtlas.h explains the method and its stretch bound): its
// builder, stage by stage, and applying it to a mesh.
#include "scene/UvAtlas.h"
#include "scene/UvGeometry.h"

#include "scene/Scene.h"

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

namespace {

// build_atlas's stages, pbrt-style: each is a method named for what it does, over the
// state the stages share (members, filled in stage order).
class AtlasBuilder {
 public:
  AtlasBuilder(const Mesh& mesh, const AtlasOptions& options)
      : options(options), P(mesh.positions), I(mesh.indices), n(mesh.triangle_count()) {}
  UvAtlas build();

 private:
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  void classify_faces();
  void find_neighbours();
  void smooth_axes();
  void project_faces();
  void grow_charts();
  void orient_charts();
  void pack_charts();
  void lay_out_uvs();
  void unfold_gutters();
  std::optional<std::array<glm::dvec2, 3>> unfold_across(std::uint32_t t, std::uint32_t parent,
                                                         const std::array<glm::dvec2, 3>& parent_uv) const;
  void measure_stretch();

  const AtlasOptions& options;
  const std::vector<glm::vec3>& P;
  const std::vector<std::uint32_t>& I;
  const std::size_t n;
  UvAtlas atlas;
  std::vector<int> axis;      // per face: 0..5 = +x, -x, +y, -y, +z, -z
  std::vector<double> area;   // per face, scene units²
  double diag = 0.0;          // of the bounding box
  std::vector<std::uint32_t> weld;                      // vertex -> the first at its position
  std::vector<std::array<std::uint32_t, 3>> neighbour;  // per face edge: the face across, or kNone
  std::vector<Tri2> proj;     // per face, in its axis plane (scene units)
  double cell = 1.0;          // of the overlap grid
  std::vector<std::vector<std::uint32_t>> chart_faces;
  std::size_t C = 0;          // charts
  std::vector<double> angle;  // per chart: its rotation
  std::vector<glm::dvec2> box_min, box_size;  // per chart, rotated (scene units)
  double pad = 0.0;           // UV
  double s = 0.0;             // UV per scene unit
  std::vector<glm::dvec2> origin;  // per chart: its padded box's corner (UV)
  double covered = 0.0;       // UV area under the triangles
  double max_stretch = 1.0;
};

glm::dvec2 rotate(const glm::dvec2& p, double a) {
  const double cs = std::cos(a), sn = std::sin(a);
  return glm::dvec2(cs * p.x - sn * p.y, sn * p.x + cs * p.y);
}

UvAtlas AtlasBuilder::build() {
  const auto start = std::chrono::steady_clock::now();
  classify_faces();   // 1
  find_neighbours();
  smooth_axes();
  project_faces();
  grow_charts();      // 2
  orient_charts();    // 3
  pack_charts();      // 4
  lay_out_uvs();      // 5
  unfold_gutters();   // 6
  measure_stretch();
  atlas.stats.charts = C;
  atlas.stats.uv_per_unit = s;
  atlas.stats.utilization = covered;
  atlas.stats.max_stretch = max_stretch;
  atlas.stats.split_vertices = atlas.source_vertex.size() - P.size();
  atlas.stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return std::move(atlas);
}

void AtlasBuilder::classify_faces() {
  // 1. Face axes: the closest of ±x, ±y, ±z to the (area-weighted) face normal.
  axis.assign(n, 0);
  area.assign(n, 0.0);
  for (std::size_t t = 0; t < n; ++t) {
    const glm::dvec3 a(P[I[3 * t]]), b(P[I[3 * t + 1]]), c(P[I[3 * t + 2]]);
    const glm::dvec3 nrm = glm::cross(b - a, c - a);
    area[t] = 0.5 * glm::length(nrm);
    int best = 0;
    double best_dot = -std::numeric_limits<double>::infinity();
    for (int k = 0; k < 6; ++k) {
      const double d = (k % 2 == 0 ? 1.0 : -1.0) * nrm[k / 2];
      if (d > best_dot) best_dot = d, best = k;
    }
    axis[t] = best;
  }
}

void AtlasBuilder::find_neighbours() {
  // Edge adjacency: triangles across each undirected edge, with vertices welded by
  // position (an input UV seam duplicates vertices; it must not split a chart).
  // Welding snaps positions to a grid of 1e-6 of the bounding-box diagonal, so a seam
  // whose two sides were computed separately (a UV sphere's u = 0 and u = 1) still welds.
  glm::dvec3 pmin(std::numeric_limits<double>::infinity()), pmax(-pmin);
  for (const glm::vec3& p : P) pmin = glm::min(pmin, glm::dvec3(p)), pmax = glm::max(pmax, glm::dvec3(p));
  diag = P.empty() ? 0.0 : glm::length(pmax - pmin);
  const double snap = diag > 0.0 ? 1e-6 * diag : 1.0;
  weld.assign(P.size(), 0);
  {
    struct Key {
      std::int64_t x, y, z;
      bool operator==(const Key&) const = default;
    };
    struct Hash {
      std::size_t operator()(const Key& k) const {
        return std::size_t(k.x) * 73856093u ^ std::size_t(k.y) * 19349663u ^ std::size_t(k.z) * 83492791u;
      }
    };
    std::unordered_map<Key, std::uint32_t, Hash> first;
    first.reserve(P.size());
    for (std::uint32_t v = 0; v < P.size(); ++v) {
      const glm::dvec3 q = glm::round((glm::dvec3(P[v]) - pmin) / snap);
      weld[v] = first.try_emplace(Key{std::int64_t(q.x), std::int64_t(q.y), std::int64_t(q.z)}, v)
                    .first->second;
    }
  }
  std::unordered_map<std::uint64_t, std::array<std::uint32_t, 2>> edge_map;
  edge_map.reserve(3 * n);
  auto edge_key = [&](std::uint32_t a, std::uint32_t b) {
    a = weld[a], b = weld[b];
    if (a > b) std::swap(a, b);
    return (std::uint64_t(a) << 32) | b;
  };
  neighbour.assign(n, {kNone, kNone, kNone});
  for (std::uint32_t t = 0; t < n; ++t)
    for (int e = 0; e < 3; ++e) {
      auto [it, fresh] = edge_map.try_emplace(edge_key(I[3 * t + e], I[3 * t + (e + 1) % 3]),
                                              std::array<std::uint32_t, 2>{t, kNone});
      if (!fresh && it->second[1] == kNone) it->second[1] = t;
      // A non-manifold edge (3+ faces) keeps its first two: the others start other charts.
    }
  for (std::uint32_t t = 0; t < n; ++t)
    for (int e = 0; e < 3; ++e) {
      const auto& pair = edge_map[edge_key(I[3 * t + e], I[3 * t + (e + 1) % 3])];
      neighbour[t][e] = pair[0] == t ? pair[1] : (pair[1] == t ? pair[0] : kNone);
    }
}

void AtlasBuilder::smooth_axes() {
  // Smoothing: a face whose neighbours mostly (2 or 3) took another axis takes it too,
  // if that axis is within 54.7° of its normal (cos θ ≥ 1/√3, the closest axis's own
  // guarantee, so the stretch bound holds). It removes the one-face charts along the
  // zigzag where two axes tie.
  for (int pass = 0; pass < 4; ++pass) {
    std::vector<int> next = axis;
    for (std::uint32_t t = 0; t < n; ++t) {
      if (!(area[t] > 0.0)) continue;
      for (std::uint32_t a : neighbour[t]) {
        if (a == kNone || axis[a] == axis[t]) continue;
        int votes = 0;
        for (std::uint32_t b : neighbour[t]) votes += b != kNone && axis[b] == axis[a];
        const glm::dvec3 a0(P[I[3 * t]]);
        const glm::dvec3 nrm = glm::cross(glm::dvec3(P[I[3 * t + 1]]) - a0, glm::dvec3(P[I[3 * t + 2]]) - a0);
        const double d = (axis[a] % 2 == 0 ? 1.0 : -1.0) * nrm[axis[a] / 2] / glm::length(nrm);
        if (votes >= 2 && d >= 1.0 / std::sqrt(3.0)) next[t] = axis[a];
        break;
      }
    }
    axis.swap(next);
  }
}

void AtlasBuilder::project_faces() {
  // Projected triangles, per face in its own axis plane (scene units).
  proj.assign(n, Tri2{});
  double edge_sum = 0.0;
  for (std::size_t t = 0; t < n; ++t) {
    glm::dvec3 u, v;
    axis_basis(axis[t], u, v);
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 p(P[I[3 * t + k]]);
      proj[t][k] = glm::dvec2(glm::dot(p, u), glm::dot(p, v));
    }
    edge_sum += glm::length(proj[t][1] - proj[t][0]);
  }
  cell = std::max(2.0 * edge_sum / double(std::max<std::size_t>(n, 1)), 1e-30);
}

void AtlasBuilder::grow_charts() {
  // 2. Charts: breadth-first growth over edges between faces of one axis, refusing a face
  //    whose projection overlaps the chart's (so the chart stays injective). The tolerance,
  //    1e-7 of the diagonal, lets welded seams touch; it stays far below check_uvs's
  //    1e-5 UV once scaled by s.
  const double grow_tolerance = 1e-7 * diag;
  atlas.triangle_chart.assign(n, kNone);
  TriGrid grid(cell);
  std::vector<std::uint32_t> stamp(n, kNone), members;
  std::deque<std::uint32_t> queue;
  for (std::uint32_t seed = 0; seed < n; ++seed) {
    if (atlas.triangle_chart[seed] != kNone) continue;
    const auto c = std::uint32_t(chart_faces.size());
    members.clear();
    grid.clear();
    queue.assign(1, seed);
    stamp[seed] = c;  // stamp: considered for chart c
    while (!queue.empty()) {
      const std::uint32_t t = queue.front();
      queue.pop_front();
      bool clash = false;
      grid.visit(proj[t], [&](std::uint32_t o) {
        if (!clash && o != t && overlaps(proj[t], proj[o], grow_tolerance)) clash = true;
      });
      if (clash) continue;  // left for a later chart
      atlas.triangle_chart[t] = c;
      members.push_back(t);
      grid.insert(proj[t], t);
      for (std::uint32_t nb : neighbour[t])
        if (nb != kNone && atlas.triangle_chart[nb] == kNone && stamp[nb] != c &&
            axis[nb] == axis[seed]) {
          stamp[nb] = c;
          queue.push_back(nb);
        }
    }
    chart_faces.push_back(members);
  }
}

void AtlasBuilder::orient_charts() {
  // 3. Per chart: the rotation (of 32 in [0, π/2)) with the smallest bounding box, turned
  //    to lie flat (width >= height) for the shelf packing.
  C = chart_faces.size();
  angle.assign(C, 0.0);
  box_min.assign(C, glm::dvec2(0.0));
  box_size.assign(C, glm::dvec2(0.0));
  for (std::size_t c = 0; c < C; ++c) {
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 32; ++k) {
      const double a = 0.5 * std::numbers::pi * k / 32.0;
      glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-lo);
      for (std::uint32_t t : chart_faces[c])
        for (const glm::dvec2& p : proj[t]) {
          const glm::dvec2 q = rotate(p, a);
          lo = glm::min(lo, q), hi = glm::max(hi, q);
        }
      double a_final = a;
      glm::dvec2 size = hi - lo;
      if (size.y > size.x) {  // a further quarter turn lays it flat
        a_final = a + 0.5 * std::numbers::pi;
        lo = glm::dvec2(-hi.y, lo.x);
        size = glm::dvec2(size.y, size.x);
      }
      const double boxed = size.x * size.y;
      if (boxed < best) best = boxed, angle[c] = a_final, box_min[c] = lo, box_size[c] = size;
    }
  }
}

void AtlasBuilder::pack_charts() {
  // 4. One scale for all charts: the largest s for which the shelf packing fits.
  std::vector<std::uint32_t> order(C);
  for (std::uint32_t c = 0; c < C; ++c) order[c] = c;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return box_size[a].y > box_size[b].y; });
  pad = double(options.padding_texels) / double(std::max(options.resolution, 1u));
  origin.assign(C, glm::dvec2(0.0));
  struct Shelf {
    double y, height, x;
  };
  std::vector<Shelf> shelves;
  auto pack = [&](double s) {  // true when everything fits; origins of the padded boxes
    shelves.clear();
    double top = 0.0;
    for (std::uint32_t c : order) {
      const double w = s * box_size[c].x + 2.0 * pad, h = s * box_size[c].y + 2.0 * pad;
      if (w > 1.0) return false;
      Shelf* shelf = nullptr;  // first fit: sorted by height, every shelf is tall enough
      for (Shelf& sh : shelves)
        if (sh.x + w <= 1.0) {
          shelf = &sh;
          break;
        }
      if (!shelf) {
        if (top + h > 1.0) return false;
        shelves.push_back({top, h, 0.0});
        top += h;
        shelf = &shelves.back();
      }
      origin[c] = glm::dvec2(shelf->x, shelf->y);
      shelf->x += w;
    }
    return true;
  };
  double max_side = 0.0;
  for (std::size_t c = 0; c < C; ++c) max_side = std::max({max_side, box_size[c].x, box_size[c].y});
  double lo_s = 0.0, hi_s = max_side > 0.0 ? 1.0 / max_side : 1.0;
  for (int it = 0; it < 50; ++it) {
    const double mid = 0.5 * (lo_s + hi_s);
    (pack(mid) ? lo_s : hi_s) = mid;
  }
  s = lo_s;
  pack(s);
}

void AtlasBuilder::lay_out_uvs() {
  // 5. UVs and the vertex split: one new vertex per (input vertex, chart).
  std::unordered_map<std::uint64_t, std::uint32_t> split;
  split.reserve(2 * P.size());
  atlas.indices.resize(I.size());
  atlas.charts.resize(C);
  for (std::size_t c = 0; c < C; ++c) {
    atlas.charts[c].axis = axis[chart_faces[c].front()];
    atlas.charts[c].triangles = chart_faces[c].size();
    atlas.charts[c].uv_min = glm::vec2(origin[c] + pad);
    atlas.charts[c].uv_max = glm::vec2(origin[c] + pad + s * box_size[c]);
  }
  covered = 0.0;
  for (std::uint32_t t = 0; t < n; ++t) {
    const std::uint32_t c = atlas.triangle_chart[t];
    atlas.charts[c].area += area[t];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = I[3 * t + k];
      auto [it, fresh] = split.try_emplace((std::uint64_t(v) << 32) | c,
                                           std::uint32_t(atlas.source_vertex.size()));
      if (fresh) {
        atlas.source_vertex.push_back(v);
        const glm::dvec2 q = (rotate(proj[t][k], angle[c]) - box_min[c]) * s + origin[c] + pad;
        atlas.uv.emplace_back(glm::clamp(glm::vec2(q), glm::vec2(0.0f), glm::vec2(1.0f)));
      }
      atlas.indices[3 * t + k] = it->second;
    }
    const glm::dvec2 a(atlas.uv[atlas.indices[3 * t]]), b(atlas.uv[atlas.indices[3 * t + 1]]),
        d(atlas.uv[atlas.indices[3 * t + 2]]);
    covered += std::abs(0.5 * cross2(b - a, d - a));
  }
}

// Face t unfolded across the edge it shares with the placed face `parent` (at UVs
// parent_uv) into the parent's UV map; nothing where they share no edge or a face is
// degenerate.
std::optional<std::array<glm::dvec2, 3>> AtlasBuilder::unfold_across(
    std::uint32_t t, std::uint32_t parent, const std::array<glm::dvec2, 3>& parent_uv) const {
  // The shared edge: the parent's corners whose welded vertices t also has.
  int pe[3] = {-1, -1, -1};  // for each corner of t, the parent's corner (or -1)
  int shared = 0;
  for (int k = 0; k < 3; ++k)
    for (int q = 0; q < 3; ++q)
      if (weld[I[3 * t + k]] == weld[I[3 * parent + q]]) pe[k] = q, ++shared;
  if (shared != 2) return std::nullopt;
  int kc = 0;
  while (pe[kc] >= 0) ++kc;
  const int ka = (kc + 1) % 3, kb = (kc + 2) % 3;
  const glm::dvec3 a(P[I[3 * t + ka]]), b(P[I[3 * t + kb]]), cc(P[I[3 * t + kc]]);
  const glm::dvec2 A = parent_uv[pe[ka]], B = parent_uv[pe[kb]];
  const int parent_third = 3 - pe[ka] - pe[kb];
  // c turned about ab into the parent's plane, on the side away from the parent's
  // third corner, then mapped by the parent's own affine 3D -> UV map: the gutter
  // keeps the chart's anisotropic scale (a tilted chart's texels are longer across
  // the tilt), so the blur's texel sizes agree across the border.
  const glm::dvec3 third(P[I[3 * parent + parent_third]]);
  const glm::dvec3 ab = b - a;
  const double ab2 = glm::dot(ab, ab);
  if (!(ab2 > 0.0)) return std::nullopt;
  const double along = glm::dot(cc - a, ab) / ab2;
  const double height = glm::length(cc - (a + along * ab));
  glm::dvec3 side = (third - a) - ab * (glm::dot(third - a, ab) / ab2);  // in the parent's plane
  const double side_len = glm::length(side);
  if (!(side_len > 0.0)) return std::nullopt;
  const glm::dvec3 unfolded = a + along * ab - side / side_len * height;
  // The parent's affine map from barycentric-style coordinates on its edges.
  const glm::dvec3 e1 = b - a, e2 = third - a, d = unfolded - a;
  const double g11 = glm::dot(e1, e1), g12 = glm::dot(e1, e2), g22 = glm::dot(e2, e2);
  const double det = g11 * g22 - g12 * g12;
  if (!(std::abs(det) > 0.0)) return std::nullopt;
  const double r1 = glm::dot(d, e1), r2 = glm::dot(d, e2);
  const double alpha = (r1 * g22 - r2 * g12) / det, beta = (r2 * g11 - r1 * g12) / det;
  const glm::dvec2 C3 = parent_uv[parent_third];
  std::array<glm::dvec2, 3> uv;
  uv[ka] = A;
  uv[kb] = B;
  uv[kc] = A + alpha * (B - A) + beta * (C3 - A);
  return uv;
}

void AtlasBuilder::unfold_gutters() {
  // 6. Seam gutters: each chart's neighbourhood unfolded into its padding, triangle by
  //    triangle across shared edges (breadth-first): a triangle across edge ab of a placed
  //    triangle (a chart triangle at its chart's map, or a gutter triangle already placed)
  //    keeps a and b where they are and puts its third corner c where the placed
  //    triangle's own affine map sends c turned about ab into its plane. So the gutter
  //    continues the surface at the chart's local (anisotropic) scale however sharply it
  //    turns at the chart's border (a projection along the chart's axis would fold there),
  //    out to 1.5 x the padding's width in scene units (surface path between centroids).
  double reach = 3.0 * pad / std::max(s, 1e-30);
  if (options.max_gutter_reach > 0.0) reach = std::min(reach, options.max_gutter_reach);
  std::vector<glm::dvec3> to_u(C), to_v(C);
  std::vector<glm::dvec2> offset(C);
  for (std::size_t c = 0; c < C; ++c) {
    glm::dvec3 u, v;
    axis_basis(atlas.charts[c].axis, u, v);
    const double cs = std::cos(angle[c]), sn = std::sin(angle[c]);
    to_u[c] = s * (cs * u - sn * v);
    to_v[c] = s * (sn * u + cs * v);
    offset[c] = -s * box_min[c] + origin[c] + pad;
  }
  const auto centroid = [&](std::uint32_t t) {
    return (glm::dvec3(P[I[3 * t]]) + glm::dvec3(P[I[3 * t + 1]]) + glm::dvec3(P[I[3 * t + 2]])) / 3.0;
  };
  struct Placed {
    std::array<glm::dvec2, 3> uv;
    double dist = 0.0;  // surface path from the chart, scene units
  };
  std::vector<std::uint32_t> seen(n, kNone);
  std::unordered_map<std::uint32_t, Placed> placed;
  std::deque<std::pair<std::uint32_t, std::uint32_t>> frontier;  // (triangle, placed parent)
  for (std::uint32_t c = 0; c < C; ++c) {
    placed.clear();
    frontier.clear();
    for (std::uint32_t t : chart_faces[c]) {
      seen[t] = c;
      Placed pl;
      for (int k = 0; k < 3; ++k) {
        const glm::dvec3 p(P[I[3 * t + k]]);
        pl.uv[k] = glm::dvec2(glm::dot(to_u[c], p), glm::dot(to_v[c], p)) + offset[c];
      }
      placed[t] = pl;
      for (std::uint32_t nb : neighbour[t])
        if (nb != kNone && atlas.triangle_chart[nb] != c) frontier.emplace_back(nb, t);
    }
    const std::uint32_t host = chart_faces[c].front();
    while (!frontier.empty()) {
      const auto [t, parent] = frontier.front();
      frontier.pop_front();
      if (seen[t] == c) continue;
      const Placed& pp = placed.at(parent);
      const auto uv = unfold_across(t, parent, pp.uv);
      if (!uv) continue;
      Placed pl;
      pl.uv = *uv;
      pl.dist = pp.dist + glm::length(centroid(t) - centroid(parent));
      if (pl.dist > reach) continue;
      seen[t] = c;
      GutterTriangle g;
      g.host_triangle = host;
      for (int k = 0; k < 3; ++k) {
        g.source[k] = I[3 * t + k];
        g.uv[k] = glm::vec2(pl.uv[k]);
        g.depth[k] = float(0.25 + 0.5 * std::min(1.0, pl.dist / reach));
      }
      atlas.gutter.push_back(g);
      placed[t] = pl;
      for (std::uint32_t nb : neighbour[t])
        if (nb != kNone && seen[nb] != c && atlas.triangle_chart[nb] != c) frontier.emplace_back(nb, t);
    }
  }
}

void AtlasBuilder::measure_stretch() {
  // Stretch: mm per UV over the triangle, relative to 1/s, from the singular values of
  // the 3D -> UV map (its largest is s, its smallest s·cos θ).
  max_stretch = 1.0;
  for (std::uint32_t t = 0; t < n; ++t) {
    if (!(area[t] > 0.0)) continue;
    const glm::dvec3 p0(P[I[3 * t]]), e1 = glm::dvec3(P[I[3 * t + 1]]) - p0,
                     e2 = glm::dvec3(P[I[3 * t + 2]]) - p0;
    const glm::dvec2 w0(atlas.uv[atlas.indices[3 * t]]);
    const glm::dvec2 f1 = glm::dvec2(atlas.uv[atlas.indices[3 * t + 1]]) - w0,
                     f2 = glm::dvec2(atlas.uv[atlas.indices[3 * t + 2]]) - w0;
    const glm::dvec3 t1 = glm::normalize(e1);
    const glm::dvec3 t2 = glm::normalize(e2 - glm::dot(e2, t1) * t1);
    // Local 2D coords: e1 = (a, 0), e2 = (b, c). J = F · E^-1.
    const double a = glm::dot(e1, t1), b = glm::dot(e2, t1), cc = glm::dot(e2, t2);
    if (!(a > 0.0 && cc > 0.0)) continue;
    const glm::dvec2 j1 = f1 / a;                   // J column 1
    const glm::dvec2 j2 = (f2 - b * j1) / cc;       // J column 2
    const double E = 0.5 * (glm::dot(j1, j1) + glm::dot(j2, j2));
    const double det = std::abs(cross2(j1, j2));
    const double smin = std::sqrt(std::max(E - std::sqrt(std::max(E * E - det * det, 0.0)), 0.0));
    if (smin > 0.0) max_stretch = std::max(max_stretch, s / smin);
  }
}

}  // namespace

UvAtlas build_atlas(const Mesh& mesh, const AtlasOptions& options) {
  return AtlasBuilder(mesh, options).build();
}

AtlasStats generate_atlas(Mesh& mesh, const AtlasOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  UvAtlas atlas = build_atlas(mesh, options);
  auto gather = [&](const auto& src) {
    std::remove_cvref_t<decltype(src)> out;
    if (src.empty()) return out;
    out.reserve(atlas.source_vertex.size());
    for (std::uint32_t v : atlas.source_vertex) out.push_back(src[v]);
    return out;
  };
  mesh.positions = gather(mesh.positions);
  mesh.normals = gather(mesh.normals);
  mesh.uv0 = gather(mesh.uv0);
  mesh.tangents = gather(mesh.tangents);
  // Gutter corners take the first new vertex of their input vertex (positions, normals and
  // tangents are the same in every copy); the host is its triangle's first new vertex.
  {
    constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
    std::uint32_t sources = 0;
    for (std::uint32_t v : atlas.source_vertex) sources = std::max(sources, v + 1);
    std::vector<std::uint32_t> by_source(sources, kNone);
    for (std::uint32_t v = 0; v < atlas.source_vertex.size(); ++v)
      if (by_source[atlas.source_vertex[v]] == kNone) by_source[atlas.source_vertex[v]] = v;
    Mesh::AtlasGutter& g = mesh.uv_atlas_gutter;
    g = {};
    for (const GutterTriangle& t : atlas.gutter) {
      for (int k = 0; k < 3; ++k) {
        g.vertices.push_back(by_source[t.source[k]]);
        g.uv.push_back(t.uv[k]);
        g.depth.push_back(t.depth[k]);
      }
      g.host.push_back(atlas.indices[3 * t.host_triangle]);
    }
  }
  mesh.indices = std::move(atlas.indices);
  mesh.uv_atlas = std::move(atlas.uv);
  atlas.stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return atlas.stats;
}

const std::vector<glm::vec2>& sss_uvs(const Mesh& mesh) {
  return mesh.uv_atlas.empty() ? mesh.uv0 : mesh.uv_atlas;
}

}  // namespace sss::scene
