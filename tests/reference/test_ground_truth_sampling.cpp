// The random walk's sampling routines and its light connection (issue 16), each against an
// independent computation, as pbrt-v4 and Mitsuba 3 test their samplers: histograms of a
// million samples against the probability each bin must hold, judged by chi-square with
// bins pooled to at least 5 expected counts, at a significance of 1e-3 per test.
//   * Henyey–Greenstein directions (WalkSampling.h) against the closed-form CDF of the
//     scattering cosine and a uniform azimuth; the pdf against that CDF's derivative.
//   * Refraction and Fresnel: light arriving cosine-distributed from the air, transmitted
//     with probability 1 - walk::fresnel and bent by walk::refract, against the transmitted
//     cosine's distribution from profiles' Fresnel (its own code) and étendue,
//     dμi² = η² dμt²; the reflectance itself against profiles' on both sides.
//   * The light connection (DirectBeams.h): the fluence of direct light inside a faceted
//     sphere and the bunny, predicted cell by cell from the direct beams, against photons
//     traced forward from the light through the faces (own Snell, profiles' Fresnel).
#include "GroundTruthTestSupport.h"

#include "reference/DirectBeams.h"
#include "reference/MediumMesh.h"
#include "reference/RayScene.h"
#include "reference/WalkSampling.h"

#include "profiles/Fresnel.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cstdio>
#include <functional>
#include <optional>
#include <vector>

