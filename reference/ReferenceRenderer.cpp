#include "reference/ReferenceRenderer.h"

#include "image/Tonemap.h"
#include "reference/PixelShading.h"
#include "reference/ProbeReference.h"
#include "reference/ReferenceChecks.h"
#include "reference/RandomWalk.h"
#include "reference/SamplePasses.h"
#include "reference/RayScene.h"
#include "reference/Shading.h"
#include "reference/SingleScatter.h"
#include "reference/SurfaceSampling.h"
#include "reference/Thickness.h"

#include "profiles/Fresnel.h"
#include "profiles/GaussianSumProfile.h"

#include <glm/geometric.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <cmath>
#include <memory>
#include <mutex>
#include <optional>

namespace sss::reference {

namespace {

constexpr double kPi = 3.14159265358979323846;

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// One SSS material: its exact profile, its points and their octree.
struct Group {
  std::uint32_t material = 0;
  std::unique_ptr<profiles::RgbProfile> profile;
  double spacing_mm = 0.0;
  TriangleSoup soup;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> source;  // soup triangle -> (instance, triangle)
  SampledSurface surface;
  std::unique_ptr<ScatterKernel> kernel;
  double area_mm2 = 0.0;        // of the soup
  double planned_points = 0.0;  // area / spacing², before rounding up
  std::vector<IrradiancePoint> points_for_octree;
  std::unique_ptr<PointOctree> octree;
};

class Reporter {
 public:
  Reporter(const ProgressFn& fn, const std::atomic<bool>* cancel) : fn_(fn), cancel_(cancel) {}
  // Workers finish out of order: a stage's fraction is only ever passed on rising.
  void report(const char* stage, double fraction) {
    if (!fn_) return;
    std::lock_guard<std::mutex> lock(mutex_);
    if (stage != stage_) {
      stage_ = stage;
      best_ = -1.0;
    }
    if (fraction <= best_) return;
    best_ = fraction;
    fn_(stage, fraction);
  }
  bool cancelled() const { return cancel_ && cancel_->load(std::memory_order_relaxed); }
  void check() const {
    if (cancelled()) throw Cancelled();
  }

