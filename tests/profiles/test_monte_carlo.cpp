// Monte Carlo random walk: tested statistically (Z tests in standard errors, Mitsuba
// style) against exact transport, exactly where the walk is deterministic, and for
// determinism, bookkeeping and input errors. TabulatedProfile's tests are at the end.
#include "profiles/Fresnel.h"
#include "profiles/HFunction.h"
#include "profiles/Integrate.h"
#include "profiles/MonteCarlo.h"
#include "profiles/Presets.h"
#include "profiles/Profile.h"
#include "profiles/Random.h"
#include "profiles/SingleScattering.h"
#include "profiles/TabulatedProfile.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace sss::profiles {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kEps = std::numeric_limits<double>::epsilon();

// A two-sided Z test at 4 standard errors fails by chance with probability
// erfc(4/√2) ≈ 6.3e-5 per check: rare enough for CI, yet it flags a bias of a few SE.
constexpr double kZ = 4.0;

// The z with two-sided tail probability p, P(|Z| > z) = erfc(z/√2) = p (bisection).
double z_for_two_sided(double p) {
  double lo = 0.0, hi = 40.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (std::erfc(mid / std::numbers::sqrt2) > p ? lo : hi) = mid;
  }
  return hi;
}

// Upper tail Q(k/2, x/2) of the chi-square distribution with k degrees of freedom:
// 1 - P with P(a, x) = e^-x x^a Σ_n x^n / Γ(a + n + 1) (the series converges for all x).
double chi_square_p_value(double chi2, int dof) {
  const double a = 0.5 * dof, x = 0.5 * chi2;
  double term = std::exp(-x + a * std::log(x) - std::lgamma(a + 1.0));
  double sum = 0.0;
  for (int n = 1; n < 100000 && term > 1e-300; ++n) {
    sum += term;
    term *= x / (a + n);
  }
  return 1.0 - sum;
}

Coefficients index_matched(double albedo) { return {1.0 - albedo, albedo, 0.0, 1.0}; }

MonteCarloOptions options(std::uint64_t photons, std::uint64_t seed = 1) {
  MonteCarloOptions o;
  o.photons = photons;
  o.seed = seed;
  o.threads = 1;  // tests measure on one core; determinism tests vary this
  return o;
}

// ---------------------------------------------------------------------------------------
// Exact transport: total reflectance of an index-matched isotropic half-space.

class MonteCarloIndexMatched : public ::testing::TestWithParam<std::pair<double, std::uint64_t>> {};

TEST_P(MonteCarloIndexMatched, TotalReflectanceMatchesHFunction) {
  const auto [albedo, photons] = GetParam();
  const MonteCarloResult r = run_monte_carlo(index_matched(albedo), options(photons));
  const double exact = exact_total_reflectance_index_matched(albedo);
  EXPECT_EQ(r.truncated_photons, 0u);
  EXPECT_NEAR(r.reflectance.total, exact, kZ * r.reflectance.total_stderr);
  // The photon counts are chosen (from the per-photon spread measured while writing
  // this) so that SE < 0.3% of the value: the test then detects a 1.2% bias.
  EXPECT_LT(r.reflectance.total_stderr, 0.003 * exact);
  EXPECT_EQ(r.transmittance.total, 0.0);  // a half-space has no bottom face
}

INSTANTIATE_TEST_SUITE_P(Albedos, MonteCarloIndexMatched,
                         ::testing::Values(std::pair{0.5, std::uint64_t{1} << 19},
                                           std::pair{0.9, std::uint64_t{1} << 17},
                                           std::pair{0.99, std::uint64_t{1} << 15}));

