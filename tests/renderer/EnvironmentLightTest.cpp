// The environment light on the GPU (issue 20 part 3): a uniform sky of radiance L on a
// convex object gives every point E = pi L (nothing occludes it), and scattering moves no
// energy across a uniform irradiance, so the frame with the sky less the frame without it
// is, at every pixel of the sphere, the closed form
//   dL = albedo x T x L  (T the material's total diffuse reflectance, which --sss off
//                         keeps as a Lambertian's albedo),
// whatever the blur (follow surface falls back to the centre value, which equals every
// other). The key light, its shadows, the specular and S(1) are the same in both frames.
#include "RenderTest.h"

#include "renderer/scene/BuiltinScenes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace sss::renderer::testing {
namespace {

class EnvironmentLightTest : public RenderTest {};

struct Mode {
  SssMode sss;
  SssKind kind;
  const char* name;
  // Relative error of one frame's pixel (derived): float32 chains (off, separable) round
  // each of ~20 sums at 2^-24, and the separable cell means divide running sums over runs
  // of at most 160 px by widths of at least a pixel (160 x 2^-24 = 1e-5 per cell, 2
  // passes): 5e-5; the gaussians and texture chains hold rgba16f intermediates, 3N
  // roundings of 2^-11 for N = 6 Gaussians (EdgeTest): 8.8e-3.
  double relative;
};

TEST_F(EnvironmentLightTest, AUniformSkyAddsAlbedoTimesTotalReflectanceTimesItsRadiance) {
  const glm::vec3 sky(0.5f, 0.4f, 0.3f);
  const Mode modes[] = {{SssMode::Off, SssKind::Separable, "off", 5e-5},
                        {SssMode::Screen, SssKind::Separable, "separable", 5e-5},
                        {SssMode::Screen, SssKind::Gaussians, "gaussians", 8.8e-3},
                        {SssMode::Texture, SssKind::Gaussians, "texture", 8.8e-3}};
  for (const Mode& mode : modes) {
    scene::Scene plain = scene::sphere_scene();
    scene::Scene lit = plain;
    lit.environment = scene::uniform_environment(sky);
    const RenderOptions options = small_options(160, 90, mode.sss, mode.kind);
    const Frame without = render(plain, options);
    const Frame with = render(lit, options);
    const glm::vec4 albedo = plain.materials[0].base_color;
    ASSERT_FALSE(plain.materials[0].base_color_texture.has_value());
    double T[3];
    const MaterialProfile& p = *with.materials.profiles[0];
    for (int c = 0; c < 3; ++c)
      T[c] = mode.kind == SssKind::Separable ? p.kernel.total_reflectance[c] : p.fit.total_reflectance[c];
    int pixels = 0;
    double worst = 0.0;
    for (int y = 0; y < 90; ++y)
      for (int x = 0; x < 160; ++x) {
        const float* a = without.hdr.pixel(x, y);
        const float* b = with.hdr.pixel(x, y);
        if (a[3] <= 0.0f) {  // background: no light of any kind
          for (int c = 0; c < 3; ++c) EXPECT_EQ(b[c], 0.0f) << mode.name << " background at " << x << "," << y;
          continue;
        }
        ++pixels;
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

}  // namespace
}  // namespace sss::renderer::testing
