// Debug views (RenderOptions::debug_view, debug_view.comp): what each view shows, checked
// where the answer is known exactly, plus what every view leaves alone (the HDR frame).
//
// Tolerances. The display image is rgba8, so a value shown directly is within 0.5/255 of
// the shader's float; every "same as" comparison below allows 1.5 codes (the half-code
// rounding plus the float differences between the test's C++ and the shader's GLSL of the
// same formula: filmic + sRGB pow, ~1e-6 relative, far below a code). Heat maps are decoded
// back through the same viridis fit (nearest of 4096 samples): a channel's 0.5-code rounding
// moves the decoded t by at most 0.5 / 255 / max |dc/dt| ~ 0.002 where the views are read
// (|dc/dt| >= 0.9 for some channel over t in [0.1, 0.9]); the 4096-sample search adds
// 1.2e-4. So t is known to 0.003: thickness (t x 291.5 mm) to 0.9 mm, the kernel radius
// (2^(6 t) pixels) to 6 x 0.003 x ln 2 = 1.3 %, the uv stretch (linear in codes, top 916 mm)
// to 0.5 / 255 x 916 = 1.8 mm. The bounds used are 1.5 mm, 3 % and 2.5 mm.
#include "RenderTest.h"

#include "profiles/SingleScattering.h"
#include "renderer/DebugViewPass.h"
#include "image/Image.h"
#include "image/Tonemap.h"
#include "scene/BuiltinScenes.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <set>
#include <vector>

