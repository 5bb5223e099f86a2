// The environment light on the GPU (issue 20 part 3): a uniform sky of radiance L on a
// convex object gives every point E = pi L (nothing occludes it), and scattering moves no
// energy across a uniform irradiance, so the frame with the sky less the frame without it
// is, at every pixel of the sphere, the closed form
//   dL = albedo x T x L  (T the material's total diffuse reflectance, which --sss off
//                         keeps as a Lambertian's albedo),
// whatever the blur (follow surface falls back to the centre value, which equals every
// other), on the frame less its specular target. The key light, its shadows, its specular
// and S(1) are the same in both frames.
//
// The specular part: with a uniform sky every lobe average is L, so the split sum gives
// dS = L (F0 A(n.v, r) + B(n.v, r)) exactly (scene/SplitSum.h); checked on a flat slab
// under a perspective camera, where n.v at each pixel follows from the camera alone.
#include "RenderTest.h"

#include "scene/BuiltinScenes.h"
#include "common/BoxedSphere.h"
#include "reference/SkyOcclusion.h"
#include "scene/Shapes.h"
#include "scene/SplitSum.h"
#include "profiles/Fresnel.h"
#include "profiles/Profile.h"
#include "renderer/MaterialTable.h"
#include "image/Image.h"
#include "image/Tonemap.h"
#include "scene/SssExtras.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <variant>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