 private:
  const ProgressFn& fn_;
  const std::atomic<bool>* cancel_;
  std::mutex mutex_;
  std::string stage_;
  double best_ = -1.0;
};


double soup_area(const TriangleSoup& soup) {
  double area = 0.0;
  for (std::size_t t = 0; t < soup.triangle_count(); ++t) {
    const glm::vec3* p = &soup.positions_mm[3 * t];
    area += 0.5 * double(glm::length(glm::cross(p[1] - p[0], p[2] - p[0])));
  }
  return area;
}


std::vector<Group> make_groups(const scene::Scene& s, const RayScene& rays, const ReferenceOptions& o,
                               Reporter& reporter) {
  std::vector<Group> groups;
  std::vector<int> group_of(s.materials.size(), -1);
  for (std::uint32_t m = 0; m < s.materials.size(); ++m) {
    if (!s.materials[m].sss.enabled) continue;
    group_of[m] = int(groups.size());
    Group g;
    g.material = m;
    groups.push_back(std::move(g));
  }
  for (std::uint32_t i = 0; i < s.instances.size(); ++i) {
    const scene::Mesh& mesh = s.meshes[s.instances[i].mesh];
    const int gi = group_of[mesh.material];
    if (gi < 0) continue;
    Group& g = groups[std::size_t(gi)];
    const std::vector<glm::vec3>& world = rays.world_positions(i);
    const glm::mat3& nm = rays.normal_matrix(i);
    for (std::uint32_t t = 0; t < mesh.triangle_count(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = mesh.indices[3 * t + k];
        g.soup.positions_mm.push_back(world[v]);
        const glm::vec3 n = nm * mesh.normals[v];
        const float len = glm::length(n);
        g.soup.normals.push_back(len > 0.0f ? n / len : glm::vec3(0.0f));  // 0: the sampler uses the face's
      }
      g.source.emplace_back(i, t);
    }
  }
  // A material no instance uses (or whose triangles have no area) spreads no points.
  for (Group& g : groups) g.area_mm2 = soup_area(g.soup);
  std::erase_if(groups, [](const Group& g) { return !(g.area_mm2 > 0.0); });
  // Profiles first (the Monte Carlo model takes a while), then the spacing they imply.
  for (std::size_t k = 0; k < groups.size(); ++k) {
    reporter.check();
    Group& g = groups[k];
    const scene::SssMaterial& sss = s.materials[g.material].sss;
    const profiles::Medium medium = sss.effective_medium();
    profiles::ModelOptions profile_options = o.profile_options();
    profile_options.mc_progress = [&reporter, k, n = groups.size()](double f) {  // model mc's walk
      reporter.report("profiles", (double(k) + f) / double(n));
      reporter.check();
    };
    g.profile = reference_profile(sss, o.kernel, profile_options);
    g.spacing_mm = o.spacing_mfp * detail::smallest_mfp(medium);
    g.planned_points = g.area_mm2 / (g.spacing_mm * g.spacing_mm);
    reporter.report("profiles", double(k + 1) / double(groups.size()));
  }
  return groups;
}

}  // namespace

std::string_view estimator_name(Estimator e) { return e == Estimator::Probe ? "probe" : "octree"; }
std::string_view kernel_source_name(KernelSource k) { return k == KernelSource::Fit ? "fit" : "exact"; }
std::string_view shadows_name(Shadows s) { return s == Shadows::ShadowMap ? "shadow-map" : "ray-traced"; }
std::string_view transmission_name(Transmission t) {
  return t == Transmission::Local ? "local" : t == Transmission::Off ? "off" : "profile";
}

std::unique_ptr<profiles::RgbProfile> reference_profile(const scene::SssMaterial& sss, KernelSource kernel,
                                                        const profiles::ModelOptions& model_options) {
  if (kernel == KernelSource::Exact) return std::make_unique<profiles::RgbProfile>(sss.profile(model_options));
  profiles::ModelOptions fit_options;  // the GPU's: defaults but for the S(1) switch
  fit_options.single_scattering_apart = model_options.single_scattering_apart;
  fit_options.mc_progress = model_options.mc_progress;  // model mc's walk: progress, cancel
  const profiles::RgbProfile exact = sss.profile(fit_options);
  return std::make_unique<profiles::RgbProfile>(
      profiles::make_kernel_profile(profiles::fit_kernel(exact, sss.gaussians, sss.transmits()), sss.model));
}

namespace {


// Transmission::Local's path towards the light from p: the distance to the last surface
// along l before the light (the first one the light meets, what a shadow map stores), 0
// where nothing lies between p and the light.
double thickness_towards(const RayScene& rays, const glm::vec3& p, const glm::vec3& l, float distance_mm) {
  float t_near = 1e-4f * std::max(1.0f, glm::length(p)), last = 0.0f;
  const float t_far = std::isfinite(distance_mm) ? distance_mm : std::numeric_limits<float>::max();
  for (int guard = 0; guard < 256 && t_near < t_far; ++guard) {
    const std::optional<Hit> hit = rays.intersect(p, l, t_near, t_far);
    if (!hit) break;
    last = hit->t;
    t_near = hit->t + 1e-5f * std::max(1.0f, std::abs(hit->t) + glm::length(p));
  }
  return double(last);
}

// The environment's thickness for Transmission::Local, ray-cast: the distance from p along
// -n (the interpolated normal) to the first surface, what the GPU's per-vertex inward
// thickness (Thickness.h) is at its vertices; -1 where the ray leaves the scene.
double thickness_inward(const RayScene& rays, const glm::vec3& p, const glm::vec3& n) {
  const float t_near = 1e-4f * std::max(1.0f, glm::length(p));
  const std::optional<Hit> hit = rays.intersect(p, -n, t_near, std::numeric_limits<float>::max());
  return hit ? double(hit->t) : -1.0;
}

}  // namespace


namespace {

// A material's light through thin parts for Transmission::Local: T(d) / R_d per channel,
// from R's tail (RadialSampler holds its cumulative mass), or a slab's total transmittance
// / R_d.
struct LocalTransmittance {
  Rgb slab_t, slab_r;
  bool slab = false;
  std::vector<ProfileTable> tables;
  std::vector<RadialSampler> tails;

