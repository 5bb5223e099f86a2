// The reference's environment light (reference/Shading.h: environment_irradiance):
// on the GPU's terms it is the spherical harmonics exactly; on its own it samples the
// hemisphere with shadow rays, checked here against closed forms on the builtin sphere:
// exact for a uniform sky seen whole, zero where everything is occluded, and unbiased for
// a linear sky (a Z-test over independent points, each estimate's spread measured).
#include "profiles/Fresnel.h"
#include "reference/GroundTruth.h"
#include "reference/ReferenceRenderer.h"
#include "reference/RayScene.h"
#include "reference/Shading.h"
#include "scene/BuiltinScenes.h"
#include "scene/Environment.h"
#include "scene/SplitSum.h"
#include "tests/common/BoxedSphere.h"
#include "tests/common/GgxQuadrature.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <vector>

namespace sss::reference {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Sphere {
  scene::Scene scene = scene::sphere_scene();
  glm::vec3 centre_mm{0.0f};
  float radius_mm = 0.0f;
  Sphere() {
    const scene::Bounds b = scene.bounds();
    centre_mm = 0.5f * (b.min + b.max) * float(scene.mm_per_unit);
    radius_mm = 0.5f * (b.max.x - b.min.x) * float(scene.mm_per_unit);
  }
  // A point at `scale` x the radius along unit n, facing along n.
  SurfacePoint point(const glm::vec3& n, float scale) const {
    SurfacePoint p;
    p.position_mm = centre_mm + n * (radius_mm * scale);
    p.geometric_normal = n;
    p.normal = n;
    return p;
  }
};

// Directions spread over the sphere (a Fibonacci lattice), the same in every run.
std::vector<glm::vec3> directions(int count) {
  std::vector<glm::vec3> d;
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double y = 1.0 - 2.0 * (i + 0.5) / count, r = std::sqrt(1.0 - y * y);
    d.push_back(glm::vec3(float(r * std::cos(golden * i)), float(y), float(r * std::sin(golden * i))));
  }
  return d;
}

scene::Environment linear_sky(float a, float b) {
  const int w = 128, h = 64;
  std::vector<float> rgba(std::size_t(w) * h * 4, 1.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float v = a + b * float(std::cos(kPi * (y + 0.5) / h));  // y = cos(theta)
      for (int c = 0; c < 3; ++c) rgba[(std::size_t(y) * w + x) * 4 + c] = v;
    }
  return scene::image_environment("linear sky", w, h, rgba);
}

TEST(ReferenceEnvironment, OnTheGpusTermsItIsTheSphericalHarmonics) {
  const Sphere s;
  const RayScene rays(s.scene);
  const scene::Environment env = linear_sky(1.0f, 0.5f);
  for (const glm::vec3& n : directions(16)) {
    const glm::dvec3 e = environment_irradiance(env, rays, s.point(n, 1.01f), n, true);
    const glm::vec3 sh = env.irradiance(n);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(e[c], double(sh[c]));
  }
}

// A uniform sky over an unoccluded point: every sample sees L, so the estimate is pi L to
// rounding. A point inside the sphere: every ray meets the sphere, E = 0.
TEST(ReferenceEnvironment, AUniformSkyIsPiLInTheOpenAndZeroInside) {
  const Sphere s;
  const RayScene rays(s.scene);
  const scene::Environment env = scene::uniform_environment({0.5f, 1.0f, 2.0f});
  for (const glm::vec3& n : directions(64)) {
    const glm::dvec3 open = environment_irradiance(env, rays, s.point(n, 1.01f), n, false);
    EXPECT_NEAR(open.x, kPi * 0.5, 1e-6);
    EXPECT_NEAR(open.z, kPi * 2.0, 1e-6);
    const glm::dvec3 inside = environment_irradiance(env, rays, s.point(n, 0.5f), n, false);
    EXPECT_EQ(inside.x, 0.0);
  }
}

