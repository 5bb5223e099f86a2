// DirectBeams: the light that reaches a point inside a medium without scattering (issue 16).
//
// A delta light (directional, point, spot) behind a smooth refractive boundary cannot be
// reached by next-event estimation with a shadow ray: from a point x inside, the straight
// line to the light is not the path light takes, which bends at the surface (Snell). So
// for each x this finds every point y on the medium's faces through which the light's
// refracted ray passes x, exactly, and the irradiance of that ray at x. It is manifold
// next-event estimation (Hanika, Droske & Fascione 2015, "Manifold next event estimation")
// for one refractive vertex, solved without iteration on a triangle mesh:
//
//   * Faces are flat, so the boundary's normal at y is the face's geometric normal.
//   * Directional light: one face refracts the whole beam into one direction d, so the
//     points its light reaches form a prism, the face swept along d. x lies in it when the
//     line back from x along -d meets the face; y is that point. The beam's cross-section
//     does not change: E_b = E cos θi T(θi) / cos θt (T = 1 - Fresnel).
//   * Point and spot lights: the refraction point on the face's plane is the minimum of the
//     optical path |L - y| + η |y - x| (Fermat's principle; strictly convex, so it is
//     unique), found by safeguarded Newton in the plane of incidence. E_b = I T cos θi /
//     (|L - y|² A⊥), A⊥ the cross-section of the refracted ray tube at x per unit face area
//     (from the analytic derivative of the refracted direction over the face).
//   * Every face's reachable region is cut into chunks along the ray and bounded by boxes
//     in a BVH (for point lights the boxes widen by the angle the face subtends at the
//     light: refraction into a denser medium never spreads directions, so that bounds the
//     refracted directions), so a query visits only the few faces whose light can pass x.
//   * Then the ray x -> y must stay inside the medium and y must see the light (shadow
//     ray; any surface blocks it, as in the other renderers). The light's half-space mask
//     and spot cone apply at y.
// Nothing is sampled and nothing is truncated: a query returns every direct beam at x.
// η = 1 has no refraction: the beam is the straight line to the light, one intersection
// ray finds where it enters, and no BVH is built.
#pragma once

#include "reference/MediumMesh.h"
#include "reference/RayScene.h"
#include "scene/Scene.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace sss::reference {

struct DirectBeam {
  std::uint32_t light = 0;
  glm::dvec3 direction{0.0};   // of travel inside the medium at x (unit)
  double distance_mm = 0.0;    // from the entry point y to x
  glm::dvec3 irradiance{0.0};  // E_b at x before attenuation (perpendicular to the beam), RGB
  std::uint32_t instance = 0, triangle = 0;  // the face it enters through
  glm::vec2 barycentric{0.0f};               // of y on that face (corners 1 and 2)
};

class DirectBeams {
 public:
  // The beams of every scene light into `surface`'s medium of refractive index `eta`.
  DirectBeams(const scene::Scene& scene, const RayScene& rays, const MediumSurface& surface, double eta);
  ~DirectBeams();
  DirectBeams(const DirectBeams&) = delete;
  DirectBeams& operator=(const DirectBeams&) = delete;

  // Appends every direct beam that reaches x (world mm, inside the medium) unblocked.
  void gather(const glm::dvec3& x, std::vector<DirectBeam>& out) const;

  std::size_t chunk_count() const;  // BVH primitives over all lights (0 when eta = 1)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Offset off a surface that keeps a ray from meeting the face it leaves (world mm): 64
// float ulps of the largest coordinate, so rounding in Embree's watertight test cannot
// find the face again. At 100 mm it is 5e-4 mm.
double surface_offset_mm(const glm::dvec3& p);

}  // namespace sss::reference
