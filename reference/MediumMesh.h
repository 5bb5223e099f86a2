// MediumMesh: the closed surfaces that bound the random walk's media (issue 16).
//
// Every subsurface material's triangles (over all instances that use it, in world mm) are
// welded by vertex position (within 1e-6 of the surface's size), so that a mesh split at UV seams (UvAtlas.h) or a
// surface made of several glTF primitives is judged as the one surface it is. Then:
//   * each edge must be shared by exactly two triangles (a closed manifold surface);
//   * triangles wound against their neighbours are turned to agree with them (scans often
//     mix windings), and each connected piece then gets its orientation from the sign of
//     its volume, so that every triangle knows which side of it is outside.
// The walk itself never needs the orientation (it tracks inside and outside along the
// path, and the geometric normal of each face it meets); the direct beams do, to know
// which faces the light enters through.
#pragma once

#include "reference/RayScene.h"
#include "scene/Scene.h"

#include <cstdint>
#include <string>
#include <vector>

namespace sss::reference {

struct MediumTopology {
  std::size_t triangles = 0;
  std::size_t boundary_edges = 0;      // used by one triangle: the rims of holes
  std::size_t non_manifold_edges = 0;  // used by more than two
  std::size_t rewound_triangles = 0;   // wound against their neighbours, turned to agree
  std::size_t unorientable_edges = 0;  // still traversed the same way after that (a Moebius band)
  std::size_t pieces = 0;              // connected components
  double volume_mm3 = 0.0;             // enclosed, after orienting every piece outward
  // A closed surface bounds a medium: every edge has exactly two triangles. Winding does
  // not matter (it is made consistent); an unorientable surface bounds nothing.
  bool closed() const { return boundary_edges == 0 && non_manifold_edges == 0 && unorientable_edges == 0; }
};

// One subsurface material's surfaces.
struct MediumSurface {
  std::uint32_t material = 0;
  std::vector<std::uint32_t> instances;  // Scene::instances whose mesh uses the material
  MediumTopology topology;
  // Per instance (indexed like Scene::instances; empty for the others): +1 where the
  // triangle's winding normal points out of the medium, -1 where it points in.
  std::vector<std::vector<std::int8_t>> outward;
};

// The surfaces of every enabled subsurface material that some instance uses.
std::vector<MediumSurface> medium_surfaces(const scene::Scene& scene, const RayScene& rays);

// The warning for a surface that is not closed (empty when it is): it names the material
// and its meshes, what is wrong, and how the walk treats it.
std::string medium_warning(const scene::Scene& scene, const MediumSurface& surface);

}  // namespace sss::reference