namespace sss::renderer::testing {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr float kCode = 1.0f / 255.0f;

// composite.glsl's display_encode (exposure applied by the caller): the same formulas
// (shaders/shared/tonemap.h) on the CPU.
float encode(float x) { return image::srgb_encode(image::filmic(x)); }

// debug_view.comp's viridis fit.
std::array<float, 3> viridis(float t) {
  static const float c[7][3] = {{0.2777273272234177f, 0.005407344544966578f, 0.3340998053353061f},
                                {0.1050930431085774f, 1.404613529898575f, 1.384590162594685f},
                                {-0.3308618287255563f, 0.214847559468213f, 0.09509516302823659f},
                                {-4.634230498983486f, -5.799100973351585f, -19.33244095627987f},
                                {6.228269936347081f, 14.17993336680509f, 56.69055260068105f},
                                {4.776384997670288f, -13.74514537774601f, -65.35303263337234f},
                                {-5.435455855934631f, 4.645852612178535f, 26.3124352495832f}};
  std::array<float, 3> out{};
  for (int k = 0; k < 3; ++k) {
    float v = c[6][k];
    for (int i = 5; i >= 0; --i) v = c[i][k] + t * v;
    out[k] = std::clamp(v, 0.0f, 1.0f);
  }
  return out;
}

// The t whose viridis colour is nearest to the pixel's.
float decode_viridis(const float* p) {
  float best_t = 0.0f, best = 1e30f;
  for (int i = 0; i <= 4096; ++i) {
    const float t = float(i) / 4096.0f;
    const auto c = viridis(t);
    const float d = (c[0] - p[0]) * (c[0] - p[0]) + (c[1] - p[1]) * (c[1] - p[1]) +
                    (c[2] - p[2]) * (c[2] - p[2]);
    if (d < best) best = d, best_t = t;
  }
  return best_t;
}

RenderOptions view_options(std::uint32_t w, std::uint32_t h, DebugView view,
                           SssTechnique technique = SssTechnique::Separable) {
  RenderOptions o = small_options(w, h, technique);
  o.debug_view = view;
  // The views show the lighting input E and the scattered R * E; their closed forms below
  // (E = 1, the frame equal to the scattered view) hold without the directional Fresnel
  // factors, which multiply E on entry and the frame on exit, and without single
  // scattering, which adds S(1) to the specular target (SingleScatteringViewIsS1Alone has it).
  o.fresnel = false;
  o.single_scattering = false;
  return o;
}

// builtin:edge lit everywhere (E = 1 at normal incidence), white, no specular.
scene::Scene lit_slab(double half_width_mm = 20.0) {
  scene::EdgeOptions e;
  e.half_width_mm = half_width_mm;
  scene::Scene s = scene::edge_scene(e);
  s.lights[0].mask.reset();
  return s;
}

// The scene's bounding diameter in mm: the thickness heat map's top (DebugViewPass).
float diameter_mm(const scene::Scene& s) { return float(2.0 * s.bounds().radius() * s.mm_per_unit); }

class DebugViewTest : public RenderTest {};

TEST(DebugViewNames, ParseEveryNameBackAndRejectOthers) {
  std::set<std::string_view> names;
  for (DebugView v : all_debug_views()) {
    names.insert(debug_view_name(v));
    EXPECT_EQ(parse_debug_view(debug_view_name(v)), v);
  }
  EXPECT_EQ(names.size(), 9u);
  EXPECT_EQ(all_debug_views().front(), DebugView::None);
  EXPECT_FALSE(parse_debug_view("Irradiance"));
  EXPECT_FALSE(parse_debug_view(""));
}

// Every view changes the display image only: the HDR frame is the shaded frame, bit for
// bit (lavapipe is deterministic), so an EXR written with a view on is still the render.
TEST_F(DebugViewTest, HdrStaysTheShadedFrameInEveryView) {
  const scene::Scene s = scene::materials_scene();
  const Frame shaded = render(s, view_options(96, 54, DebugView::None));
  for (DebugView v : all_debug_views()) {
    const Frame f = render(s, view_options(96, 54, v));
    ASSERT_EQ(f.hdr.rgba.size(), shaded.hdr.rgba.size());
    EXPECT_EQ(std::memcmp(f.hdr.rgba.data(), shaded.hdr.rgba.data(),
                          f.hdr.rgba.size() * sizeof(float)),
              0)
        << debug_view_name(v);
    if (v == DebugView::None) {
      EXPECT_EQ(f.display.rgba, shaded.display.rgba);
    } else {
      EXPECT_NE(f.display.rgba, shaded.display.rgba) << debug_view_name(v);
    }
    for (std::size_t i = 3; i < f.display.rgba.size(); i += 4)  // the same coverage alpha
      ASSERT_EQ(f.display.rgba[i], shaded.display.rgba[i]) << debug_view_name(v) << " " << i;
  }
}

// Irradiance: E / pi tonemapped. On the lit edge scene E = 1 at every slab pixel (the light
// at normal incidence); on builtin:edge the half x > 0 is masked off (E = 0, black).
TEST_F(DebugViewTest, IrradianceIsTheTonemappedLightingInput) {
  const int n = 32;
  const Frame lit = render(lit_slab(), view_options(n, n, DebugView::Irradiance));
  const float expected = encode(1.0f / kPi);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(lit.display.pixel(x, y)[c], expected, 1.5f * kCode);
  const Frame edge = render(scene::edge_scene(), view_options(n, n, DebugView::Irradiance));
  EXPECT_NEAR(edge.display.pixel(n / 4, n / 2)[1], expected, 1.5f * kCode);  // lit half
  EXPECT_EQ(edge.display.pixel(3 * n / 4, n / 2)[1], 0.0f);                  // masked half
  EXPECT_EQ(edge.display.pixel(3 * n / 4, n / 2)[3], 1.0f);                  // still geometry
}

// Specular: the GGX term alone. With N = L = V (light and orthographic camera straight
// down on the slab): D = 1 / (pi a^2), the visibility term 1 / (4 (NdotL NdotV)) x ... =
// 0.25 for alpha = roughness^2 = 1, F = F0: S = F0 / (4 pi) x E. Exposure 100 puts it mid-curve.
TEST_F(DebugViewTest, SpecularIsTheTonemappedSpecularTerm) {
  scene::Scene s = lit_slab();
  s.materials[0].specular = 1.0f;
  RenderOptions o = view_options(16, 16, DebugView::Specular);
  o.exposure = 100.0f;
  const Frame f = render(s, o);
  const float f0 = f.materials.gpu[0].f0;
  ASSERT_GT(f0, 0.0f);
  const float expected = encode(100.0f * f0 / (4.0f * kPi));
  ASSERT_GT(expected, 0.3f);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(f.display.pixel(8, 8)[c], expected, 1.5f * kCode);
  const Frame none = render(lit_slab(), o);  // specular 0: black
  EXPECT_EQ(none.display.pixel(8, 8)[0], 0.0f);
}

// Single scattering: S(1) alone, the planar closed form E μi f1 (profiles::
// single_scattering_brdf) for the slab lit and seen straight down (μi = μo = 1, the light
// turned straight back: cos θ = -1), whether the switch is on or off; the frame's specular
// target holds it only with the switch on. Tolerance: the display code's rounding, 1.5 codes
// as the specular view's.
TEST_F(DebugViewTest, SingleScatteringViewIsS1Alone) {
  const scene::Scene s = lit_slab();
  for (const bool on : {false, true}) {
    RenderOptions o = view_options(16, 16, DebugView::SingleScattering);
    o.single_scattering = on;
    o.exposure = 4.0f;
    const Frame f = render(s, o);
    const profiles::Medium medium = s.materials[0].sss.effective_medium();
    for (int c = 0; c < 3; ++c) {
      const double s1 = profiles::single_scattering_brdf(medium.channel(c), 1.0, 1.0, 1.0);
      const float expected = encode(4.0f * float(s1));
      EXPECT_NEAR(f.display.pixel(8, 8)[c], expected, 1.5f * kCode) << "channel " << c << (on ? " on" : " off");
      // One half-float ulp (Vulkan may round toward zero) + the shader's float arithmetic
      // (1e-4, as EdgeTest's S(1) check).
      EXPECT_NEAR(f.specular.pixel(8, 8)[c], on ? s1 : 0.0, on ? (1.0 / 1024.0 + 1e-4) * s1 : 1e-7) << "channel " << c;
    }
  }
}

// Scattered: (R * E) / pi before albedo. The slab is white with no specular, so the
// shaded frame is exactly that (L = 1 x diffuse / pi): the view equals the frame, in both
// SSS modes, and it is blurred across the light's edge where the irradiance view is a step.
TEST_F(DebugViewTest, ScatteredIsTheDiffuseBeforeAlbedo) {
  const int n = 64;
  for (SssTechnique mode : {SssTechnique::Off, SssTechnique::Separable}) {
    const Frame shaded = render(scene::edge_scene(), view_options(n, n, DebugView::None, mode));
    const Frame view = render(scene::edge_scene(), view_options(n, n, DebugView::Scattered, mode));
    for (std::size_t i = 0; i < view.display.rgba.size(); ++i)
      ASSERT_NEAR(view.display.rgba[i], shaded.display.rgba[i], 1.5f * kCode)
          << technique_name(mode) << " " << i;
  }
  const Frame e = render(scene::edge_scene(), view_options(n, n, DebugView::Irradiance));
  const Frame s = render(scene::edge_scene(), view_options(n, n, DebugView::Scattered));
  const int x = n / 2 + 1;  // just inside the masked half: E = 0, light scattered in
  EXPECT_EQ(e.display.pixel(x, n / 2)[0], 0.0f);
  EXPECT_GT(s.display.pixel(x, n / 2)[0], 10.0f * kCode);
}

// Kernel radius: range_mm x pixels per mm, here on a range of 1..64 px given by
// --debug-range (log2 0..6). Orthographic builtin:edge spans 2 x half_width mm over n
// pixels, so the radius is range_mm n / (2 hw) pixels; zooming in 2x doubles it; zoomed
// out below 1 px it is magenta. The automatic range's top is that radius: an orthographic
// camera has one scale, and the slab faces it (no foreshortening).
TEST_F(DebugViewTest, KernelRadiusIsTheKernelExtentInPixels) {
  const int n = 48;
  const auto radius_px = [&](double half_width_mm, float* range_mm) {
    RenderOptions o = view_options(n, n, DebugView::KernelRadius);
    o.debug_range = {1.0f, 64.0f};
    const Frame f = render(lit_slab(half_width_mm), o);
    EXPECT_EQ(f.debug_range, o.debug_range);
    *range_mm = f.materials.gpu[0].range_mm;
    const float t = decode_viridis(f.display.pixel(n / 2, n / 2));
    return std::exp2(t * 6.0f);
  };
  float range_mm = 0.0f;
  const float wide = radius_px(20.0, &range_mm);
  const float expected = range_mm * float(n) / 40.0f;
  ASSERT_GT(expected, 1.5f);
  ASSERT_LT(expected, 60.0f);
  EXPECT_NEAR(wide, expected, 0.03f * expected);
  const float zoomed = radius_px(10.0, &range_mm);  // closer: twice the pixels per mm
  EXPECT_NEAR(zoomed / wide, 2.0f, 0.06f);
  const Frame automatic = render(lit_slab(20.0), view_options(n, n, DebugView::KernelRadius));
  EXPECT_EQ(automatic.debug_range[0], 1.0f);
  // Both sides from the same float32 kernel reach: the projection's 1/xmag, the test's
  // product and quotient, and the range's conversion to float round once each, half an
  // ulp (6e-8) apiece: 4 x 6e-8 < 1e-6 relative.
  EXPECT_NEAR(automatic.debug_range[1], expected, 1e-6f * expected);
  const Frame far = render(lit_slab(100.0 * expected), view_options(n, n, DebugView::KernelRadius));
  const float* m = far.display.pixel(n / 2, n / 2);
  EXPECT_EQ(m[0], 1.0f);
  EXPECT_EQ(m[1], 0.0f);
  EXPECT_EQ(m[2], 1.0f);
}

// Profile id: one flat colour per material (every pixel of a sphere the same, no two
// spheres alike), black background with alpha 0.
TEST_F(DebugViewTest, ProfileIdGivesEachMaterialOneDistinctColour) {
  const scene::Scene s = scene::materials_scene();
  const Frame f = render(s, view_options(192, 108, DebugView::ProfileId));
  std::set<std::array<int, 3>> colours;
  for (int y = 0; y < f.display.height; ++y)
    for (int x = 0; x < f.display.width; ++x) {
      const float* p = f.display.pixel(x, y);
      if (p[3] == 0.0f) {
        ASSERT_EQ(p[0] + p[1] + p[2], 0.0f);
        continue;
      }
      colours.insert({int(std::lround(p[0] * 255)), int(std::lround(p[1] * 255)),
                      int(std::lround(p[2] * 255))});
    }
  EXPECT_EQ(colours.size(), s.materials.size());  // every sphere is in view
  for (auto a = colours.begin(); a != colours.end(); ++a)
    for (auto b = std::next(a); b != colours.end(); ++b) {
      int d = 0;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs((*a)[c] - (*b)[c]));
      EXPECT_GE(d, 24) << "two materials look alike";
    }
}