namespace sss::renderer::testing {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A 64 x 32 equirectangular sky that changes along u and v (so a flipped axis, a wrong
// wrap or swapped levels would show): r = base + slope u, g = base + slope v,
// b = base + slope u (1 - v), at texel centres.
scene::Environment gradient_sky(const glm::vec3& base, const glm::vec3& slope) {
  constexpr int kSkyW = 64, kSkyH = 32;
  std::vector<float> rgba(std::size_t(kSkyW) * kSkyH * 4, 1.0f);
  for (int y = 0; y < kSkyH; ++y)
    for (int x = 0; x < kSkyW; ++x) {
      float* p = &rgba[(std::size_t(y) * kSkyW + x) * 4];
      const float u = (x + 0.5f) / kSkyW, v = (y + 0.5f) / kSkyH;
      p[0] = base.x + slope.x * u;
      p[1] = base.y + slope.y * v;
      p[2] = base.z + slope.z * u * (1.0f - v);
    }
  return scene::image_environment("gradient", kSkyW, kSkyH, rgba);
}

// d (unit) turned by `turn` rad about +y (azimuth), and towards +y (elevation): what the
// GPU's atan and acos may move a lookup by.
std::pair<glm::vec3, glm::vec3> turned(const glm::vec3& d, float turn) {
  const glm::vec3 around(d.x * std::cos(turn) + d.z * std::sin(turn), d.y,
                         -d.x * std::sin(turn) + d.z * std::cos(turn));
  const glm::vec3 side = glm::normalize(glm::cross(d, glm::vec3(0.0f, 1.0f, 0.0f)));
  const glm::vec3 up = glm::normalize(d * std::cos(turn) + glm::cross(side, d) * std::sin(turn));
  return {around, up};
}

class EnvironmentLightTest : public RenderTest {};

struct Mode {
  SssTechnique technique;
  const char* name;
  // Relative error of one frame's pixel (derived): float32 chains (off, separable) round
  // each of ~20 sums at 2^-24, and the separable cell means divide running sums over runs
  // of at most 160 px by widths of at least a pixel (160 x 2^-24 = 1e-5 per cell, 2
  // passes): 5e-5; the gaussians and texture chains hold rgba16f intermediates, 3N
  // roundings of 2^-11 for N = 6 Gaussians (EdgeTest): 8.8e-3.
  double relative;
  // Whether the frame's total reflectance is the separable kernel's (off applies it
  // locally) rather than the Gaussian fit's (gaussians, texture).
  bool kernel_total() const {
    return technique == SssTechnique::Off || technique == SssTechnique::Separable;
  }
};

TEST_F(EnvironmentLightTest, AUniformSkyAddsAlbedoTimesTotalReflectanceTimesItsRadiance) {
  const glm::vec3 sky(0.5f, 0.4f, 0.3f);
  const Mode modes[] = {{SssTechnique::Off, "off", 5e-5},
                        {SssTechnique::Separable, "separable", 5e-5},
                        {SssTechnique::Gaussians, "gaussians", 8.8e-3},
                        {SssTechnique::Texture, "texture", 8.8e-3}};
  for (const Mode& mode : modes) {
    scene::Scene plain = scene::sphere_scene();
    scene::Scene lit = plain;
    lit.environment = scene::uniform_environment(sky);
    const RenderOptions options = small_options(160, 90, mode.technique);
    const Frame without = render(plain, options);
    const Frame with = render(lit, options);
    const glm::vec4 albedo = plain.materials[0].base_color;
    ASSERT_FALSE(plain.materials[0].base_color_texture.has_value());
    double T[3];
    const MaterialProfile& p = *with.materials.profiles[0];
    for (int c = 0; c < 3; ++c)
      T[c] = mode.kernel_total() ? p.kernel.total_reflectance[c] : p.fit.total_reflectance[c];
    int pixels = 0;
    double worst = 0.0;
    for (int y = 0; y < 90; ++y)
      for (int x = 0; x < 160; ++x) {
        const float* ha = without.hdr.pixel(x, y);
        const float* hb = with.hdr.pixel(x, y);
        if (ha[3] <= 0.0f) {  // background: no light of any kind
          for (int c = 0; c < 3; ++c) EXPECT_EQ(hb[c], 0.0f) << mode.name << " background at " << x << "," << y;
          continue;
        }
        ++pixels;
        const float* sa = without.specular.pixel(x, y);
        const float* sb = with.specular.pixel(x, y);
        float a[3], b[3];  // diffuse: the frame less its specular
        for (int c = 0; c < 3; ++c) {
          a[c] = ha[c] - sa[c];
          b[c] = hb[c] - sb[c];
        }
        for (int c = 0; c < 3; ++c) {
          const double expected = double(albedo[c]) * T[c] * sky[c];
          const double tol = mode.relative * (std::fabs(a[c]) + std::fabs(b[c])) + 1e-6;
          EXPECT_NEAR(b[c] - a[c], expected, tol) << mode.name << " pixel " << x << "," << y << " channel " << c;
          worst = std::max(worst, std::fabs(b[c] - a[c] - expected) / expected);
        }
      }
    EXPECT_GT(pixels, 1000) << mode.name;
    std::printf("[ environment %s ] %d pixels, worst |dL - albedo T L| / (albedo T L) %.2e\n", mode.name, pixels,
                worst);
  }
}

// With directional Fresnel a subsurface material takes the part of a sky that enters,
// c = profiles::fresnel_exit_normalization(eta) (exact for a uniform sky), and the
// composite lets M F_t(eta, n.v) / (c pi) out, so the frame's diffuse part grows by
//   dL = albedo x T x L x F_t(eta, n.v)
// at each pixel, n.v being what the composite itself reads (the specular target's alpha).
// Same float bounds as the test above; F_t is evaluated here in double and on the GPU in
// float from the same stored n.v (1e-6 more).
TEST_F(EnvironmentLightTest, WithDirectionalFresnelTheSkyEntersAndLeavesThroughTheBoundary) {
  const glm::vec3 sky(0.5f, 0.4f, 0.3f);
  const Mode modes[] = {{SssTechnique::Off, "off", 5e-5},
                        {SssTechnique::Separable, "separable", 5e-5}};
  for (const Mode& mode : modes) {
    scene::Scene plain = scene::sphere_scene();
    scene::Scene lit = plain;
    lit.environment = scene::uniform_environment(sky);
    RenderOptions options = small_options(160, 90, mode.technique);
    options.fresnel = true;
    const Frame without = render(plain, options);
    const Frame with = render(lit, options);
    const glm::vec4 albedo = plain.materials[0].base_color;
    const auto eta = plain.materials[0].sss.medium.eta;
    const MaterialProfile& p = *with.materials.profiles[0];
    int pixels = 0;
    double worst = 0.0;
    for (int y = 0; y < 90; ++y)
      for (int x = 0; x < 160; ++x) {
        if (without.hdr.pixel(x, y)[3] <= 0.0f) continue;
        ++pixels;
        const double nv = with.specular.pixel(x, y)[3];
        for (int c = 0; c < 3; ++c) {
          const double a = without.hdr.pixel(x, y)[c] - without.specular.pixel(x, y)[c];
          const double b = with.hdr.pixel(x, y)[c] - with.specular.pixel(x, y)[c];
          const double T = mode.kernel_total() ? p.kernel.total_reflectance[c] : p.fit.total_reflectance[c];
          const double expected = double(albedo[c]) * T * sky[c] * profiles::fresnel_transmittance(nv, eta[c]);
          const double tol = mode.relative * (std::fabs(a) + std::fabs(b)) + 1e-6;
          EXPECT_NEAR(b - a, expected, tol) << mode.name << " pixel " << x << "," << y << " channel " << c;
          if (expected > 0.0) worst = std::max(worst, std::fabs(b - a - expected) / tol);
        }
      }
    EXPECT_GT(pixels, 1000) << mode.name;
    std::printf("[ environment with Fresnel, %s ] %d pixels, worst |dL - albedo T L F_t| / tol %.3f\n", mode.name,
                pixels, worst);
  }
}

// The edge slab with a specular lobe, seen from kHeight mm above by a perspective camera
// looking straight down: the slab's normal is +y everywhere, so a pixel whose ray leaves
// the axis at camera-space slope (sx, sy) has n.v = 1 / sqrt(1 + sx² + sy²), from 1 at the
// centre to 0.46 in the corners. dS must be L (F0 A + B) at that n.v, read from the same
// table with scene::dfg_lookup (the table itself is checked against an independent
// quadrature in tests/scene/test_split_sum.cpp). Tolerance: the specular target is
// rgba16f, and each frame's S loses up to one unit of its last place, 2^-10 relative:
// Vulkan lets the conversion round either way, and lavapipe truncates (on the unlit half,
// where the frame without the sky has S = 0, every error is negative and under 1 ulp);
// n.v from the float camera is good to 1e-6 and the table's slope in n.v is under 3
// (|d(F0 A + B)/dn.v| ≤ 3 at r ≥ 0.25, test_split_sum.cpp), so 1e-5 L more.
// The slab with a specular lobe of `roughness` (F0 0.04), seen from 12 mm above over
// +-20 mm across.
scene::Scene specular_slab(float roughness, double aspect) {
  scene::Scene s = scene::edge_scene();
  s.materials[0].specular = 1.0f;
  s.materials[0].roughness = roughness;
  s.materials[0].metallic = 0.0f;
  look_straight_down(s.cameras[0], 12.0, 20.0, aspect);
  return s;
}

TEST_F(EnvironmentLightTest, AUniformSkysSpecularIsTheSplitSumOfItsRadiance) {
  constexpr int kW = 160, kH = 90;
  const glm::vec3 sky(0.5f, 0.4f, 0.3f);
  for (const float roughness : {0.3f, 0.6f, 0.9f}) {
    const scene::Scene plain = specular_slab(roughness, double(kW) / kH);
    const scene::Camera& cam = plain.cameras[0];
    scene::Scene lit = plain;
    lit.environment = scene::uniform_environment(sky);
    const RenderOptions options = small_options(kW, kH, SssTechnique::Off);
    const Frame without = render(plain, options);
    const Frame with = render(lit, options);
    const double f0 = 0.04;
    double worst = 0.0;
    int pixels = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        if (without.hdr.pixel(x, y)[3] <= 0.0f) continue;
        ++pixels;
        const float nv = -pixel_ray(cam, x, y, kW, kH).y;
        const glm::vec2 ab = scene::dfg_lookup(nv, roughness);
        for (int c = 0; c < 3; ++c) {
          const double a = without.specular.pixel(x, y)[c], b = with.specular.pixel(x, y)[c];
          const double expected = double(sky[c]) * (f0 * ab.x + ab.y);
          const double tol = std::ldexp(1.0, -10) * (std::fabs(a) + std::fabs(b)) + 1e-5 * sky[c];
          EXPECT_NEAR(b - a, expected, tol) << "r " << roughness << " pixel " << x << "," << y << " channel " << c;
          worst = std::max(worst, std::fabs(b - a - expected) / tol);
        }
      }
    EXPECT_EQ(pixels, kW * kH) << "the slab fills the frame";
    std::printf("[ environment specular, r %.1f ] %d pixels, worst |dS - L (F0 A + B)| / tol %.3f\n", roughness,
                pixels, worst);
  }
}

// The prefiltered lookup on the GPU against scene::specular_lookup in C++, on a sky that
// changes along u and v (so a flipped axis, a wrong wrap or swapped levels would show), on
// the slab in perspective: each pixel's dS must be Lp(R, r) (F0 A + B), R the mirror of
// its view ray about the slab's normal. Tolerance: the rgba16f bound above, plus what the
// GPU's atan and acos may change: Vulkan allows them 4096 ulp, 1.5e-3 rad at most, so
// the larger change of Lp when R turns by 2e-3 rad in azimuth or in elevation, computed
// per pixel; plus 1e-5 of the sky's largest radiance for n.v (as above).
TEST_F(EnvironmentLightTest, AnImageSkysSpecularIsThePrefilteredLookup) {
  constexpr int kW = 160, kH = 90;
  const scene::Environment sky = gradient_sky({0.2f, 0.2f, 0.1f}, {0.6f, 0.6f, 0.8f});
  for (const float roughness : {0.25f, 0.5f, 0.8f}) {
    const scene::Scene plain = specular_slab(roughness, double(kW) / kH);
    const scene::Camera& cam = plain.cameras[0];
    scene::Scene lit = plain;
    lit.environment = sky;
    const RenderOptions options = small_options(kW, kH, SssTechnique::Off);
    const Frame without = render(plain, options);
    const Frame with = render(lit, options);
    const double f0 = 0.04;
    double worst = 0.0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const glm::vec3 d = pixel_ray(cam, x, y, kW, kH);
        const glm::vec3 r(d.x, -d.y, d.z);  // mirrored about +y
        const float nv = -d.y;
        const glm::vec2 ab = scene::dfg_lookup(nv, roughness);
        const double k = f0 * ab.x + ab.y;
        const glm::vec3 lp = sky.specular_radiance(r, roughness);
        // Lp's change when r turns by 2e-3 rad about +y, or towards / away from +y.
        const auto [around, up] = turned(r, 2e-3f);
        const glm::vec3 moved = glm::max(glm::abs(sky.specular_radiance(around, roughness) - lp),
                                         glm::abs(sky.specular_radiance(up, roughness) - lp));
        for (int c = 0; c < 3; ++c) {
          const double a = without.specular.pixel(x, y)[c], b = with.specular.pixel(x, y)[c];
          const double expected = double(lp[c]) * k;
          const double tol = std::ldexp(1.0, -10) * (std::fabs(a) + std::fabs(b)) + double(moved[c]) * k + 1e-5;
          EXPECT_NEAR(b - a, expected, tol) << "r " << roughness << " pixel " << x << "," << y << " channel " << c;
          worst = std::max(worst, std::fabs(b - a - expected) / tol);
        }
      }
    std::printf("[ environment specular, image sky, r %.2f ] worst |dS - Lp (F0 A + B)| / tol %.3f\n", roughness, worst);
  }
}

