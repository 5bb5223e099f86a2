// The display image beyond the shading (issue 20 part 3): anti-aliasing (renderer/README.md
// "Anti-aliasing"), FXAA over the display image, on in the window by default, and the
// background colour.
//
// What a user cares about: silhouettes are no longer staircases, and nothing else moves.
// The staircase is measured on coverage, which a 4x4-supersampled render gives exactly
// (to 1/16) and which does not depend on how colours are blended: the display's alpha is
// 1 on geometry and 0 on the background, and FXAA's bilinear tap blends it with the
// colour, so its alpha is the coverage it reconstructs.
#include "RenderTest.h"

#include "scene/BuiltinScenes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <array>
#include <cstdio>
#include <string>

namespace sss::renderer::testing {
namespace {

// Each pixel's share of its 4x4 block of `fine` that has geometry (alpha > 1/2).
image::Image coverage(const image::Image& fine, int w, int h) {
  image::Image c(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      int inside = 0;
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) inside += fine.pixel(4 * x + i, 4 * y + j)[3] > 0.5f;
      c.pixel(x, y)[3] = float(inside) / 16.0f;
    }
  return c;
}

}  // namespace

// The bunny at 480x270, lit skin against the black background, with the 4x4-supersampled
// frame's coverage c as the truth. On the silhouette pixels (0 < c < 1) the aliased
// frame's alpha is 0 or 1, so its error is min(c, 1 - c) for a pixel whose centre falls
// on the majority side: with c uniform on (0, 1) that error is uniform on (0, 1/2), mean
// 1/4 (the staircase) and standard deviation 1 / (2 sqrt 12) = 0.144, so over the ~700
// pixels measured its mean lies within 0.017 of 1/4 at 3 standard errors. The check
// > 0.15 says the aliased frame really is binary along its outline (a filtered one is not). FXAA is a heuristic: it rebuilds a long shallow step as a ramp, but a
// near-45-degree step is a pixel long and it has nothing to rebuild, so no fixed fraction
// of the error follows for a curved outline. What must hold:
// - the error drops beyond chance: the mean paired difference |aa - c| - |off - c| over
//   the silhouette pixels is below -3 standard errors (a one-sided Z-test at 0.13%);
// - and by more than 1/16, the truth's own quantum (one of its 16 samples): a smaller
//   gain would be below what the supersampled reference can resolve.
// FXAA leaves an edge alone whose luma step is below max(1/32, 1/8 of the brightest of
// the pixel and its 4 neighbours) (the bunny's unlit back against the black background
// is such an edge), so the check is made where that step is larger in the aliased frame.
// Elsewhere: a pixel whose 3x3 neighbourhood is one colour is not on an edge and keeps its
// value bit for bit, and the HDR image is never filtered.
TEST_F(RenderTest, FxaaReducesTheSilhouettesStaircaseAndLeavesTheRestAlone) {
  const scene::Scene scene = std::get<scene::Scene>(scene::bunny_scene());
  const int w = 480, h = 270;
  RenderOptions o = small_options(w, h, SssTechnique::Separable);
  const Frame off = render(scene, o);
  o.antialias = Antialias::Fxaa;
  const Frame aa = render(scene, o);
  RenderOptions fine_options = small_options(4 * w, 4 * h, SssTechnique::Separable);
  const image::Image truth = coverage(render(scene, fine_options).display, w, h);

  // The HDR image (the EXR, the compare suite) is never filtered.
  ASSERT_EQ(off.hdr.rgba, aa.hdr.rgba);

  auto luma = [](const float* p) { return 0.299f * p[0] + 0.587f * p[1] + 0.114f * p[2]; };
  double err_off = 0.0, err_aa = 0.0, diff_sq = 0.0;
  int edge = 0, flat = 0, flat_changed = 0;
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      const float* p = off.display.pixel(x, y);
      // A pixel whose 3x3 neighbourhood is one colour is not on an edge: it must keep its
      // value exactly.
      bool same = true;
      for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i)
          for (int c = 0; c < 4; ++c) same = same && off.display.pixel(x + i, y + j)[c] == p[c];
      if (same) {
        ++flat;
        for (int c = 0; c < 4; ++c) flat_changed += aa.display.pixel(x, y)[c] != p[c];
        continue;
      }
      const float c = truth.pixel(x, y)[3];
      if (!(c > 0.0f && c < 1.0f)) continue;
      float lo = luma(p), hi = luma(p);
      for (const auto& [i, j] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        lo = std::min(lo, luma(off.display.pixel(x + i, y + j)));
        hi = std::max(hi, luma(off.display.pixel(x + i, y + j)));
      }
      if (hi - lo < std::max(1.0f / 32.0f, hi / 8.0f)) continue;
      ++edge;
      const double e_off = std::abs(p[3] - c), e_aa = std::abs(aa.display.pixel(x, y)[3] - c);
      err_off += e_off;
      err_aa += e_aa;
      diff_sq += (e_aa - e_off) * (e_aa - e_off);
    }
  ASSERT_GT(edge, 200) << "too few silhouette pixels to measure";
  err_off /= edge;
  err_aa /= edge;
  const double gain = err_off - err_aa;
  const double se = std::sqrt((diff_sq / edge - gain * gain) / (edge - 1));
  std::printf("silhouette pixels %d: mean |alpha - coverage| aliased %.4f, fxaa %.4f (%.0f%%), "
              "gain %.4f +- %.4f; flat pixels %d\n",
              edge, err_off, err_aa, 100.0 * err_aa / err_off, gain, se, flat);
  EXPECT_GT(err_off, 0.15) << "the aliased frame should show a staircase (1/4 expected)";
  EXPECT_GT(gain, 3.0 * se);
  EXPECT_GT(gain, 1.0 / 16.0);
  EXPECT_GT(flat, w * h / 2);
  EXPECT_EQ(flat_changed, 0);
}