// Thickness along light 0 (straight down) through the 50 mm slab: 0 on the lit top face;
// seen from below, every pixel of the bottom face is 50 mm from the top face.
TEST_F(DebugViewTest, ThicknessIsTheDistanceThroughTheObjectAlongTheLight) {
  const int n = 32;
  scene::Scene top = lit_slab();
  const float top_mm = diameter_mm(top);  // the slab is the scene: its diameter
  const Frame lit = render(top, view_options(n, n, DebugView::Thickness));
  EXPECT_EQ(lit.debug_range[0], 0.0f);
  EXPECT_NEAR(lit.debug_range[1], top_mm, 1e-6f * top_mm);
  for (int y = 0; y < n; y += 3)
    for (int x = 0; x < n; x += 3)
      EXPECT_LT(decode_viridis(lit.display.pixel(x, y)) * top_mm, 1.5f) << x << "," << y;

  scene::Scene below = top;
  const float mm = float(1.0 / below.mm_per_unit);
  below.cameras[0].world =
      scene::look_at_world({0.0f, -150 * mm, 0.0f}, glm::vec3(0.0f), {0.0f, 0.0f, -1.0f});
  const Frame f = render(below, view_options(n, n, DebugView::Thickness));
  for (int y = 0; y < n; y += 3)
    for (int x = 0; x < n; x += 3) {
      ASSERT_EQ(f.display.pixel(x, y)[3], 1.0f);
      EXPECT_NEAR(decode_viridis(f.display.pixel(x, y)) * top_mm, 50.0f, 1.5f) << x << "," << y;
    }
}