// The sky's transmission through a thin part (shading.glsl): builtin:slab (30 x 30 x 2 mm,
// base colour 1, no specular) without its light, under a uniform sky of radiance L: both
// faces receive pi L, and the back's crosses the slab to the front. Fresnel off (M/pi),
// at the front's centre (8 x 8 px), where the slab is uniform over the kernel's reach, so
// the blur moves no energy (TransmissionTest.cpp's header):
//   L_out = L (R + T), per channel (albedo 1),
// R the total reflectance the mode uses (as above), T the total transmittance across the
// 2 mm:
// - the multipole slab: its closed-form total, profiles::RgbProfile::total_transmittance
//   (the fit of T(r) keeps it exactly, TransmissionTest's SlabFitKeepsTheMultipoleTotal);
// - better-dipole (semi-infinite) on the same box: the fit's T(d) = Σ w_i exp(-d²/2v_i)
//   at d = 2 mm, the thickness the G-buffer got from reference::inward_thickness (a box's
//   side exactly, test_thickness.cpp, in float: 0.002 m x 1000).
// Tolerance: the Mode's float chain, as above, and for better-dipole the thickness's
// storage: the G-buffer keeps it in a half float, one unit of the last place either way
// (round or truncate, as lavapipe does), 2^-10 relative: L |dT/dd| d 2^-10, dT/dd =
// -Σ w_i exp(-d²/2v_i) d/v_i. Without the sky's transmission the centre is L R, short by
// L T: 14-48% of it here.
TEST_F(EnvironmentLightTest, AThinSlabTransmitsTheSkyBehindIt) {
  const glm::vec3 sky(0.5f, 0.4f, 0.3f);
  const Mode modes[] = {{SssTechnique::Separable, "separable", 5e-5},
                        {SssTechnique::Gaussians, "gaussians", 8.8e-3},
                        {SssTechnique::Texture, "texture", 8.8e-3}};
  for (const bool semi_infinite : {false, true}) {
    scene::Scene s = scene::slab_scene();
    s.lights.clear();
    s.environment = scene::uniform_environment(sky);
    if (semi_infinite) {
      profiles::Medium medium = s.materials[0].sss.medium;
      medium.thickness_mm = std::numeric_limits<double>::infinity();
      auto made = scene::make_sss_material(scene::CoefficientSource{medium}, profiles::Model::BetterDipole);
      ASSERT_TRUE(std::holds_alternative<scene::SssMaterial>(made));
      s.materials[0].sss = std::get<scene::SssMaterial>(made);
    }
    const profiles::RgbProfile rgb(s.materials[0].sss.model, s.materials[0].sss.effective_medium());
    for (const Mode& mode : modes) {
      RenderOptions options = small_options(160, 90, mode.technique);
      options.fresnel = false;
      options.texture_size = 512;
      const Frame f = render(s, options);
      const MaterialProfile& p = *f.materials.profiles[0];
      for (int c = 0; c < 3; ++c) {
        double T = rgb.total_transmittance()[c], dT = 0.0;  // dT: |dT/dd| at d = 2 mm
        if (semi_infinite) {
          const double d = 2.0;
          T = 0.0;
          for (std::size_t i = 0; i < p.fit.variances_mm2.size(); ++i) {
            const double v = p.fit.variances_mm2[i], term = p.fit.weights[i][c] * std::exp(-d * d / (2.0 * v));
            T += term;
            dT += term * d / v;
          }
        }
        const double R = mode.kernel_total() ? p.kernel.total_reflectance[c] : p.fit.total_reflectance[c];
        double L = 0.0;
        for (int y = 41; y < 49; ++y)
          for (int x = 76; x < 84; ++x) L += (f.hdr.pixel(x, y)[c] - f.specular.pixel(x, y)[c]) / 64.0;
        const double expected = sky[c] * (R + T);
        std::printf("[ sky through the %s slab, %s ] channel %d: %.5f, L (R + T) %.5f (T/R %.3f), error %.2e\n",
                    semi_infinite ? "better-dipole" : "multipole", mode.name, c, L, expected, T / R,
                    L / expected - 1.0);
        const double storage = sky[c] * dT * 2.0 * std::ldexp(1.0, -10);
        EXPECT_NEAR(L, expected, mode.relative * expected + storage + 1e-6) << mode.name << " channel " << c;
      }
    }
  }
}

