#include "reference/ProbeReference.h"

#include "reference/ReferenceChecks.h"

#include "reference/GroundTruth.h"
#include "reference/SingleScatter.h"
#include "reference/PixelShading.h"
#include "reference/SamplePasses.h"
#include "reference/Shading.h"

#include "image/Tonemap.h"

#include "profiles/Integrate.h"
#include "profiles/Medium.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <limits>
#include <mutex>
#include <optional>
#include <cmath>
#include <stdexcept>
#include <string>

namespace sss::reference {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kCellsPerDecade = 64.0;
constexpr double kInnerFraction = 1e-4;  // the first cell is [0, 1e-4 inner radius]

// Fibonacci lattices (n = F_k points, generator F_{k-1}): rank-1 lattices whose 2D points
// are as evenly spread as any of that size (Niederreiter 1992, §5.3).
struct Lattice {
  int n, generator;
};
constexpr Lattice kNormalLattice{ProbeEstimator::kNormalProbes, 55};
constexpr Lattice kTangentLattice{ProbeEstimator::kTangentProbes, 13};

double frac(double x) { return x - std::floor(x); }

}  // namespace

RadialSampler::RadialSampler(const ProfileTable& R, double inner_mm, double support_mm) : support_(support_mm) {
  if (!(support_mm > 0.0 && std::isfinite(support_mm)) || !(inner_mm > 0.0))
    throw std::invalid_argument("profile sampler: the support and inner radius must be > 0");
  r_lo_ = std::min(kInnerFraction * inner_mm, 0.5 * support_mm);
  inv_step_ = kCellsPerDecade / std::log(10.0);
  edges_.push_back(0.0);
  const int cells = std::max(1, int(std::ceil(std::log(support_mm / r_lo_) * inv_step_)));
  for (int k = 0; k < cells; ++k) edges_.push_back(r_lo_ * std::exp(double(k) / inv_step_));
  edges_.push_back(support_mm);
  const profiles::GaussLegendreRule& rule = profiles::gauss_legendre(16);
  std::vector<double> mass(edges_.size() - 1, 0.0);
  for (std::size_t k = 0; k + 1 < edges_.size(); ++k) {
    const double a = edges_[k], b = edges_[k + 1], half = 0.5 * (b - a), mid = 0.5 * (a + b);
    double sum = 0.0;
    for (std::size_t j = 0; j < rule.nodes.size(); ++j) {
      const double r = mid + half * rule.nodes[j];
      sum += rule.weights[j] * 2.0 * kPi * r * std::max(R(r), 0.0);
    }
    mass[k] = half * sum;
    total_ += mass[k];
  }
  if (!(total_ > 0.0 && std::isfinite(total_)))
    throw std::invalid_argument("profile sampler: the profile has no finite mass within its support");
  cdf_.assign(edges_.size(), 0.0);
  for (std::size_t k = 0; k < mass.size(); ++k) cdf_[k + 1] = cdf_[k] + mass[k] / total_;
  cdf_.back() = 1.0;
}

std::size_t RadialSampler::cell_of(double r) const {
  const auto it = std::upper_bound(edges_.begin(), edges_.end(), r);
  return std::size_t(std::clamp<std::ptrdiff_t>(it - edges_.begin() - 1, 0, std::ptrdiff_t(edges_.size()) - 2));
}

double RadialSampler::sample(double u) const {
  // The cell k with cdf_[k] <= u < cdf_[k + 1] (cells without mass are never chosen).
  const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
  const std::size_t k =
      std::size_t(std::clamp<std::ptrdiff_t>(it - cdf_.begin() - 1, 0, std::ptrdiff_t(cdf_.size()) - 2));
  const double w = cdf_[k + 1] - cdf_[k];
  const double t = w > 0.0 ? std::clamp((u - cdf_[k]) / w, 0.0, 1.0) : 0.5;
  return std::min(edges_[k] + t * (edges_[k + 1] - edges_[k]), std::nextafter(support_, 0.0));
}

double RadialSampler::mass_beyond(double r) const {
  if (!(r > 0.0)) return total_;
  if (r >= support_) return 0.0;
  const std::size_t k = cell_of(r);
  const double within = (r - edges_[k]) / (edges_[k + 1] - edges_[k]);
  return total_ * std::max(0.0, 1.0 - (cdf_[k] + within * (cdf_[k + 1] - cdf_[k])));
}

double RadialSampler::density(double r) const {
  if (!(r >= 0.0) || r >= support_) return 0.0;
  const std::size_t k = cell_of(r);
  return (cdf_[k + 1] - cdf_[k]) / (edges_[k + 1] - edges_[k]);
}

