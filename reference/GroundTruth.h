// The random-walk ground truth (issue 16; sss-reference --method random-walk): the same
// Scene, camera, opaque shading, specular, albedo modes and tonemap as the diffusion
// reference (PixelShading.h), with the light that crosses a medium computed by true
// volumetric transport (RandomWalk.h) instead of a diffusion profile.
//
// Per pixel: one ray through the pixel centre, as the other renderers. Opaque surfaces and
// the specular lobe are deterministic (direct light, ray-traced shadows). A subsurface
// surface adds, per sample, the eye ray refracted at its face (Fresnel transmission
// T(θo), radiance divided by η²) and one random walk behind it. The estimate is the mean
// over the samples; its variance of the mean comes from the same samples (Welford).
//
// Reproducible: sample k of pixel i draws from its own stream (seed, i, k), and a pixel's
// samples are summed in order by one thread, so the image depends on the seed alone: not
// on the thread count, the tiling, or the machine (bit for bit). A tile renders the rows y
// with y mod N = K - 1 (interleaved, so every tile sees the same mix of easy and hard rows).
#pragma once

#include "image/Image.h"
#include "reference/RandomWalk.h"
#include "reference/ReferenceRenderer.h"
#include "reference/TileMerge.h"
#include "scene/Scene.h"

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace sss::reference {


struct GroundTruthOptions {
  std::uint32_t width = 640;
  std::uint32_t height = 360;
  float exposure = 1.0f;  // display image only
  // Samples per pixel. With target_error > 0 it is the most a pixel gets (0: no limit).
  std::uint64_t spp = 0;
  // > 0: add samples to every pixel until the frame's relative standard error (below) is at
  // most this. Passes grow the sample count towards the projected need, at most 4x a pass.
  double target_error = 0.0;
  bool diffuse_only = false;  // only the light that crossed a medium, before the albedo
  // Write M/π, M the exitant flux per unit area at each visible point (the cosine-weighted
  // mean of the radiance leaving it over the hemisphere: exit directions sampled, plus the
  // light that leaves without scattering, a delta in direction that no eye ray sees), where
  // the default is the radiance towards the eye. The diffusion reference's --diffuse-only
  // writes the same quantity, so the two compare directly.
  bool exitance = false;
  int threads = 0;  // 0: every hardware thread
  std::uint64_t seed = 1;
  TileSpec tile;
  // Called during setup for each warning (also kept in GroundTruthStats::warnings), so a
  // long render reports a mesh that is not closed before it starts.
  std::function<void(const std::string&)> on_warning;
};

struct GroundTruthStats {
  WalkStats walk;
  std::uint64_t spp = 0;                  // samples per subsurface pixel
  std::uint64_t subsurface_pixels = 0;    // that were sampled (in the tile)
  int passes = 0;
  double relative_standard_error = 0.0;   // of the rendered pixels; NaN with 1 sample per pixel
  double seconds = 0.0, setup_seconds = 0.0;
  std::size_t beam_chunks = 0;            // DirectBeams BVH primitives
  std::vector<std::string> warnings;      // e.g. meshes that are not closed
};

struct GroundTruthImage {
  image::Image hdr;       // linear radiance (mean), alpha 1 on geometry
  image::Image variance;  // per channel: the variance of the mean; alpha as hdr
  image::Image display;   // tonemapped
  GroundTruthStats stats;
};

// The frame's relative standard error: sqrt(Σ var) / sqrt(Σ mean²) over every channel of
// every pixel with geometry, the relative RMS difference the image's own noise makes
// against its expectation (comparable with image::compare's relative RMSE).
double relative_standard_error(const image::Image& mean, const image::Image& variance);

// Throws std::invalid_argument for unusable options (the message names the option:
// "spp", "target error", "tile", ...) or scenes, Cancelled when *cancel becomes true.
// Progress: ("setup", f) then ("walk", f), f the fraction of the planned samples done;
// with a target error the first pass is ("noise", f), and each later pass plans anew.
GroundTruthImage render_ground_truth(const scene::Scene& scene, const GroundTruthOptions& options,
                                     const ProgressFn& progress = {}, const std::atomic<bool>* cancel = nullptr);

}  // namespace sss::reference
