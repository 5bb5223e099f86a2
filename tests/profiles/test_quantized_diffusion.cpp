// Quantized diffusion (profiles/QuantizedDiffusion.h) against independent computations:
//  - erfcx against published values of ½ erfcx (../shared/research/missing-models.md §1.5,
//    7 digits) across the range where float 1 - erf(x) fails, and its two branches against
//    each other and the asymptote;
//  - the per-Gaussian closed forms: with the published schedule (v0, golden ratio, 45 terms)
//    R(r) must reproduce the research's independently computed 45-term profile (§1.4a, 5
//    digits) and totals (§1.4c, 4 digits);
//  - the model's continuous-time limit: the total of the extended beam source with the
//    improved boundary has a closed form (derived below), which the sum must approach as
//    the time steps shrink; the default schedule must be within 0.5% of it.
#include "profiles/BetterDipole.h"
#include "profiles/GaussianFit.h"
#include "profiles/Integrate.h"
#include "profiles/Presets.h"
#include "profiles/Profile.h"
#include "profiles/QuantizedDiffusion.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

namespace sss::profiles {
namespace {

// ½ erfcx(x) (research §1.5, computed there with arbitrary precision; 7 significant digits).
TEST(Erfcx, MatchesPublishedValuesWhereFloatCancellationFails) {
  const double x[] = {1, 2, 3, 3.5, 3.9, 4.0, 4.4, 4.5, 5, 8};
  const double half[] = {0.2137918,  0.1276978,  0.08950058, 0.07764683, 0.07015709,
                         0.06849973, 0.06257083, 0.06124240, 0.05535232, 0.03499258};
  for (std::size_t i = 0; i < std::size(x); ++i)
    EXPECT_NEAR(0.5 * erfcx(x[i]), half[i], 5e-8 * 1.0001) << "x = " << x[i];  // half a unit of the 7th digit
  EXPECT_EQ(erfcx(0.0), 1.0);
  // What the lecture warns of: in float, exp(x²)(1 - erf(x)) has lost every digit at x = 4.
  const float naive = std::exp(16.0f) * (1.0f - std::erf(4.0f));
  EXPECT_GT(std::fabs(naive - float(erfcx(4.0))), 0.5f * float(erfcx(4.0)));
}

TEST(Erfcx, BranchesAgreeAndFollowTheAsymptote) {
  // Below 26 exp(x²) erfc(x), above it the series: continuous across the switch to the
  // series' truncation (< 2e-15) plus exp(x²)'s rounding (x² ≈ 676 carries 676 x 1.1e-16).
  const double below = erfcx(std::nextafter(26.0, 0.0)), above = erfcx(26.0);
  EXPECT_NEAR(below, above, 2e-13 * above);
  // x √π erfcx(x) = 1 - 1/(2x²) + 3/(4x⁴) - ...: at x = 1e3 and 1e8 to double precision.
  for (double xl : {1e3, 1e8}) {
    const double expect = 1.0 - 0.5 / (xl * xl) + 0.75 / (xl * xl * xl * xl);
    EXPECT_NEAR(xl * std::sqrt(std::numbers::pi) * erfcx(xl), expect, 4e-16) << xl;
  }
  EXPECT_THROW(erfcx(-1.0), std::invalid_argument);
  EXPECT_THROW(erfcx(std::nan("")), std::invalid_argument);
}

QdSchedule published() {
  QdSchedule s;
  s.ratio = (1.0 + std::sqrt(5.0)) / 2.0;
  s.fixed_terms = 45;
  s.first_step_scale = 1.0;
  return s;
}

// Research §1.4(a): σs = 1, σa = 0.01, g = 0, η = 1.4, 45 terms of the published schedule;
// R in mm⁻², 5 significant digits (so within half a unit of the 5th).
TEST(QuantizedDiffusion, PublishedScheduleReproducesTheIndependentProfile) {
  const QuantizedDiffusion qd({0.01, 1.0, 0.0, 1.4}, published());
  ASSERT_EQ(qd.terms().size(), 45u);
  const double r[] = {0.05, 0.10, 0.25, 0.5, 1, 2, 4, 8};
  const double R[] = {4.2846e-1, 2.6248e-1, 9.3974e-2, 4.5237e-2, 2.0313e-2, 7.8676e-3, 2.2115e-3, 3.4550e-4};
  for (std::size_t i = 0; i < std::size(r); ++i)
    EXPECT_NEAR(qd.reflectance(r[i]), R[i], 5e-5 * R[i] + 1e-12) << "r = " << r[i];
}

// The total of the continuous model (the same integrals without quantizing time): a unit
// point source at depth z with its negative image 2 z_b lower sends through the plane
// φ_tot = (e^{-σtr z} - e^{-σtr(z + d_e)})/(2Dσtr) and E_tot = (e^{-σtr z} + e^{-σtr(z + d_e)})/2;
// the beam α'σ e^{-σz} (σ = σt') weighs e^{-σtr z} by α'σ/(σ + σtr), so
// R_tot = α'² σ/(σ + σtr) [Cφ (1 - e^{-σtr d_e})/(2Dσtr) + CE (1 + e^{-σtr d_e})/2].
double continuous_total(const Coefficients& c) {
  const DipoleTerms t = DipoleTerms::make(c);
  const double s = c.sigma_t_reduced(), str = t.sigma_tr, de = 2.0 * t.z_e, ap = c.albedo_reduced();
  return ap * ap * s / (s + str) *
         (t.c_phi * -std::expm1(-str * de) / (2.0 * t.D * str) + t.c_e * (1.0 + std::exp(-str * de)) / 2.0);
}

TEST(QuantizedDiffusion, ContinuousTotalIsTheResearchValue) {
  // §1.4(c): α' = 0.9, η = 1.4, σt' = 1 gives 0.236379 (6 digits).
  EXPECT_NEAR(continuous_total({0.1, 0.9, 0.0, 1.4}), 0.236379, 5e-7);
}

// §1.4(c) 45-term totals (4-5 digits), and the quantization's convergence to the continuous
// total: the error shrinks as the steps do (the first step and the ratio both), reaching
// 0.05% at ratio 1.01 and v0/10⁴; the default schedule is within 0.5%, below the 1% that
// the project asks of every model's total (the totals goal of mc-table and issue 18).
TEST(QuantizedDiffusion, QuantizationConvergesToTheContinuousModel) {
  const double alphas[] = {0.5, 0.9, 0.99};
  const double published_totals[] = {0.03344, 0.23218, 0.59893};
  for (std::size_t i = 0; i < std::size(alphas); ++i) {
    const Coefficients c{1.0 - alphas[i], alphas[i], 0.0, 1.4};
    const double exact = continuous_total(c);
    EXPECT_NEAR(QuantizedDiffusion(c, published()).total_reflectance(), published_totals[i], 5e-6)
        << "alpha' " << alphas[i];
    double previous = 1.0;
    for (const auto& [ratio, scale] : {std::pair{1.2, 1.0}, {1.05, 1e-2}, {1.01, 1e-4}}) {
      QdSchedule s;
      s.ratio = ratio;
      s.first_step_scale = scale;
      s.max_terms = 100000;
      const double error = std::fabs(QuantizedDiffusion(c, s).total_reflectance() / exact - 1.0);
      EXPECT_LT(error, 0.5 * previous) << "alpha' " << alphas[i] << " ratio " << ratio;
      previous = error;
    }
    EXPECT_LT(previous, 5e-4) << "alpha' " << alphas[i];
    const QuantizedDiffusion d(c);
    EXPECT_NEAR(d.total_reflectance(), exact, 5e-3 * exact) << "default, alpha' " << alphas[i];
    // The total is the sum of the Gaussians' weights, each Gaussian normalised: the profile
    // integrates to it over its support (geometric Gauss-Legendre panels from a thousandth
    // of the narrowest Gaussian's width, independent of the weights' sum).
    const double inner = 1e-3 * std::sqrt(d.terms().front().variance_mm2);
    const double integral = integrate_radial([&](double r) { return d.reflectance(r); }, inner, d.support_radius());
    EXPECT_NEAR(integral, d.total_reflectance(), 1e-6 * d.total_reflectance()) << "alpha' " << alphas[i];
  }
}

// The similarity relation, as every model here: g enters only through σs' = σs(1 - g).
TEST(QuantizedDiffusion, DependsOnTheReducedCoefficientsOnlyAndRefusesNoScattering) {
  const QuantizedDiffusion a({0.02, 1.0, 0.0, 1.3}), b({0.02, 2.0, 0.5, 1.3});
  // The first step uses the unreduced σs and albedo (v0), so the schedules differ: the
  // profiles agree to the default schedule's quantization (0.5%, above).
  for (double r : {0.1, 1.0, 5.0}) EXPECT_NEAR(a.reflectance(r), b.reflectance(r), 5e-3 * a.reflectance(r)) << r;
  EXPECT_THROW(QuantizedDiffusion({0.02, 0.0, 0.0, 1.3}), std::invalid_argument);
  QdSchedule bad;
  bad.ratio = 1.0;
  EXPECT_THROW(QuantizedDiffusion({0.02, 1.0, 0.0, 1.3}, bad), std::invalid_argument);
  EXPECT_EQ(parse_model("qd"), Model::Qd);
  EXPECT_EQ(model_name(Model::Qd), "qd");
}

// Issue 18 asks whether qd's own terms, merged into at most 8 Gaussians, make a better
// real-time kernel than the fit. The GPU shares one set of variances between R, G and B,
// while qd's terms differ per channel (D per channel); the merge here puts every term
// onto a log grid of `count` shared variances spanning the terms that hold all but 1% of
// each channel's light (a term between two grid variances is split between them keeping
// its weight and its variance, i.e. the kernel's total and mean squared radius; terms
// outside go whole to the ends). Measured (relative L2 of r·R(r), fit_gaussians' error
// measure, on make_fit_target's samples), 8 Gaussians: merge 14.6/15.5/16.9% (skin1),
// 13.7/14.3/14.9% (marble), 18.5/20.1/20.5% (ketchup), where the fit is 3.0/2.9/4.1%,
// 2.5/2.3/2.5% and 4.5/4.7/5.7%; at 6 Gaussians 25-41% against 5.8-12.4%. Splitting a
// Gaussian across a factor of (v_hi/v_lo)^(1/7) in variance keeps its moments, not its
// shape: the fit remains qd's real-time kernel. Run with
//   build/tests/test_profiles --gtest_also_run_disabled_tests --gtest_filter='QdStudy.*'
GaussianFit merge_terms(const RgbProfile& p, int count, double tail) {
  double lo = 1e300, hi = 0.0;
  for (int c = 0; c < 3; ++c) {
    const auto& q = dynamic_cast<const QuantizedDiffusion&>(p.channel(c));
    double cum = 0.0;
    for (const auto& t : q.terms())
      if ((cum += t.coefficient) > tail * q.total_reflectance()) {
        lo = std::min(lo, t.variance_mm2);
        break;
      }
    cum = 0.0;
    for (auto it = q.terms().rbegin(); it != q.terms().rend(); ++it)
      if ((cum += it->coefficient) > tail * q.total_reflectance()) {
        hi = std::max(hi, it->variance_mm2);
        break;
      }
  }
  GaussianFit f;
  for (int i = 0; i < count; ++i) f.variances_mm2.push_back(lo * std::pow(hi / lo, double(i) / (count - 1)));
  f.weights.assign(std::size_t(count), Rgb{0.0, 0.0, 0.0});
  for (int c = 0; c < 3; ++c)
    for (const auto& t : dynamic_cast<const QuantizedDiffusion&>(p.channel(c)).terms()) {
      const double v = std::clamp(t.variance_mm2, lo, hi);
      const std::size_t k = std::min<std::size_t>(
          std::size_t(std::upper_bound(f.variances_mm2.begin(), f.variances_mm2.end(), v) - f.variances_mm2.begin()),
          std::size_t(count) - 1);
      const double va = f.variances_mm2[k - 1], vb = f.variances_mm2[k];
      f.weights[k - 1][c] += t.coefficient * (vb - v) / (vb - va);
      f.weights[k][c] += t.coefficient * (v - va) / (vb - va);
    }
  return f;
}

Rgb relative_l2(const GaussianFit& f, const FitTarget& t) {
  Rgb num{0.0, 0.0, 0.0}, den{0.0, 0.0, 0.0};
  for (std::size_t j = 0; j < t.r_mm.size(); ++j) {
    const Rgb e = f.evaluate(t.r_mm[j]);
    for (int c = 0; c < 3; ++c) {
      const double r = t.r_mm[j], d = r * (t.R[j][c] - e[c]);
      num[c] += t.dr[j] * d * d;
      den[c] += t.dr[j] * r * r * t.R[j][c] * t.R[j][c];
    }
  }
  for (int c = 0; c < 3; ++c) num[c] = std::sqrt(num[c] / den[c]);
  return num;
}

TEST(QdStudy, DISABLED_MergedTermsAgainstTheFit) {
  for (const char* name : {"skin1", "marble", "ketchup"}) {
    const RgbProfile p(Model::Qd, preset_medium(*find_preset(name)));
    const FitTarget t = make_fit_target(p, 96, 0.0);
    for (int n : {6, 8}) {
      FitOptions o;
      o.gaussians = n;
      const GaussianFit fit = fit_gaussians(t, o);
      const GaussianFit merged = merge_terms(p, n, 0.01);
      const Rgb e = relative_l2(merged, t);
      std::printf("%-8s %d Gaussians: fit %.1f / %.1f / %.1f %%, merged terms %.1f / %.1f / %.1f %%\n", name, n,
                  100 * fit.relative_error[0], 100 * fit.relative_error[1], 100 * fit.relative_error[2], 100 * e[0],
                  100 * e[1], 100 * e[2]);
      for (int c = 0; c < 3; ++c) {
        double sum = 0.0;
        for (const Rgb& w : merged.weights) sum += w[c];
        EXPECT_NEAR(sum, p.total_reflectance()[c], 1e-12);  // the merge keeps the total
      }
    }
  }
}

}  // namespace
}  // namespace sss::profiles