// ---------------------------------------------------------------------------------------
// Without scattering the walk is deterministic: the beam goes down and up the slab,
// losing e^{-τ} (τ = σa d) per pass and splitting with F = ((η-1)/(η+1))² at each face:
//   T = (1-F) e^{-τ} Σ_k (F² e^{-2τ})^k = (1-F) e^{-τ} / (1 - F² e^{-2τ}),
//   R = (1-F) F e^{-2τ} Σ_k (F² e^{-2τ})^k = (1-F) F e^{-2τ} / (1 - F² e^{-2τ}),
//   A = 1 - R - T, every exit at r = 0.
// Each photon's contributions are identical; summing N of them in any order is exact to
// N ε relative, and each contribution and the formulas carry a few more ε (the walk's
// ~170 reflections shrink the weight geometrically, so only the first terms matter):
// tolerance (N + 64) ε relative.
TEST(MonteCarlo, NonScatteringSlabIsExact) {
  const double sigma_a = 0.3, d = 2.0;
  const std::uint64_t n = 1000;
  for (double eta : {1.0, 1.5}) {
    MonteCarloOptions o = options(n);
    o.thickness_mm = d;
    o.bin_edges_mm = {0.0, 0.5, 1.0};
    const MonteCarloResult r = run_monte_carlo({sigma_a, 0.0, 0.0, eta}, o);
    const double f = std::pow((eta - 1.0) / (eta + 1.0), 2), e = std::exp(-sigma_a * d);
    const double series = 1.0 / (1.0 - f * f * e * e);
    const double t = (1.0 - f) * e * series, rr = (1.0 - f) * f * e * e * series;
    const double tol = (n + 64) * kEps;
    EXPECT_NEAR(r.transmittance.total, t, tol * t) << "eta " << eta;
    EXPECT_NEAR(r.reflectance.total, rr, tol * rr + 1e-300) << "eta " << eta;
    EXPECT_NEAR(r.absorbed, 1.0 - t - rr, tol) << "eta " << eta;
    const double disc = kPi * 0.25;  // everything exits in the first bin, r in [0, 0.5)
    EXPECT_NEAR(r.transmittance.value[0], t / disc, tol * t / disc);
    EXPECT_NEAR(r.reflectance.value[0], rr / disc, tol * rr / disc + 1e-300);
    EXPECT_EQ(r.transmittance.value[1], 0.0);
    EXPECT_EQ(r.scattering_events, 0u);
  }
}

// R + T + absorbed = 1 in expectation (roulette is unbiased; nothing is truncated).
// The three tallies are correlated, but SD(R + T + A) <= SD(R) + SD(T) + SD(A), so a 4 SE
// test on the sum with that bound fails by chance less often than a plain 4 SE test.
TEST(MonteCarlo, EnergyBalanceInAScatteringSlab) {
  MonteCarloOptions o = options(1 << 14);
  o.thickness_mm = 1.0;
  const MonteCarloResult r = run_monte_carlo({0.05, 5.0, 0.7, 1.4}, o);
  EXPECT_EQ(r.truncated_photons, 0u);
  const double sum = r.reflectance.total + r.transmittance.total + r.absorbed;
  const double se = r.reflectance.total_stderr + r.transmittance.total_stderr + r.absorbed_stderr;
  EXPECT_NEAR(sum, 1.0, kZ * se);
  EXPECT_GT(r.transmittance.total, 0.0);
  EXPECT_GT(r.reflectance.total, 0.0);
}

// Two independent runs with very different roulette settings estimate the same
// expectation: |R1 - R2| < 4 √(SE1² + SE2²).
TEST(MonteCarlo, RouletteIsUnbiased) {
  const Coefficients c{0.02, 1.0, 0.5, 1.3};
  MonteCarloOptions a = options(1 << 14, 11), b = options(1 << 14, 12);
  b.roulette_weight = 0.5;
  b.roulette_survival = 0.5;
  const MonteCarloResult ra = run_monte_carlo(c, a), rb = run_monte_carlo(c, b);
  EXPECT_NEAR(ra.reflectance.total, rb.reflectance.total,
              kZ * std::hypot(ra.reflectance.total_stderr, rb.reflectance.total_stderr));
}

// With one interaction allowed, a photon in an index-matched slab either crosses it
// unscattered (probability e^{-σs d}, leaving weight e^{-σa d} through the bottom) or
// is truncated at its first scattering event. The truncated count is binomial.
TEST(MonteCarlo, TruncationIsCounted) {
  const double sa = 0.1, ss = 1.0, d = 0.7;
  const std::uint64_t n = 20000;
  MonteCarloOptions o = options(n);
  o.thickness_mm = d;
  o.max_interactions_per_photon = 1;
  const MonteCarloResult r = run_monte_carlo({sa, ss, 0.0, 1.0}, o);
  const double p = 1.0 - std::exp(-ss * d);
  EXPECT_NEAR(static_cast<double>(r.truncated_photons) / n, p, kZ * std::sqrt(p * (1 - p) / n));
  EXPECT_NEAR(r.transmittance.total, std::exp(-(sa + ss) * d), kZ * r.transmittance.total_stderr);
  EXPECT_EQ(r.reflectance.total, 0.0);
}

// ---------------------------------------------------------------------------------------
// Radial profile: single scattering in a half-space, in closed form.
// A photon scatters at depth z (density σs e^{-σs z}, weight e^{-σa z}), leaves upward
// with cosine μ (density 2π p(-μ) for the phase function p about +z), reaches the face
// unscattered with e^{-σt z/μ} at r = z √(1-μ²)/μ, and a fraction 1 - Fr(μ) escapes (the
// reflected part would need a second scattering event to come back). So the flux into
// [r0, r1) is
//   ∫0^∞ dz σs e^{-σt z} ∫_{μ1(z)}^{μ0(z)} 2π p(-μ) (1 - Fr(μ)) e^{-σt z/μ} dμ,
// μi = z/√(z² + ri²), and Fr = 1 below the critical cosine μc = √(1 - 1/η²).
double hg(double g, double cos_theta) {
  return (1.0 - g * g) / (4.0 * kPi * std::pow(1.0 + g * g - 2.0 * g * cos_theta, 1.5));
}