  explicit LocalTransmittance(const profiles::RgbProfile& profile)
      : slab_t(profile.total_transmittance()), slab_r(profile.total_reflectance()) {
    slab = slab_t[0] > 0.0 || slab_t[1] > 0.0 || slab_t[2] > 0.0;
    if (slab) return;
    const double inner = profile.inner_radius(), S = profile.support_radius();
    const bool costly = profiles::model_is_costly(profile.model());
    for (int c = 0; c < 3; ++c) tables.emplace_back(profile.channel(c), false, costly, 1e-7 * inner, S);
    for (int c = 0; c < 3; ++c) tails.emplace_back(tables[std::size_t(c)], inner, S);
  }
  // The fraction of R_d that channel c transmits through d mm.
  double fraction(int c, double d) const {
    return slab ? slab_t[c] / slab_r[c] : tails[std::size_t(c)].mass_beyond(d) / tails[std::size_t(c)].total();
  }
};

// One octree render: what its stages share. The stages are render_reference's, in order.
struct OctreeRender {
  const scene::Scene& s;
  const ReferenceOptions& o;
  Reporter& reporter;
  tbb::task_arena& arena;
  const RayScene& rays;
  const ShadowMaps* shadow_maps;     // what shadows: the GPU's maps, or null (ray cast)
  const ShadowMaps* thickness_maps;  // the thickness's source, likewise
  // The GPU's inward thickness per mesh vertex (Thickness.h), in mesh units, for the
  // environment's transmission with Thickness::ShadowMap (what the G-buffer interpolates);
  // empty otherwise, and the thickness is ray-cast at each point.
  const std::vector<std::vector<float>>& vertex_thickness;