// A linear sky L = a + b w.y: E(n) = pi a + (2 pi / 3) b n.y exactly. Each point's
// estimate is an average of 64 stratified cosine-weighted samples with its own seed, so
// the residuals of N points are independent; their mean over its standard error is a
// Z statistic, |Z| < 4 (a false alarm 1 time in 16,000). The spread itself must be
// small: stratification bounds each estimate within a few per cent of b.
TEST(ReferenceEnvironment, ALinearSkyIsSampledWithoutBias) {
  const Sphere s;
  const RayScene rays(s.scene);
  const float a = 1.0f, b = 0.8f;
  const scene::Environment env = linear_sky(a, b);
  std::vector<double> residual;
  for (const glm::vec3& n : directions(400)) {
    const double expected = kPi * a + 2.0 * kPi / 3.0 * b * n.y;
    residual.push_back(environment_irradiance(env, rays, s.point(n, 1.01f), n, false).x - expected);
  }
  double mean = 0.0;
  for (double r : residual) mean += r;
  mean /= double(residual.size());
  double var = 0.0;
  for (double r : residual) var += (r - mean) * (r - mean);
  var /= double(residual.size() - 1);
  const double se = std::sqrt(var / double(residual.size()));
  std::printf("[ environment reference ] mean residual %.2e, sd %.2e, Z %.2f\n", mean, std::sqrt(var), mean / se);
  EXPECT_LT(std::fabs(mean), 4.0 * se + 1e-12);
  EXPECT_LT(std::sqrt(var), 0.05 * kPi * b);
}

// With directional Fresnel only the part that enters counts: for a uniform sky each point
// gets pi L c(eta), c the cosine-weighted mean of F_t (profiles::fresnel_exit_normalization,
// integrated by its own quadrature), per channel; here each of 64 stratified directions is
// weighted by its own F_t, so |Z| < 4 over 100 points as above. On the GPU's terms it is
// the harmonics times c exactly.
TEST(ReferenceEnvironment, WithDirectionalFresnelASkyEntersByTheHemispheresTransmittance) {
  const Sphere s;
  const RayScene rays(s.scene);
  const float L = 0.7f;
  const scene::Environment env = scene::uniform_environment({L, L, L});
  const glm::dvec3 eta(1.0, 1.3, 1.6);
  glm::dvec3 c;
  for (int k = 0; k < 3; ++k) c[k] = profiles::fresnel_exit_normalization(eta[k]);
  std::vector<glm::dvec3> residual;
  for (const glm::vec3& n : directions(100)) {
    const glm::dvec3 e = environment_irradiance(env, rays, s.point(n, 1.01f), n, false, &eta);
    residual.push_back(e - kPi * double(L) * c);
    const glm::dvec3 gpu = environment_irradiance(env, rays, s.point(n, 1.01f), n, true, &eta);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(gpu[k], double(env.irradiance(n)[k]) * c[k]);
  }
  for (int k = 0; k < 3; ++k) {
    double mean = 0.0, var = 0.0;
    for (const glm::dvec3& r : residual) mean += r[k];
    mean /= double(residual.size());
    for (const glm::dvec3& r : residual) var += (r[k] - mean) * (r[k] - mean);
    var /= double(residual.size() - 1);
    const double se = std::sqrt(var / double(residual.size()));
    std::printf("[ environment entry, eta %.1f ] c %.5f, mean residual %.2e, Z %.2f\n", eta[k], c[k], mean,
                se > 0.0 ? mean / se : 0.0);
    EXPECT_LT(std::fabs(mean), 4.0 * se + 1e-9) << "eta " << eta[k];
  }
  EXPECT_NEAR(c[0], 1.0, 1e-12);  // eta 1: nothing is reflected
}

// A view direction at cosine nv to n, turned by `turn` about it.
glm::vec3 view_at(const glm::vec3& n, double nv, double turn) {
  const glm::vec3 t = std::fabs(n.x) > 0.9f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
  const glm::vec3 b1 = glm::normalize(glm::cross(t, n)), b2 = glm::cross(n, b1);
  const double s = std::sqrt(1.0 - nv * nv);
  return glm::normalize(n * float(nv) + b1 * float(s * std::cos(turn)) + b2 * float(s * std::sin(turn)));
}

// The specular of the environment on the GPU's terms is the split sum, lookup for lookup.
TEST(ReferenceEnvironment, OnTheGpusTermsItsSpecularIsTheSplitSum) {
  const Sphere s;
  const RayScene rays(s.scene);
  const scene::Environment env = linear_sky(1.0f, 0.5f);
  int i = 0;
  for (const glm::vec3& n : directions(16)) {
    SpecularInputs spec;
    spec.to_eye = view_at(n, 0.6, 0.7 * ++i);
    spec.f0 = glm::vec3(0.04f, 0.5f, 1.0f);
    spec.roughness = 0.45f;
    const glm::dvec3 got = environment_specular(env, rays, s.point(n, 1.01f), n, spec, true);
    const glm::vec3 lp = env.specular_radiance(glm::reflect(-spec.to_eye, n), spec.roughness);
    const glm::vec2 ab = scene::dfg_lookup(glm::dot(n, spec.to_eye), spec.roughness);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(got[c], double(lp[c]) * (double(spec.f0[c]) * ab.x + ab.y));
  }
}

