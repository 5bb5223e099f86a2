// The probe estimator of the diffusion reference (issue 17; sss-reference --estimator
// probe): per pixel, an unbiased Monte Carlo estimate of the model's own surface integral
//
//   M(x_o) = ∫_S K(x_o, x_i) E(x_i) dA_i,
//
// over every surface of the pixel's SSS material, with K = R(|x_o − x_i|) the exact model
// profile (0 beyond its support radius S), or, for a profile with a transmittance (the
// multipole's finite slab) and a point on the far side (n_i · n_o < 0), K = T(ρ), ρ the
// distance from x_i to the normal line through x_o: the integral the point octree
// (PointOctree.h) approximates, without its point spacing or point cap. E is the
// ray-traced irradiance of the scene's lights at x_i (Shading.h), times √albedo there for
// pre/post albedo materials; the composite is the octree reference's.
//
// Sampling, as pbrt-v3/v4 sample their separable BSSRDF (Pharr, Jakob & Humphreys,
// Physically Based Rendering, 3rd ed. §15.4, "Sampling subsurface reflection functions"),
// with the balance heuristic over every technique: a technique is an axis a of the frame
// (n_o, t, b) at x_o and a colour channel c. It draws a radius r from channel c's radial
// density ∝ 2πr R_c(r) on [0, S] (RadialSampler: piecewise uniform in r on a log grid,
// so its density is known exactly) and an angle φ, giving a point q on the disc about x_o
// normal to a, and casts a probe segment through q along a, of half-length √(S² − r²)
// (so that it covers the ball |x_i − x_o| ≤ S). Every hit of the material's surfaces on
// the segment is a sample, of area density p_{a,c}(x_i) = f_c(r_a) / (2π r_a) |n_g · a|,
// r_a the distance of x_i from x_o across a, f_c the radial density, n_g the face normal.
//
// One sample of a pixel (what SamplePasses.h averages and takes the variance of) is a batch
// of probes: per channel 13 along n_o and 8 along each tangent (pbrt's ½, ¼, ¼), each set a
// randomly shifted rank-1 (Fibonacci) lattice in (u_r, u_φ), so a batch is stratified and
// batches are independent. Channel c is estimated from its own probes only, with the
// multi-sample balance heuristic over its three axes (Veach 1997, §9.2.2):
// Σ_hits K_c E_c / Σ_a n_a p_{a,c}, n_a the probes along axis a. Unlike pbrt, the channels
// are not mixed: on a uniformly lit plane each probe then returns R_d/n exactly, where a
// mixture of the three radial densities left 1% of R_d of noise per pixel at 16 batches
// on skin1's red (measured). The variance of a pixel comes from independent batches, not
// from correlated points.
#pragma once

#include "reference/ProfileTable.h"
#include "reference/RayScene.h"
#include "reference/ReferenceRenderer.h"
#include "reference/ShadowMaps.h"
#include "reference/WalkSampling.h"
#include "scene/Scene.h"

#include "profiles/Profile.h"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace sss::reference {

// r ~ f(r) ∝ 2πr R(r) on [0, S]: cells [0, r_lo] and then 64 per decade up to S, uniform in
// r within each cell, with the cell's mass ∫ 2πr R dr (16-point Gauss–Legendre).
class RadialSampler {
 public:
  // Throws std::invalid_argument when R has no mass on [0, S].
  RadialSampler(const ProfileTable& R, double inner_mm, double support_mm);
  double sample(double u) const;    // u in [0, 1)
  double density(double r) const;   // f(r), per mm; 0 beyond S
  // ∫_r^S 2πs R(s) ds as the cells hold it (total() at r <= 0, 0 from S on): the light a
  // point source at depth r below a plane sends through it, R's tail beyond r.
  double mass_beyond(double r) const;
  double support() const { return support_; }
  double total() const { return total_; }  // ∫_0^S 2πr R dr as the cells hold it

 private:
  std::size_t cell_of(double r) const;
  std::vector<double> edges_;  // cell k is [edges_[k], edges_[k + 1])
  std::vector<double> cdf_;    // cdf_[k] = mass of cells < k, normalised; cdf_.back() = 1
  double support_ = 0.0, total_ = 0.0, r_lo_ = 0.0, inv_step_ = 0.0;
};

struct ProbeStats {
  std::uint64_t probes = 0, hits = 0, shadow_rays = 0;
  void add(const ProbeStats& o) {
    probes += o.probes;
    hits += o.hits;
    shadow_rays += o.shadow_rays;
  }
};

// Everything about one SSS material that its pixels' samples need.
struct ProbeGroup {
  std::uint32_t material = 0;
  std::unique_ptr<profiles::RgbProfile> profile;
  std::vector<ProfileTable> reflect, transmit;  // per channel; transmit empty without T
  std::vector<RadialSampler> radial;            // per channel
  double support_mm = 0.0;
  bool pre_post = false;
  // Directional Fresnel at the probe hits (entry F_t(η, θi)); false: all light enters.
  bool entry_fresnel = false;
  glm::dvec3 eta{1.0};
};

class ProbeEstimator {
 public:
  // Builds a group per SSS material that some instance uses. Throws std::invalid_argument
  // for a material whose profile cannot be built.
  // `options`: the model options and the kernel source (ReferenceProfile); `maps`: shadow
  // maps to light the probe hits with (null: ray-traced shadows).
  ProbeEstimator(const scene::Scene& scene, const RayScene& rays, const ReferenceOptions& options,
                 const ShadowMaps* maps = nullptr);
  const ProbeGroup* group(std::uint32_t material) const;
  const std::vector<ProbeGroup>& groups() const { return groups_; }

  // One batch: an unbiased estimate of M(x_o) (mm^-2 times E's units) at the point x_o of
  // material `g` with interpolated normal n_o (unit).
  glm::dvec3 sample(const ProbeGroup& g, const glm::dvec3& x_o, const glm::dvec3& n_o, walk::WalkRng& rng,
                    ProbeStats& stats) const;

  static constexpr int kNormalProbes = 89, kTangentProbes = 21;  // per channel and batch

 private:
  const scene::Scene& scene_;
  const RayScene& rays_;
  const ShadowMaps* maps_ = nullptr;
  std::vector<ProbeGroup> groups_;
  std::vector<int> group_of_;  // material -> groups_ index, -1
};

// render_reference() with Estimator::Probe: the same pixels, composite and refusals as
// the octree path, each SSS pixel sampled in passes (SamplePasses.h).
ReferenceImage render_probe_reference(const scene::Scene& scene, const ReferenceOptions& options,
                                      const ProgressFn& progress, const std::atomic<bool>* cancel);

}  // namespace sss::reference