  // Checks the planned total against --max-points, then samples every group's surface
  // (groups in parallel).
  void sample_points(std::vector<Group>& groups, ReferenceStats& stats) const;
  // The irradiance at each of g's points, and its kernel.
  void light_points(Group& g, std::atomic<std::size_t>& lit, std::size_t total) const;
  // The light a local transmission adds at p (normal n) through the object, per channel:
  // each light's through its thickness towards the light, and the environment's through
  // `inward_mm` (the thickness along -n; negative: none).
  glm::dvec3 transmitted(const LocalTransmittance& t, const SurfacePoint& p, const glm::vec3& n,
                         const glm::dvec3* entry_eta, double inward_mm) const;
  // inward_mm for a sampled point of triangle `tri` of `instance`: the GPU's interpolated
  // vertex thickness, or ray-cast along the interpolated normal.
  double inward_thickness_at(const SurfacePoint& p, std::uint32_t instance, std::uint32_t tri,
                             const glm::vec2& barycentric) const;
  void build_octrees(std::vector<Group>& groups, ReferenceStats& stats) const;
  // One primary ray per pixel centre.
  void render_pixels(const std::vector<Group>& groups, ReferenceImage& out) const;
};

void OctreeRender::sample_points(std::vector<Group>& groups, ReferenceStats& stats) const {
  double planned = 0.0;  // in double: a tiny spacing must not overflow a size_t
  for (const Group& g : groups) planned += std::ceil(g.planned_points);
  if (!(planned <= double(o.max_points)))
    throw std::invalid_argument(
        "spacing: " + message_number(planned) + " irradiance points at spacing " +
        message_number(o.spacing_mfp) + " mfp exceed the limit of " + std::to_string(o.max_points) +
        " (raise the spacing or the point limit)");
  // Groups in parallel; progress is each group's fraction weighted by its share of the
  // points, and Ctrl-C abandons the elimination loops instead of waiting for them.
  std::vector<double> share(groups.size(), 0.0), sampled(groups.size(), 0.0);
  for (std::size_t k = 0; k < groups.size(); ++k)
    share[k] = std::ceil(groups[k].planned_points) / std::max(planned, 1.0);
  std::mutex done_mutex;
  arena.execute([&] {
    tbb::parallel_for(std::size_t(0), groups.size(), [&](std::size_t k) {
      Group& g = groups[k];
      SamplingOptions so;
      so.spacing_mm = g.spacing_mm;
      so.seed = o.seed + k;
      so.max_points = o.max_points;
      so.progress = [&, k](double f) {
        double total = 0.0;
        {
          std::lock_guard<std::mutex> lock(done_mutex);
          sampled[k] = f;
          for (std::size_t j = 0; j < sampled.size(); ++j) total += sampled[j] * share[j];
        }
        reporter.report("points", std::min(total, 1.0));
        return !reporter.cancelled();
      };
      g.surface = sample_surface(g.soup, so);
    });
  });
  reporter.check();
  for (const Group& g : groups) stats.points += g.surface.points.size();
  reporter.report("points", 1.0);
}

glm::dvec3 OctreeRender::transmitted(const LocalTransmittance& t, const SurfacePoint& p,
                                     const glm::vec3& n, const glm::dvec3* entry_eta, double inward_mm) const {
  glm::dvec3 sum(0.0);
  for (std::size_t i = 0; i < s.lights.size(); ++i) {
    // The GPU transmits only lights with a shadow map, which point lights lack.
    if (s.lights[i].type == scene::LightType::Point) continue;
    const std::optional<LightArrival> a = light_arrival(s, i, p.position_mm, shadow_maps);
    if (!a) continue;
    const double cosine = -double(glm::dot(n, a->l));
    if (!(cosine > 0.0)) continue;
    const double d = thickness_maps ? thickness_maps->thickness_mm(i, p.position_mm)
                                    : thickness_towards(rays, p.position_mm, a->l, a->distance_mm);
    if (d < 0.0) continue;  // outside the light's map: the GPU transmits nothing
    for (int c = 0; c < 3; ++c) {
      const double f = entry_eta ? profiles::fresnel_transmittance(cosine, (*entry_eta)[c]) : 1.0;
      sum[c] += a->radiance[c] * cosine * f * t.fraction(c, d);
    }
  }
  // The environment (shading.glsl): no one light's map gives the sky's path, so the surface
  // behind p is taken inward_mm away along -n, facing -n. It receives the sky's irradiance
  // about -n (the part that enters, with directional Fresnel) and sends T(d) / R_d of it
  // through. As the GPU takes it with its shadow maps (spherical harmonics, no occlusion);
  // ray-traced otherwise, from that far point. Exact for a flat slab under any sky.
  if (s.environment && inward_mm >= 0.0 && std::isfinite(inward_mm)) {
    SurfacePoint behind = p;
    behind.position_mm = p.position_mm - n * float(inward_mm);
    behind.geometric_normal = -n;
    behind.sky_blocked = {};  // the GPU does not occlude the sky behind
    const glm::dvec3 e =
        environment_irradiance(*s.environment, rays, behind, -n, shadow_maps != nullptr, entry_eta);
    for (int c = 0; c < 3; ++c) sum[c] += e[c] * t.fraction(c, inward_mm);
  }
  return sum;
}

double OctreeRender::inward_thickness_at(const SurfacePoint& p, std::uint32_t instance, std::uint32_t tri,
                                         const glm::vec2& b) const {
  if (!s.environment) return -1.0;
  const std::uint32_t mesh_index = s.instances[instance].mesh;
  if (vertex_thickness.empty()) return thickness_inward(rays, p.position_mm, p.normal);
  // The GPU's: the vertices' values interpolated (a -1 among them pulls it below 0, and
  // the GPU then transmits nothing), in mm by the scene's unit alone (shaders'
  // thickness_mm(): frame.scale.x, the instance's scale not applied).
  const std::vector<float>& v = vertex_thickness[mesh_index];
  const std::vector<std::uint32_t>& idx = s.meshes[mesh_index].indices;
  if (v.empty()) return -1.0;
  const double t = v[idx[3 * tri]] * (1.0 - b.x - b.y) + v[idx[3 * tri + 1]] * b.x + v[idx[3 * tri + 2]] * b.y;
  return t * s.mm_per_unit;
}

void OctreeRender::light_points(Group& g, std::atomic<std::size_t>& lit, std::size_t total) const {
  // Directional Fresnel: the part of each light that enters (F_t(η, θi)) here, the exit
  // lobe at the pixel.
  const scene::SssMaterial& sss = s.materials[g.material].sss;
  const bool pre_post = sss.albedo_mode == scene::AlbedoMode::PrePost;
  const glm::dvec3 eta(sss.medium.eta[0], sss.medium.eta[1], sss.medium.eta[2]);
  const glm::dvec3* entry_eta = o.applies_fresnel() ? &eta : nullptr;
  const bool local = o.transmission == Transmission::Local;
  std::optional<LocalTransmittance> transmittance;
  if (local) transmittance.emplace(*g.profile);
  std::vector<IrradiancePoint> points(g.surface.points.size());
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 1024),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        if (reporter.cancelled()) return;
                        for (std::size_t i = r.begin(); i != r.end(); ++i) {
                          const SampledPoint& sp = g.surface.points[i];
                          const auto [instance, tri] = g.source[sp.triangle];
                          SurfacePoint p = surface_at(s, rays, instance, tri, sp.barycentric);
                          p.position_mm = sp.position_mm;
                          // The G-buffer's normal: normal-mapped, not flipped (no viewer).
                          const glm::vec3 n = shading_normal(s, p, sp.normal);
                          const DirectLight d = direct_light(s, rays, p, n, nullptr, shadow_maps, entry_eta);
                          glm::dvec3 e = d.irradiance;
                          if (local)
                            e += transmitted(*transmittance, p, n, entry_eta,
                                             inward_thickness_at(p, instance, tri, sp.barycentric));
                          if (pre_post) e *= glm::sqrt(glm::dvec3(base_colour(s, p)));
                          points[i] = {sp.position_mm, sp.normal, glm::vec3(e)};
                        }
                        const std::size_t done = lit.fetch_add(r.size()) + r.size();
                        reporter.report("irradiance", double(done) / double(std::max<std::size_t>(total, 1)));
                      });
  });
  reporter.check();
  arena.execute([&] {  // its table is built with TBB: within --threads too
    g.kernel = std::make_unique<ScatterKernel>(*g.profile, std::max(g.surface.point_area_mm2, 1e-12),
                                               o.transmission != Transmission::Profile);
  });
  g.points_for_octree = std::move(points);
}

