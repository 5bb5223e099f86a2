#include "reference/RandomWalk.h"

#include "reference/Shading.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace sss::reference {

namespace {

// A guard against a walk that never ends (a numerical trap); no physical walk of the
// media the library accepts comes near it (the mean event count of the brightest, albedo
// 1 - 1e-12, is about 5e6 in a half-space).
constexpr std::uint64_t kMaxEvents = std::uint64_t(1) << 28;

int pick_channel(const glm::dvec3& weight, double sum, double u) {
  const double x = u * sum;
  if (x < weight.x && weight.x > 0.0) return 0;
  if (x < weight.x + weight.y && weight.y > 0.0) return 1;
  if (weight.z > 0.0) return 2;
  return weight.y > 0.0 ? 1 : 0;
}

// The sky a walk meets where it reaches a face (an environment light): the part of the
// walk the face transmits continues outside along the refracted direction and meets the
// sky there unless the scene is in the way. Radiance entering the denser medium gains
// eta^2 (L / n^2 is conserved), so the walk adds beta (1 - F) eta^2 L_env V and goes on
// with the reflected part (the same estimate as choosing between the two with
// probabilities F and 1 - F, with less noise). Pre/post albedo: sqrt(albedo) at the
// entry, as the direct beams. `sky` gets (1 - F) eta^2 L_env (x sqrt(albedo)); false
// where nothing refracts out or the scene hides the sky.
bool sky_through_face(const scene::Scene& s, const RayScene& rays, bool pre_post, double eta, const Hit& hit,
                      const glm::dvec3& p, const glm::dvec3& w, const glm::dvec3& out, double reflectance,
                      glm::dvec3& sky) {
  glm::dvec3 w_out;
  if (!walk::refract(w, -out, eta, 1.0, w_out)) return false;
  const glm::vec3 origin = glm::vec3(p + out * surface_offset_mm(p));
  if (rays.occluded(origin, glm::vec3(w_out), 0.0f, std::numeric_limits<float>::infinity())) return false;
  sky = glm::dvec3(s.environment->radiance(glm::vec3(w_out))) * ((1.0 - reflectance) * eta * eta);
  if (pre_post)
    sky *= glm::sqrt(glm::dvec3(base_colour(s, surface_at(s, rays, hit.instance, hit.triangle, hit.barycentric))));
  return true;
}

// Next-event estimation at a scattering event at p: every direct beam of the band there,
// scattered into the walk's direction w reversed (light arriving along b.direction leaves
// along -w), times beta, added to L beam by beam.
void add_next_event(const scene::Scene& s, const RayScene& rays, const WalkMedium& medium,
                    const WalkMedium::Band& band, const glm::dvec3& p, const glm::dvec3& w, const glm::dvec3& beta,
                    glm::dvec3& L, WalkStats& stats) {
  thread_local std::vector<DirectBeam> beams;
  beams.clear();
  band.beams->gather(p, beams);
  stats.beams += beams.size();
  for (const DirectBeam& b : beams) {
    const double cos_theta = -glm::dot(b.direction, w);
    glm::dvec3 phase;
    for (int k = 0; k < 3; ++k) phase[k] = walk::hg_pdf(medium.g[k], cos_theta);
    glm::dvec3 contribution = b.irradiance * phase * glm::exp(-medium.sigma_t * b.distance_mm);
    if (medium.pre_post) {
      const SurfacePoint y = surface_at(s, rays, b.instance, b.triangle, b.barycentric);
      contribution *= glm::sqrt(glm::dvec3(base_colour(s, y)));
    }
    L += beta * contribution;
  }
}

// No face ahead of a walk at p going w: a hole. It scatters as sampled (after `flight`)
// if that is still within the medium's bounds; true when it has left them instead.
bool leaves_bounds(const WalkMedium& medium, const glm::dvec3& p, const glm::dvec3& w, double flight) {
  double exit = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (w[a] > 0.0) exit = std::min(exit, (medium.hi[a] - p[a]) / w[a]);
    if (w[a] < 0.0) exit = std::min(exit, (medium.lo[a] - p[a]) / w[a]);
  }
  return !(flight < exit);
}

// The walk's direction after a scattering event of channel c: Henyey–Greenstein about w.
// When the band's channels have different g (one_g false), the lobe is one channel's,
// picked by throughput, and beta takes the balance-heuristic weight over the channels'
// lobes (one-sample MIS).
glm::dvec3 next_direction(const WalkMedium& medium, bool one_g, int c, const glm::dvec3& w, glm::dvec3& beta,
                          walk::WalkRng& rng) {
  if (one_g) return walk::hg_sample(medium.g[c], w, rng.uniform(), rng.uniform());
  const int k = pick_channel(beta, beta.x + beta.y + beta.z, rng.uniform());
  const glm::dvec3 next = walk::hg_sample(medium.g[k], w, rng.uniform(), rng.uniform());
  const double cos_theta = glm::dot(w, next);
  glm::dvec3 pdf;
  for (int j = 0; j < 3; ++j) pdf[j] = walk::hg_pdf(medium.g[j], cos_theta);
  const glm::dvec3 q = beta / (beta.x + beta.y + beta.z);
  beta *= pdf / glm::dot(q, pdf);
  return next;
}

}  // namespace

