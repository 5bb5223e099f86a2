#include "reference/GroundTruth.h"

#include "image/Tonemap.h"
#include "reference/PixelShading.h"
#include "reference/SamplePasses.h"

#include <glm/geometric.hpp>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>

namespace sss::reference {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// What a pixel needs for its samples, fixed before the first one.
struct PixelPlan {
  std::uint32_t index = 0;           // y * width + x
  const WalkMedium* medium = nullptr;
  glm::dvec3 base{0.0};              // deterministic radiance: opaque shading or specular
  glm::dvec3 factor{1.0};            // multiplies the light that crossed the medium
  glm::dvec3 x_o{0.0};               // the visible face point (world mm)
  glm::dvec3 outward{0.0};           // its geometric normal on the eye's side
  glm::dvec3 eye_travel{0.0};        // the eye ray's direction
};

void check_options(const GroundTruthOptions& o) {
  if (o.width == 0 || o.height == 0)
    throw std::invalid_argument("width/height: the image must be at least 1x1, got " + std::to_string(o.width) + "x" +
                                std::to_string(o.height));
  if (o.width > 16384 || o.height > 16384) throw std::invalid_argument("width/height: at most 16384 pixels a side");
  if (std::uint64_t(o.width) * o.height > image::kMaxImagePixels)
    throw std::invalid_argument("width/height: at most " + std::to_string(image::kMaxImagePixels) + " pixels");
  check_sample_counts(o.spp, o.target_error, "samples");
  if (!(std::isfinite(o.exposure) && o.exposure >= 0.0f))
    throw std::invalid_argument("exposure: must be finite and >= 0, got " + message_number(o.exposure));
  if (o.threads < 0) throw std::invalid_argument("threads: must be >= 0 (0: all), got " + std::to_string(o.threads));
  check_tile(o.tile, o.height, o.target_error);
}

// A cosine-weighted direction about n (unit), away from the surface.
glm::dvec3 cosine_direction(const glm::dvec3& n, double u1, double u2) {
  glm::dvec3 t, b;
  walk::basis(n, t, b);
  const double r = std::sqrt(u1), phi = 2.0 * walk::kPi * u2;
  return glm::normalize(t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0, 1.0 - u1)));
}

// One sample of the light that crossed the medium and leaves the pixel's point towards the
// eye (or, with `exitance`, towards a cosine-distributed direction: the mean over those
// is M/π), before `factor`.
glm::dvec3 sample_pixel(const WalkScene& walk, const PixelPlan& px, bool exitance, walk::WalkRng& rng, WalkStats& stats) {
  const glm::dvec3 travel =
      exitance ? -cosine_direction(px.outward, rng.uniform(), rng.uniform()) : px.eye_travel;
  return walk.sample_exitant(*px.medium, px.x_o, px.outward, travel, rng, stats);
}

}  // namespace

double relative_standard_error(const image::Image& mean, const image::Image& variance) {
  double var = 0.0, sq = 0.0;
  const std::size_t n = std::size_t(mean.width) * std::size_t(mean.height);
  for (std::size_t i = 0; i < n; ++i) {
    if (!(mean.rgba[4 * i + 3] > 0.5f)) continue;
    for (int c = 0; c < 3; ++c) {
      sq += double(mean.rgba[4 * i + std::size_t(c)]) * mean.rgba[4 * i + std::size_t(c)];
      var += variance.rgba[4 * i + std::size_t(c)];
    }
  }
  return sq > 0.0 ? std::sqrt(var / sq) : 0.0;
}