void OctreeRender::build_octrees(std::vector<Group>& groups, ReferenceStats& stats) const {
  for (Group& g : groups) {
    OctreeOptions oo;
    oo.max_solid_angle = o.max_solid_angle;
    g.octree = std::make_unique<PointOctree>(std::move(g.points_for_octree),
                                             std::max(g.surface.point_area_mm2, 1e-12), oo);
    GroupStats gs;
    gs.material = s.materials[g.material].name;
    gs.points = g.surface.points.size();
    gs.spacing_mm = g.spacing_mm;
    gs.area_mm2 = g.surface.area_mm2;
    gs.octree = g.octree->stats();
    stats.groups.push_back(gs);
  }
  reporter.report("octree", 1.0);
}

void OctreeRender::render_pixels(const std::vector<Group>& groups, ReferenceImage& out) const {
  const bool fresnel = o.applies_fresnel();
  const CameraRays camera(s.cameras[0], o.width, o.height, s.mm_per_unit);
  std::vector<int> group_of(s.materials.size(), -1);
  for (std::size_t k = 0; k < groups.size(); ++k) group_of[groups[k].material] = int(k);
  out.hdr = image::Image(int(o.width), int(o.height));
  out.specular = image::Image(int(o.width), int(o.height));
  std::atomic<std::uint32_t> rows_done{0};
  arena.execute([&] {
    tbb::parallel_for(std::uint32_t(0), o.height, [&](std::uint32_t y) {
      if (reporter.cancelled()) return;
      for (std::uint32_t x = 0; x < o.width; ++x) {
        const CameraRays::Ray ray = camera.pixel(x, y);
        const std::optional<Hit> hit = rays.intersect(ray.origin, ray.direction, 0.0f, ray.t_far);
        float* px = out.hdr.pixel(int(x), int(y));
        if (!hit) continue;
        VisibleSurface v = visible_surface(s, rays, camera, *hit, ray.direction, o.diffuse_only, shadow_maps);
        if (o.applies_single_scattering()) add_single_scattering(s, rays, v, shadow_maps);
        const int gi = group_of[v.point.material];
        glm::dvec3 L;
        if (gi >= 0) {
          const Group& g = groups[std::size_t(gi)];
          // The points carry the mesh's interpolated normals: so does x_o here (not the
          // viewer-facing, normal-mapped one), or the far-side rule would misfire.
          const glm::dvec3 diffuse = o.brute_force ? g.octree->gather_brute_force(v.point.position_mm, v.point.normal, *g.kernel)
                                                   : g.octree->gather(v.point.position_mm, v.point.normal, *g.kernel);
          L = o.diffuse_only ? diffuse / kPi
                             : v.scatter_factor * (fresnel ? v.exit_fresnel : glm::dvec3(1.0)) * diffuse / kPi +
                                   v.specular;
        } else {
          L = o.diffuse_only ? glm::dvec3(0.0) : v.opaque_radiance();
        }
        px[0] = float(L.x);
        px[1] = float(L.y);
        px[2] = float(L.z);
        px[3] = 1.0f;
        store_specular(out.specular, x, y, v, o.diffuse_only);
      }
      const std::uint32_t done = rows_done.fetch_add(1) + 1;
      reporter.report("render", double(done) / double(o.height));
    });
  });
  reporter.check();
}

}  // namespace

