// What the ground-truth tests (test_ground_truth_*.cpp) share: scenes built from the edge
// slab with any medium, measured exitance with its standard error, and statistics.
#pragma once

#include "renderer/reference/GroundTruth.h"
#include "renderer/scene/BuiltinScenes.h"
#include "renderer/scene/Material.h"
#include "renderer/scene/Shapes.h"

#include "profiles/Fresnel.h"
#include "profiles/Medium.h"

#include <glm/vec3.hpp>

#include <cmath>
#include <stdexcept>
#include <variant>

namespace sss::reference::testing {

inline constexpr double kPi = 3.14159265358979323846;

// The medium of `s`'s first material replaced (a coefficient source, no scale).
inline void set_medium(scene::Scene& s, const profiles::Medium& m, std::uint32_t material = 0) {
  auto made = scene::make_sss_material(scene::CoefficientSource{m}, profiles::Model::McTable);
  if (auto* e = std::get_if<FieldError>(&made)) throw std::invalid_argument(e->what());
  s.materials[material].sss = std::get<scene::SssMaterial>(made);
}

inline profiles::Medium grey_medium(double sigma_a, double sigma_s, double g, double eta) {
  profiles::Medium m;
  for (std::size_t c = 0; c < 3; ++c) {
    m.sigma_a[c] = sigma_a;
    m.sigma_s[c] = sigma_s;
    m.g[c] = g;
    m.eta[c] = eta;
  }
  return m;
}

// builtin:edge's 200 x 200 x 50 mm slab (top face y = 0, camera straight down over
// x in [-half_width, half_width] mm) with medium `m`; lit at normal incidence with
// irradiance 1, on x < 0 only when `edge`.
inline scene::Scene edge_slab(const profiles::Medium& m, bool edge, double half_width_mm = 20.0) {
  scene::EdgeOptions eo;
  eo.half_width_mm = half_width_mm;
  scene::Scene s = scene::edge_scene(eo);
  set_medium(s, m);
  if (!edge) s.lights[0].mask.reset();
  return s;
}

// Fresnel transmission at normal incidence from the air into index eta (profiles/Fresnel,
// not the walk's own).
inline double normal_transmission(double eta) { return 1.0 - profiles::fresnel_dielectric(1.0, eta); }

struct Estimate {
  glm::dvec3 mean{0.0}, se{0.0};
};

// The exitance M (π times the --exitance --diffuse-only pixel) averaged over the pixels of
// columns [x0, x1) of every row, with the standard error of that average.
inline Estimate mean_exitance(const GroundTruthImage& img, int x0 = 0, int x1 = -1) {
  if (x1 < 0) x1 = img.hdr.width;
  Estimate e;
  int n = 0;
  for (int y = 0; y < img.hdr.height; ++y)
    for (int x = x0; x < x1; ++x) {
      for (int c = 0; c < 3; ++c) {
        e.mean[c] += img.hdr.pixel(x, y)[c];
        e.se[c] += img.variance.pixel(x, y)[c];
      }
      ++n;
    }
  e.mean *= kPi / n;
  e.se = kPi * glm::sqrt(e.se) / double(n);
  return e;
}

inline GroundTruthImage render_exitance(const scene::Scene& s, std::uint32_t w, std::uint32_t h, std::uint64_t spp,
                                        std::uint64_t seed = 1) {
  GroundTruthOptions o;
  o.width = w;
  o.height = h;
  o.spp = spp;
  o.seed = seed;
  o.exitance = true;
  o.diffuse_only = true;
  return render_ground_truth(s, o);
}

// P(χ²_k > x): the upper tail of the chi-square distribution, by the Wilson–Hilferty cube
// root normal approximation (accurate to a few percent of the tail probability for k >= 10,
// which is all a pass/fail at 1e-3 needs).
inline double chi_square_upper_tail(double x, int k) {
  const double h = 2.0 / (9.0 * k);
  const double z = (std::cbrt(x / k) - (1.0 - h)) / std::sqrt(h);
  return 0.5 * std::erfc(z / std::sqrt(2.0));
}

}  // namespace sss::reference::testing