// A debug view is data: its colours map values on a colour bar, and blending two of them
// makes a value that is not there. The anti-aliasing switch leaves it as it is.
TEST_F(RenderTest, AntialiasingLeavesDebugViewsAlone) {
  const scene::Scene scene = scene::materials_scene();
  RenderOptions o = small_options(320, 180, SssTechnique::Separable);
  o.debug_view = DebugView::ProfileId;
  const Frame off = render(scene, o);
  o.antialias = Antialias::Fxaa;
  const Frame aa = render(scene, o);
  EXPECT_EQ(off.display.rgba, aa.display.rgba);
}

// --background (issue 20 part 3: "the background and the unlit faces are both black, and a
// cube's dark face disappears"): the display's pixels without geometry take the colour,
// given as sRGB codes, opaque; a UNORM clear stores the nearest code, so they must be
// round(255 c) / 255 exactly. Every pixel with geometry keeps its value bit for bit, and
// the HDR image (EXR) is unchanged, background included.
TEST_F(RenderTest, BackgroundColourFillsOnlyWhereThereIsNoGeometry) {
  const scene::Scene scene = scene::sphere_scene();
  RenderOptions o = small_options(160, 90, SssTechnique::Separable);
  const Frame plain = render(scene, o);
  const std::array<float, 3> colour{0.25f, 0.5f, 0.75f};
  o.background = colour;
  const Frame grey = render(scene, o);
  ASSERT_EQ(plain.hdr.rgba, grey.hdr.rgba);
  int background = 0, geometry = 0;
  for (int y = 0; y < 90; ++y)
    for (int x = 0; x < 160; ++x) {
      const float* p = plain.display.pixel(x, y);
      const float* g = grey.display.pixel(x, y);
      if (p[3] == 0.0f) {
        ++background;
        for (int c = 0; c < 3; ++c) ASSERT_EQ(g[c], std::round(255.0f * colour[c]) / 255.0f) << x << "," << y;
        ASSERT_EQ(g[3], 1.0f);
      } else {
        ++geometry;
        for (int c = 0; c < 4; ++c) ASSERT_EQ(g[c], p[c]) << x << "," << y;
      }
    }
  EXPECT_GT(background, 1000);
  EXPECT_GT(geometry, 1000);
}

}  // namespace sss::renderer::testing