double critical_cosine(double eta) { return eta > 1.0 ? std::sqrt(1.0 - 1.0 / (eta * eta)) : 0.0; }

// ∫_lo^hi f(μ) dμ over the part above μc, with μ = lo + (hi - lo) s²: Fr has a square-root
// kink at μc, which this substitution smooths when lo = μc.
template <class F>
double integrate_escape(F f, double lo, double hi, double eta, int panels) {
  lo = std::max(lo, critical_cosine(eta));
  if (!(hi > lo)) return 0.0;
  const double span = hi - lo;
  return integrate(
      [&](double s) {
        const double mu = lo + span * s * s;
        return f(mu) * (1.0 - fresnel_dielectric(mu, 1.0 / eta)) * 2.0 * span * s;
      },
      0.0, 1.0, panels, 16);
}

// `per_decade` panels per factor 10 in z, `mu_panels` panels in μ (16 points each). The
// μ range [μ1(z), μ0(z)] meets μc at z = ri μc/√(1 - μc²), where the integrand in z has
// a kink: z is integrated piecewise between those points (geometric panels from each
// piece's start), and not past 40/σt (the rest is < e^-40).
double single_scattering_flux(const Coefficients& c, double r0, double r1, int per_decade,
                              int mu_panels) {
  const double st = c.sigma_t(), mu_c = critical_cosine(c.eta);
  auto inner = [&](double z) {
    const double mu0 = r0 > 0.0 ? z / std::hypot(z, r0) : 1.0, mu1 = z / std::hypot(z, r1);
    auto f = [&](double mu) { return 2.0 * kPi * hg(c.g, -mu) * std::exp(-st * z / mu); };
    return c.sigma_s * std::exp(-st * z) * integrate_escape(f, mu1, mu0, c.eta, mu_panels);
  };
  std::vector<double> breaks{0.0, 40.0 / st};
  if (mu_c > 0.0)
    for (double ri : {r0, r1}) breaks.push_back(ri * mu_c / std::sqrt(1.0 - mu_c * mu_c));
  std::sort(breaks.begin(), breaks.end());
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double a = breaks[i], len = std::min(breaks[i + 1], 40.0 / st) - a;
    if (len <= 0.0) continue;
    sum += integrate_log([&](double u) { return inner(a + u); },
                         std::min({r1, 1.0 / st, 0.5 * len}), len, per_decade, 16);
  }
  return sum;
}

TEST(MonteCarlo, SingleScatteringRadialProfile) {
  for (auto [g, eta] : {std::pair{0.0, 1.0}, std::pair{0.7, 1.0}, std::pair{-0.3, 1.4}}) {
    const Coefficients c{0.2, 1.0, g, eta};
    MonteCarloOptions o = options(1 << 18, 7);
    o.max_scattering_order = 1;
    // Out to 1.5 mm every bin expects > 100 photons (asserted below), so the normal
    // approximation behind the Z test holds (beyond, TIR at η = 1.4 empties the bins).
    o.bin_edges_mm = log_bin_edges(0.05, 1.5, 10);
    const MonteCarloResult r = run_monte_carlo(c, o);
    const std::size_t bins = r.reflectance.value.size();
    // Bonferroni: bins + 1 checks at a family-wise false-failure probability of 1e-4.
    const double z = z_for_two_sided(1e-4 / (bins + 1));
    for (std::size_t b = 0; b < bins; ++b) {
      const double r0 = o.bin_edges_mm[b], r1 = o.bin_edges_mm[b + 1];
      const double area = kPi * (r1 * r1 - r0 * r0);
      const double exact = single_scattering_flux(c, r0, r1, 12, 8) / area;
      // Weights are <= 1, so the expected number of exits is >= the expected weight.
      ASSERT_GT(exact * area * static_cast<double>(o.photons), 100.0) << "bin " << b;
      // Quadrature check: a rule with half the panels in z and in μ agrees to far less
      // than one SE, so the exact value's own error is negligible in the Z test.
      EXPECT_LT(std::fabs(single_scattering_flux(c, r0, r1, 6, 4) / area - exact),
                0.01 * r.reflectance.stderr_[b]);
      EXPECT_NEAR(r.reflectance.value[b], exact, z * r.reflectance.stderr_[b])
          << "g " << g << " eta " << eta << " bin " << b << " [" << r0 << ", " << r1 << ")";
    }
    // The total: ∫ α 2π p(-μ) (1 - Fr) μ/(1+μ) dμ; (α/2)(1 - ln 2) when isotropic, η = 1.
    const double total = integrate_escape(
        [&](double mu) { return c.albedo() * 2.0 * kPi * hg(g, -mu) * mu / (1.0 + mu); }, 0.0,
        1.0, eta, 8);
    if (g == 0.0 && eta == 1.0) {  // 128 Gauss points on a smooth integrand: rounding only
      EXPECT_NEAR(total, 0.5 * c.albedo() * (1.0 - std::log(2.0)), 1e-14);
    }
    EXPECT_NEAR(r.reflectance.total, total, z * r.reflectance.total_stderr) << "g " << g;
  }
}

