#include "profiles/ClassicalDipole.h"
#include "profiles/EdgeResponse.h"
#include "profiles/Integrate.h"
#include "profiles/Presets.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace sss::profiles;

namespace {

// R(r) = T·G(v, r): a profile whose edge response is known in closed form.
class GaussianProfile final : public RadialProfile {
 public:
  GaussianProfile(double variance, double total) : v_(variance), t_(total) {}
  double reflectance(double r) const override { return t_ * gaussian_2d(v_, r); }
  double total_reflectance() const override { return t_; }
  // 12 standard deviations: the truncated tail holds e^-72 of the energy.
  double support_radius() const override { return 12.0 * std::sqrt(v_); }
  double inner_radius() const override { return std::sqrt(v_); }

 private:
  double v_, t_;
};

GaussianFit single(double variance, double total) {
  GaussianFit f;
  f.variances_mm2 = {variance};
  f.weights = {{total, total, total}};
  f.total_reflectance = {total, total, total};
  return f;
}

Coefficients skin1_red() { return preset_medium(*find_preset("skin1")).channel(0); }

}  // namespace

TEST(EdgeResponse, GaussianClosedFormMatchesNumeric) {
  // The numeric integral (Gauss–Legendre on geometric panels) against ½ erfc(x/√(2v)).
  // Tolerance 1e-8·T (the contract); the truncation at 12σ contributes e^-72.
  for (const double v : {0.05, 1.0, 20.0}) {
    const double T = 0.7, sd = std::sqrt(v);
    const GaussianProfile profile(v, T);
    const GaussianFit fit = single(v, T);
    for (const double k : {1e-6, 0.01, 0.3, 1.0, 2.5, 6.0}) {
      for (const double x : {k * sd, -k * sd}) {
        EXPECT_NEAR(edge_response(profile, x), edge_response(fit, x)[0], 1e-8 * T)
            << "v=" << v << " x=" << x;
      }
    }
  }
}

TEST(EdgeResponse, HalfAtTheEdgeAndTotalDeepInTheLight) {
  const ClassicalDipole d(skin1_red());
  const double T = d.total_reflectance();
  EXPECT_EQ(edge_response(d, 0.0), 0.5 * T);
  EXPECT_EQ(edge_response(d, -d.support_radius()), T);
  EXPECT_EQ(edge_response(d, 2.0 * d.support_radius()), 0.0);
  // Monotone: M decreases with x (R >= 0).
  double previous = T;
  for (double x = -20.0; x <= 20.0; x += 0.25) {
    const double m = edge_response(d, x);
    EXPECT_LE(m, previous) << x;
    previous = m;
  }
  // The closed form of a fit: ½ erfc(0) = ½ exactly, and erfc(-∞) = 2.
  GaussianFit f;
  f.variances_mm2 = {0.1, 1.0, 10.0};
  f.weights = {{0.1, 0.2, 0.3}, {0.2, 0.1, 0.05}, {0.05, 0.05, 0.05}};
  const sss::Rgb half = edge_response(f, 0.0);
  const sss::Rgb all = edge_response(f, -1e3);
  const sss::Rgb none = edge_response(f, 1e3);
  for (int c = 0; c < 3; ++c) {
    const double total = f.weights[0][c] + f.weights[1][c] + f.weights[2][c];
    // Three products and sums: rounding below 4 ulp of the total.
    EXPECT_NEAR(half[c], 0.5 * total, 4e-16 * total);
    EXPECT_NEAR(all[c], total, 4e-16 * total);
    EXPECT_EQ(none[c], 0.0);
  }
}

TEST(EdgeResponse, SlopeAtTheEdgeIsTheMarginalAtZero) {
  // M'(0) = -m(0) with m(0) = ∫ R(|y|) dy = 2∫_0^∞ R(r) dr, and m is even, so
  // M(ε) = T/2 - ε m(0) + O(ε³ m''). With ε = 1e-4·inner radius and m'' ~ m(0)/inner²,
  // the cubic term is ~2e-9 of the linear one; the quadratures' absolute errors (~1e-13·T,
  // with ε m(0) ~ 1e-4·T) add ~1e-9. Tolerance: 1e-6 of the linear term.
  const ClassicalDipole d(skin1_red());
  const double eps = 1e-4 * d.inner_radius();
  const double m0 = 2.0 * integrate_log([&](double r) { return d.reflectance(r); },
                                        d.inner_radius(), d.support_radius());
  const double linear = eps * m0;
  const double T = d.total_reflectance();
  EXPECT_NEAR(0.5 * T - edge_response(d, eps), linear, 1e-6 * linear);
  EXPECT_NEAR(edge_response(d, -eps) - 0.5 * T, linear, 1e-6 * linear);
}

TEST(EdgeResponse, ClassicalDipoleMatchesACartesianDoubleIntegral) {
  // Independent of the acos kernel: for x > 0, M(x) = 2∫_x^S du ∫_0^√(S²-u²) R(√(u²+y²)) dy
  // over the disc r <= S (the same truncation as edge_response), each 1D integral by
  // Gauss–Legendre on geometric panels. Its quadrature error is estimated from two
  // resolutions (5 and 10 panels per decade); the error falls geometrically with the
  // resolution, so the finer one's error is far below their difference, and
  // tolerance = 2·difference + 1e-10·T, the last for edge_response's own quadrature
  // (8 panels per decade of order 16, which matches the Gaussian closed form to < 1e-12).
  const ClassicalDipole d(skin1_red());
  const double S = d.support_radius(), T = d.total_reflectance(), inner = d.inner_radius();
  auto brute = [&](double x, int per_decade) {
    auto column = [&](double u) {
      const double top = std::sqrt(std::max(0.0, S * S - u * u));
      return integrate_log([&](double y) { return d.reflectance(std::sqrt(u * u + y * y)); },
                           std::max(u, inner), top, per_decade, 16);
    };
    return 2.0 * integrate_log([&](double s) { return column(x + s); }, inner, S - x,
                               per_decade, 16);
  };
  for (const double x : {0.1 * inner, inner, 4.0 * inner}) {
    const double coarse = brute(x, 5), fine = brute(x, 10);
    const double tol = 2.0 * std::fabs(coarse - fine) + 1e-10 * T;
    EXPECT_NEAR(edge_response(d, x), fine, tol) << "x=" << x;
  }
}

TEST(EdgeResponse, RgbIsPerChannel) {
  const RgbProfile profile(Model::Dipole, preset_medium(*find_preset("marble")));
  for (const double x : {-1.0, 0.0, 0.3, 2.0}) {
    const sss::Rgb m = edge_response(profile, x);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(m[c], edge_response(profile.channel(c), x));
  }
}
