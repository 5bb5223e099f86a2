#include "profiles/BetterDipole.h"
#include "profiles/ClassicalDipole.h"
#include "profiles/Fresnel.h"
#include "profiles/Integrate.h"
#include "profiles/Presets.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace sss::profiles;

namespace {
template <class P>
double numeric_total(const P& p) {
  return integrate_radial([&](double r) { return p.reflectance(r); }, p.inner_radius(),
                          p.support_radius());
}
}  // namespace

TEST(ClassicalDipole, TotalMatchesJensenClosedForm) {
  // Jensen 2001 eq. 5 written out independently of the implementation's form.
  for (const Preset& p : presets()) {
    const Medium m = preset_medium(p);
    if (m.validate()) continue;
    for (int c = 0; c < 3; ++c) {
      const Coefficients k = m.channel(c);
      const double a = k.albedo_reduced();
      const double fdr = fresnel_diffuse_reflectance_fit(k.eta);
      const double A = (1 + fdr) / (1 - fdr);
      const double s = std::sqrt(3.0 * (1.0 - a));
      const double rd = 0.5 * a * (1.0 + std::exp(-4.0 / 3.0 * A * s)) * std::exp(-s);
      EXPECT_NEAR(ClassicalDipole(k).total_reflectance(), rd, 1e-13) << p.name << c;
    }
  }
}

TEST(ClassicalDipole, ProfileIntegratesToItsTotal) {
  // Gauss–Legendre on geometric panels: measured agreement 1e-12; tolerance 1e-9.
  for (const Preset& p : presets()) {
    const Medium m = preset_medium(p);
    if (m.validate()) continue;
    for (int c = 0; c < 3; ++c) {
      ClassicalDipole d(m.channel(c));
      EXPECT_NEAR(numeric_total(d) / d.total_reflectance(), 1.0, 1e-9) << p.name << c;
    }
  }
}

TEST(ClassicalDipole, JensenTableDiffuseReflectance) {
  // Jensen et al. 2001 print the diffuse reflectance to two decimals. Their values come
  // from a variant we cannot reproduce exactly (they differ from eq. 5 at η = 1.3 by up
  // to 0.026, chicken1 blue, the lowest albedo); high-albedo media agree to rounding.
  // Tolerance: 0.03 each, and a mean absolute deviation below 0.008 (measured 0.0045),
  // which a wrong A, source depth or missing α' (errors of 0.05-0.3) would break.
  double sum = 0.0;
  int n = 0;
  for (const Preset& p : presets()) {
    const Medium m = preset_medium(p);
    if (m.validate()) continue;
    for (int c = 0; c < 3; ++c) {
      const double d = ClassicalDipole(m.channel(c)).total_reflectance();
      EXPECT_NEAR(d, p.published_reflectance[c], 0.03) << p.name << " channel " << c;
      sum += std::fabs(d - p.published_reflectance[c]);
      ++n;
    }
  }
  EXPECT_LT(sum / n, 0.008);
}

TEST(BetterDipole, ProfileIntegratesToItsTotal) {
  for (const Preset& p : presets()) {
    const Medium m = preset_medium(p);
    if (m.validate()) continue;
    for (int c = 0; c < 3; ++c) {
      BetterDipole d(m.channel(c));
      EXPECT_NEAR(numeric_total(d) / d.total_reflectance(), 1.0, 1e-9) << p.name << c;
    }
  }
}

TEST(BetterDipole, IndexMatchedLimitIsTheExtrapolatedBoundaryDipole) {
  // At η = 1 the Fresnel moments vanish up to the fit's error (2e-3), so Cφ = 1/4,
  // CE = 1/2, z_e = 2D. Compare with those constants written out.
  const Coefficients k{0.05, 1.0, 0.0, 1.0};
  const DipoleTerms t = DipoleTerms::make(k);
  const double D = (2 * 0.05 + 1.0) / (3 * 1.05 * 1.05);
  EXPECT_NEAR(t.D, D, 1e-15);
  EXPECT_NEAR(t.c_phi, 0.25, 2e-3);
  EXPECT_NEAR(t.c_e, 0.5, 4e-3);
  EXPECT_NEAR(t.z_e / (2 * D), 1.0, 2e-2);
}

TEST(Dipoles, FiniteAtTheOriginAndDecreasing) {
  const Coefficients k{0.032, 0.74, 0.0, 1.3};
  ClassicalDipole cd(k);
  BetterDipole bd(k);
  double prev_c = cd.reflectance(0.0), prev_b = bd.reflectance(0.0);
  EXPECT_TRUE(std::isfinite(prev_c));
  EXPECT_TRUE(std::isfinite(prev_b));
  for (double r = 0.01; r < 200.0; r *= 1.3) {
    EXPECT_LT(cd.reflectance(r), prev_c);
    EXPECT_LT(bd.reflectance(r), prev_b);
    prev_c = cd.reflectance(r);
    prev_b = bd.reflectance(r);
  }
  EXPECT_GE(cd.reflectance(1e6), 0.0);
}
