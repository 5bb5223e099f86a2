#include "reference/SingleScatter.h"

#include "profiles/Fresnel.h"
#include "profiles/SingleScattering.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace sss::reference {

namespace {

// The refraction of the unit direction `d` (travelling towards the surface, d·n < 0) into
// a medium of relative index eta, n the unit normal on the side d comes from (Snell).
glm::dvec3 refract_in(const glm::dvec3& d, const glm::dvec3& n, double eta) {
  const double cos_i = -glm::dot(d, n);
  const double k = 1.0 - (1.0 - cos_i * cos_i) / (eta * eta);
  return d / eta + n * (cos_i / eta - std::sqrt(std::max(k, 0.0)));
}

}  // namespace

glm::dvec3 marched_single_scattering(const scene::Scene& s, const RayScene& rays, const VisibleSurface& v,
                                     const ShadowMaps* maps, int samples) {
  glm::dvec3 out(0.0);
  if (!v.subsurface || v.material == nullptr || samples < 1) return out;
  const profiles::Medium medium = v.material->sss.effective_medium();
  const glm::dvec3 n(v.normal), to_eye(v.to_eye);
  const double mu_o = std::clamp(glm::dot(n, to_eye), 0.0, 1.0);
  if (!(mu_o > 0.0)) return out;
  const glm::vec3 x_o = v.point.position_mm;
  const float eps = 1e-4f * std::max(1.0f, glm::length(x_o)) + 1e-4f;
  bool done[3] = {false, false, false};
  for (int c0 = 0; c0 < 3; ++c0) {
    if (done[c0]) continue;
    // The channels that share this η share the march (the refracted rays are the same).
    const double eta = medium.eta[c0];
    bool group[3] = {false, false, false};
    double st_min = 0.0;
    for (int c = c0; c < 3; ++c)
      if (!done[c] && medium.eta[c] == eta) {
        group[c] = done[c] = true;
        const double st = medium.sigma_a[c] + medium.sigma_s[c];
        st_min = st_min == 0.0 ? st : std::min(st_min, st);
      }
    if (!(st_min > 0.0)) continue;
    const glm::dvec3 in_o = refract_in(-to_eye, n, eta);  // ω_o', marching into the medium
    const glm::dvec3 t_out = -in_o;                      // the once-scattered light's travel
    // Where the refracted eye ray leaves the object again.
    double t_far = std::numeric_limits<double>::infinity();
    if (const auto back = rays.intersect(x_o - glm::vec3(n) * eps, glm::vec3(in_o), 0.0f))
      t_far = double(back->t);
    const double exit = profiles::fresnel_transmittance(mu_o, eta) / (eta * eta);
    glm::dvec3 sum(0.0);
    for (int k = 0; k < samples; ++k) {
      const double u = (double(k) + 0.5) / double(samples);
      const double depth = -std::log1p(-u) / st_min;  // the u-quantile of σt_min e^(−σt_min s)
      if (depth >= t_far) break;
      const glm::vec3 x_s = x_o + glm::vec3(in_o * depth);
      for (std::size_t index = 0; index < s.lights.size(); ++index) {
        std::optional<LightArrival> a = light_arrival(s, index, x_s, maps);
        if (!a) continue;
        // The beam enters where the straight line from x_s towards the light leaves.
        const auto entry = rays.intersect(x_s, a->l, 0.0f, a->distance_mm);
        if (!entry) continue;
        SurfacePoint p = surface_at(s, rays, entry->instance, entry->triangle, entry->barycentric);
        if (p.material != v.point.material) continue;  // another medium: not this one's beam
        glm::vec3 n_i = p.normal;
        if (glm::dot(n_i, a->l) < 0.0f) n_i = -n_i;  // the outward side, facing the light
        const double mu_i = glm::dot(glm::dvec3(n_i), glm::dvec3(a->l));
        if (!(mu_i > 0.0)) continue;
        // The light as it arrives at x_i (a point light's distance is from x_i).
        const std::optional<LightArrival> at_entry = light_arrival(s, index, p.position_mm, maps);
        if (!at_entry) continue;
        const double visibility = light_visibility(rays, index, p, n_i, *at_entry, maps);
        if (!(visibility > 0.0)) continue;
        const double s_i = double(entry->t);
        const double mu_i_in = profiles::refracted_cosine(mu_i, eta);
        const double s_i_in = s_i * mu_i / mu_i_in;  // Jensen's refracted path length
        const glm::dvec3 t_in = refract_in(-glm::dvec3(at_entry->l), glm::dvec3(n_i), eta);
        const double cos_theta = std::clamp(glm::dot(t_in, t_out), -1.0, 1.0);
        const double beam = mu_i * profiles::fresnel_transmittance(mu_i, eta) / mu_i_in * visibility;
        for (int c = 0; c < 3; ++c) {
          if (!group[c]) continue;
          const double ss = medium.sigma_s[c], st = medium.sigma_a[c] + ss;
          // σs p Φ e^(−σt s) over the sampling density σt_min e^(−σt_min s).
          const double weight = ss * std::exp(-st * (depth + s_i_in) + st_min * depth) / st_min;
          sum[c] += weight * profiles::henyey_greenstein(medium.g[c], cos_theta) * beam * at_entry->radiance[c];
        }
      }
    }
    for (int c = 0; c < 3; ++c)
      if (group[c]) out[c] = sum[c] * exit / double(samples);
  }
  return out;
}

void add_single_scattering(const scene::Scene& s, const RayScene& rays, VisibleSurface& v, const ShadowMaps* maps) {
  if (!v.subsurface) return;
  v.specular += marched_single_scattering(s, rays, v, maps) * glm::dvec3(v.albedo) * (1.0 - double(v.material->metallic));
}

}  // namespace sss::reference
