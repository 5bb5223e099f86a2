// Shadow maps: a bar hovering over a white Lambertian slab, lit at 45 degrees, seen from
// straight above (the builtin:edge camera, x in [-20, 20] mm). The bar's shadow must be
// black, the lit slab must have exactly E cos(45) / pi everywhere (no acne, no peter-
// panning beyond a shadow-map texel or two), and lights without shadows must not darken.
#include "RenderTest.h"

#include "renderer/scene/BuiltinScenes.h"
#include "renderer/scene/Shapes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sss::renderer::testing {
namespace {

constexpr float kMm = 0.001f;

scene::Scene bar_scene() {
  scene::Scene s = scene::edge_scene();
  scene::Material& m = s.materials[0];
  m.sss = scene::SssMaterial{};  // opaque Lambertian
  m.specular = 0.0f;
  m.metallic = 0.0f;
  // A bar across the image (z in +-50 mm) over x in [-5, 5] mm, 10..12 mm above the slab.
  scene::Mesh bar = scene::make_box({-5 * kMm, 10 * kMm, -50 * kMm}, {5 * kMm, 12 * kMm, 50 * kMm}, 0);
  s.meshes.push_back(std::move(bar));
  s.instances.push_back({1, glm::mat4(1.0f), "bar"});
  // Light travelling toward -x and down at 45 degrees: the shadow of the bar's underside
  // falls on x in [-15, -5] mm, the top's on [-17, -7] mm; no mask.
  s.lights = {scene::directional_light("key", {-1.0f, -1.0f, 0.0f}, 1.0f)};
  return s;
}

float mm_to_px(float x_mm, int width) { return (x_mm + 20.0f) / 40.0f * float(width); }

TEST_F(RenderTest, ShadowMapDarkensWhatTheBarHides) {
  const int w = 256, h = 32;
  const Frame f = render(bar_scene(), small_options(w, h));
  const float lit = std::cos(0.25f * 3.14159265f) / 3.14159265f;
  for (int y = 0; y < h; ++y) {
    // Fully in shadow: x in [-14, -8] mm.
    for (int x = int(mm_to_px(-14, w)); x <= int(mm_to_px(-8, w)); ++x)
      EXPECT_LT(f.hdr.pixel(x, y)[0], 1e-4f) << "shadow at px " << x << "," << y;
    // Fully lit slab: x in [7, 19] mm (beyond the bar, nothing between it and the light).
    for (int x = int(mm_to_px(7, w)); x <= int(mm_to_px(19, w)); ++x)
      EXPECT_NEAR(f.hdr.pixel(x, y)[0], lit, 1e-3f * lit) << "lit at px " << x << "," << y;
    // Lit slab left of the shadow: x in [-19, -18.5] mm.
    EXPECT_NEAR(f.hdr.pixel(int(mm_to_px(-19, w)), y)[0], lit, 1e-3f * lit);
  }
}

TEST_F(RenderTest, MaskedLightStopsAtItsHalfSpaceWithoutAShadowBlur) {
  // builtin:edge with the SSS off and a Lambertian slab: E = 1 exactly up to the pixel
  // before x = 0 and 0 from the pixel after it.
  scene::Scene s = scene::edge_scene();
  s.materials[0].sss = scene::SssMaterial{};
  const int w = 256;
  const Frame f = render(s, small_options(w, 8));
  EXPECT_NEAR(f.hdr.pixel(w / 2 - 1, 4)[0], 1.0f / 3.14159265f, 1e-4f);
  EXPECT_EQ(f.hdr.pixel(w / 2, 4)[0], 0.0f);
  EXPECT_NEAR(f.hdr.pixel(3, 4)[1], 1.0f / 3.14159265f, 1e-4f);
}

}  // namespace
}  // namespace sss::renderer::testing
