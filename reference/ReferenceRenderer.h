// The offline CPU reference (DESIGN.md §6): the same Scene, Material and camera as the
// real-time renderer, with every real-time approximation replaced by the exact thing.
//
//   1. For each SSS material (a "scattering group": every instance that uses it),
//      irradiance points are spread over its surfaces (SurfaceSampling.h: area-uniform,
//      blue noise) at a spacing of `spacing_mfp` times the smallest reduced mean free path
//      1/σt' of the material's effective medium over R, G, B. Lower spacing_mfp for more
//      points; `max_points` caps the total.
//   2. Each point's irradiance comes from the scene's lights with ray-traced shadows
//      (Shading.h), times √albedo there for pre/post albedo materials.
//   3. The points go into a Jensen–Buhler octree (PointOctree.h) and the exact model
//      profile R(r), averaged over each point's disc (ScatterKernel.h), is summed at each
//      pixel's visible point: M(x_o) = Σ K(|x_o − x_i|) E_i A. Far-side points of slabs
//      contribute through the profile's transmittance. No Gaussian fit is involved.
//   4. Composite as shaders/composite.comp: L = albedo·(1 − metallic)·M/π + specular for
//      SSS materials, albedo·(1 − metallic)·E/π + specular for opaque ones; the display
//      image is tonemapped as on the GPU (image::tonemap).
//
// One ray per pixel centre, as the rasterizer samples. Parallel over rows with TBB.
//
// Estimator::Probe (ProbeReference.h) replaces steps 1-3 by a per-pixel Monte Carlo
// estimate of the same integral with the exact R(r) (no point spacing, no point cap), and
// reports each pixel's variance of the mean; spp / target_error say how long it samples.
#pragma once

#include "image/Image.h"
#include "reference/PointOctree.h"
#include "reference/TileMerge.h"
#include "scene/Scene.h"

