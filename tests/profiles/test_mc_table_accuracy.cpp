// Model mc-table's accuracy, as a user gets it (make_profile(Model::McTable, ...) with the
// shipped table, interpolation between nodes included), against Monte Carlo run at test
// time: issue 8's accuracy goals.
//  1. Total diffuse reflectance within 1% of the independent analog walk
//     (profiles/MonteCarlo.h) for α' in [0.3, 0.999], at media that are NOT table nodes.
//  2. η = 1: the total within 0.5% of the exact 1 - H(1)√(1 - α') (HFunction.h) on a dense
//     sweep of α' over [0.01, 0.9999] and past the last node.
//  3. R(r) within 5% RMS over r in [0.25, 8] mfp (validate_against_monte_carlo) for the
//     Jensen presets and for random media, with the Monte Carlo noise small enough for 5%
//     to mean something, and the RMS consistent with that noise.
//  4. Interpolation error at midpoints between table nodes below the Monte Carlo noise,
//     across (α', η) and across r, against fresh generate_mc_table runs.
// The table's DATA at its nodes is tested in test_mc_table_data.cpp and the lookup's unit
// properties in test_mc_table_profile.cpp; neither is repeated here.
//
// Every statistical bound is in standard errors (the table's stored ones, interpolated as
// the lookup does, and the test-time run's), at a family-wise false-failure probability of
// 1e-4; the fixed goals are asserted next to them. Every Monte Carlo run here uses
// one thread: ctest runs the cases side by side (-j$(nproc)).
#include "profiles/HFunction.h"
#include "profiles/Integrate.h"
#include "profiles/McTable.h"
#include "profiles/McTableProfile.h"
#include "profiles/Medium.h"
#include "profiles/MonteCarlo.h"
#include "profiles/Presets.h"
#include "profiles/Profile.h"
#include "profiles/Validation.h"

#include "McTableTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>
#include <numeric>
#include <ostream>
#include <random>
#include <string>
#include <vector>