// At η = 1 every exit is tallied once, so Σ value · area over bins that cover every
// possible exit radius is the total. A photon travels at most 1e6 interactions × 37/σs
// (the longest flight -ln(2^-53)/σs), so edges up to 1e8 mm cover everything. The two
// sides sum the same positive terms in different orders: each is exact to (terms) ε
// relative, terms <= scattering events + photons (an exit follows a scattering event or
// the entry), plus 8 ε for the divisions and products.
TEST(MonteCarlo, BinsSumToTheTotal) {
  MonteCarloOptions o = options(1 << 12);
  o.bin_edges_mm = log_bin_edges(0.01, 1e8, 60);
  const MonteCarloResult r = run_monte_carlo({0.05, 1.0, 0.3, 1.0}, o);
  double sum = 0.0;
  for (std::size_t b = 0; b + 1 < o.bin_edges_mm.size(); ++b) {
    const double r0 = o.bin_edges_mm[b], r1 = o.bin_edges_mm[b + 1];
    sum += r.reflectance.value[b] * kPi * (r1 * r1 - r0 * r0);
  }
  const double terms = static_cast<double>(r.scattering_events + r.photons);
  EXPECT_NEAR(sum, r.reflectance.total, (2.0 * terms + 8.0) * kEps * r.reflectance.total);
}

// ---------------------------------------------------------------------------------------
// Determinism.

TEST(MonteCarlo, DeterministicForAnyThreadCount) {
  const Coefficients c{0.03, 1.5, 0.6, 1.4};
  MonteCarloOptions o = options(3 * kMonteCarloChunkPhotons + 123, 42);
  o.bin_edges_mm = log_bin_edges(0.05, 10.0, 16);
  o.thickness_mm = 3.0;
  const MonteCarloResult one = run_monte_carlo(c, o);
  for (int threads : {1, 2, 3}) {
    o.threads = threads;
    const MonteCarloResult r = run_monte_carlo(c, o);
    EXPECT_EQ(r.reflectance.value, one.reflectance.value) << threads;
    EXPECT_EQ(r.reflectance.stderr_, one.reflectance.stderr_) << threads;
    EXPECT_EQ(r.transmittance.value, one.transmittance.value) << threads;
    EXPECT_EQ(r.reflectance.total, one.reflectance.total) << threads;
    EXPECT_EQ(r.transmittance.total, one.transmittance.total) << threads;
    EXPECT_EQ(r.absorbed, one.absorbed) << threads;
    EXPECT_EQ(r.scattering_events, one.scattering_events) << threads;
  }
  o.seed = 43;
  const MonteCarloResult other = run_monte_carlo(c, o);
  EXPECT_NE(other.reflectance.total, one.reflectance.total);
  EXPECT_NE(other.reflectance.value, one.reflectance.value);
}

TEST(MonteCarlo, ProgressIsMonotoneAndErrorsPropagate) {
  MonteCarloOptions o = options(5 * kMonteCarloChunkPhotons);
  o.threads = 2;
  std::vector<double> seen;  // calls never overlap (documented), so no lock is needed
  o.progress = [&](double f) { seen.push_back(f); };
  run_monte_carlo(index_matched(0.5), o);
  ASSERT_EQ(seen.size(), 5u);
  for (std::size_t i = 1; i < seen.size(); ++i) EXPECT_GT(seen[i], seen[i - 1]);
  EXPECT_EQ(seen.back(), 1.0);
  o.progress = [](double) { throw std::runtime_error("cancelled"); };
  EXPECT_THROW(run_monte_carlo(index_matched(0.5), o), std::runtime_error);
}