// The octree estimator (Jensen & Buhler 2002): points on every SSS surface, their
// irradiance, one octree per material, then a gather per pixel.
ReferenceImage render_reference(const scene::Scene& s, const ReferenceOptions& o,
                                const ProgressFn& progress, const std::atomic<bool>* cancel) {
  detail::check_options(o);
  detail::check_scene(s);
  if (o.estimator == Estimator::Probe) return render_probe_reference(s, o, progress, cancel);
  const auto t_start = Clock::now();
  Reporter reporter(progress, cancel);
  tbb::task_arena arena(o.threads > 0 ? o.threads : tbb::task_arena::automatic);
  ReferenceImage out;
  ReferenceStats& stats = out.stats;

  RayScene rays(s, o.threads);
  const auto t0 = Clock::now();
  // The GPU's maps, for its shadows, its thickness or both.
  std::unique_ptr<ShadowMaps> built;
  if (o.shadows == Shadows::ShadowMap || o.thickness == Thickness::ShadowMap)
    arena.execute([&] { built = std::make_unique<ShadowMaps>(s, rays, o.shadow_map_size); });
  if (detail::gpu_sky_occlusion(s, o)) arena.execute([&] { rays.set_sky_transfers(sky_occlusion(s, rays, cancel)); });
  // The environment's transmission through the GPU's thickness: its per-vertex bake.
  std::vector<std::vector<float>> vertex_thickness;
  if (s.environment && o.transmission == Transmission::Local && o.thickness == Thickness::ShadowMap) {
    vertex_thickness.resize(s.meshes.size());
    for (std::size_t m = 0; m < s.meshes.size(); ++m)
      if (s.materials[s.meshes[m].material].sss.enabled) vertex_thickness[m] = inward_thickness(s.meshes[m]);
  }
  const OctreeRender run{s, o, reporter, arena, rays,
                         o.shadows == Shadows::ShadowMap ? built.get() : nullptr,
                         o.thickness == Thickness::ShadowMap ? built.get() : nullptr, vertex_thickness};
  std::vector<Group> groups = make_groups(s, rays, o, reporter);
  stats.profile_ms = ms_since(t0);

  // Each stage, timed into its stats field.
  const auto timed = [](double& ms, auto&& stage) {
    const auto begin = Clock::now();
    stage();
    ms = ms_since(begin);
  };
  timed(stats.sampling_ms, [&] { run.sample_points(groups, stats); });
  reporter.check();
  std::atomic<std::size_t> lit{0};
  timed(stats.irradiance_ms, [&] {
    for (Group& g : groups) run.light_points(g, lit, stats.points);
  });
  timed(stats.octree_ms, [&] { run.build_octrees(groups, stats); });
  reporter.check();
  timed(stats.render_ms, [&] { run.render_pixels(groups, out); });
  out.display = image::tonemap(out.hdr, o.exposure);
  stats.total_ms = ms_since(t_start);
  return out;
}

}  // namespace sss::reference