// The environment behind the geometry (RenderOptions::background_environment): each
// background pixel of the display image is the sky's radiance along the pixel's view ray
// (pixel_ray, from the field of view alone; scene::Environment::radiance, bilinear in the
// image, in C++), through exposure, filmic and sRGB (image::filmic, image::srgb_encode),
// as a code of 8 bits. Tolerance, in codes: the code's rounding (1/2) and the GPU's
// (lavapipe rounds the store: another 1/2), plus the change of the expected code when the
// ray turns by 2e-3 rad in azimuth or elevation (Vulkan's atan and acos: 1.5e-3 rad at
// most, as the specular test above). The sky changes along u and v, so a flipped axis or
// a wrong wrap shows. The geometry's pixels and the whole HDR image are the frame without
// it, bit for bit: the option touches only the display's background.
TEST_F(EnvironmentLightTest, TheEnvironmentBehindTheGeometryIsTheSkyAlongEachPixelsRay) {
  constexpr int kW = 160, kH = 90;
  scene::Scene s = scene::sphere_scene();
  s.cameras[0].aspect = 0.0f;  // the image's, as pixel_ray assumes
  s.environment = gradient_sky({0.1f, 0.1f, 0.05f}, {1.5f, 1.2f, 2.0f});
  const scene::Environment& sky = *s.environment;
  RenderOptions options = small_options(kW, kH, SssTechnique::Separable);
  options.exposure = 1.5f;
  const Frame plain = render(s, options);
  options.background_environment = true;
  const Frame behind = render(s, options);

  const auto code = [&](const glm::vec3& d, int c) {
    return 255.0 * double(image::srgb_encode(image::filmic(options.exposure * sky.radiance(d)[c])));
  };
  const float turn = 2e-3f;
  int background = 0, geometry_differs = 0;
  double worst = 0.0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      for (int c = 0; c < 4; ++c)
        EXPECT_EQ(plain.hdr.pixel(x, y)[c], behind.hdr.pixel(x, y)[c]) << x << "," << y;
      if (plain.display.pixel(x, y)[3] > 0.0f) {  // geometry
        for (int c = 0; c < 4; ++c) geometry_differs += plain.display.pixel(x, y)[c] != behind.display.pixel(x, y)[c];
        continue;
      }
      ++background;
      const glm::vec3 d = pixel_ray(s.cameras[0], x, y, kW, kH);
      const auto [around, up] = turned(d, turn);
      EXPECT_EQ(behind.display.pixel(x, y)[3], 1.0f) << x << "," << y;
      for (int c = 0; c < 3; ++c) {
        const double expected = code(d, c);
        const double tol = 1.0 + std::max(std::fabs(code(around, c) - expected), std::fabs(code(up, c) - expected));
        const double got = 255.0 * behind.display.pixel(x, y)[c];
        EXPECT_NEAR(got, expected, tol) << "pixel " << x << "," << y << " channel " << c;
        worst = std::max(worst, std::fabs(got - expected) / tol);
      }
    }
  EXPECT_EQ(geometry_differs, 0);
  EXPECT_GT(background, kW * kH / 4);
  std::printf("[ environment behind ] %d background pixels, worst |code - expected| / tol %.3f\n",
              background, worst);
}