// Model mc's walk reports through ModelOptions::mc_progress: RgbProfile gives each
// channel's run a third, so the fractions rise through (0, 1/3], (1/3, 2/3], (2/3, 1],
// one call per chunk of each channel, and end at exactly 1. A callback that throws (how
// sss-reference cancels) leaves the constructor with its exception.
TEST(MonteCarlo, TheMcModelReportsEachChannelAsAThirdAndCanBeStopped) {
  ModelOptions o;
  o.mc_photons = 3 * kMonteCarloChunkPhotons;
  o.mc_threads = 2;
  std::vector<double> seen;  // calls never overlap within a run; channels run one by one
  o.mc_progress = [&](double f) { seen.push_back(f); };
  const Medium skin = preset_medium(*find_preset("skin1"));
  const RgbProfile profile(Model::MonteCarlo, skin, o);
  ASSERT_EQ(seen.size(), 9u);
  for (std::size_t i = 1; i < seen.size(); ++i) EXPECT_GT(seen[i], seen[i - 1]) << i;
  for (std::size_t i = 0; i < 9; ++i) {
    EXPECT_GT(seen[i], double(i / 3) / 3.0) << i;
    EXPECT_LE(seen[i], double(i / 3 + 1) / 3.0 + 1e-15) << i;
  }
  EXPECT_EQ(seen.back(), 1.0);
  o.mc_progress = [](double f) {
    if (f > 0.1) throw std::runtime_error("cancelled");
  };
  EXPECT_THROW(RgbProfile(Model::MonteCarlo, skin, o), std::runtime_error);
}

// ---------------------------------------------------------------------------------------
// Bad input: std::invalid_argument whose message starts with the field.

void expect_field_error(const Coefficients& c, const MonteCarloOptions& o,
                        const std::string& field) {
  try {
    run_monte_carlo(c, o);
    ADD_FAILURE() << "no exception for " << field;
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind(field + ":", 0), 0u) << e.what();
  }
}

TEST(MonteCarlo, RejectsBadInput) {
  const Coefficients good{0.1, 1.0, 0.0, 1.3};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const MonteCarloOptions o = options(100);
  expect_field_error({0.1, nan, 0.0, 1.3}, o, "sigma_s");
  expect_field_error({0.0, 1.0, 0.0, 1.3}, o, "sigma_a");
  expect_field_error({0.1, 1.0, 1.0, 1.3}, o, "g");
  MonteCarloOptions bad = o;
  bad.photons = 0;
  expect_field_error(good, bad, "photons");
  bad = o;
  bad.bin_edges_mm = {0.0, 2.0, 1.0};
  expect_field_error(good, bad, "bin_edges_mm");
  bad.bin_edges_mm = {0.0, nan};
  expect_field_error(good, bad, "bin_edges_mm");
  bad.bin_edges_mm = {1.0};
  expect_field_error(good, bad, "bin_edges_mm");
  bad = o;
  bad.thickness_mm = nan;
  expect_field_error(good, bad, "thickness_mm");
  bad.thickness_mm = -1.0;
  expect_field_error(good, bad, "thickness_mm");
  bad = o;
  bad.threads = -1;
  expect_field_error(good, bad, "threads");
  bad = o;
  bad.roulette_survival = 1.0;
  expect_field_error(good, bad, "roulette_survival");
  bad = o;
  bad.max_scattering_order = -1;
  expect_field_error(good, bad, "max_scattering_order");
  bad = o;
  bad.min_scattering_order = -1;
  expect_field_error(good, bad, "min_scattering_order");
  bad.max_scattering_order = 1;
  bad.min_scattering_order = 2;  // nothing could be tallied
  expect_field_error(good, bad, "min_scattering_order");
  // Allowed: min = max (order k alone), and any min when every order is walked.
  bad.min_scattering_order = 1;
  EXPECT_NO_THROW(run_monte_carlo(good, bad));
  bad.max_scattering_order = 0;
  bad.min_scattering_order = 50;
  EXPECT_NO_THROW(run_monte_carlo(good, bad));
}

// ---------------------------------------------------------------------------------------
// min_scattering_order (issue 18 part 2: single scattering apart).

