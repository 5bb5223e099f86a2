#include "reference/MediumMesh.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>
#include <unordered_map>

namespace sss::reference {

namespace {

struct TriangleRef {
  std::uint32_t instance, triangle;
  std::array<std::uint32_t, 3> v;  // welded vertex ids, in winding order
};

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
}

// Whether triangle t traverses the edge (a, b) from a to b.
bool traverses(const TriangleRef& t, std::uint32_t a, std::uint32_t b) {
  for (int k = 0; k < 3; ++k)
    if (t.v[k] == a && t.v[(k + 1) % 3] == b) return true;
  return false;
}

// The surface's triangles over welded vertex ids, and the welded positions. Positions
// closer than 1e-6 of the surface's size are one: seams split for UV charts share their
// positions bit for bit, but a generated sphere's seam (cos 2π vs cos 0) differs in the
// last bits. Cells of that size, a position matched against its 27 neighbours. Triangles
// whose welded corners coincide (no area) are left out.
struct WeldedSurface {
  std::vector<TriangleRef> tris;
  std::vector<glm::dvec3> positions;
};

WeldedSurface weld_triangles(const scene::Scene& s, const RayScene& rays, const std::vector<std::uint32_t>& instances) {
  double extent = 0.0;
  {
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (std::uint32_t i : instances)
      for (const glm::vec3& p : rays.world_positions(i)) {
        lo = glm::min(lo, glm::dvec3(p));
        hi = glm::max(hi, glm::dvec3(p));
      }
    extent = glm::length(hi - lo);
  }
  const double tol = std::max(1e-6 * extent, 1e-12);
  struct CellHash {
    std::size_t operator()(const std::array<std::int64_t, 3>& k) const {
      return std::size_t(k[0] * 73856093LL ^ k[1] * 19349663LL ^ k[2] * 83492791LL);
    }
  };
  std::unordered_map<std::array<std::int64_t, 3>, std::vector<std::uint32_t>, CellHash> cells;
  WeldedSurface out;
  std::vector<glm::dvec3>& positions = out.positions;
  auto weld = [&](const glm::dvec3& p) {
    const std::array<std::int64_t, 3> k = {std::int64_t(std::floor(p.x / tol)), std::int64_t(std::floor(p.y / tol)),
                                           std::int64_t(std::floor(p.z / tol))};
    for (std::int64_t dz = -1; dz <= 1; ++dz)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
          const auto it = cells.find({k[0] + dx, k[1] + dy, k[2] + dz});
          if (it == cells.end()) continue;
          for (std::uint32_t id : it->second)
            if (glm::length(positions[id] - p) <= tol) return id;
        }
    const std::uint32_t id = std::uint32_t(positions.size());
    positions.push_back(p);
    cells[k].push_back(id);
    return id;
  };
  for (std::uint32_t i : instances) {
    const scene::Mesh& mesh = s.meshes[s.instances[i].mesh];
    const std::vector<glm::vec3>& world = rays.world_positions(i);
    for (std::uint32_t t = 0; t < mesh.triangle_count(); ++t) {
      TriangleRef ref{i, t, {}};
      for (int k = 0; k < 3; ++k) ref.v[std::size_t(k)] = weld(glm::dvec3(world[mesh.indices[3 * t + k]]));
      if (ref.v[0] == ref.v[1] || ref.v[1] == ref.v[2] || ref.v[0] == ref.v[2]) continue;  // no area
      out.tris.push_back(ref);
    }
  }
  return out;
}

using EdgeUsers = std::unordered_map<std::uint64_t, std::vector<std::uint32_t>>;  // edge -> triangles

// Each piece's orientation: breadth-first propagation across manifold edges, a neighbour
// must traverse the shared edge the other way, else it is flipped. Fills flip, piece and
// the topology's pieces, unorientable edges and rewound triangles.
void orient_pieces(const std::vector<TriangleRef>& tris, EdgeUsers& edges, std::vector<int>& flip,
                   std::vector<int>& piece, MediumTopology& topo) {
  flip.assign(tris.size(), 0);
  piece.assign(tris.size(), -1);
  std::unordered_map<std::uint64_t, bool> conflicts;
  for (std::uint32_t seed = 0; seed < tris.size(); ++seed) {
    if (piece[seed] >= 0) continue;
    const int id = int(topo.pieces++);
    piece[seed] = id;
    std::queue<std::uint32_t> todo;
    todo.push(seed);
    while (!todo.empty()) {
      const std::uint32_t t = todo.front();
      todo.pop();
      for (int k = 0; k < 3; ++k) {
        std::uint32_t a = tris[t].v[k], b = tris[t].v[(k + 1) % 3];
        if (flip[t]) std::swap(a, b);  // the direction t traverses it after its flip
        const std::vector<std::uint32_t>& users = edges[edge_key(a, b)];
        if (users.size() != 2) continue;
        const std::uint32_t u = users[0] == t ? users[1] : users[0];
        const bool same = traverses(tris[u], a, b) != bool(flip[u]);
        if (piece[u] < 0) {
          piece[u] = id;
          flip[u] = same ? 1 : 0;
          todo.push(u);
        } else if (same) {
          conflicts[edge_key(a, b)] = true;  // found from either side
        }
      }
    }
  }
  topo.unorientable_edges = conflicts.size();
  for (int f : flip) topo.rewound_triangles += std::size_t(f);
}