// Its own estimate, for a uniform sky over open points, is L times the lobe's directional
// albedo F0 A + B, computed here by the midpoint rule (tests/common/GgxQuadrature.h), for
// each (n.v, r) over 100 points whose estimates are independent (each seeded by its
// position): |Z| < 4 on their mean, as for the irradiance. A point inside the sphere
// sees nothing.
TEST(ReferenceEnvironment, AUniformSkysSpecularIsTheLobesAlbedoTimesItsRadiance) {
  const Sphere s;
  const RayScene rays(s.scene);
  const float L = 0.8f, f0 = 0.04f;
  const scene::Environment env = scene::uniform_environment({L, L, L});
  for (const double nv : {0.3, 0.7, 1.0})
    for (const float r : {0.3f, 0.7f}) {
      const glm::dvec2 q = sss::testing::ggx_albedo_quadrature(nv, r, 1200, 600);
      const double expected = L * (f0 * q.x + q.y);
      std::vector<double> residual;
      int i = 0;
      for (const glm::vec3& n : directions(100)) {
        SpecularInputs spec;
        spec.to_eye = view_at(n, nv, 2.399963 * ++i);
        spec.f0 = glm::vec3(f0);
        spec.roughness = r;
        residual.push_back(environment_specular(env, rays, s.point(n, 1.01f), n, spec, false).x - expected);
        if (i <= 4) {
          EXPECT_EQ(environment_specular(env, rays, s.point(n, 0.5f), n, spec, false).x, 0.0);
        }
      }
      double mean = 0.0, var = 0.0;
      for (double x : residual) mean += x;
      mean /= double(residual.size());
      for (double x : residual) var += (x - mean) * (x - mean);
      var /= double(residual.size() - 1);
      const double se = std::sqrt(var / double(residual.size()));
      std::printf("[ environment specular reference, n.v %.1f r %.1f ] expected %.5f, mean residual %.2e, Z %.2f\n",
                  nv, r, expected, mean, se > 0.0 ? mean / se : 0.0);
      EXPECT_LT(std::fabs(mean), 4.0 * se + 1e-9 * expected) << nv << " " << r;
    }
}

// The ground truth's random walk in a furnace: a sphere of a medium that hardly absorbs
// (sigma_a = 1e-6 / mm, sigma_s = 0.1 / mm, g = 0), no lights, a uniform sky of radiance
// L. In equilibrium the light inside is isotropic at eta^2 L (L / n^2 is conserved across
// the boundary), and the radiance leaving towards the outside is F_t(theta) L, whatever
// the scattering. So:
//  * eta = 1 (no Fresnel reflection), the light that crossed the medium towards the eye
//    is L at every pixel;
//  * eta = 1.3, its exitance (--exitance: M / pi, the cosine-weighted mean over the
//    outside hemisphere) is c L, c = 1 - 2 m1(1/eta) (profiles::
//    fresnel_exit_normalization), which checks the eta^2 and the 1 - F of the walk's
//    boundary term.
// Less what the medium absorbs: the mean path length through a body under uniform
// incidence is 4 V eta^2 / S whether or not the medium scatters (Blanco & Fournier 2003;
// the eta^2 for a mismatched boundary: Savo et al. 2017), 4 R eta^2 / 3 for a sphere, so
// the loss is about sigma_a 4 R eta^2 / 3 of the value (1e-4 at most here). Tolerance:
// that, plus 4 standard errors of the frame mean (Russian roulette makes each walk 0 or
// a full weight).
TEST(ReferenceEnvironment, TheRandomWalkInAFurnaceReturnsTheSky) {
  for (const double eta : {1.0, 1.3}) {
    Sphere s;
    s.scene.lights.clear();
    for (scene::Material& m : s.scene.materials) {
      if (!m.sss.enabled) continue;
      m.sss.medium.sigma_a = {1e-6, 1e-6, 1e-6};
      m.sss.medium.sigma_s = {0.1, 0.1, 0.1};
      m.sss.medium.g = {0.0, 0.0, 0.0};
      m.sss.medium.eta = {eta, eta, eta};
      m.sss.scale = 1.0;
    }
    const glm::vec3 sky(0.7f, 0.5f, 0.3f);
    s.scene.environment = scene::uniform_environment(sky);
    GroundTruthOptions o;
    o.width = 64;
    o.height = 36;
    o.spp = 16;
    o.diffuse_only = true;
    o.exitance = eta != 1.0;
    o.threads = 2;
    const GroundTruthImage g = render_ground_truth(s.scene, o);
    double sum[3] = {0, 0, 0}, var[3] = {0, 0, 0};
    int n = 0;
    for (int y = 0; y < g.hdr.height; ++y)
      for (int x = 0; x < g.hdr.width; ++x) {
        const float* p = g.hdr.pixel(x, y);
        if (p[3] <= 0.0f) continue;
        ++n;
        for (int c = 0; c < 3; ++c) {
          sum[c] += p[c];
          var[c] += g.variance.pixel(x, y)[c];
        }
      }
    ASSERT_GT(n, 100);
    const double factor = eta == 1.0 ? 1.0 : profiles::fresnel_exit_normalization(eta);
    const double loss = 1e-6 * 4.0 * s.radius_mm * eta * eta / 3.0;
    for (int c = 0; c < 3; ++c) {
      const double mean = sum[c] / n, se = std::sqrt(var[c]) / n, expected = factor * sky[c];
      std::printf("[ furnace eta %.1f ] channel %d: mean %.6f, expected %.6f, SE %.2e over %d pixels\n", eta, c,
                  mean, expected, se, n);
      EXPECT_NEAR(mean, expected, 4.0 * se + loss * expected + 1e-6) << "eta " << eta << " channel " << c;
    }
  }
}