ProbeEstimator::ProbeEstimator(const scene::Scene& s, const RayScene& rays, const ReferenceOptions& o,
                               const ShadowMaps* maps)
    : scene_(s), rays_(rays), maps_(maps), group_of_(s.materials.size(), -1) {
  std::vector<bool> used(s.materials.size(), false);
  for (const scene::Instance& inst : s.instances) used[s.meshes[inst.mesh].material] = true;
  std::vector<std::uint32_t> sss_materials;
  for (std::uint32_t m = 0; m < s.materials.size(); ++m)
    if (s.materials[m].sss.enabled && used[m]) sss_materials.push_back(m);
  const profiles::ModelOptions model_options = o.profile_options();
  for (std::uint32_t m : sss_materials) {
    const scene::SssMaterial& sss = s.materials[m].sss;
    ProbeGroup g;
    g.material = m;
    profiles::ModelOptions material_options = model_options;
    if (model_options.mc_progress)  // model mc's walk: material k of n spans [k/n, (k+1)/n]
      material_options.mc_progress = [&model_options, k = double(groups_.size()),
                                      n = double(sss_materials.size())](double f) {
        model_options.mc_progress((k + f) / n);
      };
    g.profile = reference_profile(sss, o.kernel, material_options);
    g.support_mm = g.profile->support_radius();
    g.pre_post = sss.albedo_mode == scene::AlbedoMode::PrePost;
    g.entry_fresnel = o.applies_fresnel();
    g.eta = glm::dvec3(sss.medium.eta[0], sss.medium.eta[1], sss.medium.eta[2]);
    const bool costly = profiles::model_is_costly(g.profile->model());
    const bool transmits = [&] {
      const Rgb t = g.profile->total_transmittance();
      return t[0] > 0.0 || t[1] > 0.0 || t[2] > 0.0;
    }();
    const double inner = g.profile->inner_radius();
    for (int c = 0; c < 3; ++c) {
      const profiles::RadialProfile& ch = g.profile->channel(c);
      const double r0 = 1e-7 * inner;
      g.reflect.emplace_back(ch, false, costly, r0, g.support_mm);
      if (transmits) g.transmit.emplace_back(ch, true, costly, r0, g.support_mm);
    }
    for (int c = 0; c < 3; ++c) g.radial.emplace_back(g.reflect[std::size_t(c)], inner, g.support_mm);
    group_of_[m] = int(groups_.size());
    groups_.push_back(std::move(g));
  }
}

const ProbeGroup* ProbeEstimator::group(std::uint32_t material) const {
  if (material >= group_of_.size() || group_of_[material] < 0) return nullptr;
  return &groups_[std::size_t(group_of_[material])];
}