MediumSurface make_surface(const scene::Scene& s, const RayScene& rays, std::uint32_t material,
                           const std::vector<std::uint32_t>& instances) {
  MediumSurface out;
  out.material = material;
  out.instances = instances;
  out.outward.resize(s.instances.size());
  for (std::uint32_t i : instances) out.outward[i].assign(s.meshes[s.instances[i].mesh].triangle_count(), 1);
  const WeldedSurface welded = weld_triangles(s, rays, instances);
  const std::vector<TriangleRef>& tris = welded.tris;
  const std::vector<glm::dvec3>& positions = welded.positions;
  MediumTopology& topo = out.topology;
  topo.triangles = tris.size();

  EdgeUsers edges;
  edges.reserve(tris.size() * 2);
  for (std::uint32_t t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) edges[edge_key(tris[t].v[k], tris[t].v[(k + 1) % 3])].push_back(t);
  for (const auto& [key, users] : edges) {
    if (users.size() == 1) ++topo.boundary_edges;
    if (users.size() > 2) ++topo.non_manifold_edges;
  }
  std::vector<int> flip, piece;
  orient_pieces(tris, edges, flip, piece, topo);

  // Each piece's volume (divergence theorem); a negative one means it is wound inward.
  std::vector<double> volume(topo.pieces, 0.0);
  for (std::uint32_t t = 0; t < tris.size(); ++t) {
    const glm::dvec3 &p0 = positions[tris[t].v[0]], &p1 = positions[tris[t].v[1]], &p2 = positions[tris[t].v[2]];
    const double v = glm::dot(p0, glm::cross(p1, p2)) / 6.0;
    volume[std::size_t(piece[t])] += flip[t] ? -v : v;
  }
  for (std::uint32_t t = 0; t < tris.size(); ++t) {
    const bool inward = volume[std::size_t(piece[t])] < 0.0;
    out.outward[tris[t].instance][tris[t].triangle] = (bool(flip[t]) != inward) ? -1 : 1;
  }
  for (double v : volume) topo.volume_mm3 += std::abs(v);
  return out;
}

}  // namespace

std::vector<MediumSurface> medium_surfaces(const scene::Scene& s, const RayScene& rays) {
  std::vector<MediumSurface> out;
  std::vector<std::vector<std::uint32_t>> users(s.materials.size());
  for (std::uint32_t i = 0; i < s.instances.size(); ++i) {
    const scene::Mesh& mesh = s.meshes[s.instances[i].mesh];
    if (mesh.material < s.materials.size() && s.materials[mesh.material].sss.enabled && mesh.triangle_count() > 0)
      users[mesh.material].push_back(i);
  }
  for (std::uint32_t m = 0; m < s.materials.size(); ++m)
    if (!users[m].empty()) out.push_back(make_surface(s, rays, m, users[m]));
  return out;
}

std::string medium_warning(const scene::Scene& s, const MediumSurface& surface) {
  const MediumTopology& t = surface.topology;
  if (t.closed()) return {};
  std::string meshes;
  for (std::uint32_t i : surface.instances) {
    const std::string& name = s.meshes[s.instances[i].mesh].name;
    if (meshes.find("'" + name + "'") == std::string::npos) meshes += (meshes.empty() ? "'" : ", '") + name + "'";
  }
  std::string what;
  auto add = [&](std::size_t n, const char* label) {
    if (n == 0) return;
    what += (what.empty() ? "" : ", ") + std::to_string(n) + " " + label;
  };
  add(t.boundary_edges, "open edges (holes)");
  add(t.non_manifold_edges, "edges shared by more than two triangles");
  add(t.unorientable_edges, "edges where the surface cannot be oriented");
  return "material '" + s.materials[surface.material].name + "' (mesh " + meshes +
         ") is not a closed surface: " + what +
         ". The random walk treats a hole as an open window: no light enters through it, and a walk "
         "that leaves the object's bounds through it is lost, so the medium near a hole is darker "
         "than the closed object would be (within about two diffusion lengths of its rim; "
         "reference/README.md, \"Holes\")";
}

}  // namespace sss::reference