// Sky occlusion on the GPU (RenderOptions::sky_occlusion): inside a closed box
// (common/BoxedSphere.h) the sky is blocked everywhere, so with it on the sky adds nothing
// to the diffuse frame, in every mode, where without it the sphere gets albedo x T x L as
// in the open (the first test). Transmission is off: the sky's transmitted part is not occluded (README).
// Tolerance: E_blocked reaches the lighting through an rgba16f target. Vulkan does not
// require round-to-nearest there, and lavapipe truncates (the worst residual measured is
// one half-float step of E), so E_open - E_blocked is at most one unit in the last place,
// 2^-10 = 9.8e-4 of E_open (below 0 it is clamped); the gaussians and texture chains keep
// that residual in rgba16f, which moves it by 2^-10 of itself: 2e-3 x albedo T L, plus
// 1e-6 for the float32 frames' own rounding of the unchanged light.
TEST_F(EnvironmentLightTest, InsideAClosedBoxTheSkyAddsNothing) {
  const glm::vec3 sky_radiance(0.5f, 0.4f, 0.3f);
  const Mode modes[] = {{SssTechnique::Off, "off", 0.0},
                        {SssTechnique::Separable, "separable", 0.0},
                        {SssTechnique::Gaussians, "gaussians", 0.0},
                        {SssTechnique::Texture, "texture", 0.0}};
  const scene::Scene lit = sss::testing::boxed_sphere(sky_radiance);
  scene::Scene dark = lit;
  dark.environment.reset();
  const glm::vec4 albedo = lit.materials[0].base_color;
  for (const Mode& mode : modes) {
    RenderOptions options = small_options(160, 90, mode.technique);
    options.transmission = false;
    const Frame without = render(dark, options);
    const Frame with = render(lit, options);
    options.sky_occlusion = false;
    const Frame open = render(lit, options);
    // The sphere's pixels: those the sphere covers without the box.
    const Frame mask = render(scene::sphere_scene(), small_options(160, 90, mode.technique));
    const MaterialProfile& p = *with.materials.profiles[0];
    int sphere = 0, walls = 0;
    double worst = 0.0, open_mean = 0.0;
    for (int y = 0; y < 90; ++y)
      for (int x = 0; x < 160; ++x) {
        ASSERT_GT(with.hdr.pixel(x, y)[3], 0.0f) << "the camera is inside the box: geometry everywhere";
        const bool on_sphere = mask.hdr.pixel(x, y)[3] > 0.0f;
        ++(on_sphere ? sphere : walls);
        for (int c = 0; c < 3; ++c) {
          const double a = without.hdr.pixel(x, y)[c] - without.specular.pixel(x, y)[c];
          const double b = with.hdr.pixel(x, y)[c] - with.specular.pixel(x, y)[c];
          const double T = on_sphere ? (mode.kernel_total() ? p.kernel.total_reflectance[c]
                                                            : p.fit.total_reflectance[c])
                                     : 1.0;
          const double full = double(albedo[c]) * T * sky_radiance[c];  // unoccluded dL
          const double tol = 2e-3 * full + 1e-6;
          EXPECT_NEAR(b - a, 0.0, tol) << mode.name << (on_sphere ? " sphere" : " wall") << " pixel " << x << ","
                                       << y << " channel " << c;
          worst = std::max(worst, std::fabs(b - a) / tol);
          if (on_sphere)
            open_mean += (open.hdr.pixel(x, y)[c] - open.specular.pixel(x, y)[c] - a) / full;
        }
      }
    EXPECT_GT(sphere, 1000) << mode.name;
    EXPECT_GT(walls, 1000) << mode.name;
    open_mean /= 3.0 * sphere;
    // The test's power: with the occlusion off the sphere gets the open sky's albedo T L
    // (the first test, to its tolerances).
    EXPECT_NEAR(open_mean, 1.0, 1e-2) << mode.name;
    std::printf("[ sky occlusion %s ] %d sphere + %d wall pixels, worst |dL| / tol %.3f; without "
                "occlusion the sphere's dL / (albedo T L) %.4f\n",
                mode.name, sphere, walls, worst, open_mean);
  }
}

