#include "profiles/Fresnel.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace sss::profiles;

TEST(Fresnel, NormalIncidenceClosedForm) {
  for (double eta : {1.0, 1.3, 1.5, 2.4, 0.75}) {
    const double f0 = (eta - 1.0) / (eta + 1.0);
    EXPECT_NEAR(fresnel_dielectric(1.0, eta), f0 * f0, 1e-15) << "eta " << eta;
  }
}

TEST(Fresnel, TotalInternalReflectionAndGrazing) {
  // From inside η = 1.5 (relative index 1/1.5) the critical cosine is √(1 - 1/1.5²).
  const double mu_c = std::sqrt(1.0 - 1.0 / (1.5 * 1.5));
  EXPECT_EQ(fresnel_dielectric(mu_c * 0.999, 1.0 / 1.5), 1.0);
  EXPECT_LT(fresnel_dielectric(mu_c * 1.01, 1.0 / 1.5), 1.0);
  EXPECT_NEAR(fresnel_dielectric(1e-9, 1.5), 1.0, 1e-8);  // grazing reflects everything
}

TEST(Fresnel, IndexMatchedBoundaryIsInvisible) {
  for (double mu : {0.01, 0.3, 0.9}) EXPECT_NEAR(fresnel_dielectric(mu, 1.0), 0.0, 1e-15);
  EXPECT_NEAR(fresnel_moment(1, 1.0), 0.0, 1e-15);
  EXPECT_NEAR(fresnel_moment(2, 1.0), 0.0, 1e-15);
}

TEST(Fresnel, MomentsClosedFormForTotalReflection) {
  // The TIR part alone: for η → ∞ every direction but normal reflects, so m_i → 1/(i+1).
  EXPECT_NEAR(fresnel_moment(1, 1e4), 0.5, 1e-3);
  EXPECT_NEAR(fresnel_moment(2, 1e4), 1.0 / 3.0, 1e-3);
}

TEST(Fresnel, NumericalMomentsConverged) {
  // Two independent quadratures of the same integral: the module's (substitution
  // μ = μc + (1-μc)s², 8×32 points) and a brute-force midpoint rule with 2e6 points,
  // whose error for a function with a √ kink is O(h^1.5) ≈ 1e-9.
  for (double eta : {0.8, 1.3, 1.5}) {
    for (int i = 1; i <= 2; ++i) {
      const int n = 2000000;
      double s = 0.0;
      for (int k = 0; k < n; ++k) {
        const double mu = (k + 0.5) / n;
        s += fresnel_dielectric(mu, 1.0 / eta) * std::pow(mu, i);
      }
      EXPECT_NEAR(fresnel_moment(i, eta), s / n, 1e-8) << "eta " << eta << " i " << i;
    }
  }
}

TEST(Fresnel, PublishedFitsMatchNumericalMoments) {
  // d'Eon's polynomial fits are accurate to about 1e-3 over η ∈ [0.7, 2]; the largest gap
  // measured here is 1.5e-3 (m2 at η = 1.1) and 2.2e-3 at η = 1 exactly, where the
  // polynomial does not reach zero. Tolerance 2.5e-3.
  for (double eta = 0.7; eta <= 2.0001; eta += 0.05) {
    EXPECT_NEAR(fresnel_moment1_fit(eta), fresnel_moment(1, eta), 2.5e-3) << eta;
    EXPECT_NEAR(fresnel_moment2_fit(eta), fresnel_moment(2, eta), 2.5e-3) << eta;
  }
}

TEST(Fresnel, GroenhuisFitTracksTwiceTheFirstMoment) {
  // Fdr (Groenhuis 1983) is the hemispherical internal reflectance 2∫Fr μ dμ; the fit is
  // good to ~1% of the value for η ∈ [1.2, 1.6] (measured max 0.6%): tolerance 1.5%.
  for (double eta : {1.2, 1.3, 1.4, 1.5, 1.6}) {
    const double exact = 2.0 * fresnel_moment(1, eta);
    EXPECT_NEAR(fresnel_diffuse_reflectance_fit(eta), exact, 0.015 * exact) << eta;
  }
}

TEST(Fresnel, ExitFactorCarriesTheExitanceOut) {
  // The exit lobe F_t(η, θ) / (c π) must integrate against cos θ over the outside
  // hemisphere to 1, so that M F_t / (c π) leaves exactly the exitance M (issue 18 part 1).
  // Checked by a plain midpoint rule in θ (dω = 2π sin θ dθ), independent of the
  // Gauss–Legendre moment behind c: 200000 cells give the integral to ~1e-9, far inside
  // the 1e-6 tolerance.
  for (double eta : {1.0, 1.2, 1.33, 1.4, 1.55, 2.0}) {
    const double c = fresnel_exit_normalization(eta);
    const int n = 200000;
    const double h = (M_PI / 2.0) / n;
    double s = 0.0;
    for (int k = 0; k < n; ++k) {
      const double theta = (k + 0.5) * h;
      s += fresnel_transmittance(std::cos(theta), eta) * std::cos(theta) * std::sin(theta);
    }
    EXPECT_NEAR(2.0 * M_PI * s * h / (c * M_PI), 1.0, 1e-6) << "eta " << eta;
  }
  // pbrt-v3's value at η = 1.4, 1 - 2 FresnelMoment1(1/1.4) (research notes §3.4): the
  // published figure has 5 digits, and pbrt's polynomial fit is good to ~2e-3 in m1, so
  // the two agree to 5e-3.
  EXPECT_NEAR(fresnel_exit_normalization(1.4), 0.92321, 5e-3);
  EXPECT_DOUBLE_EQ(fresnel_exit_normalization(1.0), 1.0);
}

TEST(Fresnel, TransmittanceIsReciprocal) {
  // Light leaving the medium into the outside direction θo crosses with the same
  // transmittance as light entering from θo (Stokes relations): the exit factor may use the
  // outside angle. Inside, the refracted cosine; exact to rounding.
  for (double eta : {1.3, 1.4, 1.6})
    for (double cos_o : {1.0, 0.8, 0.5, 0.2, 0.05}) {
      const double sin_t = std::sqrt(1.0 - cos_o * cos_o) / eta;
      const double cos_inside = std::sqrt(1.0 - sin_t * sin_t);
      EXPECT_NEAR(fresnel_transmittance(cos_o, eta), 1.0 - fresnel_dielectric(cos_inside, 1.0 / eta), 1e-12)
          << eta << " " << cos_o;
    }
}