// The option changes what is tallied, never the walk: with the same seed the photons take
// the same paths and draw the same numbers, so every exit of the full run is either
// tallied by the min-order run or counted in its low_order_exits. The two sides add the
// same terms grouped differently per photon: equal to ~1e-15 relative (asserted 1e-12).
// In a slab both faces take part, and bins, totals and exit-cosine bins all drop the
// low orders (each bin can only lose, and the exit-cosine bins still add up to the total).
TEST(MonteCarlo, MinScatteringOrderOnlyMovesExitsToLowOrderExits) {
  const Coefficients c{0.05, 2.0, 0.6, 1.4};
  MonteCarloOptions o = options(1 << 13, 5);
  o.thickness_mm = 1.5;
  o.bin_edges_mm = log_bin_edges(0.01, 8.0, 24);
  o.exit_cosine_bins = 10;
  const MonteCarloResult full = run_monte_carlo(c, o);
  EXPECT_EQ(full.low_order_exits, 0.0);
  for (int k : {1, 2, 3}) {
    o.min_scattering_order = k;
    const MonteCarloResult part = run_monte_carlo(c, o);
    SCOPED_TRACE("min_scattering_order " + std::to_string(k));
    EXPECT_EQ(part.scattering_events, full.scattering_events);
    EXPECT_EQ(part.absorbed, full.absorbed);
    EXPECT_NEAR(part.reflectance.total + part.transmittance.total + part.low_order_exits,
                full.reflectance.total + full.transmittance.total, 1e-12);
    // Even k = 1 leaves something out: unscattered light crosses the slab (order 0), and
    // what the bottom face reflects of it can leave through the top unscattered too.
    EXPECT_GT(part.low_order_exits, 0.0);
    EXPECT_LT(part.transmittance.total, full.transmittance.total);
    EXPECT_LE(part.reflectance.total, full.reflectance.total);
    double by_cos = 0.0;
    for (double v : part.reflectance_by_exit_cosine.value) by_cos += v / 10.0;
    EXPECT_NEAR(by_cos, part.reflectance.total, 1e-12);
    for (std::size_t b = 0; b < full.reflectance.value.size(); ++b) {
      EXPECT_LE(part.reflectance.value[b], full.reflectance.value[b] * (1.0 + 1e-12)) << b;
      EXPECT_LE(part.transmittance.value[b], full.transmittance.value[b] * (1.0 + 1e-12)) << b;
    }
  }
}

// What min_scattering_order = 2 leaves out of a half space's reflectance is the once-
// scattered light, whose total is the closed form of SingleScattering.h integrated over the
// exit cosine (normal incidence; 16 x 16 Gauss-Legendre, converged to 1e-9): low_order_exits
// against it by its standard error, 4 SE (3 media: a false alarm 3 x 6.3e-5 = 2e-4). And
// the balance reflectance + low_order_exits + absorbed = 1 (nothing truncated, no
// transmittance), by the sum of the three SEs (a bound whatever their correlation).
TEST(MonteCarlo, LowOrderExitsAreTheOnceScatteredLight) {
  const Coefficients media[] = {{0.2, 0.8, 0.0, 1.0}, {0.032, 0.74, 0.0, 1.3}, {0.05, 2.0, 0.8, 1.4}};
  for (const Coefficients& c : media) {
    MonteCarloOptions o = options(1 << 16, 9);
    o.min_scattering_order = 2;
    const MonteCarloResult r = run_monte_carlo(c, o);
    ASSERT_EQ(r.truncated_photons, 0u);
    const double closed = integrate([&](double mu) { return single_scattering_exit_density(c, 1.0, mu); },
                                    0.0, 1.0, 16, 16);
    EXPECT_NEAR(r.low_order_exits, closed, kZ * r.low_order_exits_stderr)
        << "g " << c.g << " eta " << c.eta << ": low-order exits " << r.low_order_exits << " +- "
        << r.low_order_exits_stderr << ", closed form " << closed;
    EXPECT_NEAR(r.reflectance.total + r.low_order_exits + r.absorbed, 1.0,
                kZ * (r.reflectance.total_stderr + r.low_order_exits_stderr + r.absorbed_stderr));
    std::printf("g %.1f eta %.1f: once-scattered %.5f +- %.5f (closed form %.5f), rest %.5f\n", c.g,
                c.eta, r.low_order_exits, r.low_order_exits_stderr, closed, r.reflectance.total);
  }
}