namespace {

// What the walk needs of a scene, else std::invalid_argument naming the part: a camera,
// instances and meshes whose indices hold, meshes that check_mesh accepts.
void check_walk_scene(const scene::Scene& s) {
  if (s.cameras.empty()) throw std::invalid_argument("scene '" + s.name + "' has no camera");
  for (const scene::Instance& inst : s.instances)
    if (inst.mesh >= s.meshes.size()) throw std::invalid_argument("instance '" + inst.node + "': mesh index out of range");
  for (const scene::Mesh& mesh : s.meshes) {
    if (auto broken = scene::check_mesh(mesh)) throw std::invalid_argument("mesh '" + mesh.name + "': " + *broken);
    if (mesh.material >= s.materials.size())
      throw std::invalid_argument("mesh '" + mesh.name + "': material index out of range");
  }
}

// One primary ray per pixel of the tile: opaque pixels (and the alpha of every hit) are
// written to out's hdr and variance; subsurface pixels are returned, in pixel order, with
// what is deterministic about them.
template <typename CancelledFn>
std::vector<PixelPlan> plan_pixels(const scene::Scene& s, const RayScene& rays, const WalkScene& walk,
                                   const GroundTruthOptions& o, tbb::task_arena& arena, const CancelledFn& cancelled,
                                   GroundTruthImage& out) {
  const CameraRays camera(s.cameras[0], o.width, o.height, s.mm_per_unit);
  return plan_rows<PixelPlan>(o.height, o.tile, arena, cancelled, [&](std::uint32_t y, std::vector<PixelPlan>& row) {
    for (std::uint32_t x = 0; x < o.width; ++x) {
      const CameraRays::Ray ray = camera.pixel(x, y);
      const std::optional<Hit> hit = rays.intersect(ray.origin, ray.direction, 0.0f, ray.t_far);
      if (!hit) continue;
      const VisibleSurface v = visible_surface(s, rays, camera, *hit, ray.direction, o.diffuse_only);
      float* px = out.hdr.pixel(int(x), int(y));
      px[3] = 1.0f;
      out.variance.pixel(int(x), int(y))[3] = 1.0f;
      const WalkMedium* medium = v.subsurface ? walk.medium(v.point.material) : nullptr;
      if (!medium) {
        const glm::dvec3 L = o.diffuse_only ? glm::dvec3(0.0) : v.opaque_radiance();
        for (int c = 0; c < 3; ++c) px[c] = float(L[c]);
        continue;
      }
      PixelPlan p;
      p.index = y * o.width + x;
      p.medium = medium;
      p.base = o.diffuse_only ? glm::dvec3(0.0) : v.specular;
      p.factor = o.diffuse_only ? glm::dvec3(1.0) : v.scatter_factor;
      p.x_o = glm::dvec3(v.point.position_mm);
      p.eye_travel = glm::dvec3(ray.direction);
      const glm::dvec3 ng = face_normal(s, rays, hit->instance, hit->triangle);
      p.outward = glm::dot(ng, p.eye_travel) < 0.0 ? ng : -ng;
      // M/π includes the light that leaves without scattering (a delta in direction).
      if (o.exitance) p.base += p.factor * walk.unscattered_exitance(*medium, p.x_o, p.outward) / walk::kPi;
      row.push_back(p);
    }
  });
}

// The media, their topology and direct beams (WalkScene), built within the arena; its
// warnings go to stats and o.on_warning, its beam chunks are counted.
std::unique_ptr<WalkScene> make_walk_scene(const scene::Scene& s, const RayScene& rays, const GroundTruthOptions& o,
                                           tbb::task_arena& arena, GroundTruthStats& stats) {
  std::unique_ptr<WalkScene> walk;
  arena.execute([&] { walk = std::make_unique<WalkScene>(s, rays, &stats.warnings); });
  if (o.on_warning)
    for (const std::string& w : stats.warnings) o.on_warning(w);
  for (const WalkMedium& m : walk->media())
    for (const WalkMedium::Band& b : m.bands) stats.beam_chunks += b.beams->chunk_count();
  return walk;
}

}  // namespace

GroundTruthImage render_ground_truth(const scene::Scene& s, const GroundTruthOptions& o, const ProgressFn& progress,
                                     const std::atomic<bool>* cancel) {
  check_options(o);
  check_walk_scene(s);
  const auto t_start = Clock::now();
  auto cancelled = [&] { return cancel && cancel->load(std::memory_order_relaxed); };
  std::mutex progress_mutex;
  auto report = [&](const char* stage, double f) {
    if (!progress) return;
    std::lock_guard<std::mutex> lock(progress_mutex);
    progress(stage, std::min(f, 1.0));
  };
  tbb::task_arena arena(o.threads > 0 ? o.threads : tbb::task_arena::automatic);
  GroundTruthImage out;
  GroundTruthStats& stats = out.stats;

  const RayScene rays(s, o.threads);
  const std::unique_ptr<WalkScene> walk = make_walk_scene(s, rays, o, arena, stats);
  report("setup", 0.5);
  if (cancelled()) throw Cancelled();

  // Every pixel of the tile: its visible surface and what is deterministic about it.
  out.hdr = image::Image(int(o.width), int(o.height));
  out.variance = image::Image(int(o.width), int(o.height));
  const std::vector<PixelPlan> plans = plan_pixels(s, rays, *walk, o, arena, cancelled, out);
  if (cancelled()) throw Cancelled();
  stats.subsurface_pixels = plans.size();
  stats.setup_seconds = seconds_since(t_start);
  report("setup", 1.0);

  // Passes of samples over every subsurface pixel.
  std::vector<PixelAccumulator> acc;
  tbb::enumerable_thread_specific<WalkStats> walk_stats;
  auto write_pixels = [&](const std::vector<PixelAccumulator>& a) {
    write_pixel_estimates(plans, a, out.hdr, out.variance);
    return relative_standard_error(out.hdr, out.variance);
  };
  const PassResult passes = run_sample_passes(
      plans.size(), {o.spp, o.target_error, "walk"}, arena, walk_stats, acc,
      [&](std::size_t i, std::uint64_t k, WalkStats& ws) {
        walk::WalkRng rng(o.seed, plans[i].index, k);
        return sample_pixel(*walk, plans[i], o.exitance, rng, ws);
      },
      write_pixels, cancelled, report);
  if (cancelled()) throw Cancelled();
  stats.passes = passes.passes;
  const std::uint64_t done = passes.spp;
  // A tile (or frame) without a subsurface pixel still took the samples it was asked for:
  // its tiles must agree on the count to merge.
  stats.spp = plans.empty() ? o.spp : done;
  for (const WalkStats& ws : walk_stats) stats.walk.add(ws);
  // One sample per pixel says nothing of the noise: the error is unknown, not 0.
  stats.relative_standard_error = stats.spp >= 2 ? relative_standard_error(out.hdr, out.variance)
                                                 : std::numeric_limits<double>::quiet_NaN();
  out.display = image::tonemap(out.hdr, o.exposure);
  stats.seconds = seconds_since(t_start);
  return out;
}

}  // namespace sss::reference