// UV stretch: the slab's top face maps uv 0..1 across its 200 mm in both directions, so
// 200 mm per unit of u (red) and of v (green), over a top of pi x the bounding diameter;
// the bunny has no UVs: flat grey.
TEST_F(DebugViewTest, UvStretchIsMmOfSurfacePerUnitOfUv) {
  const int n = 32;
  const scene::Scene s = lit_slab();
  const float top = kPi * diameter_mm(s);
  const Frame f = render(s, view_options(n, n, DebugView::UvStretch));
  EXPECT_NEAR(f.debug_range[1], top, 1e-6f * top);
  for (int y = 1; y < n - 1; y += 3)
    for (int x = 1; x < n - 1; x += 3) {
      EXPECT_NEAR(f.display.pixel(x, y)[0] * top, 200.0f, 2.5f) << x << "," << y;
      EXPECT_NEAR(f.display.pixel(x, y)[1] * top, 200.0f, 2.5f) << x << "," << y;
      EXPECT_EQ(f.display.pixel(x, y)[2], 0.0f);
    }
  auto loaded = scene::load_scene("builtin:bunny");
  const scene::Scene bunny = std::get<scene::Scene>(std::move(loaded));
  const Frame b = render(bunny, view_options(64, 36, DebugView::UvStretch));
  int geometry = 0;
  for (int y = 0; y < b.display.height; ++y)
    for (int x = 0; x < b.display.width; ++x) {
      const float* p = b.display.pixel(x, y);
      if (p[3] == 0.0f) continue;
      ++geometry;
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(p[c], 0.25f, 0.5f * kCode);
    }
  EXPECT_GT(geometry, 100);
}

