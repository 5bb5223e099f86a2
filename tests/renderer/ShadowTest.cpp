// Shadow maps: a bar hovering over a white Lambertian slab, lit at 45 degrees, seen from
// straight above (the builtin:edge camera, x in [-20, 20] mm). The bar's shadow must be
// black, the lit slab must have exactly E cos(45) / pi everywhere (no acne, no peter-
// panning beyond a shadow-map texel or two), and lights without shadows must not darken.
#include "RenderTest.h"

#include "scene/BuiltinScenes.h"
#include "scene/Shapes.h"

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

// The same slab and bar through a perspective camera whose near plane is a million times
// closer than the slab (znear 50 nm, zfar 1 km: a glTF camera's znear of 0.05 with its
// subject a thousand units away, as in 2CylinderEngine.glb, is 2e4; this is 50 times
// worse), looking down at 45 degrees at the bar's shadow from beside it (the bar hides
// none of the slab at x <= 0 from it), with 4096² shadow maps. Every pixel whose ray meets
// the slab (found from the camera's field of view) more than a margin inside the shadow,
// x in [-17, -5] mm, must be dark, and every one more than that outside it, up to x = 0,
// must be E cos(45) / pi to the same 1e-3 as above. The margin is what the shadow test
// itself may move an edge by, 5.5 texels of the map (0.07 mm each here, 0.39 mm): the
// 3x3 PCF of bilinear taps reads texels up to 2 away, the normal offset lifts the lookup
// 1.5 texels, and the depth bias of 2 texels' depth shifts the edge by 2 texels along a
// slab lit at 45 degrees (ShadowFrustum.cpp). The point lighting rebuilds from the depth
// buffer must therefore not move by more than that. With the usual depth mapping one float step of depth is 6e-8 z^2 /
// znear, about 4 mm at 55 mm: the shadow's edges moved by millimetres, as the engine's
// fins striped its faces; with the reversed mapping (CameraSetup.h) a step is 2^-24 of
// the distance at any znear.
TEST_F(RenderTest, ACameraWithATinyNearPlaneKeepsTheShadowsEdges) {
  const int w = 128, h = 96;
  scene::Scene s = bar_scene();
  const double texel_mm = 2.0 * double(s.bounds().radius()) * s.mm_per_unit / 4096.0;
  const double margin = 5.5 * texel_mm;
  scene::Camera& cam = s.cameras[0];
  cam.projection = scene::Projection::Perspective;
  cam.yfov = 0.6f;
  cam.aspect = 0.0f;
  cam.znear = 5e-8f;
  cam.zfar = 1000.0f;
  const glm::vec3 eye(-40.0f * kMm, 40.0f * kMm, 0.0f);
  cam.world = scene::look_at_world(eye, {-10.0f * kMm, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f});
  RenderOptions options = small_options(w, h);
  options.shadow_map_size = 4096;
  const Frame f = render(s, options);
  const float lit = std::cos(0.25f * 3.14159265f) / 3.14159265f;
  int lit_checked = 0, dark_checked = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::dvec3 d(pixel_ray(cam, x, y, w, h));
      if (!(d.y < 0.0)) continue;
      const glm::dvec3 hit = (glm::dvec3(eye) - d * (double(eye.y) / d.y)) / double(kMm);  // slab top, mm
      if (hit.x > 0.0 || std::fabs(hit.z) > 40.0) continue;
      const float v = f.hdr.pixel(x, y)[0];
      if (hit.x > -17.0 + margin && hit.x < -5.0 - margin) {
        ++dark_checked;
        EXPECT_LT(v, 1e-4f) << "shadow at px " << x << "," << y << " (slab x " << hit.x << " mm)";
      } else if (hit.x < -17.0 - margin || hit.x > -5.0 + margin) {
        ++lit_checked;
        EXPECT_NEAR(v, lit, 1e-3f * lit) << "lit at px " << x << "," << y << " (slab x " << hit.x << " mm)";
      }
    }
  EXPECT_GT(lit_checked, 500);
  EXPECT_GT(dark_checked, 500);
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

// A spot light 50 mm above the slab pointing down (inner cone 10, outer 15 degrees), with
// a bar 25 mm above the slab across x in [-3, 3] mm: E = I cos(theta) / d^2 inside the
// inner cone, 0 outside the outer cone, and the bar's shadow (x in [-6, 6] mm on the slab,
// magnified 2x from the light) black where the camera sees the slab past the bar.
TEST_F(RenderTest, SpotLightFallsOffWithDistanceAndCastsAPerspectiveShadow) {
  scene::Scene s = bar_scene();
  s.meshes[1] = scene::make_box({-3 * kMm, 24 * kMm, -50 * kMm}, {3 * kMm, 25 * kMm, 50 * kMm}, 0);
  scene::Light spot;
  spot.name = "spot";
  spot.type = scene::LightType::Spot;
  spot.intensity = 0.0025f;  // W/sr: E = 1 straight below at 50 mm
  spot.inner_cone = 10.0f * 3.14159265f / 180.0f;
  spot.outer_cone = 15.0f * 3.14159265f / 180.0f;
  spot.world = scene::look_at_world({0.0f, 50 * kMm, 0.0f}, glm::vec3(0.0f), {0.0f, 0.0f, -1.0f});
  s.lights = {spot};
  const int w = 256, h = 16;
  const Frame f = render(s, small_options(w, h));
  const auto expected = [](float x_mm) {
    const float d2 = (50.0f * 50.0f + x_mm * x_mm) * 1e-6f;
    const float cos_theta = 50.0f / std::sqrt(50.0f * 50.0f + x_mm * x_mm);
    return 0.0025f * cos_theta / d2 / 3.14159265f;  // I cos(theta) / d^2 / pi
  };
  for (float x_mm : {-8.0f, 7.5f, 8.5f}) {
    const float px = mm_to_px(x_mm, w);
    const float x_center = (std::floor(px) + 0.5f) / float(w) * 40.0f - 20.0f;
    EXPECT_NEAR(f.hdr.pixel(int(px), h / 2)[0], expected(x_center), 2e-3f * expected(x_center))
        << "lit at x=" << x_center << " mm";
  }
  for (float x_mm : {-5.0f, -4.0f, 4.0f, 5.0f})
    EXPECT_LT(f.hdr.pixel(int(mm_to_px(x_mm, w)), h / 2)[0], 1e-4f) << "shadow at x=" << x_mm;
  for (float x_mm : {-19.0f, 16.0f, 19.0f})  // beyond atan(15 deg) * 50 mm = 13.4 mm
    EXPECT_EQ(f.hdr.pixel(int(mm_to_px(x_mm, w)), h / 2)[0], 0.0f) << "outside the cone at " << x_mm;
}

}  // namespace
}  // namespace sss::renderer::testing
