// Chandrasekhar's H-function for isotropic scattering: published values, exact
// identities, and the small-albedo expansion.
#include "profiles/HFunction.h"
#include "profiles/Integrate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace sss::profiles {
namespace {

// ∫0^1 f(μ) dμ with μ = t² (H has a μ ln μ kink at 0 that this smooths), composite
// Gauss–Legendre: 64 panels of 16 points. Halving the panels changes the results below
// by < 1e-14 (checked while writing the test), so this rule contributes nothing at the
// tolerances used.
template <class F>
double integrate_unit(F f) {
  return integrate([&](double t) { return f(t * t) * 2.0 * t; }, 0.0, 1.0, 64, 16);
}

// The solver's own quadrature error is ~1e-14 (64 nodes agree with 128 to that, see
// HFunction.cpp); summing ~1000 terms of size ~1 adds rounding ~1000 · 1.1e-16 ≈ 1e-13.
// 1e-10 leaves a factor of ~1000 for other compilers and libm, and is still 100 times
// tighter than the 1e-8 the design asks for.
constexpr double kIdentityTol = 1e-10;

TEST(HFunction, PublishedTotalReflectance) {
  // Published five-decimal values of 1 - H(1)√(1-α), the exact total reflectance of an
  // index-matched isotropic half-space (as quoted in the project's brief for this
  // module). Rounded to 5 decimals they are exact to ±5e-6; 5e-5 (one unit of the last
  // published digit) is the tolerance the brief states.
  EXPECT_NEAR(exact_total_reflectance_index_matched(0.9), 0.41495, 5e-5);
  EXPECT_NEAR(exact_total_reflectance_index_matched(0.99), 0.75272, 5e-5);
}

TEST(HFunction, ConservativeHOfOne) {
  // α = 1: H(1) = 2.9078 (Chandrasekhar 1960, "Radiative Transfer", table of H for
  // ϖ0 = 1), ±5e-5 for the rounding of the last published digit. At α = 1 the total
  // reflectance is exactly 1 (nothing is absorbed in a half-space).
  EXPECT_NEAR(chandrasekhar_h(1.0, 1.0), 2.9078, 5e-5);
  EXPECT_NEAR(exact_total_reflectance_index_matched(1.0), 1.0, 1e-15);
}

TEST(HFunction, ZerothMomentIdentity) {
  // Integrating the H equation over μ gives h0 = 1 + (α/2) h0² for h0 = ∫0^1 H dμ
  // (Chandrasekhar 1960, ch. V), whose root that tends to 1 as α -> 0 is
  // h0 = (2/α)(1 - √(1 - α)). The integral here uses chandrasekhar_h at arbitrary μ, so
  // this also checks the Nyström interpolation between the solver's nodes.
  for (double albedo : {0.1, 0.5, 0.9, 0.99, 0.9999, 1.0}) {
    const double h0 = integrate_unit([&](double mu) { return chandrasekhar_h(mu, albedo); });
    const double exact = 2.0 / albedo * (1.0 - std::sqrt(1.0 - albedo));
    EXPECT_NEAR(h0, exact, kIdentityTol) << "albedo " << albedo;
  }
}

TEST(HFunction, SatisfiesTheOriginalEquation) {
  // The solver uses 1/H = √(1-α) + (α/2)∫μ'H/(μ+μ'); check the other form,
  // H = 1 + (α/2) μ H ∫ H(μ')/(μ+μ') dμ', at points between the solver's nodes.
  for (double albedo : {0.5, 0.99, 1.0}) {
    for (double mu : {0.05, 0.3, 0.77, 1.0}) {
      const double h = chandrasekhar_h(mu, albedo);
      const double integral = integrate_unit(
          [&](double m) { return chandrasekhar_h(m, albedo) / (mu + m); });
      EXPECT_NEAR(h, 1.0 + 0.5 * albedo * mu * h * integral, kIdentityTol)
          << "albedo " << albedo << " mu " << mu;
    }
  }
}

TEST(HFunction, HOfZeroIsOne) {
  // The equation gives H(0) = 1 exactly for every α.
  for (double albedo : {1e-6, 0.5, 0.99, 1.0})
    EXPECT_NEAR(chandrasekhar_h(0.0, albedo), 1.0, kIdentityTol) << "albedo " << albedo;
}

TEST(HFunction, TendsToOneWithTheRightSlope) {
  // Expanding H = 1 + α h1 + α² h2 + ... in the equation:
  //   h1(μ) = (μ/2) ln((1 + μ)/μ),
  //   h2(μ) = h1(μ)² + (μ/2) ∫ h1(μ')/(μ+μ') dμ'
  //         <= h1(μ) (h1(μ) + max h1) <= 0.7 h1(μ),
  // since h1 increases with μ to h1(1) = ln(2)/2 < 0.35. Every h_k >= 0 and
  // Σ h_k = H(μ, α = 1) <= 2.91, so h_k <= 2.91 and the terms past α² sum to at most
  // 2.91 α³ / (1 - α). Hence |H - 1 - α h1| <= 0.7 α² h1 + 2.91 α³/(1 - α) (+ 1e-15 for
  // rounding).
  const double albedo = 1e-3;
  for (double mu : {0.01, 0.2, 0.5, 1.0}) {
    const double h1 = 0.5 * mu * std::log((1.0 + mu) / mu);
    const double bound =
        0.7 * albedo * albedo * h1 + 2.91 * albedo * albedo * albedo / (1.0 - albedo) + 1e-15;
    EXPECT_NEAR(chandrasekhar_h(mu, albedo), 1.0 + albedo * h1, bound) << "mu " << mu;
    // and the first-order term really is there (so the bound is not vacuous):
    EXPECT_GT(chandrasekhar_h(mu, albedo) - 1.0, 0.5 * albedo * h1);
  }
}

TEST(HFunction, RejectsBadArguments) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (double albedo : {0.0, -0.1, 1.5, nan}) {
    EXPECT_THROW(chandrasekhar_h(0.5, albedo), std::invalid_argument) << albedo;
    EXPECT_THROW(exact_total_reflectance_index_matched(albedo), std::invalid_argument);
  }
  for (double mu : {-0.1, 1.1, nan}) EXPECT_THROW(chandrasekhar_h(mu, 0.5), std::invalid_argument);
}

}  // namespace
}  // namespace sss::profiles