// Issue 20 part 3: the kernel-radius view was solid yellow on the bunny (its top, 64 px,
// below the skin's reach at 960x540), and the thickness view's top was the scene's size.
// The automatic ranges: no SSS pixel of the bunny lies above the kernel-radius top (it is
// an upper bound: the reach at the object's nearest depth, unforeshortened), and the top
// is within 4x of the largest radius on screen (the nearest depth is the box's corner, the
// surface there is foreshortened); the view spans at least half of viridis. On
// builtin:materials the thickness top is one sphere's bounding diameter (a cube's
// diagonal around the 30 mm sphere: 30 sqrt 3 mm), not the row of spheres.
TEST_F(DebugViewTest, AutomaticRangesFitTheObjectsOnScreen) {
  auto loaded = scene::load_scene("builtin:bunny");
  const scene::Scene bunny = std::get<scene::Scene>(std::move(loaded));
  const std::uint32_t w = 480, h = 270;  // the old fixed top, 64 px, saturated here
  const Frame f = render(bunny, view_options(w, h, DebugView::KernelRadius));
  ASSERT_EQ(f.debug_range[0], 1.0f);
  const float log_hi = std::log2(f.debug_range[1]);
  ASSERT_GT(log_hi, 1.0f);
  float t_min = 1.0f, t_max = 0.0f;
  int scattering = 0, at_top = 0;
  for (std::uint32_t y = 0; y < h; ++y)
    for (std::uint32_t x = 0; x < w; ++x) {
      const float* p = f.display.pixel(int(x), int(y));
      const auto code = [&](int c) { return std::lround(p[c] * 255.0f); };
      if (p[3] == 0.0f || (code(0) == 64 && code(1) == 64 && code(2) == 64)) continue;  // no value
      if (p[0] == 1.0f && p[1] == 0.0f && p[2] == 1.0f) continue;       // below 1 px
      const float t = decode_viridis(p);
      ++scattering;
      t_min = std::min(t_min, t);
      t_max = std::max(t_max, t);
      at_top += t >= 1.0f ? 1 : 0;
    }
  ASSERT_GT(scattering, 1000);
  EXPECT_LT(at_top, scattering / 100) << "the top saturates";
  EXPECT_GT(t_max, 1.0f - 2.0f / log_hi) << "top within 4x (2 stops) of the largest radius";
  EXPECT_GT(t_max - t_min, 0.5f) << "the view spans half the map";

  const scene::Scene spheres = scene::materials_scene();
  const Frame k = render(spheres, view_options(192, 108, DebugView::Thickness));
  // make_uv_sphere(15 mm, 48, 24): 7.5-degree facets, whose vertices reach at least
  // R cos(3.75 deg) along each axis, so the box diagonal is 30 sqrt 3 mm within
  // 30 sqrt 3 (1 - cos 3.75 deg) = 0.11 mm.
  const float diagonal = 30.0f * std::sqrt(3.0f);
  EXPECT_NEAR(k.debug_range[1], diagonal, diagonal * (1.0f - std::cos(3.75f * kPi / 180.0f)));
  EXPECT_LT(k.debug_range[1], 0.5f * diameter_mm(spheres)) << "not the row's size";
}

TEST(DebugRange, RefusesWhatCannotBeAHeatMap) {
  using V = DebugView;
  EXPECT_EQ(debug_range_error(V::Thickness, {0.0f, 0.0f}), "");
  EXPECT_EQ(debug_range_error(V::Thickness, {0.0f, 5.0f}), "");
  EXPECT_EQ(debug_range_error(V::KernelRadius, {0.5f, 200.0f}), "");
  EXPECT_NE(debug_range_error(V::KernelRadius, {0.0f, 64.0f}).find("LO must be > 0"), std::string::npos);
  EXPECT_NE(debug_range_error(V::Thickness, {5.0f, 5.0f}).find("LO < HI"), std::string::npos);
  EXPECT_NE(debug_range_error(V::UvStretch, {-1.0f, 5.0f}).find(">= 0"), std::string::npos);
  EXPECT_NE(debug_range_error(V::Thickness, {0.0f, std::numeric_limits<float>::quiet_NaN()}),
            "");
  EXPECT_TRUE(debug_view_has_range(V::Thickness));
  EXPECT_FALSE(debug_view_has_range(V::ProfileId));
}

}  // namespace
}  // namespace sss::renderer::testing