glm::dvec3 ProbeEstimator::sample(const ProbeGroup& g, const glm::dvec3& x_o, const glm::dvec3& n_o,
                                  walk::WalkRng& rng, ProbeStats& stats) const {
  glm::dvec3 t, b;
  walk::basis(n_o, t, b);
  const glm::dvec3 axes[3] = {n_o, t, b};
  const Lattice lattice[3] = {kNormalLattice, kTangentLattice, kTangentLattice};
  const double S = g.support_mm;
  // The balance heuristic's denominator at x_i for channel c: Σ over its three axes of
  // n_a p_{a,c}(x_i). Each channel is estimated from its own probes only: their radii follow
  // its own profile, so on a uniformly lit plane every probe returns exactly R_d / n (no
  // variance), where mixing in the other channels' probes would not.
  auto mis_density = [&](int c, const glm::dvec3& d, const glm::dvec3& ng) {
    double sum = 0.0;
    for (int a = 0; a < 3; ++a) {
      const double along = glm::dot(d, axes[a]);
      const double r_a = std::sqrt(std::max(glm::dot(d, d) - along * along, 0.0));
      const double cosine = std::abs(glm::dot(ng, axes[a]));
      if (cosine == 0.0) continue;
      if (!(r_a > 0.0)) return std::numeric_limits<double>::infinity();
      sum += double(lattice[a].n) * g.radial[std::size_t(c)].density(r_a) / (2.0 * kPi * r_a) * cosine;
    }
    return sum;
  };
  glm::dvec3 total(0.0);
  for (int c = 0; c < 3; ++c) {
    for (int a = 0; a < 3; ++a) {
      const glm::dvec3& axis = axes[a];
      const glm::dvec3& e1 = axes[(a + 1) % 3];
      const glm::dvec3& e2 = axes[(a + 2) % 3];
      const Lattice L = lattice[a];
      const double s1 = rng.uniform(), s2 = rng.uniform();
      for (int i = 0; i < L.n; ++i) {
        const double r = g.radial[std::size_t(c)].sample(frac(double(i) / L.n + s1));
        const double phi = 2.0 * kPi * frac(double(i * L.generator) / L.n + s2);
        const double half = std::sqrt(std::max(S * S - r * r, 0.0));
        ++stats.probes;
        if (!(half > 0.0)) continue;
        const glm::dvec3 q = x_o + r * (std::cos(phi) * e1 + std::sin(phi) * e2);
        const glm::vec3 origin(q - half * axis);
        const glm::vec3 dir(axis);
        const float t_far = float(2.0 * half);
        float t_near = 0.0f;
        for (int guard = 0; guard < 64; ++guard) {
          const std::optional<Hit> hit = rays_.intersect(origin, dir, t_near, t_far);
          if (!hit) break;
          // Past this face, by more than float rounding at this distance.
          t_near = hit->t + 1e-5f * std::max(1.0f, std::abs(hit->t) + glm::length(origin));
          const scene::Mesh& mesh = scene_.meshes[scene_.instances[hit->instance].mesh];
          if (mesh.material != g.material) continue;
          const SurfacePoint p = surface_at(scene_, rays_, hit->instance, hit->triangle, hit->barycentric);
          const glm::dvec3 d = glm::dvec3(p.position_mm) - x_o;
          const double dist = glm::length(d);
          if (!(dist < S)) continue;
          const double denominator = mis_density(c, d, glm::dvec3(p.geometric_normal));
          if (!(denominator > 0.0) || !std::isfinite(denominator)) continue;
          ++stats.hits;
          double K;
          if (!g.transmit.empty() && glm::dot(glm::dvec3(p.normal), n_o) < 0.0) {
            const double along = glm::dot(d, n_o);
            K = g.transmit[std::size_t(c)](std::sqrt(std::max(dist * dist - along * along, 0.0)));
          } else {
            K = g.reflect[std::size_t(c)](dist);
          }
          if (!(K > 0.0)) continue;
          // The G-buffer's normal: normal-mapped, not flipped (no viewer), as the points'.
          const glm::vec3 n = shading_normal(scene_, p, p.normal);
          double e = direct_light(scene_, rays_, p, n, nullptr, maps_, g.entry_fresnel ? &g.eta : nullptr).irradiance[c];
          stats.shadow_rays += scene_.lights.size();
          if (g.pre_post) e *= std::sqrt(double(base_colour(scene_, p)[c]));
          total[c] += K * e / denominator;
        }
      }
    }
  }
  return total;
}

namespace {

// What a pixel needs for its batches, fixed before the first one.
struct ProbePixel {
  std::uint32_t index = 0;  // y * width + x
  const ProbeGroup* group = nullptr;
  glm::dvec3 base{0.0};     // specular (or 0 for diffuse_only)
  glm::dvec3 factor{1.0};   // composite: scatter factor / π, or 1/π
  glm::dvec3 x_o{0.0}, n_o{0.0};
};

// One primary ray per pixel of the tile: what is deterministic (opaque pixels, specular,
// single scattering, the alpha of every hit) is written to `out`; subsurface pixels are
// returned, in pixel order, with what their batches need.
template <class Cancelled>
std::vector<ProbePixel> plan_probe_pixels(const scene::Scene& s, const RayScene& rays, const ProbeEstimator& estimator,
                                          const ShadowMaps* maps, const ReferenceOptions& o, tbb::task_arena& arena,
                                          const Cancelled& cancelled, ReferenceImage& out) {
  const CameraRays camera(s.cameras[0], o.width, o.height, s.mm_per_unit);
  return plan_rows<ProbePixel>(o.height, o.tile, arena, cancelled, [&](std::uint32_t y, std::vector<ProbePixel>& row) {
    for (std::uint32_t x = 0; x < o.width; ++x) {
      const CameraRays::Ray ray = camera.pixel(x, y);
      const std::optional<Hit> hit = rays.intersect(ray.origin, ray.direction, 0.0f, ray.t_far);
      if (!hit) continue;
      VisibleSurface v = visible_surface(s, rays, camera, *hit, ray.direction, o.diffuse_only, maps);
      if (o.applies_single_scattering()) add_single_scattering(s, rays, v, maps);
      float* px = out.hdr.pixel(int(x), int(y));
      px[3] = 1.0f;
      out.variance.pixel(int(x), int(y))[3] = 1.0f;
      store_specular(out.specular, x, y, v, o.diffuse_only);
      const ProbeGroup* g = v.subsurface ? estimator.group(v.point.material) : nullptr;
      if (!g) {
        const glm::dvec3 L = o.diffuse_only ? glm::dvec3(0.0) : v.opaque_radiance();
        for (int c = 0; c < 3; ++c) px[c] = float(L[c]);
        continue;
      }
      ProbePixel p;
      p.index = y * o.width + x;
      p.group = g;
      p.base = o.diffuse_only ? glm::dvec3(0.0) : v.specular;
      p.factor = (o.diffuse_only ? glm::dvec3(1.0) : v.scatter_factor * (o.applies_fresnel() ? v.exit_fresnel : glm::dvec3(1.0))) / kPi;
      // The mesh's interpolated normal at x_o, as the octree gathers with.
      p.x_o = glm::dvec3(v.point.position_mm);
      p.n_o = glm::normalize(glm::dvec3(v.point.normal));
      row.push_back(p);
    }
  });
}

}  // namespace

