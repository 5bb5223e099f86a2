// Irradiance sample points on the surfaces of one scattering group (Jensen & Buhler
// 2002, §3.1): area-uniform, with blue-noise spacing, each standing for an equal share of
// the surface area.
//
// Method: weighted sample elimination (Yuksel 2015, "Sample Elimination for Generating
// Poisson Disk Sample Sets"): draw 5N area-uniform candidates, then remove the candidate
// with the most crowded neighbourhood until N remain. N = ceil(area / spacing²), so the
// spacing is the side of the square each point stands for. Distances are Euclidean in 3D.
// Deterministic for a given seed (xoshiro256**, profiles/Random.h). Details in the .cpp:
// - the weights are ordered to 1/65536 of the largest (a bucket queue);
// - near an open rim (edges of one triangle only, matched by corner positions) weights
//   are divided by the fraction of the weight kernel inside the surface, which brings the
//   density within one spacing of the rim from 1.18x to 1.10x of the mean;
// - measured on a plane: nearest-neighbour distance >= 0.74 spacing, mean 0.85 spacing
//   (independent points: mean 0.5; hexagonal packing: 1.07 for all). The elimination
//   is bound by memory latency: each removal updates ~18 neighbours among ~53
//   candidates, at a random place in memory (its cost: reference/README.md,
//   "Performance").
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace sss::reference {

// The triangles of one group (every instance of one SSS material) in world mm,
// unindexed: corners 3t, 3t+1, 3t+2 of triangle t.
struct TriangleSoup {
  std::vector<glm::vec3> positions_mm;
  std::vector<glm::vec3> normals;  // unit shading normals at the corners (or none)
  std::size_t triangle_count() const { return positions_mm.size() / 3; }
};

struct SampledPoint {
  glm::vec3 position_mm{0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f};  // interpolated shading normal, unit
  std::uint32_t triangle = 0;          // index into the soup
  glm::vec2 barycentric{0.0f};         // weights of corners 1 and 2 (corner 0: 1 - x - y)
};

struct SamplingOptions {
  double spacing_mm = 0.5;  // > 0; each point stands for spacing² of surface
  std::uint64_t seed = 1;
  std::size_t max_points = 8'000'000;  // refuse to allocate beyond this
  // Called from the calling thread about every 1% of the elimination with the fraction
  // of the work done; returning false abandons the sampling, and sample_surface() then
  // returns no points (a cancelled render does not wait for it).
  std::function<bool(double fraction)> progress;
};

struct SampledSurface {
  std::vector<SampledPoint> points;
  double area_mm2 = 0.0;        // total area of the soup
  double point_area_mm2 = 0.0;  // area_mm2 / points.size() (every point the same)
};

// Throws std::invalid_argument for a spacing that is not finite and > 0 ("spacing"), or
// when N would exceed max_points (the message gives N, the area and the spacing, and
// says to raise the spacing); also for a soup whose corners are not a whole number of
// triangles ("positions_mm"), that has a non-finite corner ("positions_mm: triangle t"),
// or whose normals are neither empty nor one per corner ("normals"). An empty soup or
// zero area gives no points. Without normals, or where the interpolated normal vanishes,
// a point takes its triangle's geometric normal (counter-clockwise corners).
SampledSurface sample_surface(const TriangleSoup& soup, const SamplingOptions& options);

}  // namespace sss::reference