TEST(MonteCarlo, LogBinEdges) {
  const auto e = log_bin_edges(0.1, 100.0, 3);
  ASSERT_EQ(e.size(), 5u);  // count + 2
  EXPECT_EQ(e[0], 0.0);
  EXPECT_EQ(e[1], 0.1);
  EXPECT_EQ(e[4], 100.0);
  // ratio 10 per bin, to the rounding of exp and log (a few ε)
  EXPECT_NEAR(e[2], 1.0, 8 * kEps);
  EXPECT_NEAR(e[3], 10.0, 80 * kEps);
  EXPECT_THROW(log_bin_edges(0.0, 1.0, 3), std::invalid_argument);
  EXPECT_THROW(log_bin_edges(1.0, 0.5, 3), std::invalid_argument);
  EXPECT_THROW(log_bin_edges(0.1, 1.0, 0), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------
// Samplers: chi-square tests against the exact distributions (pbrt-v4 style).

// Pearson's chi-square over `bins` cells with expected probabilities from `cdf`;
// the test fails when the p-value is below 1e-4 (the false-failure rate per check).
template <class Cdf, class Sample>
void expect_chi_square(Cdf cdf, Sample sample, double lo, double hi, int bins, int n,
                       const std::string& what) {
  std::vector<double> counts(bins, 0.0);
  for (int i = 0; i < n; ++i) {
    const double x = sample();
    const int b = std::min(bins - 1, static_cast<int>((x - lo) / (hi - lo) * bins));
    counts[b] += 1.0;
  }
  double chi2 = 0.0;
  for (int b = 0; b < bins; ++b) {
    const double expected =
        n * (cdf(lo + (hi - lo) * (b + 1) / bins) - cdf(lo + (hi - lo) * b / bins));
    ASSERT_GT(expected, 5.0) << what << ": too few expected counts for Pearson's test";
    chi2 += (counts[b] - expected) * (counts[b] - expected) / expected;
  }
  EXPECT_GT(chi_square_p_value(chi2, bins - 1), 1e-4) << what << " chi2 " << chi2;
}

TEST(MonteCarloSampling, HenyeyGreensteinChiSquare) {
  for (double g : {0.8, -0.3, 0.0}) {
    Xoshiro256ss rng(123, static_cast<std::uint64_t>(g * 1000 + 1000));
    // CDF of cos θ: (1-g²)/(2g) (1/√(1+g²-2gμ) - 1/(1+g)); (1+μ)/2 at g = 0.
    auto cdf = [g](double mu) {
      if (g == 0.0) return 0.5 * (1.0 + mu);
      return (1 - g * g) / (2 * g) * (1 / std::sqrt(1 + g * g - 2 * g * mu) - 1 / (1 + g));
    };
    expect_chi_square(cdf, [&] { return sample_hg_cos(g, rng.uniform()); }, -1.0, 1.0, 40,
                      1000000, "HG g=" + std::to_string(g));
  }
}

TEST(MonteCarloSampling, HenyeyGreensteinInversionIsStable) {
  // Against the textbook formula evaluated in long double (64-bit mantissa): its
  // cancellation costs ~ε_ld/|g| <= 5.4e-20/1e-3 ≈ 0.5 ε here, so the reference is good
  // to ~1 ε and the sampler, built from non-negative terms, to a few ε: 8 ε.
  for (double g : {0.999, -0.999, 0.5, -0.5, 1e-3, -1e-3})
    for (double xi : {0.0, 1e-6, 0.1, 0.5, 0.9, 1.0 - 1e-6, 1.0}) {
      const long double gl = g, s = (1 - gl * gl) / (1 - gl + 2 * gl * xi);
      const double textbook = static_cast<double>((1 + gl * gl - s * s) / (2 * gl));
      EXPECT_NEAR(sample_hg_cos(g, xi), textbook, 8 * kEps) << "g " << g << " xi " << xi;
    }
  // For tiny g it is isotropic to first order: d cos θ/dg at g = 0 is (3 - 3a²)/2 <= 1.5
  // (a = 2ξ - 1), so |cos θ - a| <= 1.5 |g| + O(g²) (+ rounding).
  for (double xi : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    EXPECT_NEAR(sample_hg_cos(1e-9, xi), 2 * xi - 1, 1.5e-9 + 4 * kEps);
    EXPECT_EQ(sample_hg_cos(0.0, xi), 2 * xi - 1);
  }
  for (double g : {0.9, -0.9, 0.0}) {  // the end points are exact by construction
    EXPECT_EQ(sample_hg_cos(g, 1.0), 1.0);
    EXPECT_EQ(sample_hg_cos(g, 0.0), -1.0);
  }
}

TEST(MonteCarloSampling, AzimuthIsUniform) {
  Xoshiro256ss rng(5);
  auto sample = [&] {
    double c, s;
    sample_azimuth(rng, c, s);
    EXPECT_NEAR(c * c + s * s, 1.0, 4 * kEps);
    return std::atan2(s, c);
  };
  expect_chi_square([](double phi) { return (phi + kPi) / (2 * kPi); }, sample, -kPi, kPi, 36,
                    200000, "azimuth");
}

// ---------------------------------------------------------------------------------------
// TabulatedProfile. Its evaluation is a few log/exp of arguments up to ~10 in size, so
// exact cases agree to ~10 ε of the exponent: 1e-13 relative is a safe bound.
constexpr double kTableTol = 1e-13;

TEST(TabulatedProfile, PowerLawIsExactBetweenNodes) {
  std::vector<double> r, v;
  for (int i = 0; i < 8; ++i) {
    r.push_back(0.1 * std::pow(2.0, i));
    v.push_back(2.0 * std::pow(r.back(), -1.5));
  }
  const TabulatedProfile p(r, v, 0.5);
  for (double x : {0.13, 0.5, 3.3, 12.0})
    EXPECT_NEAR(p.reflectance(x), 2.0 * std::pow(x, -1.5), kTableTol * 2.0 * std::pow(x, -1.5));
  EXPECT_NEAR(p.reflectance(0.0), v.front(), kTableTol * v.front());   // constant inside
  EXPECT_NEAR(p.reflectance(0.05), v.front(), kTableTol * v.front());
  EXPECT_DOUBLE_EQ(p.inner_radius(), 0.1);
  EXPECT_DOUBLE_EQ(p.support_radius(), 12.8);
  EXPECT_EQ(p.total_reflectance(), 0.5);
}

TEST(TabulatedProfile, ExponentialTailIsExactPastTheLastNode) {
  const std::vector<double> r{1.0, 2.0, 3.0}, v{3 * std::exp(-2.0), 3 * std::exp(-4.0),
                                                3 * std::exp(-6.0)};
  const TabulatedProfile p(r, v, 0.1);
  for (double x : {3.0, 4.5, 10.0})
    EXPECT_NEAR(p.reflectance(x), 3 * std::exp(-2 * x), kTableTol * 3 * std::exp(-2 * x));
  // A tail that does not decay falls back to e-folding over the last spacing.
  const TabulatedProfile flat({1.0, 2.0}, {1.0, 1.0}, 0.1);
  EXPECT_NEAR(flat.reflectance(3.0), std::exp(-1.0), kTableTol);
}

TEST(TabulatedProfile, DropsZerosAndRejectsBadNodes) {
  const TabulatedProfile p({1.0, 2.0, 4.0}, {1.0, 0.0, 0.25}, 0.1);
  EXPECT_NEAR(p.reflectance(2.0), 0.5, kTableTol);  // log-log between 1 and 4
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(TabulatedProfile({1.0, 2.0}, {1.0}, 0.1), std::invalid_argument);
  EXPECT_THROW(TabulatedProfile({2.0, 1.0}, {1.0, 1.0}, 0.1), std::invalid_argument);
  EXPECT_THROW(TabulatedProfile({0.0, 1.0}, {1.0, 1.0}, 0.1), std::invalid_argument);
  EXPECT_THROW(TabulatedProfile({1.0, 2.0}, {1.0, nan}, 0.1), std::invalid_argument);
  EXPECT_THROW(TabulatedProfile({1.0, 2.0}, {1.0, 0.0}, 0.1), std::invalid_argument);
  EXPECT_THROW(TabulatedProfile({1.0, 2.0}, {1.0, 1.0}, nan), std::invalid_argument);
}

TEST(TabulatedProfile, FromMonteCarloUsesAreaCentresAndTotals) {
  MonteCarloResult mc;
  mc.bin_edges_mm = {0.0, 1.0, 2.0, 3.0, 4.0};
  mc.reflectance.value = {4.0, 0.0, 1.0, 0.5};
  mc.reflectance.total = 0.4;
  mc.transmittance.value = {0.0, 0.0, 0.0, 0.0};
  mc.transmittance.total = 0.2;
  const TabulatedProfile p = TabulatedProfile::from_monte_carlo(mc);
  EXPECT_DOUBLE_EQ(p.inner_radius(), std::sqrt(0.5));   // √((0² + 1²)/2)
  EXPECT_DOUBLE_EQ(p.support_radius(), std::sqrt(12.5));  // √((3² + 4²)/2)
  EXPECT_NEAR(p.reflectance(std::sqrt(6.5)), 1.0, kTableTol);  // the bin [2, 3)
  EXPECT_EQ(p.total_reflectance(), 0.4);
  EXPECT_EQ(p.total_transmittance(), 0.2);
  EXPECT_EQ(p.transmittance(1.0), 0.0);  // no transmittance bins with flux

  // A real run: the table passes through the run's bin values.
  MonteCarloOptions o = options(1 << 12);
  o.bin_edges_mm = log_bin_edges(0.1, 10.0, 8);
  o.thickness_mm = 2.0;
  const MonteCarloResult run = run_monte_carlo({0.05, 2.0, 0.0, 1.3}, o);
  const TabulatedProfile q = TabulatedProfile::from_monte_carlo(run);
  int checked = 0;
  for (std::size_t b = 0; b + 1 < o.bin_edges_mm.size(); ++b) {
    const double r0 = o.bin_edges_mm[b], r1 = o.bin_edges_mm[b + 1];
    const double centre = std::sqrt(0.5 * (r0 * r0 + r1 * r1));
    const double rv = run.reflectance.value[b], tv = run.transmittance.value[b];
    if (rv > 0.0) {
      EXPECT_NEAR(q.reflectance(centre), rv, kTableTol * rv) << b;
      ++checked;
    }
    if (tv > 0.0) {
      EXPECT_NEAR(q.transmittance(centre), tv, kTableTol * tv) << b;
      ++checked;
    }
  }
  EXPECT_GT(checked, 10);
  EXPECT_EQ(q.total_reflectance(), run.reflectance.total);
  EXPECT_EQ(q.total_transmittance(), run.transmittance.total);
}

}  // namespace
}  // namespace sss::profiles