namespace sss::profiles {
namespace {

using test::annuli_covering;
using test::chi2_over_k_quantile;
using test::EdgeRange;
using test::z_family;
using test::z_one_sided;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kFamilyP = 1e-4;  // family-wise false-failure probability of each test

// ---------------------------------------------------------------------------------------
// Statistics.

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double mean_square(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

// ---------------------------------------------------------------------------------------
// The model and where a medium sits in the table.

// A medium in optical units: σt' = sigma_tp, reduced albedo α', g = 0.
Coefficients optical(double alpha, double eta, double sigma_tp = 1.0) {
  return {(1.0 - alpha) * sigma_tp, alpha * sigma_tp, 0.0, eta};
}

std::unique_ptr<RadialProfile> model(const Coefficients& c) {
  return make_profile(Model::McTable, c, kInf, {});
}

// The α' halfway in u = √(1 - α') (the lookup's albedo coordinate) between the two table
// nodes that bracket `near`: a medium as far from every node as the table allows.
double albedo_midpoint(const McTableData& t, double near) {
  std::size_t i = 0;
  while (i + 2 < t.albedo.size() && t.albedo[i + 1] <= near) ++i;
  const double u = 0.5 * (std::sqrt(1.0 - t.albedo[i]) + std::sqrt(1.0 - t.albedo[i + 1]));
  return 1.0 - u * u;
}

// The standard error of an interpolated value. The lookup's value is Σ w_k v_k over a
// stencil of nodes (cubic Hermite in u and η, up to 4 × 4 nodes; for a flux Σ w_k ln v_k,
// whose error is Σ w_k δv_k/v_k to first order); the nodes share their random walks, so
// their errors are correlated, and Σ|w_k| se_k bounds the interpolated error whatever the
// correlation. The weights are the lookup's own: mc_table_total returns Σ|w_k| total_se_k,
// so on a copy of the table whose total_se holds any per-node values s_k it returns
// Σ|w_k| s_k (Σ|w| <= 1.25 per axis inside the grid: a Catmull-Rom segment's negative
// lobes add t(1 - t)). Tests run one at a time in a process, so one copy serves.
double stencil_weighted(const Coefficients& c, const std::vector<double>& per_node) {
  static McTableData copy = shipped_mc_table();
  copy.total_se = per_node;
  return mc_table_total(c, copy).stderr_;
}

// The node indices [lo, hi] a cubic stencil can touch on an ascending axis at x: the
// segment's two nodes and one more on each side (past the last node, the last three).
std::pair<std::size_t, std::size_t> stencil_range(const std::vector<double>& axis, double x) {
  std::size_t i = 0;
  while (i + 2 < axis.size() && axis[i + 1] <= x) ++i;
  return {i == 0 ? 0 : i - 1, std::min(axis.size() - 1, i + 2)};
}

// Upper bound on the relative standard error of the lookup's flux through table annulus
// b at medium c: Σ|w_k| (se/flux)_k over the cubic stencil, which the lookup uses wherever
// every stencil node measured the annulus to 30% (McTableProfile::kMaxRelativeError); the
// bilinear fallback's positive weights give an error of the same size.
double interpolated_flux_rel_se(const McTableData& t, const Coefficients& c, std::size_t b) {
  std::vector<double> rel(t.total.size());
  for (std::size_t n = 0; n < rel.size(); ++n) {
    const std::size_t s = n * t.bins() + b;
    rel[n] = t.flux[s] > 0.0 ? t.flux_se[s] / t.flux[s] : 1.0;
  }
  return stencil_weighted(c, rel);
}

// The model's flux through [r0, r1] (optical units, so mm are mean free paths).
double model_flux(const RadialProfile& p, double r0, double r1) {
  return annulus_average(p, r0, r1) * std::numbers::pi * (r1 * r1 - r0 * r0);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// ---------------------------------------------------------------------------------------
// 1. Total diffuse reflectance at off-node media against the analog walk.

struct OffNodeMedium {
  double alpha_near;  // the medium is the u-midpoint of the node interval holding this
  double eta;         // a midpoint of the η axis (nodes every 0.05) or, for 1.0, its end
  std::uint64_t photons;
};
void PrintTo(const OffNodeMedium& m, std::ostream* os) {
  *os << "alpha' ~" << m.alpha_near << ", eta " << m.eta << ", " << m.photons << " photons";
}
std::string medium_name(double alpha, double eta) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "Albedo%gEta%g", alpha, eta);
  std::string s = buf;
  std::replace(s.begin(), s.end(), '.', 'p');
  return s;
}

// Photons: the analog run's relative standard error of the total is s/√N with the per-
// photon relative spread s measured in test_mc_table_data.cpp (4.1 at α' 0.32, 3.6 at
// 0.6, 1.1 at 0.9, 0.9 at 0.97, 0.6 at 0.99, 0.3 at 0.998); N is chosen for 0.1-0.15%,
// which with the lookup's bound (0.1-0.2%) keeps the combined error under 1%/z = 0.23%
// (the 1% goal is then testable at the family-wise rate). At α' 0.31 the lookup's bound
// alone is 0.20%, so the analog run goes to 0.07% there (2^25 photons, ~6 s).
const OffNodeMedium kOffNode[] = {
    {0.3, 1.325, 1u << 25},  {0.55, 1.475, 1u << 23}, {0.8, 1.025, 1u << 21},
    {0.9, 1.775, 1u << 20},  {0.97, 1.325, 1u << 19}, {0.99, 1.0, 1u << 18},
    {0.995, 1.475, 1u << 18}, {0.999, 1.325, 1u << 16}};

class McTableAccuracyTotal : public ::testing::TestWithParam<OffNodeMedium> {};

TEST_P(McTableAccuracyTotal, WithinOnePercentOfTheAnalogWalkBetweenNodes) {
  const OffNodeMedium m = GetParam();
  const McTableData& t = shipped_mc_table();
  const double alpha = albedo_midpoint(t, m.alpha_near);
  ASSERT_GE(alpha, 0.3);
  ASSERT_LE(alpha, 0.999);
  const Coefficients c = optical(alpha, m.eta);
  const double got = model(c)->total_reflectance();
  const double got_se = mc_table_total(c, t).stderr_;  // Σ|w| se: a bound (see above)

  MonteCarloOptions o;
  o.photons = m.photons;
  o.seed = 31 + static_cast<std::uint64_t>(1e4 * alpha);
  o.threads = 1;
  // Roulette at 5% of the entry weight: unbiased for any setting (MonteCarlo.
  // RouletteIsUnbiased) and far cheaper for bright media than the default 1e-4.
  o.roulette_weight = 0.05;
  const auto t0 = std::chrono::steady_clock::now();
  const MonteCarloResult r = run_monte_carlo(c, o);
  const double secs = seconds_since(t0);
  ASSERT_EQ(r.truncated_photons, 0u);
  const double mc = r.reflectance.total, mc_se = r.reflectance.total_stderr;
  const double se = std::hypot(got_se, mc_se), rel = got / mc - 1.0;

  // Both estimate the same number; the model may also carry interpolation error, which
  // this test would see as a difference beyond the combined standard error.
  const double z = z_family(kFamilyP, std::size(kOffNode));
  EXPECT_NEAR(got, mc, z * se) << "alpha' " << alpha << " eta " << m.eta;
  // The goal, asserted where the noise alone cannot break it: se <= 1%/z.
  EXPECT_LT(se, 0.01 * mc / z) << "too few photons to test 1% at alpha' " << alpha;
  EXPECT_LT(std::fabs(rel), 0.01) << "alpha' " << alpha << " eta " << m.eta;
  RecordProperty("total_relative_error", std::to_string(rel));
  std::printf("| %.6f | %.3f | %.6f ± %.2g | %.6f ± %.2g | %llu | %+.3f%% | %+.2f | %.3f%% | %.1f s |\n",
              alpha, m.eta, got, got_se, mc, mc_se, static_cast<unsigned long long>(m.photons),
              100 * rel, (got - mc) / se, 100 * se / mc, secs);
}

struct OffNodeName {
  template <class Info>
  std::string operator()(const Info& i) const { return medium_name(i.param.alpha_near, i.param.eta); }
};
INSTANTIATE_TEST_SUITE_P(OffNode, McTableAccuracyTotal, ::testing::ValuesIn(kOffNode), OffNodeName());

// ---------------------------------------------------------------------------------------
// 2. η = 1: the exact total 1 - H(1)√(1 - α') (Chandrasekhar), on a dense sweep.

TEST(McTableAccuracyIndexMatched, TotalWithinHalfAPercentOfExactEverywhere) {
  const McTableData& t = shipped_mc_table();
  // Every node interval in u, at 8 points (t = 0, 1/8, ..., 7/8: its midpoint included),
  // then the last node and points past it (the extrapolation).
  std::vector<double> albedos;
  for (std::size_t i = 0; i + 1 < t.albedo.size(); ++i) {
    const double u0 = std::sqrt(1.0 - t.albedo[i]), u1 = std::sqrt(1.0 - t.albedo[i + 1]);
    for (int k = 0; k < 8; ++k) {
      const double u = u0 + (u1 - u0) * k / 8.0;
      albedos.push_back(k == 0 ? t.albedo[i] : 1.0 - u * u);
    }
  }
  for (double a : {t.albedo.back(), 0.99995, 0.99997, 0.99999, 1.0 - 1e-6, 1.0 - 1e-9})
    albedos.push_back(a);
  const double z = z_family(kFamilyP, albedos.size());
  double worst_rel = 0.0, worst_rel_alpha = 0.0, worst_z = 0.0, worst_mid = 0.0;
  for (double a : albedos) {
    const Coefficients c = optical(a, 1.0);
    const double got = model(c)->total_reflectance();
    const double se = mc_table_total(c, t).stderr_;
    const double exact = exact_total_reflectance_index_matched(a);
    const double rel = got / exact - 1.0;
    // The goal, 0.5% of the exact value.
    EXPECT_LT(std::fabs(rel), 0.005) << "alpha' " << a << ": model " << got << ", exact " << exact;
    // Interpolation adds no error beyond the nodes' noise: the lookup's Σ|w| se bounds
    // that noise, the exact value has none.
    EXPECT_NEAR(got, exact, z * se) << "alpha' " << a;
    if (std::fabs(rel) > worst_rel) worst_rel = std::fabs(rel), worst_rel_alpha = a;
    worst_z = std::max(worst_z, std::fabs(got - exact) / se);
    if (std::find(t.albedo.begin(), t.albedo.end(), a) == t.albedo.end() && a < t.albedo.back())
      worst_mid = std::max(worst_mid, std::fabs(rel));
  }
  RecordProperty("worst_relative_error", std::to_string(worst_rel));
  std::printf("eta = 1, %zu albedos in [%g, 1 - 1e-9]: worst |model/exact - 1| %.3g%% (alpha' %.6f), "
              "between nodes %.3g%%, worst |z| %.2f (bound %.2f)\n",
              albedos.size(), albedos.front(), 100 * worst_rel, worst_rel_alpha, 100 * worst_mid,
              worst_z, z);
}

// ---------------------------------------------------------------------------------------
// 3. R(r) over [0.25, 8] mfp against the analog walk (validate_against_monte_carlo).

struct ProfileCase {
  std::string name;
  Medium medium;
  int channel;
};
void PrintTo(const ProfileCase& p, std::ostream* os) { *os << p.name << " channel " << p.channel; }

// The Jensen presets but spectralon (albedo 1: refused by every model), one channel each,
// rotated B, R, G, B, R, ... along the preset list (4 B, 4 R, 3 G), so each channel is
// covered and the file's time stays bounded: the analog walk (roulette at 1e-4, as
// validate_against_monte_carlo runs it) of a bright channel is slow, and the rotation
// starting at R would give cream its red (α' 0.99997, past the table's last node),
// measured at 56 s alone on this 2-core machine (RMS 2.47%, noise median 1.50%: passes).
std::vector<ProfileCase> preset_cases() {
  std::vector<ProfileCase> v;
  int i = 0;
  for (const Preset& p : presets()) {
    if (p.name == "spectralon") continue;
    v.push_back({std::string(p.name), preset_medium(p), (i++ + 2) % 3});
  }
  return v;
}

// Random media (fixed seed): u = √(1 - α') uniform over u(0.999)..u(0.3) (as the table's
// own nodes, so bright media get their share), η uniform in [1, 2], σt' log-uniform in
// [0.1, 10] mm⁻¹ (a scale the lookup divides out), g = 0; channel R.
std::vector<ProfileCase> random_cases() {
  std::mt19937_64 rng(20261122);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::vector<ProfileCase> v;
  for (int i = 0; i < 6; ++i) {
    const double u = std::sqrt(1.0 - 0.999) + (std::sqrt(1.0 - 0.3) - std::sqrt(1.0 - 0.999)) * uni(rng);
    const double alpha = 1.0 - u * u, eta = 1.0 + uni(rng), stp = std::pow(10.0, -1.0 + 2.0 * uni(rng));
    const Coefficients c = optical(alpha, eta, stp);
    Medium m;
    m.sigma_a = {c.sigma_a, c.sigma_a, c.sigma_a};
    m.sigma_s = {c.sigma_s, c.sigma_s, c.sigma_s};
    m.g = {0.0, 0.0, 0.0};
    m.eta = {eta, eta, eta};
    v.push_back({"Random" + std::to_string(i), m, 0});
  }
  return v;
}

// The validation's photons: a pilot of 4096 measures the median relative error per
// annulus s0, then N = 4096 (s0 / 1.5%)², so the median lands near 1.5%; capped at 2^19.
constexpr double kTargetBinRelSe = 0.015;

class McTableAccuracyProfile : public ::testing::TestWithParam<ProfileCase> {};

TEST_P(McTableAccuracyProfile, WithinFivePercentRmsOfTheAnalogWalk) {
  const ProfileCase& pc = GetParam();
  const int c = pc.channel;
  const Coefficients k = pc.medium.channel(c);
  ValidationOptions o;
  o.models = {Model::McTable};
  o.threads = 1;
  o.channels = {c == 0, c == 1, c == 2};
  o.photons = 4096;
  o.seed = 5;
  const auto t0 = std::chrono::steady_clock::now();
  const ValidationReport pilot = validate_against_monte_carlo(pc.medium, o);
  const double s0 = pilot.median_bin_rel_stderr[c];
  const double want = 4096.0 * (s0 / kTargetBinRelSe) * (s0 / kTargetBinRelSe);
  o.photons = std::clamp<std::uint64_t>(4096 * static_cast<std::uint64_t>(std::ceil(want / 4096.0)),
                                        16384, 1u << 24);
  o.seed = 6;
  const ValidationReport r = validate_against_monte_carlo(pc.medium, o);
  const double secs = seconds_since(t0);
  const ChannelComparison& cc = r.models.at(0).channels[c];
  const MonteCarloResult& mc = r.monte_carlo[c];
  const double noise = r.median_bin_rel_stderr[c];

  // The expected squared relative difference per annulus when the model is right: the
  // analog run's relative variance plus the lookup's (its bound Σ|w_k| s_k, taking the
  // largest over the table annuli that overlap the validation annulus: the two grids have
  // nearly the same ratio, 1.1555 vs 1.1548, so each validation annulus meets two table
  // annuli, three at most).
  const McTableData& t = shipped_mc_table();
  std::vector<double> var_mc, var_all;
  const double mfp = k.mfp_reduced();
  for (std::size_t b = 1; b + 1 < mc.bin_edges_mm.size(); ++b) {
    const double v = mc.reflectance.value[b];
    if (!(v > 0.0)) continue;
    const double s_mc = mc.reflectance.stderr_[b] / v;
    const double r0 = mc.bin_edges_mm[b] / mfp, r1 = mc.bin_edges_mm[b + 1] / mfp;
    double s_tab = 0.0;
    for (std::size_t a = 1; a < t.bins(); ++a)
      if (t.r_edges[a] < r1 && t.r_edges[a + 1] > r0)
        s_tab = std::max(s_tab, interpolated_flux_rel_se(t, k, a));
    var_mc.push_back(s_mc * s_mc);
    var_all.push_back(s_mc * s_mc + s_tab * s_tab);
  }
  ASSERT_GE(var_mc.size(), 20u) << pc.name << ": annuli with light in them";
  // For a right model RMS² = (1/k) Σ v_k z_k², z_k standard normal: a weighted χ², which
  // Satterthwaite's approximation (Satterthwaite 1946, Biometrics Bulletin 2:110) treats as
  // mean(v) χ²_ν/ν with ν = (Σ v)² / Σ v² <= k (the noisier annuli count more). The
  // annuli of one analog run are correlated at η > 1 (one photon leaves through several):
  // test_mc_table_data.cpp measured var(mean z²) up to 1.2 times χ²_k/k's, so ν/2 is used,
  // with margin. Bonferroni over every case of this test.
  const std::size_t cases = preset_cases().size() + random_cases().size();
  auto noise_rms_bound = [&](const std::vector<double>& v) {
    double sum = 0.0, sum2 = 0.0;
    for (double x : v) sum += x, sum2 += x * x;
    const double nu = sum * sum / sum2;
    const double q = chi2_over_k_quantile(nu / 2.0, kFamilyP / static_cast<double>(cases));
    return std::sqrt(sum / static_cast<double>(v.size()) * q);
  };
  const double mc_bound = noise_rms_bound(var_mc), all_bound = noise_rms_bound(var_all);
  const double mc_rms = std::sqrt(std::accumulate(var_mc.begin(), var_mc.end(), 0.0) /
                                  static_cast<double>(var_mc.size()));
  const double all_rms = std::sqrt(std::accumulate(var_all.begin(), var_all.end(), 0.0) /
                                   static_cast<double>(var_all.size()));

  // The goal.
  EXPECT_LT(cc.rms_rel_error, 0.05) << pc.name;
  // 5% means something: the analog noise per annulus is small (median <= 2%), and that
  // noise alone could not reach 5% RMS at the family-wise rate.
  EXPECT_LE(noise, 0.02) << pc.name << ": too few photons for the 5% goal to be meaningful";
  EXPECT_LT(mc_bound, 0.05) << pc.name;
  // The RMS is explained by the noise of the two Monte Carlo results (the analog run's and
  // the table's, the latter by its bound): no model error beyond them.
  EXPECT_LT(cc.rms_rel_error, all_bound) << pc.name;
  RecordProperty("rms_relative_error", std::to_string(cc.rms_rel_error));
  RecordProperty("median_bin_rel_stderr", std::to_string(noise));
  std::printf("| %s | %c | %.5f | %.3f | %.2f%% | %.2f%% | %.2f%% | %.2f%% | %.2f%% | %.2f%% | %llu | %.1f s |\n",
              pc.name.c_str(), "RGB"[c], k.albedo_reduced(), k.eta, 100 * cc.rms_rel_error,
              100 * cc.max_rel_error, 100 * noise, 100 * mc_rms, 100 * all_rms, 100 * all_bound,
              static_cast<unsigned long long>(o.photons), secs);
}

struct CaseName {
  template <class Info>
  std::string operator()(const Info& i) const { return i.param.name; }
};
INSTANTIATE_TEST_SUITE_P(Presets, McTableAccuracyProfile, ::testing::ValuesIn(preset_cases()), CaseName());
INSTANTIATE_TEST_SUITE_P(RandomMedia, McTableAccuracyProfile, ::testing::ValuesIn(random_cases()),
                         CaseName());

// ---------------------------------------------------------------------------------------
// 4. Interpolation error at midpoints, against fresh generate_mc_table runs (the table's
// own generator, other seeds, small budgets) whose nodes are exactly the midpoints.
//
// Two criteria, for each of the two interpolations (across (α', η), and across r: the
// reconstruction's split of an annulus' flux).
//  a) The model (shipped table) against a fresh run at the midpoints: mean z² over every
//     annulus within its χ² bound, z = difference / √(se_model² + se_fresh²) with the
//     lookup's Σ|w| bound for se_model and the fresh run's stored (batch-means) error.
//     This is the test in standard errors; its power is limited by the noise of
//     both sides (it sees an interpolation error comparable to their combined noise).
//  b) The interpolation error itself, measured below the table's noise. "RMS of the
//     model-vs-fresh differences below the fresh run's median relative error" cannot be
//     asserted as such: that RMS contains the fresh run's own noise, whose mean square
//     over the annuli exceeds its median (relative errors grow outwards), so it would fail
//     about half the time with a perfect model. Instead each fresh run also carries the
//     table nodes around each midpoint; the lookup interpolates THOSE nodes of the same
//     run (same weights as with the shipped table: the Catmull-Rom stencil uses only the
//     segment's nodes and one more on each side, all carried) and is compared with the
//     same run's midpoint node. Both come from the same walks, so their noise largely
//     cancels and what remains is the interpolation error; its noise is measured from
//     independent repetitions (seeds). Asserted: the RMS over annuli and media of the
//     mean relative difference (noise included, so an overestimate) is below the median
//     relative standard error of the shipped table's own nodes there, i.e. interpolating
//     adds less error than the table's data already has. Across r the same idea needs a
//     known profile instead of a paired run (see HalfAnnulusReconstructionError... below).

// Differences between the model and a fresh run, per annulus.
struct Differences {
  std::vector<double> z;  // (model - fresh) / √(se_model² + se_fresh²)
  std::vector<double> rel, fresh_rel_se, model_rel_se;
  void add(double m, double m_se, double f, double f_se) {
    z.push_back((m - f) / std::hypot(m_se, f_se));
    rel.push_back(m / f - 1.0);
    fresh_rel_se.push_back(f_se / f);
    model_rel_se.push_back(m_se / m);
  }
  double mean_z2() const { return mean_square(z); }
};

// Criterion a). Every annulus of every medium of one fresh run shares its walks, so the z
// are correlated: the mean over all of them varies at most as much as one medium's mean
// over its k annuli, and that spread is bounded as in section 3 (k' = k/2). Batch means
// from 256 batches make each z Student-t with 255 degrees of freedom (E z² = 1.008).
void expect_z2_within_chi2(const Differences& d, int annuli_per_medium, const char* what) {
  const double bound = chi2_over_k_quantile(annuli_per_medium / 2.0, kFamilyP);
  EXPECT_LT(d.mean_z2(), bound) << what;
  for (double x : d.z) EXPECT_TRUE(std::isfinite(x)) << what;
  std::printf("%s, model vs fresh run: %zu annuli, mean z^2 %.3f (bound %.2f), RMS relative "
              "difference %.2f%%, fresh run's median relative error %.2f%%, model's (bound) %.2f%%\n",
              what, d.z.size(), d.mean_z2(), bound, 100 * std::sqrt(mean_square(d.rel)),
              100 * median(d.fresh_rel_se), 100 * median(d.model_rel_se));
}

// Criterion b): per compared item (medium, annulus), the relative difference of one
// repetition; items missing from a repetition (annulus not enforced there) are dropped.
struct PairedDifferences {
  std::vector<std::vector<double>> runs;  // [repetition][item]
  std::vector<double> table_rel_se;       // [item]: the shipped table's node error there
};

// Criterion b)'s assertion. Per item, the mean over R repetitions D̄ and its standard error
// sd/√R. The RMS of D̄ over the items estimates the interpolation error plus that noise; it
// must lie below the median relative error of the shipped table's nodes. Printed: also
// the noise-subtracted estimate √(mean D̄² - mean se²).
void expect_interpolation_below_table_noise(const PairedDifferences& p, const char* what) {
  const std::size_t reps = p.runs.size(), items = p.table_rel_se.size();
  ASSERT_GE(reps, 2u);
  double sum_d2 = 0.0, sum_se2 = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < items; ++i) {
    double mean = 0.0, sq = 0.0;
    for (const auto& r : p.runs) mean += r[i] / static_cast<double>(reps);
    for (const auto& r : p.runs) sq += (r[i] - mean) * (r[i] - mean);
    const double se2 = sq / static_cast<double>((reps - 1) * reps);
    sum_d2 += mean * mean;
    sum_se2 += se2;
    worst = std::max(worst, std::fabs(mean));
  }
  const double rms = std::sqrt(sum_d2 / static_cast<double>(items));
  const double noise = std::sqrt(sum_se2 / static_cast<double>(items));
  const double estimate = std::sqrt(std::max(0.0, (sum_d2 - sum_se2) / static_cast<double>(items)));
  const double table = median(p.table_rel_se);
  EXPECT_LT(rms, table) << what;
  ::testing::Test::RecordProperty(std::string(what) + " interpolation_rms", std::to_string(rms));
  std::printf("%s, paired (%zu repetitions, %zu items): interpolation error RMS %.3f%% (its noise "
              "%.3f%%, noise-subtracted %.3f%%, worst |mean| %.3f%%) vs the shipped table's median "
              "relative error %.3f%%\n",
              what, reps, items, 100 * rms, 100 * noise, 100 * estimate, 100 * worst, 100 * table);
}

McTableOptions fresh_options(std::vector<double> eta, std::vector<double> albedo,
                             std::vector<double> edges, std::uint64_t photons, std::uint64_t seed) {
  McTableOptions o;
  const McTableData& t = shipped_mc_table();
  o.eta = std::move(eta);
  o.albedo = std::move(albedo);
  o.r_edges = std::move(edges);
  o.photons = photons;
  o.chunk_photons = photons / 256;  // 256 batches: batch-means errors with 255 dof
  o.seed = seed;
  o.threads = 1;
  o.roulette_weight = t.roulette_weight;
  o.roulette_survival = t.roulette_survival;
  return o;
}

// The part of a fresh run at the given node indices (a table of its own).
McTableData subset(const McTableData& f, const std::vector<std::size_t>& ei,
                   const std::vector<std::size_t>& ai) {
  McTableData s = f;
  s.eta.clear();
  s.albedo.clear();
  s.total.clear();
  s.total_se.clear();
  s.flux.clear();
  s.flux_se.clear();
  s.single_total.clear();
  s.single_total_se.clear();
  s.single_flux.clear();
  s.single_flux_se.clear();
  s.multiple_total_se.clear();
  s.multiple_flux_se.clear();
  for (std::size_t e : ei) s.eta.push_back(f.eta[e]);
  for (std::size_t a : ai) s.albedo.push_back(f.albedo[a]);
  for (std::size_t e : ei) {
    s.single_total.push_back(f.single_total[e]);
    s.single_total_se.push_back(f.single_total_se[e]);
    for (std::size_t b = 0; b < f.bins(); ++b) {
      s.single_flux.push_back(f.single_flux[f.single_slot(e, b)]);
      s.single_flux_se.push_back(f.single_flux_se[f.single_slot(e, b)]);
    }
    for (std::size_t a : ai) {
      s.total.push_back(f.total[f.node(e, a)]);
      s.total_se.push_back(f.total_se[f.node(e, a)]);
      s.multiple_total_se.push_back(f.multiple_total_se[f.node(e, a)]);
      for (std::size_t b = 0; b < f.bins(); ++b) {
        s.flux.push_back(f.flux[f.slot(e, a, b)]);
        s.flux_se.push_back(f.flux_se[f.slot(e, a, b)]);
        s.multiple_flux_se.push_back(f.multiple_flux_se[f.slot(e, a, b)]);
      }
    }
  }
  return s;
}

std::size_t index_of(const std::vector<double>& axis, double x) {
  return static_cast<std::size_t>(std::find(axis.begin(), axis.end(), x) - axis.begin());
}

// The midpoint media of the (α', η) test: η halfway between nodes (nodes every 0.05), α'
// halfway in u between the nodes around 0.5, 0.9 and 0.98.
const std::vector<double> kMidEtas = {1.325, 1.475, 1.775};
std::vector<double> mid_albedos() {
  std::vector<double> v;
  for (double near : {0.5, 0.9, 0.98}) v.push_back(albedo_midpoint(shipped_mc_table(), near));
  return v;
}
// The table's annulus edges over [0.25, 8] mfp, after a disc from 0.
std::vector<double> covering_edges() {
  const McTableData& t = shipped_mc_table();
  const EdgeRange er = annuli_covering(t.r_edges, 0.25, 8.0);
  std::vector<double> edges = {0.0};
  edges.insert(edges.end(), t.r_edges.begin() + static_cast<std::ptrdiff_t>(er.first),
               t.r_edges.begin() + static_cast<std::ptrdiff_t>(er.last) + 1);
  return edges;
}

TEST(McTableAccuracyInterpolation, AlbedoAndEtaMidpointsAgreeWithAFreshRunThere) {
  const McTableData& t = shipped_mc_table();
  const EdgeRange er = annuli_covering(t.r_edges, 0.25, 8.0);
  const std::vector<double> albedos = mid_albedos();
  const auto t0 = std::chrono::steady_clock::now();
  // 2^18 walks: the fresh run's median relative error per annulus ~2%, the model's bound
  // ~0.8%, so z is dominated by the fresh run's noise.
  const McTableData f = generate_mc_table(fresh_options(kMidEtas, albedos, covering_edges(), 1u << 18, 4242));
  const double secs = seconds_since(t0);
  Differences d;
  for (std::size_t e = 0; e < kMidEtas.size(); ++e)
    for (std::size_t a = 0; a < albedos.size(); ++a) {
      const Coefficients c = optical(albedos[a], kMidEtas[e]);
      const auto p = model(c);
      for (std::size_t b = er.first; b < er.last; ++b) {
        const double m = model_flux(*p, t.r_edges[b], t.r_edges[b + 1]);
        const std::size_t s = f.slot(e, a, b - er.first + 1);
        d.add(m, m * interpolated_flux_rel_se(t, c, b), f.flux[s], f.flux_se[s]);
      }
    }
  std::printf("fresh run: %zu eta x %zu albedo midpoints, %llu walks, %.1f s\n", kMidEtas.size(),
              albedos.size(), static_cast<unsigned long long>(f.photons), secs);
  expect_z2_within_chi2(d, static_cast<int>(er.last - er.first), "(albedo', eta) midpoints");
}

TEST(McTableAccuracyInterpolation, AlbedoAndEtaInterpolationErrorIsBelowTheTableNoise) {
  const McTableData& t = shipped_mc_table();
  const EdgeRange er = annuli_covering(t.r_edges, 0.25, 8.0);
  const std::vector<double> mid_a = mid_albedos();
  // Each midpoint's stencil: the shipped nodes i-1 .. i+2 around its segment, on both axes.
  std::vector<double> node_eta, node_albedo;
  for (double eta : kMidEtas) {
    const auto [lo, hi] = stencil_range(t.eta, eta);
    for (std::size_t e = lo; e <= hi; ++e) node_eta.push_back(t.eta[e]);
  }
  for (double a : mid_a) {
    const auto [lo, hi] = stencil_range(t.albedo, a);
    for (std::size_t i = lo; i <= hi; ++i) node_albedo.push_back(t.albedo[i]);
  }
  auto sorted_union = [](std::vector<double> a, const std::vector<double>& b) {
    a.insert(a.end(), b.begin(), b.end());
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
    return a;
  };
  node_eta = sorted_union(node_eta, {});
  node_albedo = sorted_union(node_albedo, {});
  const std::vector<double> all_eta = sorted_union(node_eta, kMidEtas);
  const std::vector<double> all_albedo = sorted_union(node_albedo, mid_a);
  std::vector<std::size_t> ei, ai;
  for (double x : node_eta) ei.push_back(index_of(all_eta, x));
  for (double x : node_albedo) ai.push_back(index_of(all_albedo, x));

  PairedDifferences p;
  std::vector<std::vector<char>> present;
  const auto t0 = std::chrono::steady_clock::now();
  constexpr int kReps = 6;
  for (int rep = 0; rep < kReps; ++rep) {
    const McTableData f =
        generate_mc_table(fresh_options(all_eta, all_albedo, covering_edges(), 1u << 17, 5000 + rep));
    const McTableData s = subset(f, ei, ai);
    std::vector<double> run;
    std::vector<char> ok;
    for (double eta : kMidEtas)
      for (double a : mid_a) {
        const McTableProfile m(optical(a, eta), s);
        const std::size_t fe = index_of(all_eta, eta), fa = index_of(all_albedo, a);
        for (std::size_t b = 1; b < f.bins(); ++b) {
          const bool use = m.enforced()[b] != 0;
          ok.push_back(use);
          run.push_back(use ? m.target_flux()[b] / f.flux[f.slot(fe, fa, b)] - 1.0 : 0.0);
          if (rep == 0) {
            // The shipped table's relative error at this annulus, at the stencil's nodes.
            const auto [e0, e1] = stencil_range(t.eta, eta);
            const auto [a0, a1] = stencil_range(t.albedo, a);
            std::vector<double> se;
            for (std::size_t e = e0; e <= e1; ++e)
              for (std::size_t i = a0; i <= a1; ++i) {
                const std::size_t k = t.slot(e, i, er.first + b - 1);
                se.push_back(t.flux_se[k] / t.flux[k]);
              }
            p.table_rel_se.push_back(median(se));
          }
        }
      }
    p.runs.push_back(run);
    present.push_back(ok);
  }
  // Keep the items every repetition enforced.
  PairedDifferences kept;
  kept.runs.resize(kReps);
  for (std::size_t i = 0; i < p.table_rel_se.size(); ++i) {
    bool all = true;
    for (const auto& ok : present) all = all && ok[i];
    if (!all) continue;
    kept.table_rel_se.push_back(p.table_rel_se[i]);
    for (int r = 0; r < kReps; ++r) kept.runs[static_cast<std::size_t>(r)].push_back(p.runs[static_cast<std::size_t>(r)][i]);
  }
  std::printf("paired fresh runs: %zu eta x %zu albedo nodes (%zu midpoints each), %d x %u walks, %.1f s\n",
              all_eta.size(), all_albedo.size(), kMidEtas.size(), kReps, 1u << 17, seconds_since(t0));
  ASSERT_GE(kept.table_rel_se.size(), 9u * 20u) << "annuli enforced in every repetition";
  expect_interpolation_below_table_noise(kept, "(albedo', eta) midpoints");
}

// Table nodes (the lookup returns the node there, so only the reconstruction in r is
// tested): a mid albedo and a bright one, with and without internal reflection.
std::vector<double> node_albedos_for_r() {
  const McTableData& t = shipped_mc_table();
  std::vector<double> v;
  for (double near : {0.8, 0.99}) {
    const auto it = std::min_element(t.albedo.begin(), t.albedo.end(), [&](double x, double y) {
      return std::fabs(x - near) < std::fabs(y - near);
    });
    v.push_back(*it);
  }
  return v;
}
const std::vector<double> kNodeEtasForR = {1.0, 1.3};

// The table's edges over [0.25, 8] mfp with each annulus split at its log midpoint.
std::vector<double> split_edges() {
  const std::vector<double> e = covering_edges();
  std::vector<double> s = {0.0};
  for (std::size_t b = 1; b + 1 < e.size(); ++b) {
    s.push_back(e[b]);
    s.push_back(std::sqrt(e[b] * e[b + 1]));
  }
  s.push_back(e.back());
  return s;
}

TEST(McTableAccuracyInterpolation, HalfAnnuliAgreeWithAFreshRunOnTheSplitGrid) {
  const McTableData& t = shipped_mc_table();
  const EdgeRange er = annuli_covering(t.r_edges, 0.25, 8.0);
  const std::vector<double> albedos = node_albedos_for_r(), edges = split_edges();
  const auto t0 = std::chrono::steady_clock::now();
  const McTableData f = generate_mc_table(fresh_options(kNodeEtasForR, albedos, edges, 1u << 18, 4343));
  const double secs = seconds_since(t0);
  Differences d;
  for (std::size_t e = 0; e < kNodeEtasForR.size(); ++e)
    for (std::size_t a = 0; a < albedos.size(); ++a) {
      const auto p = model(optical(albedos[a], kNodeEtasForR[e]));
      const std::size_t te = index_of(t.eta, kNodeEtasForR[e]), ta = index_of(t.albedo, albedos[a]);
      ASSERT_LT(te, t.eta.size());
      ASSERT_LT(ta, t.albedo.size());
      for (std::size_t j = 1; j + 1 < edges.size(); ++j) {
        const double m = model_flux(*p, edges[j], edges[j + 1]);
        // A half annulus' error in the reconstruction: its annulus' flux error and its
        // neighbours' (they set the spline's slope across it); bounded by the largest
        // relative error of annuli b-1 .. b+1 at the node.
        const std::size_t b = er.first + (j - 1) / 2;
        double s_tab = 0.0;
        for (std::size_t n = b - 1; n <= b + 1; ++n) {
          const std::size_t k = t.slot(te, ta, n);
          s_tab = std::max(s_tab, t.flux_se[k] / t.flux[k]);
        }
        const std::size_t s = f.slot(e, a, j);
        d.add(m, m * s_tab, f.flux[s], f.flux_se[s]);
      }
    }
  std::printf("fresh run: %zu eta x %zu albedo table nodes on %zu half annuli, %llu walks, %.1f s\n",
              kNodeEtasForR.size(), albedos.size(), edges.size() - 2,
              static_cast<unsigned long long>(f.photons), secs);
  expect_z2_within_chi2(d, static_cast<int>(edges.size() - 2), "half annuli");
}

// Criterion b) in r. A paired Monte Carlo measurement does not work here: a half
// annulus' share of its annulus is a binomial-like fraction of the walks through it, so
// the noise of "reconstructed half / fresh half" does not cancel (measured: 6 runs of 2^17
// walks on the split grid, merged into whole annuli and split again by the reconstruction,
// gave an RMS of 0.85% with a noise of 0.86% on its mean, against the table's 0.34%;
// resolving 0.1% would take ~30x the walks, a minute). The reconstruction's own error is
// deterministic, though: given exact annulus fluxes of a known smooth profile, how well
// do its half-annulus integrals match the profile's? The known profiles are the two
// shapes the Monte Carlo profile lies between: Burley's (e^{-r/d} + e^{-r/3d})/r, with the
// 1/r single-scattering peak, and the better dipole's, finite at 0; both at the table
// nodes of the fresh-run test above, in optical units, tabulated on the shipped table's
// own radial grid (as one-node tables, so no (α', η) interpolation is involved).
// Asserted: RMS over the half annuli in [0.25, 8] mfp below the shipped table's median
// relative error at that node (its noise there); measured far below.
TEST(McTableAccuracyInterpolation, HalfAnnulusReconstructionErrorIsBelowTheTableNoise) {
  const McTableData& t = shipped_mc_table();
  const EdgeRange er = annuli_covering(t.r_edges, 0.25, 8.0);
  // ∫ 2π r R over [r0, r1] in x = ln r, 8 panels of 16 Gauss-Legendre points: on these
  // smooth integrands (an annulus spans 0.144 in x) exact to rounding.
  auto flux = [](const RadialProfile& p, double r0, double r1) {
    return integrate([&](double x) {
                       const double r = std::exp(x);
                       return 2.0 * std::numbers::pi * r * r * p.reflectance(r);
                     },
                     std::log(r0), std::log(r1), 8, 16);
  };
  double worst_rms = 0.0;
  for (Model shape : {Model::Burley, Model::BetterDipole})
    for (double eta : kNodeEtasForR)
      for (double alpha : node_albedos_for_r()) {
        const Coefficients c = optical(alpha, eta);
        const auto truth = make_profile(shape, c, kInf, {});
        McTableData k;
        k.photons = 2;
        k.chunk_photons = 1;
        k.eta = {eta};
        k.albedo = {alpha};
        k.r_edges = t.r_edges;
        double sum = 0.0;
        for (std::size_t b = 0; b < t.bins(); ++b) {
          // The disc from 1e-12 mfp: R grows at most like 1/r towards 0 for these shapes,
          // so q = 2π r² R vanishes like r and what lies below is ~1e-9 of the disc's flux.
          const double f = flux(*truth, b == 0 ? 1e-12 : t.r_edges[b], t.r_edges[b + 1]);
          k.flux.push_back(f);
          k.flux_se.push_back(1e-3 * f);  // every annulus reliable
          sum += f;
        }
        k.total = {std::max(sum, truth->total_reflectance())};
        k.total_se = {1e-3 * k.total[0]};
        const McTableProfile rec(c, k);
        std::vector<double> rel, table_se;
        const std::size_t te = index_of(t.eta, eta), ta = index_of(t.albedo, alpha);
        for (std::size_t b = er.first; b < er.last; ++b) {
          const double mid = std::sqrt(t.r_edges[b] * t.r_edges[b + 1]);
          for (auto [r0, r1] : {std::pair{t.r_edges[b], mid}, std::pair{mid, t.r_edges[b + 1]}})
            rel.push_back(flux(rec, r0, r1) / flux(*truth, r0, r1) - 1.0);
          table_se.push_back(t.flux_se[t.slot(te, ta, b)] / t.flux[t.slot(te, ta, b)]);
        }
        const double rms = std::sqrt(mean_square(rel)), noise = median(table_se);
        double worst = 0.0;
        for (double x : rel) worst = std::max(worst, std::fabs(x));
        EXPECT_LT(rms, noise) << model_name(shape) << " alpha' " << alpha << " eta " << eta;
        worst_rms = std::max(worst_rms, rms);
        std::printf("half annuli, %s shape at alpha' %.5f eta %.2f: reconstruction error RMS %.4f%%, "
                    "worst %.4f%% (%zu half annuli), shipped table's median relative error %.3f%%\n",
                    std::string(model_name(shape)).c_str(), alpha, eta, 100 * rms, 100 * worst,
                    rel.size(), 100 * noise);
      }
  ::testing::Test::RecordProperty("half_annulus_reconstruction_rms", std::to_string(worst_rms));
}

}  // namespace
}  // namespace sss::profiles
