// The split sum's two tables (scene/SplitSum.h), each against an independent
// computation: the DFG table against a midpoint rule over the hemisphere
// (tests/common/GgxQuadrature.h) and the mirror's closed form; the prefiltered levels
// against a uniform sky (exact) and a linear sky, whose lobe average has a 1-D closed form.
#include "scene/Environment.h"
#include "scene/SplitSum.h"
#include "tests/common/GgxQuadrature.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace sss::scene {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Each entry of the table is a 4096-point importance-sampled estimate; against the midpoint
// rule (2400 x 1200 cells, whose own error is below 1e-5 for lobes of r >= 0.3: the cells
// are 0.04 degrees where the narrowest lobe is 5 degrees wide) it must agree within 3 of
// the estimate's standard errors as if its points were random (low-discrepancy points do
// better) plus 1e-5.
TEST(SplitSum, TheDfgEntriesAreTheLobesAlbedoByAnIndependentQuadrature) {
  double worst = 0.0;
  for (const double nv : {0.15, 0.5, 0.9})
    for (const double r : {0.3, 0.5, 0.8, 1.0}) {
      const DfgEntry e = dfg_integrate(nv, r, kDfgSamples);
      const glm::dvec2 q = sss::testing::ggx_albedo_quadrature(nv, r, 2400, 1200);
      for (int k = 0; k < 2; ++k) {
        const double tol = 3.0 * e.spread[k] / std::sqrt(double(kDfgSamples)) + 1e-5;
        EXPECT_NEAR(e.ab[k], q[k], tol) << "n.v " << nv << " r " << r << (k ? " B" : " A");
        worst = std::max(worst, std::fabs(e.ab[k] - q[k]) / tol);
      }
    }
  std::printf("[ dfg ] worst |table - quadrature| / tol %.3f\n", worst);
}

// A mirror (r = 0, alpha 1e-3) reflects v whole, weighted by Schlick's Fresnel at n.v:
// A = 1 - (1 - n.v)^5, B = (1 - n.v)^5 (the visibility and the Jacobian cancel at h = n).
// The lobe's normals lie within a few alpha of n, so v.h moves by ~alpha = 1e-3 and
// Schlick's weight, whose slope 5 (1 - v.h)^4 is at most 5, by 5e-3 at most.
TEST(SplitSum, AMirrorReflectsEverythingWithSchlicksFresnel) {
  for (const double nv : {0.2, 0.5, 0.8, 1.0}) {
    const DfgEntry e = dfg_integrate(nv, 0.0, kDfgSamples);
    const double fc = std::pow(1.0 - nv, 5.0);
    EXPECT_NEAR(e.ab.x, 1.0 - fc, 5e-3) << nv;
    EXPECT_NEAR(e.ab.y, fc, 5e-3) << nv;
  }
}

// Between texel centres the lookup interpolates. The split sum is used for 8-bit display
// and beside a 5% error budget, so the requirement is 1% of the white lobe's albedo (0.01
// absolute) anywhere in n.v >= 0.1, r >= 0.1; measured against the quadrature at points
// between the nodes. The GPU test's tolerance uses |d(F0 A + B)/d n.v| <= 3 for r >= 0.25:
// checked here on the table's differences.
TEST(SplitSum, TheLookupIsWithinOnePercentBetweenTheNodes) {
  double worst = 0.0;
  for (const double nv : {0.11, 0.27, 0.43, 0.66, 0.97})
    for (const double r : {0.12, 0.29, 0.55, 0.83}) {
      const glm::vec2 ab = dfg_lookup(float(nv), float(r));
      const glm::dvec2 q = sss::testing::ggx_albedo_quadrature(nv, r, r < 0.2 ? 4800 : 1600, 1200);
      for (int k = 0; k < 2; ++k) {
        EXPECT_NEAR(ab[k], q[k], 0.01) << "n.v " << nv << " r " << r << (k ? " B" : " A");
        worst = std::max(worst, std::fabs(ab[k] - q[k]));
      }
    }
  std::printf("[ dfg lookup ] worst |lookup - quadrature| %.4f\n", worst);
  double slope = 0.0;
  const std::vector<glm::vec2>& t = dfg_table();
  for (int j = 0; j < kDfgSize; ++j) {
    if ((j + 0.5) / kDfgSize < 0.25) continue;
    for (int i = 0; i + 1 < kDfgSize; ++i)
      for (const double f0 : {0.0, 0.04, 1.0}) {
        const glm::vec2 a = t[std::size_t(j) * kDfgSize + i], b = t[std::size_t(j) * kDfgSize + i + 1];
        slope = std::max(slope, std::fabs(f0 * (b.x - a.x) + (b.y - a.y)) * kDfgSize);
      }
  }
  EXPECT_LE(slope, 3.0);
  std::printf("[ dfg ] largest |d(F0 A + B)/d n.v| at r >= 0.25: %.3f\n", slope);
}

