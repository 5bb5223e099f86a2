// What the ground-truth tests (test_ground_truth_*.cpp) share: scenes built from the edge
// slab with any medium, measured exitance with its standard error, and statistics.
#pragma once

#include "reference/GroundTruth.h"
#include "scene/BuiltinScenes.h"
#include "scene/Material.h"
#include "scene/Shapes.h"

#include "profiles/Fresnel.h"
#include "profiles/Medium.h"
#include "profiles/Presets.h"

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

// A 120 x 120 mm slab of skin1 `thickness_mm` thick (top face at y = 0), lit with E = 1
// from below by a directional light; an orthographic camera 100 mm above sees 10 mm of
// its top face, which no light reaches directly. `finite_slab`: the medium carries the
// thickness (the multipole's slab), else the model is semi-infinite.
inline scene::Scene back_lit_slab(profiles::Model model, bool finite_slab, double thickness_mm) {
  const profiles::Preset* preset = profiles::find_preset("skin1");
  if (!preset) throw std::invalid_argument("no skin1 preset");
  profiles::Medium medium = profiles::preset_medium(*preset);
  if (finite_slab) medium.thickness_mm = thickness_mm;
  auto made = scene::make_sss_material(scene::CoefficientSource{medium}, model);
  if (auto* e = std::get_if<FieldError>(&made)) throw std::invalid_argument(e->what());
  scene::Scene s;
  scene::Material m;
  m.metallic = 0.0f;
  m.specular = 0.0f;
  m.roughness = 1.0f;
  m.sss = std::get<scene::SssMaterial>(made);
  s.materials.push_back(m);
  const float mm = 1e-3f;
  s.meshes.push_back(scene::make_box({-60 * mm, -float(thickness_mm) * mm, -60 * mm}, {60 * mm, 0.0f, 60 * mm}, 0));
  s.instances.push_back({0, glm::mat4(1.0f), "slab"});
  scene::Camera cam;
  cam.projection = scene::Projection::Orthographic;
  cam.xmag = 5 * mm;
  cam.znear = 1 * mm;
  cam.zfar = 1000 * mm;
  cam.world = scene::look_at_world({0.0f, 100 * mm, 0.0f}, glm::vec3(0.0f), {0.0f, 0.0f, -1.0f});
  s.cameras.push_back(cam);
  s.lights.push_back(scene::directional_light("light", {0.0f, 1.0f, 0.0f}, 1.0f));
  return s;
}

}  // namespace sss::reference::testing
