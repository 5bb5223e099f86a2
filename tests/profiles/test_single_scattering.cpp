// Planar single scattering (profiles/SingleScattering.h, issue 18 part 2) against the
// analog walk's once-scattered paths (MonteCarlo with max_scattering_order = 1), binned by
// exit angle, at several angles of incidence, isotropic and anisotropic: an independent
// computation (the walk samples free paths, Henyey–Greenstein directions and Fresnel
// escapes; the closed form integrates depth analytically and azimuth by quadrature).
#include "profiles/Fresnel.h"
#include "profiles/MonteCarlo.h"
#include "profiles/SingleScattering.h"

#include "profiles/Integrate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

using namespace sss::profiles;

TEST(SingleScattering, IndexMatchedIsotropicTotalIsTheClassicalClosedForm) {
  // η = 1, g = 0, normal incidence: the once-scattered reflectance of a half space is
  // α (1 - ln 2)/2 (the depth integral gives α μo/(2(1 + μo)) per unit μo; Chandrasekhar's
  // first-order term). Quadrature to 1e-9.
  const Coefficients c{0.2, 0.8, 0.0, 1.0};
  const double total = integrate([&](double mu) { return single_scattering_exit_density(c, 1.0, mu); }, 0.0, 1.0, 16, 16);
  EXPECT_NEAR(total, 0.8 * (1.0 - std::numbers::ln2) / 2.0, 1e-9);
  // Reciprocity of the BRDF-like factor: f1(ωi, ωo) = f1(ωo, ωi).
  const Coefficients d{0.1, 1.2, 0.7, 1.4};
  for (double a : {0.2, 0.6, 1.0})
    for (double b : {0.1, 0.5, 0.9}) EXPECT_NEAR(single_scattering_brdf(d, a, b, -0.3), single_scattering_brdf(d, b, a, -0.3), 1e-15);
  EXPECT_NEAR(henyey_greenstein(0.0, 0.3), 1.0 / (4.0 * std::numbers::pi), 1e-15);
}

namespace {

struct Case {
  const char* name;
  Coefficients c;
  double cos_i;
};

}  // namespace

// Per configuration: 2^20 photons stopped at their second scattering event, 10 exit-cosine
// bins. Each bin's walk value is compared with the closed form averaged over the bin
// (16-point Gauss–Legendre in μo) by its standard error: |z| <= 4.5 per bin (90 bins in
// all: a false alarm has probability 90 x 6.8e-6 = 6e-4), and the sum of z² over a
// configuration's 10 bins <= 29.6, the chi-square(10) 0.999 quantile. The closed form
// carries no other error (quadrature < 1e-9 relative). A missing 1/η² is 41-49% off, a
// missing exit Fresnel factor 2-100%, the reduced σt' in place of σt 20% and more.
TEST(SingleScattering, MatchesTheAnalogWalksOnceScatteredExitsByAngle) {
  const Case cases[] = {
      {"skin1 red, normal", {0.032, 0.74, 0.0, 1.3}, 1.0},
      {"skin1 red, 60 deg", {0.032, 0.74, 0.0, 1.3}, 0.5},
      {"skin1 red, 80 deg", {0.032, 0.74, 0.0, 1.3}, std::cos(80.0 * std::numbers::pi / 180.0)},
      {"ketchup-like blue, normal", {0.6, 0.2, 0.0, 1.3}, 1.0},
      {"ketchup-like blue, 70 deg", {0.6, 0.2, 0.0, 1.3}, std::cos(70.0 * std::numbers::pi / 180.0)},
      {"g 0.8, normal", {0.05, 2.0, 0.8, 1.4}, 1.0},
      {"g 0.8, 45 deg", {0.05, 2.0, 0.8, 1.4}, std::cos(45.0 * std::numbers::pi / 180.0)},
      {"g -0.3, 30 deg", {0.05, 1.0, -0.3, 1.4}, std::cos(30.0 * std::numbers::pi / 180.0)},
      {"g 0.5, eta 1, 50 deg", {0.1, 1.0, 0.5, 1.0}, std::cos(50.0 * std::numbers::pi / 180.0)},
  };
  constexpr int kBins = 10;
  for (const Case& k : cases) {
    MonteCarloOptions o;
    o.photons = 1u << 20;
    o.seed = 11;
    o.max_scattering_order = 1;
    o.incidence_cos = k.cos_i;
    o.exit_cosine_bins = kBins;
    const MonteCarloResult r = run_monte_carlo(k.c, o);
    ASSERT_EQ(r.reflectance_by_exit_cosine.value.size(), std::size_t(kBins));
    double chi2 = 0.0, closed_total = 0.0;
    for (int b = 0; b < kBins; ++b) {
      const double lo = double(b) / kBins, hi = double(b + 1) / kBins;
      const double expected =
          integrate([&](double mu) { return single_scattering_exit_density(k.c, k.cos_i, mu); }, lo, hi, 1, 16) * kBins;
      closed_total += expected / kBins;
      const double got = r.reflectance_by_exit_cosine.value[std::size_t(b)];
      const double se = r.reflectance_by_exit_cosine.stderr_[std::size_t(b)];
      ASSERT_GT(se, 0.0) << k.name << " bin " << b;
      const double z = (got - expected) / se;
      chi2 += z * z;
      EXPECT_LE(std::fabs(z), 4.5) << k.name << " bin " << b << ": walk " << got << " closed form " << expected;
    }
    EXPECT_LE(chi2, 29.6) << k.name;
    std::printf("[ %-26s ] once-scattered total: walk %.5f +- %.5f, closed form %.5f; chi2(10) %.1f\n", k.name,
                r.reflectance.total, r.reflectance.total_stderr, closed_total, chi2);
  }
}

TEST(SingleScattering, WalkOptionsAreChecked) {
  const Coefficients c{0.1, 1.0, 0.0, 1.3};
  MonteCarloOptions o;
  o.photons = 8;
  o.incidence_cos = 0.0;
  EXPECT_THROW(run_monte_carlo(c, o), std::invalid_argument);
  o.incidence_cos = std::nan("");
  EXPECT_THROW(run_monte_carlo(c, o), std::invalid_argument);
  o.incidence_cos = 1.0;
  o.exit_cosine_bins = -1;
  try {
    run_monte_carlo(c, o);
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("exit_cosine_bins", 0), 0u) << e.what();
  }
}
