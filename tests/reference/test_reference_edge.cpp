// The reference's own end-to-end test (issue 4): builtin:edge rendered by the CPU
// reference must give π L(x) = M(x), the numerical edge response of the exact profile
// (profiles/EdgeResponse.h), within the tolerance its sampling density implies.
//
// Derivation of the per-pixel tolerance. The reference computes
//   S(x) = Σ_i K(|x − x_i|) E_i A,   A = s² (s the point spacing),
// a quadrature of M(x) = ∫ R(|x − x'|) E(x') dA' with one node per cell of area A. Two
// error terms, treated as independent from cell to cell (blue noise makes them
// negatively correlated, so this over-estimates):
//  * inside a lit cell, R varies: the node sits up to about s/√3 (RMS over a square cell)
//    from the cell's points, so the cell's error has SD ≈ |R'(r)| (s/√3) A. Summed:
//      σ_g² = A (s²/3) ∫_lit R'(r)² dA'  (cells within s/2 of x are excluded: there the
//    disc average K integrates R instead of sampling it);
//  * cells straddling the light edge x' = 0 are lit or dark as a whole: error up to
//    ± K A / 2 per cell, so σ_e² = (A/4) ∫_{|x'| < s/2} R(r)² dA'.
//  * the octree (PointOctree.h) replaces a node of area A_n at distance d by its centroid
//    only when A_n ≤ ε d². The centroid rule's error is the second-order term,
//    ½ Σ A (Δ_i · H Δ_i) with H the Hessian of R: for a flat node of side h, Σ A |Δ|² =
//    A_n h²/6 = A_n²/6, so the error is at most A_n² |R''| / 12 ≤ ε d² A_n |R''(d)| / 12,
//    and over all nodes e_h ≤ (ε/12) ∫_lit |R''(r)| r² dA'. It is one-signed (R is convex,
//    so the centroid under-estimates), hence added, not combined in quadrature. This is
//    the bound of the plain centroid rule; the octree also adds the second-order term
//    (PointOctree.h), so its actual error is far below it (tests/reference/test_octree.cpp).
//    Since the near field is a ratio estimate (PointOctree.h), σ_g and σ_e over-estimate
//    the near cells' share too: measured errors are 0.1–0.15 of this tolerance.
// Tolerance = 4 √(σ_g² + σ_e²) + e_h + 1e-3 M(x) (the kernel table's accuracy,
// ScatterKernel.h) + 1e-6 (float storage).
#include "reference/ReferenceRenderer.h"

#include "profiles/EdgeResponse.h"
#include "profiles/Integrate.h"
#include "scene/BuiltinScenes.h"
#include "scene/Shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace sss::reference {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kWidth = 256, kHeight = 8;
constexpr double kHalfWidthMm = 20.48;

// builtin:edge with a smaller block (80 x 80 mm top, 10 mm deep): the profile's support
// that matters here is a few mm, and the points elsewhere would only cost time.
scene::Scene small_edge_scene(const std::string& preset) {
  scene::EdgeOptions eo;
  eo.preset = preset;
  eo.half_width_mm = kHalfWidthMm;
  scene::Scene s = scene::edge_scene(eo);
  const float mm = 1e-3f;
  s.meshes[0] = scene::make_box({-40 * mm, -10 * mm, -40 * mm}, {40 * mm, 0.0f, 40 * mm}, 0);
  return s;
}

// ∫ over the lit half-plane x' < 0 of f(r), r the distance to (x, 0), for r >= r0.
double half_plane_integral(const std::function<double(double)>& f, double x, double r0, double r1) {
  auto angle = [x](double r) {  // the part of the circle of radius r about x with x' < 0
    if (x <= 0.0) return r <= -x ? 2.0 * kPi : 2.0 * kPi - 2.0 * std::acos(-x / r);
    return r <= x ? 0.0 : 2.0 * std::acos(x / r);
  };
  return profiles::integrate([&](double r) { return f(r) * r * angle(r); }, r0, r1, 256, 8);
}

