// RandomWalk: true light transport inside the scene's subsurface meshes (issue 16), the
// ground truth that sss-reference --method random-walk renders.
//
// Each closed subsurface mesh holds a homogeneous medium with the material's own σa, σs,
// Henyey–Greenstein g and η (its effective medium: the material's scale applied). No
// reduced coefficients, no diffusion, no flat-medium assumption: the similarity relation
// and every other model assumption show up as the diffusion models' error against this.
//
// One sample estimates the radiance L_m arriving at a boundary point x_o from inside, along
// the direction a camera ray refracted at x_o continues in (the adjoint walk from the eye):
//   * free flights with the real σt, one channel chosen in proportion to the path's weight
//     and the others weighted by the balance heuristic over channels (spectral MIS, as
//     Mitsuba 3's volpath samples its hero wavelength), so a coloured medium costs one walk;
//   * at every scattering vertex x, next-event estimation through the boundary: every
//     direct beam of every light that reaches x after refracting at the surface
//     (DirectBeams.h: exact, not sampled), weighted by the HG phase function with the real
//     g, the beam's attenuation exp(-σt t) and, for pre/post albedo, √albedo at its entry;
//   * new directions from HG; where g differs between channels, again one-sample MIS;
//   * at a face met from inside: Fresnel reflection with weight F (total internal
//     reflection: 1). The refracted part leaves the medium towards the outside, where it
//     meets no point or directional light, and the frame computes direct light only, like
//     the other renderers: no interreflection between surfaces. So it is not followed,
//     which is the same estimate with less noise. With an environment light (scene::
//     Environment) it meets the sky unless the scene is in the way (one shadow ray along
//     the refracted direction): the walk adds beta (1 - F) eta^2 L_env there (radiance
//     entering the denser medium gains eta^2) and goes on reflected;
//   * a flight that meets no face (the surface has a hole in that direction) runs on as if
//     the medium continued: it scatters where it was sampled, and only a flight that would
//     leave the medium's bounds is lost (counted in WalkStats::escaped). Ending every walk
//     whose straight line ahead passes a hole would darken the whole object (a 16 mm hole
//     in builtin:sphere's cap cut 12% of the walks from a point 25 mm away);
//   * Russian roulette on the largest channel weight after two events (survival
//     probability min(1, max β)), never a bounce cap; a walk is only cut at 2^28 events as
//     a guard against an endless loop, and counted (WalkStats::truncated).
// Every order of scattering is there, single scattering included: the first vertex's NEE
// is the single-scattering term. Inside and outside are decided by the faces' geometric
// normals, which are also the normals of the dielectric boundary: the walk solves the
// transport of the triangle mesh as it is (smooth vertex normals are a shading device of
// the other renderers; near silhouettes and the terminator the flat faces' Fresnel factors
// differ slightly from the interpolated ones).
#pragma once

#include "reference/DirectBeams.h"
#include "reference/MediumMesh.h"
#include "reference/RayScene.h"
#include "reference/WalkSampling.h"
#include "scene/Scene.h"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace sss::reference {

struct WalkStats {
  std::uint64_t paths = 0;
  std::uint64_t scattering_events = 0;
  std::uint64_t boundary_hits = 0;  // faces met from inside (Fresnel reflections)
  std::uint64_t beams = 0;          // direct beams found by next-event estimation
  std::uint64_t escaped = 0;        // walks that left the medium's bounds through a hole
  std::uint64_t truncated = 0;      // walks cut by the event guard
  void add(const WalkStats& o) {
    paths += o.paths;
    scattering_events += o.scattering_events;
    boundary_hits += o.boundary_hits;
    beams += o.beams;
    escaped += o.escaped;
    truncated += o.truncated;
  }
};

// One subsurface material's medium as the walk uses it.
struct WalkMedium {
  std::uint32_t material = 0;
  glm::dvec3 sigma_a{0.0}, sigma_s{0.0}, sigma_t{0.0}, g{0.0};
  bool pre_post = false;  // √albedo at entry and exit
  glm::dvec3 lo{0.0}, hi{0.0};  // the bounds of its surface (world mm)
  // Channels that share a refractive index share a walk (all three, unless the medium is
  // dispersive); each set has its own direct beams.
  struct Band {
    std::array<bool, 3> channels{true, true, true};
    double eta = 1.0;
    std::unique_ptr<DirectBeams> beams;
  };
  std::vector<Band> bands;
};

class WalkScene {
 public:
  // Builds the media of every subsurface material some instance uses, their topology and
  // direct beams. `warnings` receives one line per surface that is not closed.
  WalkScene(const scene::Scene& scene, const RayScene& rays, std::vector<std::string>* warnings = nullptr);

  const scene::Scene& scene() const { return *scene_; }
  const RayScene& rays() const { return *rays_; }
  // The medium of a material, or null for an opaque one.
  const WalkMedium* medium(std::uint32_t material) const {
    return material < by_material_.size() && by_material_[material] >= 0 ? &media_[std::size_t(by_material_[material])]
                                                                           : nullptr;
  }
  const std::vector<MediumSurface>& surfaces() const { return surfaces_; }
  const std::vector<WalkMedium>& media() const { return media_; }

  // One sample of the radiance that leaves the face point `x_o` of `medium`'s surface into
  // the air, travelling against `travel` (the unit direction of an eye ray that arrives at
  // x_o from outside): per channel band, the ray refracted in (Snell), the Fresnel
  // transmission T and the 1/η² of radiance leaving a denser medium (L/n² is conserved
  // across the boundary), times sample_radiance() behind it. `outward` is the face's unit
  // geometric normal on the side `travel` comes from.
  glm::dvec3 sample_exitant(const WalkMedium& medium, const glm::dvec3& x_o, const glm::dvec3& outward,
                            const glm::dvec3& travel, walk::WalkRng& rng, WalkStats& stats) const;

  // The flux per unit area of the light that leaves the face point `x_o` without having
  // scattered: the direct beams (DirectBeams.h) that travel out through the face there,
  // E_b exp(-σt t) cos θ (1 - F(θ)). It is a delta in direction (the beam's refracted
  // direction), so the radiance towards a pinhole eye never holds it (sample_exitant does
  // not either), but the exitant flux M does: a slab lit from behind passes part of the
  // light straight through. Deterministic.
  glm::dvec3 unscattered_exitance(const WalkMedium& medium, const glm::dvec3& x_o, const glm::dvec3& outward) const;

  // One sample of the radiance that reaches the face point `x_o` from inside the medium,
  // arriving against `inward` (the unit direction the eye's refracted ray travels in from
  // x_o), in `band`'s channels (the others are 0). `outward` is the face's unit normal on
  // the side the eye is.
  glm::dvec3 sample_radiance(const WalkMedium& medium, const WalkMedium::Band& band, const glm::dvec3& x_o,
                             const glm::dvec3& outward, const glm::dvec3& inward, walk::WalkRng& rng,
                             WalkStats& stats) const;

 private:
  const scene::Scene* scene_;
  const RayScene* rays_;
  std::vector<MediumSurface> surfaces_;
  std::vector<WalkMedium> media_;
  std::vector<int> by_material_;
};

// The geometric normal of a face (world mm, unit, winding order).
glm::dvec3 face_normal(const scene::Scene& scene, const RayScene& rays, std::uint32_t instance, std::uint32_t triangle);

}  // namespace sss::reference
