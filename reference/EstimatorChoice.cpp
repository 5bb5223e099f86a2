// The octree or the probe for a view (choose_estimator, with_choice, describe:
// ReferenceRenderer.h), by how the pixels' footprints compare with the octree's spacing.
#include "reference/ReferenceChecks.h"
#include "reference/ReferenceRenderer.h"

#include "reference/PixelShading.h"
#include "reference/RandomWalk.h"
#include "reference/RayScene.h"

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace sss::reference {

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + std::ptrdiff_t(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// The pixel's footprint in mm at its hit point p (normal n): the square root of the area
// spanned by where the rays of the next pixels right and below meet the tangent plane at
// p (the camera's rays are defined past the image's last column and row too); nullopt
// where one runs along the plane.
std::optional<double> surface_footprint(const CameraRays& camera, std::uint32_t x, std::uint32_t y,
                                        const glm::dvec3& p, const glm::dvec3& n) {
  auto step = [&](std::uint32_t nx, std::uint32_t ny) -> std::optional<glm::dvec3> {
    const CameraRays::Ray r = camera.pixel(nx, ny);
    const double along = glm::dot(glm::dvec3(r.direction), n);
    if (std::abs(along) < 1e-9) return std::nullopt;
    const double t = glm::dot(p - glm::dvec3(r.origin), n) / along;
    return glm::dvec3(r.origin) + t * glm::dvec3(r.direction) - p;
  };
  const auto dx = step(x + 1, y), dy = step(x, y + 1);
  if (!dx || !dy) return std::nullopt;
  const double footprint = std::sqrt(glm::length(glm::cross(*dx, *dy)));
  if (!std::isfinite(footprint)) return std::nullopt;
  return footprint;
}

// Over at most ~4096 pixels on a regular grid, those that see a scattering surface: the
// footprint, its material's point spacing (mm), and their ratio.
struct FootprintSamples {
  std::vector<double> ratios, footprints, spacings;
};

FootprintSamples sample_footprints(const scene::Scene& s, const ReferenceOptions& o,
                                   const std::vector<double>& spacing_of) {
  const RayScene rays(s, o.threads);
  const CameraRays camera(s.cameras[0], o.width, o.height, s.mm_per_unit);
  const std::uint32_t stride = std::max<std::uint32_t>(
      1, std::uint32_t(std::ceil(std::sqrt(double(o.width) * double(o.height) / 4096.0))));
  FootprintSamples out;
  for (std::uint32_t y = stride / 2; y < o.height; y += stride)
    for (std::uint32_t x = stride / 2; x < o.width; x += stride) {
      const CameraRays::Ray ray = camera.pixel(x, y);
      const std::optional<Hit> hit = rays.intersect(ray.origin, ray.direction, 0.0f, ray.t_far);
      if (!hit) continue;
      const std::uint32_t material = s.meshes[s.instances[hit->instance].mesh].material;
      if (!(spacing_of[material] > 0.0)) continue;
      const glm::dvec3 n = face_normal(s, rays, hit->instance, hit->triangle);
      const glm::dvec3 p = glm::dvec3(ray.origin) + double(hit->t) * glm::dvec3(ray.direction);
      const std::optional<double> footprint = surface_footprint(camera, x, y, p, n);
      if (!footprint) continue;
      out.ratios.push_back(*footprint / spacing_of[material]);
      out.footprints.push_back(*footprint);
      out.spacings.push_back(spacing_of[material]);
    }
  return out;
}

// Per material, the area of its scattering surfaces in mm^2 (what make_groups plans points
// over); 0 for one that does not scatter.
std::vector<double> scattering_area(const scene::Scene& s, const std::vector<double>& spacing_of) {
  std::vector<double> area(s.materials.size(), 0.0);
  for (const scene::Instance& inst : s.instances) {
    const scene::Mesh& mesh = s.meshes[inst.mesh];
    if (!(spacing_of[mesh.material] > 0.0)) continue;
    const glm::dmat4 world(inst.world);
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
      glm::dvec3 p[3];
      for (int k = 0; k < 3; ++k)
        p[k] = s.mm_per_unit * glm::dvec3(world * glm::dvec4(glm::dvec3(mesh.positions[mesh.indices[3 * t + std::size_t(k)]]), 1.0));
      area[mesh.material] += 0.5 * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
    }
  }
  return area;
}

}  // namespace

EstimatorChoice choose_estimator(const scene::Scene& s, const ReferenceOptions& o) {
  ReferenceOptions checked = o;
  checked.estimator = Estimator::Octree;
  checked.spp = 0;
  checked.target_error = 0.0;
  checked.tile = {};
  detail::check_options(checked);
  detail::check_scene(s);
  EstimatorChoice choice;
  std::vector<double> spacing_of(s.materials.size(), 0.0);
  for (std::size_t m = 0; m < s.materials.size(); ++m)
    if (s.materials[m].sss.enabled) spacing_of[m] = o.spacing_mfp * detail::smallest_mfp(s.materials[m].sss.effective_medium());
  const FootprintSamples samples = sample_footprints(s, o, spacing_of);
  const std::vector<double>& ratios = samples.ratios;
  choice.pixels = ratios.size();
  choice.ratio = median(ratios);
  choice.footprint_mm = median(samples.footprints);
  choice.spacing_mm = median(samples.spacings);
  choice.spacing_mfp = o.spacing_mfp;
  if (!ratios.empty() && choice.ratio < 1.0) choice.spacing_mfp = o.spacing_mfp * choice.ratio;
  // The points that spacing plans over every SSS surface (as make_groups plans them).
  const std::vector<double> area = scattering_area(s, spacing_of);
  for (std::size_t m = 0; m < s.materials.size(); ++m)
    if (spacing_of[m] > 0.0) {
      const double spacing_mm = spacing_of[m] * choice.spacing_mfp / o.spacing_mfp;
      choice.planned_points += area[m] / (spacing_mm * spacing_mm);
    }
  const bool fits = choice.planned_points <= double(o.max_points);
  choice.estimator = !ratios.empty() && choice.ratio < 1.0 && !fits ? Estimator::Probe : Estimator::Octree;
  if (choice.estimator == Estimator::Probe) choice.spacing_mfp = o.spacing_mfp;
  return choice;
}

ReferenceOptions with_choice(ReferenceOptions o, const EstimatorChoice& choice) {
  o.estimator = choice.estimator;
  o.spacing_mfp = choice.spacing_mfp;
  if (choice.estimator == Estimator::Probe) {
    o.spp = kDefaultProbeBatches;
    o.target_error = 0.0;
  }
  return o;
}

std::string describe(const EstimatorChoice& choice, double asked_spacing_mfp) {
  const bool probe = choice.estimator == Estimator::Probe;
  char what[160], why[400];
  if (probe)
    std::snprintf(what, sizeof what, "probe (%llu batches per pixel)", (unsigned long long)kDefaultProbeBatches);
  else
    std::snprintf(what, sizeof what, "octree at spacing %.3g mfp (%.3g points)", choice.spacing_mfp,
                  choice.planned_points);
  if (choice.pixels == 0) return std::string(what) + ": no pixel sees a medium";
  std::snprintf(why, sizeof why,
                "the pixels' median footprint on the surface is %.3g mm, the octree's point spacing %.3g mm at "
                "--spacing %.3g (median ratio %.3g over %zu subsurface pixels)%s",
                choice.footprint_mm, choice.spacing_mm, asked_spacing_mfp, choice.ratio, choice.pixels,
                probe ? "; points as dense as the pixels would exceed --max-points" : "");
  return std::string(what) + ": " + why;
}

}  // namespace sss::reference