#include "profiles/Profile.h"

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace sss::reference {

enum class Estimator {
  Octree,  // irradiance points and the Jensen-Buhler octree (steps 1-3 above)
  Probe,   // per-pixel profile importance sampling with probe rays (ProbeReference.h)
};
std::string_view estimator_name(Estimator e);  // "octree" | "probe"

// The budget's links (DESIGN.md §1): each switches one real-time approximation into the
// reference, so that the difference it makes is measured alone.
enum class KernelSource {
  Exact,  // the model's R(r) (and T(r))
  Fit,    // the material's sum-of-Gaussians fit, exactly as the GPU gets it (KernelFit.h)
};
std::string_view kernel_source_name(KernelSource k);  // "exact" | "fit"
enum class Shadows {
  RayTraced,  // a shadow ray per light (hard, exact)
  ShadowMap,  // the GPU's shadow maps and PCF, rebuilt on the CPU (ShadowMaps.h)
};
std::string_view shadows_name(Shadows s);  // "ray-traced" | "shadow-map"

// How light crosses thin parts (the error budget's transmission link, issue 17).
enum class Transmission {
  // Through the profile itself: far-side points are summed like the others, with
  // R(|x_o − x_i|) (a slab's with T(ρ)): the diffusion model's own answer.
  Profile,
  // As the real-time renderers (shaders/shared/shading.glsl): the far side is dark, and
  // each point facing away from a light (n·l < 0) adds E (−n·l) T(d) / R_d to its
  // irradiance, d the path through the geometry towards the light (ray-cast to the last
  // surface the light meets: what a shadow map stores), T(d) = ∫_d^∞ 2πs R(s) ds the
  // light a point source at depth d sends through the surface (for the Gaussian fit,
  // Σ w_i exp(−d²/2v_i), the GPU's own), a slab's total transmittance for slabs. With an
  // environment, every point also adds the sky's irradiance about −n at the surface d_in
  // behind it (the inward thickness along −n) times T(d_in) / R_d. Octree only.
  Local,
  // Far side dark, no local term: sss-viewer --transmission off. Octree only.
  Off,
};
std::string_view transmission_name(Transmission t);  // "profile" | "local" | "off"

// Transmission::Local's thickness d towards each light: ray-cast (the last surface on the
// light's line through the point), or read as the GPU reads it from the light's unbiased
// shadow map at shadow_map_size (ShadowMaps::thickness_mm: the texel's depth moved along
// its neighbours' gradient; -1 outside the map, where the GPU transmits nothing).
// The environment's inward thickness likewise: ray-cast from the point along −n, or the
// GPU's per-vertex bake (Thickness.h) interpolated as the G-buffer does.
enum class Thickness { RayCast, ShadowMap };

struct ReferenceOptions {
  std::uint32_t width = 640;
  std::uint32_t height = 360;
  float exposure = 1.0f;         // display image only
  double spacing_mfp = 0.5;      // point spacing, in smallest reduced mean free paths
  std::size_t max_points = 8'000'000;  // over all groups
  double max_solid_angle = 0.3;  // Jensen–Buhler ε (steradians); see PointOctree.h
  bool brute_force = false;      // sum every point (tests and benchmarks of the octree)
  bool diffuse_only = false;     // hdr = M/π (before albedo), no specular, opaque surfaces 0
  // Directional Fresnel on subsurface light, as RenderOptions::fresnel (diffusion and
  // probe estimators; the random walk refracts at the faces whatever this says). Ignored
  // with diffuse_only. Off by default, as RenderOptions::fresnel.
  bool fresnel = false;
  // Whether the factors apply: `fresnel`, unless diffuse_only (hdr = M/π by definition).
  bool applies_fresnel() const { return fresnel && !diffuse_only; }
  // Single scattering S(1) as RenderOptions::single_scattering: the marched S(1)
  // (SingleScatter.h) at each subsurface pixel, unblurred (in `specular`), and profiles
  // without their own once-scattered light (profiles::ModelOptions::
  // single_scattering_apart). Diffusion and probe estimators; the random walk has it by
  // construction. Ignored with diffuse_only (hdr = M/π of the whole profile). On by
  // default, as RenderOptions::single_scattering.
  bool single_scattering = true;
  bool applies_single_scattering() const { return single_scattering && !diffuse_only; }
  // model_options with single_scattering_apart set as applies_single_scattering() says:
  // what the estimators build their profiles with.
  profiles::ModelOptions profile_options() const {
    profiles::ModelOptions m = model_options;
    m.single_scattering_apart = applies_single_scattering();
    return m;
  }
  int threads = 0;               // 0: every hardware thread
  std::uint64_t seed = 1;        // of the point sets, or of the probes
  Estimator estimator = Estimator::Octree;
  // Probe only: batches of probes per pixel (with target_error: the most a pixel gets),
  // and the frame's relative standard error to stop at (0: run spp batches).
  std::uint64_t spp = 0;
  double target_error = 0.0;
  // Probe only: render the rows of this tile (TileMerge.h), with a fixed spp; the octree
  // renders whole frames (its point set and octree serve every pixel at once).
  TileSpec tile;
  profiles::ModelOptions model_options;
  KernelSource kernel = KernelSource::Exact;
  Shadows shadows = Shadows::RayTraced;
  std::uint32_t shadow_map_size = 1024;  // Shadows::ShadowMap: the GPU's (RenderOptions)
  Transmission transmission = Transmission::Profile;
  Thickness thickness = Thickness::RayCast;  // Transmission::Local only
  // Shadows::ShadowMap with an environment: the GPU's sky occlusion (RenderOptions::
  // sky_occlusion), its per-vertex bake (SkyOcclusion.h) taken from the harmonics'
  // irradiance as the GPU does. Ray-traced shadows sample the sky's occlusion itself.
  bool sky_occlusion = true;
};

// The profile the reference sums for an SSS material: its model's exact R(r), or with
// KernelSource::Fit the Gaussian fit the GPU uploads (the model's default ModelOptions
// for the fit, as renderer/MaterialTable builds it, but for single_scattering_apart, which
// it takes from `model_options`; `model_options` for the exact one).
// Throws std::invalid_argument when the profile cannot be built.
std::unique_ptr<profiles::RgbProfile> reference_profile(const scene::SssMaterial& sss, KernelSource kernel,
                                                        const profiles::ModelOptions& model_options);

struct GroupStats {
  std::string material;
  std::size_t points = 0;
  double spacing_mm = 0.0;
  double area_mm2 = 0.0;
  OctreeStats octree;
};

struct ReferenceStats {
  std::vector<GroupStats> groups;
  std::size_t points = 0;
  // Probe estimator: batches per subsurface pixel, passes, the frame's relative standard
  // error (NaN with 1 batch), probe rays, their hits on the material, shadow rays.
  std::uint64_t spp = 0, subsurface_pixels = 0, probes = 0, hits = 0, shadow_rays = 0;
  int passes = 0;
  double relative_standard_error = 0.0;
  double profile_ms = 0.0, sampling_ms = 0.0, irradiance_ms = 0.0, octree_ms = 0.0,
         render_ms = 0.0, total_ms = 0.0;
};

struct ReferenceImage {
  image::Image hdr;      // linear radiance, alpha 1 on geometry, 0 on background
  image::Image display;  // tonemapped, sRGB codes / 255
  image::Image variance; // probe estimator: the per-pixel variance of the mean (empty otherwise)
  image::Image specular; // the specular radiance in hdr (0 with diffuse_only), alpha as hdr's
  ReferenceStats stats;
};

// The stage ("profiles", "points", "irradiance", "octree", "render"; the probe estimator:
// "profiles", "setup", then "noise" with a target error, "probes") and its completed
// fraction. Called from one thread at a time (the renderer serialises the calls).
using ProgressFn = std::function<void(const char* stage, double fraction)>;

struct Cancelled : std::runtime_error {
  Cancelled() : std::runtime_error("cancelled") {}
};

// sss-reference --estimator auto (its default): how to reach a given error first on this
// frame. The octree's quadrature has a floor set by its point spacing (at a light edge
// the points near it are lit or dark as a whole), which shows pixel by pixel where the
// pixels are finer than the points (issue 17: builtin:edge at 0.1 mm pixels, 30% of R_d
// for mc-table at the default spacing, where the probe's 16 batches give 0.84% in less
// time); where each pixel covers a point or more the octree is as exact and far cheaper
// (builtin:bunny at 160x90: within 0.24% of the probe, and 36x faster; README,
// "sss-reference"). So, with r
// the median over the frame's subsurface pixels of (the pixel's footprint on the surface)
// / (the octree's spacing for its material):
//   r >= 1: the octree at its spacing;
//   r < 1: the octree with its points as dense as the pixels (spacing x r), where that
//          many points fit under max_points (the view samples the surface no finer, and
//          points cost far less than per-pixel probes); the probe where they do not (the
//          octree cannot sample the surface at the pixels' scale: builtin:edge's 120,000
//          mm² at 0.1 mm would take 12 M points).
// The footprint is the side of the square with the area the pixel covers on the tangent
// plane of its visible point (found from the neighbouring pixels' rays, so it holds for
// both projections and grows with the surface's tilt). Pixels on a grid of at most ~4096
// are looked at.
struct EstimatorChoice {
  Estimator estimator = Estimator::Octree;
  double spacing_mfp = 0.0;   // the octree's: options.spacing_mfp, or finer (above)
  double planned_points = 0;  // the octree's at spacing_mfp, over every SSS surface
  double ratio = 0.0;         // median footprint / spacing (0 when no pixel sees a medium)
  double footprint_mm = 0.0;  // median footprint over the sampled subsurface pixels
  double spacing_mm = 0.0;    // median octree spacing (at options.spacing_mfp) there
  std::size_t pixels = 0;     // subsurface pixels sampled
};
// `options`: the size, spacing, point cap and threads (the estimator field is ignored).
// Throws as render_reference for a scene without a camera or with broken meshes.
EstimatorChoice choose_estimator(const scene::Scene& scene, const ReferenceOptions& options);

// The probe's batches per pixel where nothing else says (auto's pick, sss-reference
// --estimator probe, the viewer's Compare panel). At a light edge (builtin:edge, 0.1 mm
// pixels, every preset and model) 16 batches leave a standard error of ~0.45% of R_d on
// the lit pixels, and the worst of the frame's ~10^4 pixel-channels lies ~2.4 of them
// out: 0.83-1.14% measured, over issue 17's 1% goal. 24 scale the error by
// sqrt(16/24) = 0.82, to a worst of about 0.9%, in 1.5x the time (README, "sss-reference",
// has the times).
inline constexpr std::uint64_t kDefaultProbeBatches = 24;

// `options` as `choice` says: its estimator, the octree's spacing, and for the probe
// kDefaultProbeBatches with no target error.
ReferenceOptions with_choice(ReferenceOptions options, const EstimatorChoice& choice);
// What was chosen and why, in one line, e.g. "octree at spacing 0.223 mfp (1.48e+05
// points): the pixels' median footprint on the surface is 0.598 mm, ...". `asked_spacing`
// is the spacing the choice started from (options.spacing_mfp before with_choice).
std::string describe(const EstimatorChoice& choice, double asked_spacing_mfp);

// Throws std::invalid_argument for unusable options or scenes (no camera, zero size,
// bad spacing, too many points; the message names the option), Cancelled when `cancel`
// becomes true (checked between rows and stages), std::runtime_error for Embree failures.
ReferenceImage render_reference(const scene::Scene& scene, const ReferenceOptions& options,
                                const ProgressFn& progress = {},
                                const std::atomic<bool>* cancel = nullptr);

}  // namespace sss::reference
