// The CPU rebuild of the real-time frame's shadow maps (ShadowMaps.h, issue 17's
// "lighting" link): what a texel holds and how a point is filtered, each checked against
// a computation that does not share the code's formula.
#include "reference/RayScene.h"
#include "reference/ShadowMaps.h"
#include "scene/Light.h"
#include "scene/Scene.h"
#include "scene/ShadowFrustum.h"
#include "scene/Shapes.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>

namespace sss::reference {
namespace {

constexpr float kMm = 1e-3f;

// A 40 x 40 mm block (top face y = 0, 10 mm deep) and, if `plate`, a 20 x 40 mm plate
// 5 mm above it covering x < 0; a directional light along `light_dir`.
scene::Scene scene_with(const glm::vec3& light_dir, bool plate) {
  scene::Scene s;
  s.name = "shadow test";
  s.materials.emplace_back();
  s.meshes.push_back(scene::make_box({-20 * kMm, -10 * kMm, -20 * kMm}, {20 * kMm, 0.0f, 20 * kMm}, 0));
  s.instances.push_back({0, glm::mat4(1.0f), "block"});
  if (plate) {
    s.meshes.push_back(scene::make_box({-30 * kMm, 5 * kMm, -20 * kMm}, {0.0f, 6 * kMm, 20 * kMm}, 0));
    s.instances.push_back({1, glm::mat4(1.0f), "plate"});
  }
  s.lights.push_back(scene::directional_light("sun", light_dir, 1.0f));
  return s;
}

glm::vec3 project(const glm::mat4& m, const glm::vec3& p) {
  const glm::vec4 c = m * glm::vec4(p, 1.0f);
  return glm::vec3(c) / c.w;
}

// A plane tilted by θ to the light: its depth changes by Δz = texel · tan θ / (depth
// range) per texel along the tilt. The orthographic fit (ShadowFrustum.h) spans 2r over
// `size` texels and 3r in depth, so the per-texel slope is m = 2 tan θ / (3 size), and the
// pass's bias 1.5 m = tan θ / size. A texel that sees the top face must therefore hold the
// face's depth plus tan θ / size: unprojecting its centre at (stored - tan θ / size) lands
// on the plane y = 0. (A bias off by δ moves that point by δ · 3r cos θ off the plane.)
TEST(ShadowMaps, TexelsHoldTheFacesDepthPlusTheSlopeScaledBias) {
  for (double theta_deg : {0.0, 20.0, 45.0}) {
    const double theta = theta_deg * 3.14159265358979323846 / 180.0;
    const glm::vec3 dir(float(std::sin(theta)), float(-std::cos(theta)), 0.0f);
    const scene::Scene s = scene_with(dir, false);
    const RayScene rays(s, 1);
    const std::uint32_t size = 64;
    const ShadowMaps maps(s, rays, size);
    const scene::ShadowFrustum f = scene::shadow_frustum(s.lights[0], s.bounds(), size);
    const float r = s.bounds().radius();
    int checked = 0;
    for (std::uint32_t y = 0; y < size; ++y)
      for (std::uint32_t x = 0; x < size; ++x) {
        const float stored = maps.depth(0, x, y);
        if (stored >= 1.0f) continue;
        const float nx = (x + 0.5f) / size * 2.0f - 1.0f, ny = (y + 0.5f) / size * 2.0f - 1.0f;
        const glm::vec3 q = project(f.inverse, {nx, ny, stored - float(std::tan(theta)) / size});
        // Only texels that see the top face (the light also grazes the +x side at 45°).
        if (!(std::fabs(q.x) < 19 * kMm && std::fabs(q.z) < 19 * kMm && q.y > -1 * kMm)) continue;
        EXPECT_NEAR(q.y, 0.0f, 3.0f * r * 4e-7f) << "theta " << theta_deg << " texel " << x << "," << y;
        ++checked;
      }
    EXPECT_GT(checked, 100) << theta_deg;
  }
}

// shaders/shared/shading.glsl describes its filter as the mean of 9 bilinear comparison
// taps one texel apart (and computes it with 4 taps); ShadowMaps computes it as 4 x 4
// weights. Here the 9 bilinear taps themselves, from the stored depths, at points on the
// block's face next to the plate's shadow edge, where the filter is neither 0 nor 1.
TEST(ShadowMaps, VisibilityIsTheMeanOfNineBilinearComparisonTaps) {
  const scene::Scene s = scene_with(glm::normalize(glm::vec3(0.3f, -1.0f, 0.1f)), true);
  const RayScene rays(s, 1);
  const std::uint32_t size = 128;
  const ShadowMaps maps(s, rays, size);
  const scene::ShadowFrustum f = scene::shadow_frustum(s.lights[0], s.bounds(), size);
  const glm::vec3 n(0.0f, 1.0f, 0.0f);
  auto compare = [&](int x, int y, float ref) {
    x = std::clamp(x, 0, int(size) - 1);
    y = std::clamp(y, 0, int(size) - 1);
    return ref <= maps.depth(0, std::uint32_t(x), std::uint32_t(y)) ? 1.0 : 0.0;
  };
  int partial = 0, lit = 0, dark = 0;
  for (int i = 0; i <= 400; ++i) {
    // Across the shadow edge (x from -12 to +8 mm on the face), at z = 3 mm.
    const glm::vec3 p_mm(-12.0f + 20.0f * i / 400.0f, 0.0f, 3.0f);
    const glm::vec3 c = project(f.view_proj, p_mm * kMm + n * f.normal_offset);
    const float ref = c.z - f.depth_bias;
    double expected = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const double u = (c.x * 0.5 + 0.5) * size + dx - 0.5, v = (c.y * 0.5 + 0.5) * size + dy - 0.5;
        const int x0 = int(std::floor(u)), y0 = int(std::floor(v));
        const double fu = u - x0, fv = v - y0;
        expected += (1 - fu) * (1 - fv) * compare(x0, y0, ref) + fu * (1 - fv) * compare(x0 + 1, y0, ref) +
                    (1 - fu) * fv * compare(x0, y0 + 1, ref) + fu * fv * compare(x0 + 1, y0 + 1, ref);
      }
    expected /= 9.0;
    const double got = maps.visibility(0, p_mm, n);
    EXPECT_NEAR(got, expected, 2e-6) << "x " << p_mm.x << " mm";
    if (got > 0.999) ++lit;
    else if (got < 0.001) ++dark;
    else ++partial;
  }
  // The plate's edge is crossed: dark under it, lit beyond, a filtered band between.
  EXPECT_GT(dark, 50);
  EXPECT_GT(lit, 50);
  EXPECT_GT(partial, 5);
}

// The thickness the GPU's transmission reads (thickness.glsl, ported as thickness_mm):
// through the block along the light, from a point on its bottom face, is the block's
// depth over the light's cosine, 10 mm / cos θ, exactly: the top face is one plane, so
// the texel's depth moved along its neighbours' gradient lands on it wherever the point
// projects. On the lit top face nothing lies between: 0 where the light is normal to it,
// and where it is tilted, half the depth step to a neighbouring texel (the GPU's reading
// of a surface it grazes, thickness.glsl; bound below). Under the plate it is the path
// to the plate's top, (6 mm − y) / cos θ (the air gap counts, as for the GPU: the map
// stores the first surface the light meets). Tolerance: 1e-3 mm, a hundred times float's resolution of
// the map's ~100 mm depth range (3 r), whatever the texel size.
TEST(ShadowMaps, ThicknessIsThePathBackToTheFirstSurfaceTheLightMeets) {
  for (double theta_deg : {0.0, 20.0, 45.0}) {
    const double theta = theta_deg * 3.14159265358979323846 / 180.0;
    const glm::vec3 dir(float(std::sin(theta)), float(-std::cos(theta)), 0.0f);
    for (const bool plate : {false, true}) {
      const scene::Scene s = scene_with(dir, plate);
      const RayScene rays(s, 1);
      const ShadowMaps maps(s, rays, 64);
      SCOPED_TRACE(std::to_string(theta_deg) + (plate ? " deg, plate" : " deg"));
      // The light's line from a point of height y (mm) reaches the plate's top (y = 6) at
      // x - (6 - y) tan θ: under the plate when that is < 0. Points within 3 mm (three
      // texels) of the plate's edge are left out: there the map's texels straddle it.
      const double tan_t = std::tan(theta);
      const double texel_mm = 2.0 * s.bounds().radius() / kMm / 64.0;  // the fit spans 2 r (ShadowFrustum)
      int checked = 0;
      for (float x : {-12.0f, -6.0f, 2.0f, 5.0f, 6.3f, 8.0f, 15.0f})
        for (float z : {-8.0f, -1.7f, 0.0f, 4.1f, 8.0f})
          for (const float y : {-10.0f, 0.0f}) {
            const double at_plate = x - (6.0 - y) * tan_t, entry = x + y * tan_t;  // entry: on the top face
            if (entry < -18.0 || (plate && std::fabs(at_plate) < 3.0)) continue;
            const bool under = plate && at_plate < 0.0 && at_plate > -28.0;
            const double got = maps.thickness_mm(0, {x, y, z});
            if (!under && y == 0.0f) {
              // Lit: the map holds nothing nearer the light on P's texel, so (as the GPU)
              // half the depth drop to the nearest of the 3x3 texel centres around it, at
              // most 1.5 texels from P along each axis: ≤ ½ · 1.5√2 · texel · tan θ.
              EXPECT_GE(got, 0.0) << "lit, x " << x << " z " << z;
              EXPECT_LE(got, 0.75 * std::sqrt(2.0) * texel_mm * tan_t + 1e-3) << "lit, x " << x << " z " << z;
            } else {
              const double expected = under ? (6.0 - y) / std::cos(theta) : -y / std::cos(theta);
              EXPECT_NEAR(got, expected, 1e-3) << "x " << x << " y " << y << " z " << z;
            }
            ++checked;
          }
      EXPECT_GT(checked, 30);
      EXPECT_EQ(maps.thickness_mm(0, {500.0f, 0.0f, 0.0f}), -1.0);  // outside the map
    }
  }
  // A light without a map (point) and one past the shaded ones: no thickness, as on the GPU.
  scene::Scene s = scene_with(glm::vec3(0.0f, -1.0f, 0.0f), false);
  scene::Light bulb;
  bulb.name = "bulb";
  bulb.type = scene::LightType::Point;
  s.lights.push_back(bulb);
  const RayScene rays(s, 1);
  const ShadowMaps maps(s, rays, 32);
  EXPECT_EQ(maps.thickness_mm(1, {0.0f, -10.0f, 0.0f}), -1.0);
  EXPECT_EQ(maps.thickness_mm(7, {0.0f, -10.0f, 0.0f}), -1.0);
}

// Point lights have no shadow map on the GPU (no cube maps): nothing shadows them here
// either, and lights past the GPU's SSS_MAX_LIGHTS are not shaded at all.
TEST(ShadowMaps, PointLightsAreUnshadowedAndExtraLightsUnshaded) {
  scene::Scene s = scene_with(glm::vec3(0.0f, -1.0f, 0.0f), true);
  s.lights.clear();
  for (int i = 0; i < 6; ++i) {
    scene::Light bulb;
    bulb.name = "bulb";
    bulb.type = scene::LightType::Point;
    bulb.world[3] = glm::vec4(0.0f, 0.1f, 0.0f, 1.0f);
    s.lights.push_back(bulb);
  }
  const RayScene rays(s, 1);
  const ShadowMaps maps(s, rays, 32);
  EXPECT_TRUE(maps.shaded(0));
  EXPECT_FALSE(maps.shaded(5));
  EXPECT_DOUBLE_EQ(maps.visibility(0, {-10.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}), 1.0);  // under the plate
  EXPECT_THROW(ShadowMaps(s, rays, 0), std::invalid_argument);
}

}  // namespace
}  // namespace sss::reference