namespace sss::reference::testing {
namespace {

// Chi-square of observed counts against expected probabilities, bins pooled in order until
// each pool expects at least 5; returns the upper-tail probability.
double chi_square_p(const std::vector<double>& observed, const std::vector<double>& expected_counts, int* dof = nullptr) {
  double chi = 0.0, o = 0.0, e = 0.0;
  int pools = 0;
  for (std::size_t i = 0; i < observed.size(); ++i) {
    o += observed[i];
    e += expected_counts[i];
    if (e >= 5.0 || i + 1 == observed.size()) {
      if (e > 0.0) chi += (o - e) * (o - e) / e;
      else if (o > 0.0) return 0.0;  // samples where none can be
      ++pools;
      o = e = 0.0;
    }
  }
  if (dof) *dof = pools - 1;
  return chi_square_upper_tail(chi, std::max(pools - 1, 1));
}

// P(cos θ <= μ) for Henyey–Greenstein with g (Henyey & Greenstein 1941, integrated).
double hg_cdf(double g, double mu) {
  if (g == 0.0) return 0.5 * (mu + 1.0);
  return (1.0 - g * g) / (2.0 * g) * (1.0 / std::sqrt(1.0 + g * g - 2.0 * g * mu) - 1.0 / (1.0 + g));
}

TEST(GroundTruthSampling, HenyeyGreensteinDirectionsFollowTheirDistribution) {
  constexpr int kCos = 40, kPhi = 8;
  constexpr std::uint64_t kSamples = 1u << 20;
  const glm::dvec3 axis = glm::normalize(glm::dvec3(0.3, -0.5, 0.81));
  glm::dvec3 t, b;
  walk::basis(axis, t, b);
  for (const double g : {-0.7, 0.0, 0.3, 0.9, 0.99}) {
    std::vector<double> observed(kCos * kPhi, 0.0), expected(kCos * kPhi, 0.0);
    // Bins uniform in the CDF's natural variable: cos θ through the inverse of a mild
    // power so that strongly forward g still spreads over the bins.
    auto edge = [&](int i) { return -1.0 + 2.0 * std::pow(double(i) / kCos, g > 0.5 ? 0.25 : 1.0); };
    walk::WalkRng rng(3, std::uint64_t(g * 1000 + 1000), 0);
    for (std::uint64_t n = 0; n < kSamples; ++n) {
      const glm::dvec3 d = walk::hg_sample(g, axis, rng.uniform(), rng.uniform());
      ASSERT_NEAR(glm::length(d), 1.0, 1e-12);
      const double c = glm::dot(d, axis);
      int ci = 0;
      while (ci + 1 < kCos && c > edge(ci + 1)) ++ci;
      double phi = std::atan2(glm::dot(d, b), glm::dot(d, t));
      if (phi < 0.0) phi += 2.0 * kPi;
      const int pi = std::min(kPhi - 1, int(phi / (2.0 * kPi) * kPhi));
      observed[std::size_t(ci * kPhi + pi)] += 1.0;
    }
    for (int ci = 0; ci < kCos; ++ci)
      for (int pi = 0; pi < kPhi; ++pi)
        expected[std::size_t(ci * kPhi + pi)] = kSamples * (hg_cdf(g, edge(ci + 1)) - hg_cdf(g, edge(ci))) / kPhi;
    int dof = 0;
    const double p = chi_square_p(observed, expected, &dof);
    std::printf("HG g %+.2f: chi-square p %.3g over %d degrees of freedom\n", g, p, dof);
    EXPECT_GT(p, 1e-3) << "g " << g;
    // The pdf per steradian is the CDF's derivative over 2π.
    for (double mu = -0.99; mu < 1.0; mu += 0.07) {
      const double h = 1e-6, derivative = (hg_cdf(g, mu + h) - hg_cdf(g, mu - h)) / (2 * h);
      EXPECT_NEAR(walk::hg_pdf(g, mu) * 2.0 * kPi, derivative, 1e-6 * std::max(1.0, derivative)) << g << " " << mu;
    }
  }
}

TEST(GroundTruthSampling, RefractionAndFresnelConserveEtendueAndMatchProfilesFresnel) {
  // The reflectance, both ways, against profiles' implementation (its own code).
  for (const double eta : {1.0, 1.3, 1.5, 2.4})
    for (double c = 0.001; c <= 1.0; c += 0.0137) {
      EXPECT_NEAR(walk::fresnel(c, 1.0, eta), profiles::fresnel_dielectric(c, eta), 1e-12) << eta << " " << c;
      EXPECT_NEAR(walk::fresnel(c, eta, 1.0), profiles::fresnel_dielectric(c, 1.0 / eta), 1e-12) << eta << " " << c;
    }
  constexpr int kBins = 40;
  constexpr std::uint64_t kSamples = 1u << 20;
  const glm::dvec3 n = glm::normalize(glm::dvec3(-0.2, 0.9, 0.4));  // outward
  glm::dvec3 t, b;
  walk::basis(n, t, b);
  for (const double eta : {1.3, 1.5}) {
    const double mu_min = std::sqrt(1.0 - 1.0 / (eta * eta));  // the critical cone inside
    std::vector<double> observed(kBins, 0.0), expected(kBins, 0.0);
    walk::WalkRng rng(9, std::uint64_t(eta * 100), 0);
    for (std::uint64_t k = 0; k < kSamples; ++k) {
      // Cosine-distributed arrival from the air: the direction of travel points into the surface.
      const double q = rng.uniform(), phi = 2.0 * kPi * rng.uniform();
      const glm::dvec3 from = std::sqrt(q) * (std::cos(phi) * t + std::sin(phi) * b) + std::sqrt(1.0 - q) * n;
      const glm::dvec3 w = -from;
      const double cos_i = std::sqrt(1.0 - q);
      if (rng.uniform() < walk::fresnel(cos_i, 1.0, eta)) continue;  // reflected
      glm::dvec3 d;
      ASSERT_TRUE(walk::refract(w, n, 1.0, eta, d));
      // In the plane of incidence, and Snell's law.
      EXPECT_NEAR(glm::dot(glm::cross(w, n), d), 0.0, 1e-12);
      const double sin_i = glm::length(glm::cross(w, n)), sin_t = glm::length(glm::cross(d, n));
      ASSERT_NEAR(sin_i, eta * sin_t, 1e-12);
      const double mu_t = -glm::dot(d, n);
      ASSERT_GE(mu_t, mu_min - 1e-12);
      observed[std::size_t(std::min(kBins - 1, int((mu_t - mu_min) / (1.0 - mu_min) * kBins)))] += 1.0;
    }
    // P(μt in a bin) = ∫ T(μi) d(μi²) = η² ∫ T(μi(μt)) 2 μt dμt, by Gauss–Legendre.
    const double xg[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, wg[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
    for (int i = 0; i < kBins; ++i) {
      const double a = mu_min + (1.0 - mu_min) * i / kBins, c = mu_min + (1.0 - mu_min) * (i + 1) / kBins;
      double sum = 0.0;
      for (int s = 0; s < 32; ++s) {
        const double lo = a + (c - a) * s / 32, hi = a + (c - a) * (s + 1) / 32;
        for (int k = 0; k < 3; ++k) {
          const double mu_t = 0.5 * (lo + hi) + 0.5 * (hi - lo) * xg[k];
          const double mu_i = std::sqrt(std::max(0.0, 1.0 - eta * eta * (1.0 - mu_t * mu_t)));
          sum += 0.5 * (hi - lo) * wg[k] * (1.0 - profiles::fresnel_dielectric(mu_i, eta)) * 2.0 * mu_t;
        }
      }
      expected[std::size_t(i)] = kSamples * eta * eta * sum;
    }
    int dof = 0;
    const double p = chi_square_p(observed, expected, &dof);
    std::printf("refraction eta %.1f: chi-square p %.3g over %d degrees of freedom\n", eta, p, dof);
    EXPECT_GT(p, 1e-3) << "eta " << eta;
  }
}

// The fluence of direct light in cubic cells of a medium: from photons traced forward from
// the light (track-length estimator: Σ ℓ Φ / V), and from the direct beams at random points
// of each cell (their mean). Both with their standard errors.
struct CellFluence {
  bool interior = false;
  double forward = 0.0, forward_var = 0.0, predicted = 0.0, predicted_var = 0.0;
};

// Own refraction for the forward photons: the tangential part scales by 1/η.
glm::dvec3 snell(const glm::dvec3& w, const glm::dvec3& n_out, double eta) {
  const glm::dvec3 tangential = (w - glm::dot(w, n_out) * n_out) / eta;
  return glm::normalize(tangential - n_out * std::sqrt(std::max(0.0, 1.0 - glm::dot(tangential, tangential))));
}

std::vector<CellFluence> compare_fluence(const scene::Scene& s, double eta, int cells_per_axis, std::uint64_t photons) {
  const RayScene rays(s);
  const std::vector<MediumSurface> surfaces = medium_surfaces(s, rays);
  const MediumSurface& surface = surfaces.at(0);
  const DirectBeams beams(s, rays, surface, eta);
  // The medium's box, cut into cells.
  glm::dvec3 lo(1e30), hi(-1e30);
  for (const glm::vec3& p : rays.world_positions(0)) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
  }
  const glm::dvec3 cell = (hi - lo) / double(cells_per_axis);
  const double volume = cell.x * cell.y * cell.z;
  const int n_cells = cells_per_axis * cells_per_axis * cells_per_axis;
  std::vector<double> sum(static_cast<std::size_t>(n_cells), 0.0), sum2(static_cast<std::size_t>(n_cells), 0.0);
  const scene::Light& light = s.lights.at(0);
  const glm::dvec3 centre = 0.5 * (lo + hi);
  const double radius = 0.5 * glm::length(hi - lo);
  walk::WalkRng rng(77, 0, 0);
  for (std::uint64_t k = 0; k < photons; ++k) {
    glm::dvec3 origin, w;
    double flux;  // in the renderer's irradiance units times mm²
    if (light.type == scene::LightType::Directional) {
      // Uniform over the disc that covers the medium, perpendicular to the light.
      w = glm::normalize(glm::dvec3(light.direction()));
      glm::dvec3 t, b;
      walk::basis(w, t, b);
      const double r = radius * std::sqrt(rng.uniform()), phi = 2.0 * kPi * rng.uniform();
      origin = centre - 3.0 * radius * w + r * (std::cos(phi) * t + std::sin(phi) * b);
      flux = double(light.intensity) * kPi * radius * radius / double(photons);
    } else {
      // Uniform in the cone of directions that covers the medium's bounding sphere.
      origin = glm::dvec3(light.position()) * s.mm_per_unit;
      const glm::dvec3 axis = glm::normalize(centre - origin);
      const double cos_max = std::sqrt(std::max(0.0, 1.0 - radius * radius / glm::dot(centre - origin, centre - origin)));
      const double c = 1.0 - rng.uniform() * (1.0 - cos_max), sn = std::sqrt(1.0 - c * c), phi = 2.0 * kPi * rng.uniform();
      glm::dvec3 t, b;
      walk::basis(axis, t, b);
      w = glm::normalize(c * axis + sn * (std::cos(phi) * t + std::sin(phi) * b));
      // I per scene-unit² (E = I / d², d in scene units): in mm, I mm_per_unit² per sr.
      flux = double(light.intensity) * s.mm_per_unit * s.mm_per_unit * 2.0 * kPi * (1.0 - cos_max) / double(photons);
    }
    const std::optional<Hit> in = rays.intersect(glm::vec3(origin), glm::vec3(w));
    if (!in) continue;
    const glm::dvec3 y = origin + double(in->t) * w;
    glm::dvec3 n = glm::normalize(glm::cross(glm::dvec3(rays.world_positions(0)[s.meshes[0].indices[3 * in->triangle + 1]]) -
                                                 glm::dvec3(rays.world_positions(0)[s.meshes[0].indices[3 * in->triangle]]),
                                             glm::dvec3(rays.world_positions(0)[s.meshes[0].indices[3 * in->triangle + 2]]) -
                                                 glm::dvec3(rays.world_positions(0)[s.meshes[0].indices[3 * in->triangle]])));
    if (glm::dot(n, w) > 0.0) n = -n;  // the side the photon comes from
    const double cos_i = -glm::dot(n, w);
    const double carried = flux * (1.0 - profiles::fresnel_dielectric(cos_i, eta));
    const glm::dvec3 d = snell(w, n, eta);
    const glm::dvec3 start = y - n * surface_offset_mm(y);
    const std::optional<Hit> out = rays.intersect(glm::vec3(start), glm::vec3(d));
    if (!out) continue;
    const double length = out->t;
    // Track length in every cell the segment start + [0, length] d can touch (its box's).
    const glm::dvec3 end = start + length * d;
    int range_lo[3], range_hi[3];
    for (int ax = 0; ax < 3; ++ax) {
      range_lo[ax] = std::clamp(int(std::floor((std::min(start[ax], end[ax]) - lo[ax]) / cell[ax])), 0, cells_per_axis - 1);
      range_hi[ax] = std::clamp(int(std::floor((std::max(start[ax], end[ax]) - lo[ax]) / cell[ax])), 0, cells_per_axis - 1);
    }
    for (int cz = range_lo[2]; cz <= range_hi[2]; ++cz)
      for (int cy = range_lo[1]; cy <= range_hi[1]; ++cy)
        for (int cx = range_lo[0]; cx <= range_hi[0]; ++cx) {
          const int c = (cz * cells_per_axis + cy) * cells_per_axis + cx;
          const glm::dvec3 a = lo + glm::dvec3(cx, cy, cz) * cell, z = a + cell;
          double t0 = 0.0, t1 = length;
          for (int ax = 0; ax < 3 && t0 < t1; ++ax) {
            if (std::abs(d[ax]) < 1e-300) {
              if (start[ax] < a[ax] || start[ax] > z[ax]) t1 = -1.0;
              continue;
            }
            double u0 = (a[ax] - start[ax]) / d[ax], u1 = (z[ax] - start[ax]) / d[ax];
            if (u0 > u1) std::swap(u0, u1);
            t0 = std::max(t0, u0);
            t1 = std::min(t1, u1);
          }
          if (t1 > t0) {
            const double share = (t1 - t0) * carried / volume;
            sum[std::size_t(c)] += share;
            sum2[std::size_t(c)] += share * share;
          }
        }
  }
  std::vector<CellFluence> result(static_cast<std::size_t>(n_cells));
  std::vector<DirectBeam> found;
  for (int c = 0; c < n_cells; ++c) {
    CellFluence& f = result[std::size_t(c)];
    // Each photon's share already carries 1/N: the estimate is the sum, its variance N
    // times the shares' variance.
    f.forward = sum[std::size_t(c)];
    f.forward_var = sum2[std::size_t(c)] - f.forward * f.forward / double(photons);
    const int cx = c % cells_per_axis, cy = (c / cells_per_axis) % cells_per_axis, cz = c / (cells_per_axis * cells_per_axis);
    const glm::dvec3 a = lo + glm::dvec3(cx, cy, cz) * cell;
    // Only cells wholly inside the medium: the centre inside (odd crossings along +x) and no
    // face within 1.2 half-diagonals along 26 directions. A cell the surface cuts holds a
    // sliver of medium that random points rarely find, which says nothing about the beams.
    const glm::dvec3 centre_c = a + 0.5 * cell;
    int crossings = 0;
    glm::dvec3 o = centre_c;
    for (int guard = 0; guard < 64; ++guard) {
      const std::optional<Hit> h = rays.intersect(glm::vec3(o), glm::vec3(1.0f, 0.0f, 0.0f));
      if (!h) break;
      ++crossings;
      o = o + glm::dvec3(double(h->t) + 1e-6 * (1.0 + std::abs(o.x)), 0.0, 0.0);
    }
    f.interior = crossings % 2 == 1;
    for (int dz = -1; dz <= 1 && f.interior; ++dz)
      for (int dy = -1; dy <= 1 && f.interior; ++dy)
        for (int dx = -1; dx <= 1 && f.interior; ++dx) {
          if (dx == 0 && dy == 0 && dz == 0) continue;
          const glm::dvec3 dir = glm::normalize(glm::dvec3(dx, dy, dz));
          if (rays.intersect(glm::vec3(centre_c), glm::vec3(dir), 0.0f, float(0.6 * glm::length(cell)))) f.interior = false;
        }
    if (!f.interior) continue;
    // The cell's mean of Σ E_b: 8 independent stratified estimates (8³ jittered points
    // each), their mean and the variance of that mean from their spread (the field jumps
    // across beam edges and peaks where facets focus: batches, not points, are near normal).
    constexpr int kBatches = 8, kSide = 8;
    double bs = 0.0, bs2 = 0.0;
    for (int batch = 0; batch < kBatches; ++batch) {
      double e_sum = 0.0;
      for (int i = 0; i < kSide * kSide * kSide; ++i) {
        const glm::dvec3 jitter(i % kSide + rng.uniform(), (i / kSide) % kSide + rng.uniform(), i / (kSide * kSide) + rng.uniform());
        const glm::dvec3 x = a + jitter / double(kSide) * cell;
        found.clear();
        beams.gather(x, found);
        for (const DirectBeam& bm : found) e_sum += bm.irradiance.x;
      }
      const double e = e_sum / (kSide * kSide * kSide);
      bs += e;
      bs2 += e * e;
    }
    f.predicted = bs / kBatches;
    f.predicted_var = std::max(0.0, bs2 / kBatches - f.predicted * f.predicted) / (kBatches - 1);
  }
  return result;
}

void check_fluence(const scene::Scene& s, double eta, const char* label, int cells_per_axis = 7,
                   std::uint64_t photons = 1u << 20) {
  const std::vector<CellFluence> cells = compare_fluence(s, eta, cells_per_axis, photons);
  double chi = 0.0, total_forward = 0.0, total_predicted = 0.0;
  int used = 0;
  for (const CellFluence& c : cells) {
    if (!c.interior || (c.forward == 0.0 && c.predicted == 0.0)) continue;
    const double zz = (c.forward - c.predicted) * (c.forward - c.predicted) / (c.forward_var + c.predicted_var + 1e-300);
    chi += zz;
    total_forward += c.forward;
    total_predicted += c.predicted;
    ++used;
  }
  const double p = chi_square_upper_tail(chi, used);
  std::printf("%s: %d cells, chi-square %.1f (p %.3g); mean fluence forward %.5f, direct beams %.5f\n", label, used, chi, p,
              total_forward / used, total_predicted / used);
  EXPECT_GT(used, 20) << label;
  EXPECT_GT(p, 1e-3) << label;
}

scene::Scene lens(const scene::Light& light, double eta) {
  scene::Scene s;
  s.materials.emplace_back();
  set_medium(s, grey_medium(0.1, 1.0, 0.0, eta));
  s.meshes.push_back(scene::make_uv_sphere(0.010f, 24, 12, 0));  // coarse: visible facets, a caustic
  s.instances.push_back({0, glm::mat4(1.0f), "lens"});
  s.lights.push_back(light);
  return s;
}

TEST(GroundTruthSampling, DirectBeamsCarryTheFluenceOfPhotonsTracedFromTheLight) {
  check_fluence(lens(scene::directional_light("sun", {0.3f, -1.0f, 0.2f}, 1.0f), 1.4), 1.4, "faceted sphere, directional");
  scene::Light point;
  point.type = scene::LightType::Point;
  point.intensity = 2.0f;
  point.world[3] = glm::vec4(0.004f, 0.025f, -0.006f, 1.0f);  // 25 mm above a 10 mm sphere
  check_fluence(lens(point, 1.4), 1.4, "faceted sphere, point light");
  // The bunny: not convex, so beams pass into the body, out and into the ears, and faces
  // shade each other; only the light that reaches a face from outside and crosses the
  // medium without leaving it may count.
  auto loaded = scene::load_scene("builtin:bunny");
  ASSERT_TRUE(std::holds_alternative<scene::Scene>(loaded));
  scene::Scene bunny = std::get<scene::Scene>(std::move(loaded));
  bunny.lights.resize(1);
  set_medium(bunny, grey_medium(0.1, 1.0, 0.0, 1.3));
  check_fluence(bunny, 1.3, "bunny, its key light", 14, 1u << 21);
}

// A spot light is a point light weighed by the smoothstep between its cones at the
// direction it leaves in (as Shading.cpp): its beams are the point light's times that.
TEST(GroundTruthSampling, SpotLightBeamsAreThePointLightsWeighedByItsCone) {
  scene::Light point;
  point.type = scene::LightType::Point;
  point.intensity = 2.0f;
  point.world[3] = glm::vec4(0.0f, 0.025f, 0.0f, 1.0f);
  scene::Light spot = point;
  spot.type = scene::LightType::Spot;
  spot.inner_cone = 0.1f;
  spot.outer_cone = 0.35f;
  spot.world = scene::look_at_world({0.0f, 0.025f, 0.0f}, {0.002f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f});
  const scene::Scene a = lens(point, 1.4), b = lens(spot, 1.4);
  const RayScene ra(a), rb(b);
  const auto sa = medium_surfaces(a, ra), sb = medium_surfaces(b, rb);
  const DirectBeams ba(a, ra, sa[0], 1.4), bb(b, rb, sb[0], 1.4);
  walk::WalkRng rng(1, 2, 3);
  int compared = 0;
  for (int k = 0; k < 2000; ++k) {
    const glm::dvec3 x = glm::dvec3(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5) * 12.0;
    if (glm::length(x) > 9.0) continue;
    std::vector<DirectBeam> pa, pb;
    ba.gather(x, pa);
    bb.gather(x, pb);
    // The spot drops beams outside its outer cone (they carry nothing): compare sums.
    double expected = 0.0, got = 0.0, unweighted = 0.0;
    for (const DirectBeam& bm : pa) {
      unweighted += bm.irradiance.x;
      // The direction the light leaves in: from the light towards the entry point.
      const glm::dvec3 y = x - bm.distance_mm * bm.direction;
      const glm::dvec3 leave = glm::normalize(y - glm::dvec3(point.position()) * 1000.0);
      const double c = glm::dot(leave, glm::dvec3(spot.direction()));
      const double lo = std::cos(double(spot.outer_cone)), hi = std::cos(double(spot.inner_cone));
      const double u = std::clamp((c - lo) / (hi - lo), 0.0, 1.0);
      expected += bm.irradiance.x * u * u * (3.0 - 2.0 * u);
    }
    for (const DirectBeam& bm : pb) got += bm.irradiance.x;
    // The cone factor's argument is rebuilt here from float light data and y = x - t d: a
    // cosine good to ~1e-7, through the smoothstep's slope of at most 1.5/(cos inner -
    // cos outer) = 27, bounds the factor's error by 1e-5 of the unweighted sum.
    EXPECT_NEAR(got, expected, 1e-5 * unweighted + 1e-12) << x.x << " " << x.y << " " << x.z;
    if (!pa.empty()) ++compared;
  }
  EXPECT_GT(compared, 100);
}

}  // namespace
}  // namespace sss::reference::testing