glm::dvec3 face_normal(const scene::Scene& s, const RayScene& rays, std::uint32_t instance, std::uint32_t triangle) {
  const scene::Mesh& mesh = s.meshes[s.instances[instance].mesh];
  const std::vector<glm::vec3>& w = rays.world_positions(instance);
  const glm::dvec3 p0 = w[mesh.indices[3 * triangle]], p1 = w[mesh.indices[3 * triangle + 1]],
                   p2 = w[mesh.indices[3 * triangle + 2]];
  const glm::dvec3 n = glm::cross(p1 - p0, p2 - p0);
  const double len = glm::length(n);
  return len > 0.0 ? n / len : glm::dvec3(0.0, 0.0, 1.0);
}

WalkScene::WalkScene(const scene::Scene& s, const RayScene& rays, std::vector<std::string>* warnings)
    : scene_(&s), rays_(&rays), surfaces_(medium_surfaces(s, rays)), by_material_(s.materials.size(), -1) {
  media_.reserve(surfaces_.size());
  for (const MediumSurface& surface : surfaces_) {
    if (warnings) {
      const std::string w = medium_warning(s, surface);
      if (!w.empty()) warnings->push_back(w);
    }
    const scene::Material& material = s.materials[surface.material];
    // The walk follows one medium inside a closed surface; a stack's layers would need
    // the depth below the surface at every step (issue 19, not done). Say so rather than
    // render the top layer as if it were the whole material.
    if (!material.sss.layers.empty())
      throw std::invalid_argument("material '" + material.name +
                                  "': the random-walk ground truth does not follow layered "
                                  "materials yet (extras.sss.layers); use the diffusion "
                                  "reference (--method diffusion)");
    const profiles::Medium eff = material.sss.effective_medium();
    WalkMedium m;
    m.material = surface.material;
    for (int c = 0; c < 3; ++c) {
      m.sigma_a[c] = eff.sigma_a[std::size_t(c)];
      m.sigma_s[c] = eff.sigma_s[std::size_t(c)];
      m.sigma_t[c] = m.sigma_a[c] + m.sigma_s[c];
      m.g[c] = eff.g[std::size_t(c)];
    }
    m.pre_post = s.materials[surface.material].sss.albedo_mode == scene::AlbedoMode::PrePost;
    m.lo = glm::dvec3(std::numeric_limits<double>::infinity());
    m.hi = -m.lo;
    for (std::uint32_t i : surface.instances)
      for (const glm::vec3& q : rays.world_positions(i)) {
        m.lo = glm::min(m.lo, glm::dvec3(q));
        m.hi = glm::max(m.hi, glm::dvec3(q));
      }
    for (int c = 0; c < 3; ++c) {
      const double eta = eff.eta[std::size_t(c)];
      auto band = std::find_if(m.bands.begin(), m.bands.end(), [&](const WalkMedium::Band& b) { return b.eta == eta; });
      if (band == m.bands.end()) {
        WalkMedium::Band b;
        b.channels = {false, false, false};
        b.eta = eta;
        b.beams = std::make_unique<DirectBeams>(s, rays, surface, eta);
        m.bands.push_back(std::move(b));
        band = m.bands.end() - 1;
      }
      band->channels[std::size_t(c)] = true;
    }
    by_material_[surface.material] = int(media_.size());
    media_.push_back(std::move(m));
  }
}

glm::dvec3 WalkScene::sample_exitant(const WalkMedium& medium, const glm::dvec3& x_o, const glm::dvec3& outward,
                                     const glm::dvec3& travel, walk::WalkRng& rng, WalkStats& stats) const {
  glm::dvec3 value(0.0);
  const double cos_o = -glm::dot(travel, outward);
  if (!(cos_o > 0.0)) return value;
  for (const WalkMedium::Band& band : medium.bands) {
    glm::dvec3 inward;
    if (!walk::refract(travel, outward, 1.0, band.eta, inward)) continue;
    const double weight = (1.0 - walk::fresnel(cos_o, 1.0, band.eta)) / (band.eta * band.eta);
    value += weight * sample_radiance(medium, band, x_o, outward, inward, rng, stats);
  }
  return value;
}

