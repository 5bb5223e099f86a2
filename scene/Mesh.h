// Mesh: one glTF primitive, ready for upload. Triangles only, always indexed (uint32),
// always with unit normals; uv0 and tangents are optional (empty when absent).
// Positions are in scene units (metres for glTF, see Scene::mm_per_unit).
#pragma once

#include "scene/Bounds.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sss::scene {

struct Mesh {
  std::string name;                 // "bunny" or "meshes[2].primitives[1]"
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;   // unit length, one per position
  std::vector<glm::vec2> uv0;       // empty, or one per position
  std::vector<glm::vec4> tangents;  // empty, or one per position: xyz unit, w = ±1 (glTF)
  // Empty, or one per position: a generated chart atlas for texture-space diffusion
  // (UvAtlas.h) when uv0 is not usable for it; material textures keep reading uv0.
  std::vector<glm::vec2> uv_atlas;
  // With a generated atlas: its seam gutters (UvAtlas.h), triangles of neighbouring charts
  // drawn again in a chart's own projection into the padding around it, so that the
  // texture-space blur finds the surface's continuation past the chart's border.
  struct AtlasGutter {
    std::vector<std::uint32_t> vertices;  // 3 per triangle: mesh vertices (position, normal...)
    std::vector<glm::vec2> uv;            // 3 per triangle: in the host chart's projection
    std::vector<float> depth;             // 3 per triangle: raster depth, nearer gutter wins
    std::vector<std::uint32_t> host;      // 1 per triangle: a mesh vertex of the host chart
  } uv_atlas_gutter;
  std::vector<std::uint32_t> indices;  // 3 per triangle, each < positions.size()
  std::uint32_t material = 0;       // index into Scene::materials
  Bounds bounds;                    // of positions, in the mesh's own space

  std::size_t vertex_count() const { return positions.size(); }
  std::size_t triangle_count() const { return indices.size() / 3; }
};

// Area-weighted vertex normals: each vertex gets the normalised sum of the (unnormalised)
// cross products of the triangles around it, so large faces weigh more. A vertex that
// touches no triangle with area gets +Y.
std::vector<glm::vec3> area_weighted_normals(const std::vector<glm::vec3>& positions,
                                             const std::vector<std::uint32_t>& indices);

// Normalises mesh.normals; fills them with area_weighted_normals() when they are missing,
// and replaces any zero-length or non-finite normal by the generated one. Returns how
// many normals had to be replaced (0 when all were usable).
std::size_t repair_normals(Mesh& mesh);

// 0, 1, 2, ... n-1: the index list of a non-indexed primitive.
std::vector<std::uint32_t> sequential_indices(std::uint32_t count);

void compute_bounds(Mesh& mesh);

// The structural invariants above; the message names the first broken one.
std::optional<std::string> check_mesh(const Mesh& mesh);

}  // namespace sss::scene