// A uniform sky, given as a uniform sky and as a constant image (which goes through the
// quadrature): every lobe average is the constant, to float rounding of the normalised
// weights (4 ulp).
TEST(SplitSum, AUniformSkyIsItsOwnLobeAverageAtEveryLevel) {
  const glm::vec3 colour(0.6f, 1.2f, 2.4f);
  const Environment given = uniform_environment({0.3f, 0.6f, 1.2f}, 2.0f);
  std::vector<float> rgba(std::size_t(300) * 150 * 4, 1.0f);
  for (std::size_t i = 0; i < rgba.size(); i += 4)
    for (int c = 0; c < 3; ++c) rgba[i + c] = colour[c];
  const Environment image = image_environment("constant", 300, 150, rgba);
  for (const Environment* e : {&given, &image}) {
    ASSERT_EQ(e->specular.size(), std::size_t(kSpecularWidth) * kSpecularHeight * kSpecularLevels);
    for (const float r : {0.0f, 0.13f, 0.5f, 0.77f, 1.0f})
      for (const glm::vec3 d : {glm::vec3(0, 1, 0), glm::vec3(0.3f, -0.2f, 0.9f), glm::vec3(-1, 0, 0)}) {
        const glm::vec3 l = e->specular_radiance(glm::normalize(d), r);
        for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(l[c], colour[c]) << e->source << " r " << r;
      }
  }
}

// The lobe's mean direction: with n = v = R the weight of l is D(h) (R.l), h halfway, so
// its mean of R.l is c = int D(cos(t/2)) cos^2 t sin t dt / int D(cos(t/2)) cos t sin t dt
// over t in [0, pi/2] (by symmetry about R every other component averages to 0), and a
// sky a + b y prefilters to a + b c R.y. (The lobe's scale a2/pi cancels.)
double lobe_mean_cosine(double roughness) {
  const double alpha = std::max(roughness * roughness, 1e-3), a2 = alpha * alpha;
  const int n = 200000;
  double num = 0.0, den = 0.0;
  for (int i = 0; i < n; ++i) {
    const double t = (i + 0.5) * 0.5 * kPi / n;
    const double nh = std::cos(0.5 * t), dd = nh * nh * (a2 - 1.0) + 1.0;
    const double w = std::cos(t) * std::sin(t) / (dd * dd);
    num += w * std::cos(t);
    den += w;
  }
  return num / den;
}

Environment linear_sky(float a, float b, int w, int h) {
  std::vector<float> rgba(std::size_t(w) * h * 4, 1.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      // The pixel's mean of cos(theta) over its rows' band: a box-averaged image of the sky.
      const double t0 = kPi * y / h, t1 = kPi * (y + 1) / h;
      const double mean_y = 0.5 * (std::sin(t1) * std::sin(t1) - std::sin(t0) * std::sin(t0)) /
                            (std::cos(t0) - std::cos(t1));
      for (int c = 0; c < 3; ++c) rgba[(std::size_t(y) * w + x) * 4 + c] = float(a + b * mean_y);
    }
  return image_environment("linear", w, h, rgba);
}

// Tolerance per level k (texel angle dk = pi / max(kSpecularHeight >> k, 16) of its own grid,
// d0 of the lookup's): the lobe average is computed over texels of level k - 1's grid,
// each standing for its solid angle's mean of the (linear) sky, so the discrete lobe's
// mean direction can sit up to half a source texel off the continuous one (b sin(d_{k-1}/2));
// then two bilinear steps (the level onto the 128 x 64 grid, the lookup) each add at most
// the interpolated function's curvature, b d^2 / 8 with d the step's texel angle. Level 0
// is the sky itself: its box average onto the grid (within b d0^2 / 8 of the centre value
// for a band of height d0 around a cos) and the lookup's bilinear step.
TEST(SplitSum, ALinearSkyPrefiltersToItsLobesMeanDirection) {
  const float a = 0.5f, b = 0.4f;
  const Environment e = linear_sky(a, b, 256, 128);
  for (int k = 0; k < kSpecularLevels; ++k) {
    const double r = double(k) / (kSpecularLevels - 1);
    const double c = lobe_mean_cosine(r);
    const double dk = kPi / std::max(kSpecularHeight >> k, 16), d0 = kPi / kSpecularHeight;
    const double dsrc = k == 0 ? 0.0 : kPi / std::max(kSpecularHeight >> (k - 1), 16);
    const double tol = b * (std::sin(0.5 * dsrc) + dk * dk / 8.0 + d0 * d0 / 8.0) + 1e-6;
    double worst = 0.0;
    for (int i = 0; i < 400; ++i) {
      const double y = 1.0 - 2.0 * (i + 0.5) / 400, s = std::sqrt(1.0 - y * y), phi = 2.399963 * i;
      const glm::vec3 d(float(s * std::cos(phi)), float(y), float(s * std::sin(phi)));
      const double got = e.specular_radiance(d, float(r)).x;
      const double expected = a + b * c * y;
      EXPECT_NEAR(got, expected, tol) << "level " << k << " direction " << i;
      worst = std::max(worst, std::fabs(got - expected) / tol);
    }
    std::printf("[ prefilter level %d, r %.1f ] c %.4f, worst err/tol %.3f (tol %.2e)\n", k, r, c, worst, tol);
  }
}

}  // namespace
}  // namespace sss::scene