// The GPU-shadow mode (the error budget's lighting link) lights as the GPU does, sky
// occlusion included: inside a closed box (tests/common/BoxedSphere.h) the bake blocks the
// whole sky, so the sky adds nothing to the sphere's scattered light, M/pi (diffuse_only),
// where with --sky-occlusion off every point gets the open sky and the sphere about T L.
// Tolerance: E_open - E_blocked is a difference of two float sums of ~pi L, a few ulps
// (1e-6 relative); the octree's sum of those residuals keeps them that small: 1e-5 T L.
TEST(ReferenceEnvironment, OnTheGpusTermsTheSkyTheBakeBlocksIsTakenAway) {
  const glm::vec3 sky(0.5f, 0.4f, 0.3f);
  const scene::Scene lit = sss::testing::boxed_sphere(sky);
  scene::Scene dark = lit;
  dark.environment.reset();
  ReferenceOptions o;
  o.width = 64;
  o.height = 36;
  o.diffuse_only = true;
  o.shadows = Shadows::ShadowMap;
  o.shadow_map_size = 256;
  const ReferenceImage without = render_reference(dark, o);
  const ReferenceImage with = render_reference(lit, o);
  o.sky_occlusion = false;
  const ReferenceImage open = render_reference(lit, o);
  const auto profile = reference_profile(lit.materials[0].sss, o.kernel, o.profile_options());
  int sphere = 0;
  double open_mean = 0.0;
  for (int y = 0; y < 36; ++y)
    for (int x = 0; x < 64; ++x) {
      // The sphere: lit by the open sky (the box's walls are opaque, 0 in M/pi; without the
      // sky the box keeps every light from the sphere).
      if (open.hdr.pixel(x, y)[0] <= 0.0f) continue;
      ++sphere;
      for (int c = 0; c < 3; ++c) {
        const double tl = profile->total_reflectance()[c] * sky[c];
        EXPECT_NEAR(with.hdr.pixel(x, y)[c] - without.hdr.pixel(x, y)[c], 0.0, 1e-5 * tl)
            << "pixel " << x << "," << y << " channel " << c;
        open_mean += (open.hdr.pixel(x, y)[c] - without.hdr.pixel(x, y)[c]) / tl;
      }
    }
  ASSERT_GT(sphere, 100);
  open_mean /= 3.0 * sphere;
  std::printf("%d sphere pixels; without the occlusion the sky adds %.3f T L\n", sphere, open_mean);
  EXPECT_GT(open_mean, 0.5) << "the test's power: the open sky lights the sphere";
}

}  // namespace
}  // namespace sss::reference