// Every coefficient of the transfer on the GPU, under a sky with all nine harmonics (the
// gradient sky), where a wall blocks part of it: a floor of two triangles seen from
// straight above (orthographic, so each pixel's floor point is known), the wall just
// outside the view, no lights, no subsurface scattering. Each pixel's diffuse radiance
// must be albedo / pi x max(E_sh(n) - sum_k e_k T_k, 0) with T the same bake's vertex
// transfers (reference::sky_occlusion, deterministic) interpolated over the pixel's
// triangle: what the G-buffer's attribute interpolation gives, the sky target stores and
// lighting.comp subtracts. The bake itself is checked against closed forms in
// tests/reference/test_sky_occlusion.cpp.
// Tolerance: E_blocked is stored in rgba16f, rounded or truncated, within 2^-10 of
// itself; the rest is float32 arithmetic on values of order E, 1e-5 of E_open.
TEST_F(EnvironmentLightTest, TheBlockedSkyIsEveryCoefficientOfTheBakeInterpolated) {
  scene::Scene s = scene::sphere_scene();
  scene::Material plain = s.materials[0];
  plain.sss.enabled = false;
  plain.metallic = 0.0f;
  plain.base_color = {0.8f, 0.6f, 0.4f, 1.0f};
  plain.base_color_texture.reset();
  plain.normal_texture.reset();
  s.materials = {plain};
  scene::Mesh floor;
  floor.name = "floor";
  floor.positions = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
  floor.normals.assign(4, {0.0f, 1.0f, 0.0f});
  floor.indices = {0, 1, 2, 0, 2, 3};
  scene::compute_bounds(floor);
  s.meshes = {floor, scene::make_box({1.05f, 0.0f, -3.0f}, {1.35f, 1.5f, 3.0f})};
  s.instances = {{0, glm::mat4(1.0f), "floor"}, {1, glm::mat4(1.0f), "wall"}};
  s.lights.clear();
  scene::Camera top;
  top.projection = scene::Projection::Orthographic;
  top.xmag = top.ymag = 1.0f;
  top.znear = 0.01f;
  top.zfar = 100.0f;
  // Local -Z (the view) to world -Y, local +Y (up) to world -Z, local +X to +X.
  top.world = scene::look_at_world({0.0f, 5.0f, 0.0f}, glm::vec3(0.0f), {0.0f, 0.0f, -1.0f});
  s.cameras = {top};
  s.environment = gradient_sky({0.1f, 0.1f, 0.05f}, {1.5f, 1.2f, 2.0f});
  const int n = 64;
  RenderOptions options = small_options(n, n, SssTechnique::Off);
  const Frame f = render(s, options);
  const std::vector<std::vector<reference::SkyTransfer>> bake = reference::sky_occlusion(s);
  const std::array<glm::vec3, 9>& sh = s.environment->irradiance_sh;
  const glm::vec3 open = s.environment->irradiance({0.0f, 1.0f, 0.0f});
  double worst = 0.0, blocked_most = 0.0;
  for (int py = 0; py < n; ++py)
    for (int px = 0; px < n; ++px) {
      ASSERT_GT(f.hdr.pixel(px, py)[3], 0.0f) << "the floor fills the view: " << px << "," << py;
      // The pixel's floor point, and its triangle's barycentric weights.
      const double x = (px + 0.5) / n * 2.0 - 1.0, z = -(1.0 - (py + 0.5) / n * 2.0);
      const bool first = x >= z;  // triangle (0, 1, 2) holds the side x > z
      const std::array<std::uint32_t, 3> tri = first ? std::array<std::uint32_t, 3>{0, 1, 2}
                                                     : std::array<std::uint32_t, 3>{0, 2, 3};
      const glm::dvec2 a(floor.positions[tri[0]].x, floor.positions[tri[0]].z);
      const glm::dvec2 b(floor.positions[tri[1]].x, floor.positions[tri[1]].z);
      const glm::dvec2 c(floor.positions[tri[2]].x, floor.positions[tri[2]].z);
      const double det = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
      const double wb = ((x - a.x) * (c.y - a.y) - (c.x - a.x) * (z - a.y)) / det;
      const double wc = ((b.x - a.x) * (z - a.y) - (x - a.x) * (b.y - a.y)) / det;
      const double w[3] = {1.0 - wb - wc, wb, wc};
      reference::SkyTransfer t{};
      for (int k = 0; k < 9; ++k)
        for (int v = 0; v < 3; ++v) t[k] += float(w[v] * bake[0][tri[v]][k]);
      const glm::vec3 blocked = reference::blocked_irradiance(sh, t);
      for (int ch = 0; ch < 3; ++ch) {
        const double e = std::max(double(open[ch]) - double(blocked[ch]), 0.0);
        const double albedo = plain.base_color[ch];
        const double expected = albedo * e / kPi;
        const double got = f.hdr.pixel(px, py)[ch] - f.specular.pixel(px, py)[ch];
        const double tol = albedo / kPi * (std::ldexp(std::fabs(blocked[ch]), -10) + 1e-5 * open[ch]);
        EXPECT_NEAR(got, expected, tol) << "pixel " << px << "," << py << " channel " << ch;
        worst = std::max(worst, std::fabs(got - expected) / tol);
        blocked_most = std::max(blocked_most, double(blocked[ch] / open[ch]));
      }
    }
  // The test's power: the wall takes a good part of the sky near it.
  EXPECT_GT(blocked_most, 0.2);
  std::printf("[ sky occlusion, gradient sky ] %d pixels, the wall blocks up to %.0f%% of E, worst |error| / tol "
              "%.3f\n", n * n, 100.0 * blocked_most, worst);
}

// A convex object alone bakes zero everywhere, so with an environment its frames with sky
// occlusion on and off are the same bit for bit, in every mode (the sky variants of the
// G-buffer and the atlas raster compute every other output as the plain ones do).
TEST_F(EnvironmentLightTest, AConvexObjectsFramesAreTheSameWithSkyOcclusionOnAndOff) {
  scene::Scene s = scene::sphere_scene();
  s.environment = gradient_sky({0.1f, 0.1f, 0.05f}, {1.5f, 1.2f, 2.0f});
  for (const SssTechnique t :
       {SssTechnique::Off, SssTechnique::Separable, SssTechnique::Gaussians, SssTechnique::Texture}) {
    RenderOptions options = small_options(160, 90, t);
    const Frame on = render(s, options);
    options.sky_occlusion = false;
    const Frame off = render(s, options);
    EXPECT_EQ(on.hdr.rgba, off.hdr.rgba) << technique_name(t);
  }
}

}  // namespace
}  // namespace sss::renderer::testing
