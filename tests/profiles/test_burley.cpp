#include "profiles/BetterDipole.h"
#include "profiles/Burley.h"
#include "profiles/Integrate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

using namespace sss::profiles;

namespace {
constexpr double kPi = std::numbers::pi;
// Skin1 red (Jensen et al. 2001) and a few albedos with ℓ = 1 mm.
const Coefficients kSkin1Red{0.032, 0.74, 0.0, 1.3};
}  // namespace

TEST(Burley, ScaleFitAtHandComputedAlbedos) {
  // s = 1.85 - A + 7|A - 0.8|³ by hand: A = 0.8 → 1.05; 0.5 → 1.35 + 7·0.027 = 1.539;
  // 0.2 → 1.65 + 7·0.216 = 3.162; 1 → 0.85 + 7·0.008 = 0.906; 0 → 1.85 + 7·0.512 = 5.434.
  // Exact decimals, so only rounding (a few ulps) separates them: tolerance 1e-14.
  EXPECT_NEAR(burley_scale(0.8), 1.05, 1e-14);
  EXPECT_NEAR(burley_scale(0.5), 1.539, 1e-14);
  EXPECT_NEAR(burley_scale(0.2), 3.162, 1e-14);
  EXPECT_NEAR(burley_scale(1.0), 0.906, 1e-14);
  EXPECT_NEAR(burley_scale(0.0), 5.434, 1e-14);
  // d = ℓ/s.
  EXPECT_NEAR(Burley(0.5, 2.0).scale_d(), 2.0 / 1.539, 1e-14);
}

TEST(Burley, ProfileIntegratesToTheSurfaceAlbedo) {
  // ∫2πr R dr = A. Tolerance 1e-9 A: the tail beyond support_radius = 70 d holds
  // ¼e^{-70} + ¾e^{-70/3} = 5.5e-11; the clamp r → max(r, 1e-9 d) misses at most
  // 2.5e-10 (Burley.cpp); 2πr R is smooth (two exponentials), so Gauss–Legendre on
  // geometric panels adds rounding only. Sum: 3.1e-10 < 1e-9.
  for (double A : {0.05, 0.3, 0.6, 0.8, 0.95}) {
    for (double mfp : {0.1, 1.0, 7.0}) {
      const Burley b(A, mfp);
      const double total = integrate_radial([&](double r) { return b.reflectance(r); },
                                            b.inner_radius(), b.support_radius());
      EXPECT_NEAR(total, A, 1e-9 * A) << "A " << A << " mfp " << mfp;
      EXPECT_EQ(b.total_reflectance(), A);
    }
  }
}

TEST(Burley, CdfMatchesNumericalIntegration) {
  // CDF(r) = ∫_0^r 2πr' R dr' / A = 1 - ¼e^{-r/d} - ¾e^{-r/3d} (Christensen & Burley 2015,
  // eq. 11). Same error budget as above without the tail: 2.5e-10 + rounding < 1e-9.
  const Burley b(0.7, 1.5);
  const double d = b.scale_d();
  for (double x : {0.01, 0.1, 0.5, 1.0, 3.0, 10.0, 30.0}) {
    const double r = x * d;
    const double numeric =
        integrate_log([&](double s) { return 2.0 * kPi * s * b.reflectance(s); }, 0.1 * d, r) /
        0.7;
    const double cdf = 1.0 - 0.25 * std::exp(-r / d) - 0.75 * std::exp(-r / (3.0 * d));
    EXPECT_NEAR(numeric, cdf, 1e-9) << "r/d " << x;
  }
}

TEST(Burley, MediumConstructorUsesBetterDipoleAlbedoAndReducedMfp) {
  // Burley(c) is Burley(A = better dipole total, ℓ = 1/σt'): the same arithmetic, so the
  // profiles agree to the last bit.
  const Burley from_medium(kSkin1Red);
  const Burley direct(BetterDipole(kSkin1Red).total_reflectance(), kSkin1Red.mfp_reduced());
  EXPECT_EQ(from_medium.total_reflectance(), direct.total_reflectance());
  EXPECT_EQ(from_medium.scale_d(), direct.scale_d());
  for (double r : {0.0, 0.01, 0.3, 1.0, 4.0, 20.0})
    EXPECT_EQ(from_medium.reflectance(r), direct.reflectance(r)) << r;
  // Similarity: g = 0.5 with twice the scattering has the same σs', hence the same A (the
  // better dipole depends on reduced quantities only) and the same ℓ = 1/σt'.
  const Burley forward({0.032, 1.48, 0.5, 1.3});
  EXPECT_NEAR(forward.total_reflectance() / from_medium.total_reflectance(), 1.0, 1e-14);
  EXPECT_NEAR(forward.scale_d() / from_medium.scale_d(), 1.0, 1e-14);
}

TEST(Burley, ShapeAndFiniteness) {
  const Burley b(kSkin1Red);
  EXPECT_GT(b.total_reflectance(), 0.0);
  EXPECT_LT(b.total_reflectance(), 1.0);
  // At r = 0 the clamp gives R(1e-9 d) = A(e^{-1e-9} + e^{-1e-9/3})/(8π d·1e-9 d): finite.
  const double d = b.scale_d();
  const double r0 = b.total_reflectance() * 2.0 / (8.0 * kPi * d * 1e-9 * d);
  EXPECT_TRUE(std::isfinite(b.reflectance(0.0)));
  EXPECT_NEAR(b.reflectance(0.0) / r0, 1.0, 1e-8);  // e^{-1e-9} differs from 1 by 1e-9
  double prev = b.reflectance(0.0);
  for (double r = 1e-6; r < b.support_radius(); r *= 1.5) {
    const double v = b.reflectance(r);
    EXPECT_LT(v, prev) << r;  // strictly decreasing
    prev = v;
  }
  // r R(r) at the support radius is below 1e-8 of its value at r → 0 (A/(4πd)).
  const double rs = b.support_radius();
  EXPECT_LT(rs * b.reflectance(rs), 1e-8 * b.total_reflectance() / (4.0 * kPi * d));
  EXPECT_EQ(b.reflectance(1e300), 0.0);
}

TEST(Burley, RejectsBadParameters) {
  EXPECT_THROW(Burley(-0.1, 1.0), std::invalid_argument);
  EXPECT_THROW(Burley(1.1, 1.0), std::invalid_argument);
  EXPECT_THROW(Burley(0.5, 0.0), std::invalid_argument);
  EXPECT_THROW(Burley(0.5, std::nan("")), std::invalid_argument);
  EXPECT_THROW(Burley(Coefficients{0.0, 1.0, 0.0, 1.3}), std::invalid_argument);
}