// ∫ over the strip |x'| < w/2 of f(r), r the distance to (x, 0).
double strip_integral(const std::function<double(double)>& f, double x, double w, double r1) {
  return profiles::integrate(
      [&](double xp) {
        return 2.0 * profiles::integrate([&](double y) { return f(std::hypot(x - xp, y)); }, 0.0, r1, 64, 8);
      },
      -0.5 * w, 0.5 * w, 4, 8);
}

struct EdgeCase {
  const char* preset;
  double spacing_mfp;
};

class ReferenceEdgeTest : public ::testing::TestWithParam<EdgeCase> {};

TEST_P(ReferenceEdgeTest, MatchesTheEdgeResponseWithinTheSamplingTolerance) {
  const EdgeCase c = GetParam();
  const scene::Scene s = small_edge_scene(c.preset);
  ReferenceOptions o;
  o.width = kWidth;
  o.height = kHeight;
  o.spacing_mfp = c.spacing_mfp;
  const ReferenceImage img = render_reference(s, o);
  ASSERT_EQ(img.stats.groups.size(), 1u);
  const double s_mm = img.stats.groups[0].spacing_mm;
  const double A = img.stats.groups[0].area_mm2 / double(img.stats.groups[0].points);
  const scene::SssMaterial& m = s.materials[0].sss;
  const profiles::RgbProfile profile(m.model, m.effective_medium());
  const double pixel_mm = 2.0 * kHalfWidthMm / kWidth;
  const double reach = std::min(profile.support_radius(), 38.0);
  int worst_pixel = -1;
  double worst_ratio = 0.0;
  for (int ch = 0; ch < 3; ++ch) {
    const profiles::RadialProfile& R = profile.channel(ch);
    auto dR = [&](double r) {
      const double h = 1e-4 * std::max(r, 1e-3);
      return (R.reflectance(r + h) - R.reflectance(r - h)) / (2.0 * h);
    };
    auto d2R = [&](double r) {
      const double h = 1e-3 * std::max(r, 1e-2);
      return (R.reflectance(r + h) - 2.0 * R.reflectance(r) + R.reflectance(r - h)) / (h * h);
    };
    for (int px = 0; px < kWidth; px += 4) {
      const double x = -kHalfWidthMm + (px + 0.5) * pixel_mm;
      const double exact = profiles::edge_response(R, x);
      const double got = kPi * double(img.hdr.pixel(px, kHeight / 2)[ch]);
      const double var_g = A * s_mm * s_mm / 3.0 *
                           half_plane_integral([&](double r) { return dR(r) * dR(r); }, x, 0.5 * s_mm, reach);
      const double var_e = A / 4.0 * strip_integral([&](double r) {
        const double v = R.reflectance(r);
        return v * v;
      }, x, s_mm, reach);
      const double e_h = o.max_solid_angle / 12.0 *
                         half_plane_integral([&](double r) { return std::abs(d2R(r)) * r * r; }, x, s_mm, reach);
      const double tol = 4.0 * std::sqrt(var_g + var_e) + e_h + 1e-3 * exact + 1e-6;
      const double ratio = std::abs(got - exact) / tol;
      if (ratio > worst_ratio) {
        worst_ratio = ratio;
        worst_pixel = px;
      }
      EXPECT_LE(std::abs(got - exact), tol) << c.preset << " channel " << ch << " x = " << x
                                            << " mm: reference " << got << ", exact M(x) " << exact;
    }
  }
  std::printf("[ %s spacing %.2f mfp (%.3f mm, %zu points) ] worst |error|/tolerance %.2f at pixel %d\n",
              c.preset, c.spacing_mfp, s_mm, img.stats.points, worst_ratio, worst_pixel);
}

INSTANTIATE_TEST_SUITE_P(Presets, ReferenceEdgeTest,
                         ::testing::Values(EdgeCase{"skin1", 1.0}, EdgeCase{"skin1", 0.5},
                                           EdgeCase{"marble", 1.0}),
                         [](const ::testing::TestParamInfo<EdgeCase>& i) {
                           return std::string(i.param.preset) + "_spacing" +
                                  std::to_string(int(std::lround(i.param.spacing_mfp * 100)));
                         });

}  // namespace
}  // namespace sss::reference