glm::dvec3 WalkScene::unscattered_exitance(const WalkMedium& medium, const glm::dvec3& x_o,
                                           const glm::dvec3& outward) const {
  glm::dvec3 m(0.0);
  const glm::dvec3 p = x_o - outward * surface_offset_mm(x_o);
  std::vector<DirectBeam> beams;
  for (const WalkMedium::Band& band : medium.bands) {
    beams.clear();
    band.beams->gather(p, beams);
    glm::dvec3 mask(0.0);
    for (int c = 0; c < 3; ++c) mask[c] = band.channels[std::size_t(c)] ? 1.0 : 0.0;
    for (const DirectBeam& b : beams) {
      const double cos_theta = glm::dot(b.direction, outward);
      if (!(cos_theta > 0.0)) continue;  // travelling into the medium here, not out
      glm::dvec3 e = b.irradiance * glm::exp(-medium.sigma_t * b.distance_mm) * cos_theta *
                     (1.0 - walk::fresnel(cos_theta, band.eta, 1.0));
      if (medium.pre_post)
        e *= glm::sqrt(glm::dvec3(base_colour(*scene_, surface_at(*scene_, *rays_, b.instance, b.triangle, b.barycentric))));
      m += mask * e;
    }
  }
  return m;
}

glm::dvec3 WalkScene::sample_radiance(const WalkMedium& medium, const WalkMedium::Band& band, const glm::dvec3& x_o,
                                      const glm::dvec3& outward, const glm::dvec3& inward, walk::WalkRng& rng,
                                      WalkStats& stats) const {
  ++stats.paths;
  const scene::Scene& s = *scene_;
  glm::dvec3 beta(0.0), L(0.0);
  for (int c = 0; c < 3; ++c) beta[c] = band.channels[std::size_t(c)] ? 1.0 : 0.0;
  bool one_g = true;  // every channel of the band scatters alike
  for (int j = 0; j < 3; ++j)
    for (int k = 0; k < 3; ++k)
      if (band.channels[std::size_t(j)] && band.channels[std::size_t(k)] && medium.g[j] != medium.g[k]) one_g = false;
  glm::dvec3 p = x_o - outward * surface_offset_mm(x_o);
  glm::dvec3 w = inward;
  for (std::uint64_t events = 0;; ++events) {
    if (events >= kMaxEvents) {
      ++stats.truncated;
      break;
    }
    const double sum = beta.x + beta.y + beta.z;
    if (!(sum > 0.0)) break;
    const glm::dvec3 prob = beta / sum;
    const int c = pick_channel(beta, sum, rng.uniform());
    const double flight = -std::log1p(-rng.uniform()) / medium.sigma_t[c];
    const std::optional<Hit> hit = rays_->intersect(glm::vec3(p), glm::vec3(w));
    if (!hit && leaves_bounds(medium, p, w, flight)) {  // out through a hole: lost
      ++stats.escaped;
      break;
    }
    if (hit && double(hit->t) <= flight) {
      // The face: transmittance over the flight, balance-heuristic weight over channels.
      const double t = hit->t;
      const glm::dvec3 tr = glm::exp(-medium.sigma_t * t);
      beta *= tr / glm::dot(prob, tr);
      p += w * t;
      const glm::dvec3 ng = face_normal(s, *rays_, hit->instance, hit->triangle);
      const double cos_w = glm::dot(w, ng);
      const glm::dvec3 out = cos_w > 0.0 ? ng : -ng;  // towards where the walk was going
      const double reflectance = walk::fresnel(std::abs(cos_w), band.eta, 1.0);
      // An environment light: the sky through the face (sky_through_face), then the walk
      // goes on with the reflected part.
      if (s.environment && reflectance < 1.0) {
        glm::dvec3 sky;
        if (sky_through_face(s, *rays_, medium.pre_post, band.eta, *hit, p, w, out, reflectance, sky)) L += beta * sky;
      }
      beta *= reflectance;
      ++stats.boundary_hits;
      w = glm::normalize(walk::reflect(w, out));
      p -= out * surface_offset_mm(p);
    } else {
      const glm::dvec3 tr = glm::exp(-medium.sigma_t * flight);
      beta *= medium.sigma_s * tr / glm::dot(prob, medium.sigma_t * tr);
      p += w * flight;
      ++stats.scattering_events;
      add_next_event(s, *rays_, medium, band, p, w, beta, L, stats);
      w = next_direction(medium, one_g, c, w, beta, rng);
    }
    const double m = std::max({beta.x, beta.y, beta.z});
    if (events >= 2 && m < 1.0) {
      if (rng.uniform() >= m) break;
      beta /= m;
    }
  }
  return L;
}

}  // namespace sss::reference