ReferenceImage render_probe_reference(const scene::Scene& s, const ReferenceOptions& o, const ProgressFn& progress,
                                      const std::atomic<bool>* cancel) {
  using Clock = std::chrono::steady_clock;
  const auto ms_since = [](Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  };
  const auto t_start = Clock::now();
  std::function<bool()> cancelled = [&] { return cancel && cancel->load(std::memory_order_relaxed); };
  std::mutex progress_mutex;
  std::function<void(const char*, double)> report = [&](const char* stage, double f) {
    if (!progress) return;
    std::lock_guard<std::mutex> lock(progress_mutex);
    progress(stage, std::min(f, 1.0));
  };
  tbb::task_arena arena(o.threads > 0 ? o.threads : tbb::task_arena::automatic);
  ReferenceImage out;
  ReferenceStats& stats = out.stats;
  RayScene rays(s, o.threads);
  auto t0 = Clock::now();
  std::unique_ptr<ProbeEstimator> estimator;
  std::unique_ptr<ShadowMaps> maps;
  arena.execute([&] {
    if (o.shadows == Shadows::ShadowMap) maps = std::make_unique<ShadowMaps>(s, rays, o.shadow_map_size);
    if (detail::gpu_sky_occlusion(s, o)) rays.set_sky_transfers(sky_occlusion(s, rays, cancel));
    ReferenceOptions with_progress = o;  // model mc's walk: 0 to 1 over the materials
    with_progress.model_options.mc_progress = [&](double f) {
      report("profiles", f);
      if (cancelled()) throw Cancelled();
    };
    estimator = std::make_unique<ProbeEstimator>(s, rays, with_progress, maps.get());
  });
  stats.profile_ms = ms_since(t0);
  report("profiles", 1.0);
  if (cancelled()) throw Cancelled();
  for (const ProbeGroup& g : estimator->groups()) {
    GroupStats gs;
    gs.material = s.materials[g.material].name;
    stats.groups.push_back(gs);
  }

  t0 = Clock::now();
  out.hdr = image::Image(int(o.width), int(o.height));
  out.variance = image::Image(int(o.width), int(o.height));
  out.specular = image::Image(int(o.width), int(o.height));
  const std::vector<ProbePixel> pixels = plan_probe_pixels(s, rays, *estimator, maps.get(), o, arena, cancelled, out);
  if (cancelled()) throw Cancelled();
  stats.subsurface_pixels = pixels.size();
  report("setup", 1.0);

  std::vector<PixelAccumulator> acc;
  tbb::enumerable_thread_specific<ProbeStats> probe_stats;
  auto write_pixels = [&](const std::vector<PixelAccumulator>& a) {
    write_pixel_estimates(pixels, a, out.hdr, out.variance);
    return relative_standard_error(out.hdr, out.variance);
  };
  const PassResult passes = run_sample_passes(
      pixels.size(), {o.spp, o.target_error, "probes"}, arena, probe_stats, acc,
      [&](std::size_t i, std::uint64_t k, ProbeStats& ps) {
        walk::WalkRng rng(o.seed, pixels[i].index, k);
        return estimator->sample(*pixels[i].group, pixels[i].x_o, pixels[i].n_o, rng, ps);
      },
      write_pixels, cancelled, report);
  if (cancelled()) throw Cancelled();
  stats.passes = passes.passes;
  stats.spp = pixels.empty() ? o.spp : passes.spp;
  for (const ProbeStats& ps : probe_stats) {
    stats.probes += ps.probes;
    stats.hits += ps.hits;
    stats.shadow_rays += ps.shadow_rays;
  }
  stats.relative_standard_error = stats.spp >= 2 ? relative_standard_error(out.hdr, out.variance)
                                                 : std::numeric_limits<double>::quiet_NaN();
  stats.render_ms = ms_since(t0);
  out.display = image::tonemap(out.hdr, o.exposure);
  stats.total_ms = ms_since(t_start);
  return out;
}

}  // namespace sss::reference
