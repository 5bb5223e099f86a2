// Monte Carlo random walk in a stack of layers (run_layered_monte_carlo, issue 19): the
// one-layer stack is run_monte_carlo bit for bit, a split layer walks the same paths to
// rounding, a stack of pure absorbers matches its closed form to rounding, flights carry
// their optical depth across interfaces (binomial test), energy is conserved, the base
// shows in the reflectance and a deep top layer hides it (Z tests), and bad stacks are
// refused naming the layer and field.
#include "profiles/MonteCarlo.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace sss::profiles {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Statistical checks are two-sided Z tests at 4 standard errors: each fails by chance with
// probability erfc(4/√2) ≈ 6.3e-5. This file makes 5 such checks (FlightsCarry... 1,
// EnergyBalance 2, DeepTopLayer... 2), so the family-wise false-failure probability is below
// 5 × 6.3e-5 ≈ 3.2e-4 (Bonferroni); the runs are seeded, so a given build either passes
// or fails them every time.
constexpr double kZ = 4.0;

MonteCarloOptions options(std::uint64_t photons, std::uint64_t seed = 1) {
  MonteCarloOptions o;
  o.photons = photons;
  o.seed = seed;
  o.threads = 1;  // ctest runs tests in parallel; each test measures on one core
  return o;
}

void expect_identical_tally(const MonteCarloTally& a, const MonteCarloTally& b, const char* what) {
  EXPECT_EQ(a.total, b.total) << what;
  EXPECT_EQ(a.total_stderr, b.total_stderr) << what;
  EXPECT_EQ(a.value, b.value) << what;
  EXPECT_EQ(a.stderr_, b.stderr_) << what;
}

// Every number of two results, compared with ==: bit for bit (no NaN occurs in them).
void expect_identical(const MonteCarloResult& a, const MonteCarloResult& b) {
  EXPECT_EQ(a.bin_edges_mm, b.bin_edges_mm);
  expect_identical_tally(a.reflectance, b.reflectance, "reflectance");
  expect_identical_tally(a.transmittance, b.transmittance, "transmittance");
  expect_identical_tally(a.reflectance_by_exit_cosine, b.reflectance_by_exit_cosine, "by exit cosine");
  EXPECT_EQ(a.photons, b.photons);
  EXPECT_EQ(a.scattering_events, b.scattering_events);
  EXPECT_EQ(a.absorbed, b.absorbed);
  EXPECT_EQ(a.absorbed_stderr, b.absorbed_stderr);
  EXPECT_EQ(a.low_order_exits, b.low_order_exits);
  EXPECT_EQ(a.low_order_exits_stderr, b.low_order_exits_stderr);
  EXPECT_EQ(a.truncated_photons, b.truncated_photons);
}

// ---------------------------------------------------------------------------------------
// a. run_monte_carlo is the one-layer case of the layered walk: the same code path, so a
// one-layer stack must give the same bits, for every option that changes the walk or the
// tallies. (Checked further by run_monte_carlo's own tests, which stayed green and
// reproduced their pre-change outputs to 17 digits when the walk became layered.)
TEST(LayeredMonteCarlo, OneLayerStackIsRunMonteCarlo) {
  struct Case {
    Coefficients c;
    double thickness_mm;
    MonteCarloOptions o;
  };
  std::vector<Case> cases;
  {
    MonteCarloOptions o = options(3 * kMonteCarloChunkPhotons / 2, 3);  // a partial chunk
    o.bin_edges_mm = log_bin_edges(0.01, 10.0, 8);
    o.exit_cosine_bins = 5;
    o.incidence_cos = 0.7;
    cases.push_back({{0.05, 5.0, 0.7, 1.4}, 1.0, o});  // finite slab, oblique
  }
  {
    MonteCarloOptions o = options(kMonteCarloChunkPhotons, 4);
    o.bin_edges_mm = log_bin_edges(0.01, 10.0, 8);
    o.min_scattering_order = 2;
    o.exit_cosine_bins = 3;
    cases.push_back({{0.1, 2.0, -0.3, 1.3}, kInf, o});  // semi-infinite
  }
  {
    MonteCarloOptions o = options(kMonteCarloChunkPhotons, 5);
    o.max_scattering_order = 3;
    o.min_scattering_order = 2;
    o.roulette_weight = 0.5;
    o.roulette_survival = 0.5;
    cases.push_back({{0.2, 1.0, 0.5, 1.5}, 2.0, o});  // slab, orders and roulette
  }
  {
    MonteCarloOptions o = options(kMonteCarloChunkPhotons, 6);
    o.max_interactions_per_photon = 4;
    cases.push_back({{0.02, 1.0, 0.9, 1.2}, 3.0, o});  // truncation
  }
  {
    MonteCarloOptions o = options(100, 7);
    o.bin_edges_mm = {0.0, 1.0};
    cases.push_back({{0.3, 0.0, 0.0, 1.5}, 2.0, o});  // no scattering: deterministic
  }
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    const Case& k = cases[i];
    MonteCarloOptions single = k.o;
    single.thickness_mm = k.thickness_mm;
    const MonteCarloResult a = run_monte_carlo(k.c, single);
    const MonteCarloResult b = run_layered_monte_carlo({Layer{k.c, k.thickness_mm}}, k.o);
    expect_identical(a, b);
    EXPECT_GT(a.reflectance.total, 0.0);  // the comparison is not of empty results
  }
}

// ---------------------------------------------------------------------------------------
// b. A layer split in two identical layers (thicknesses summing exactly, in binary, to
// the original) walks the same paths. Every random number is drawn at the same point of
// the walk (a crossing draws none: the flight carries its optical depth on), the
// directions are bit-identical (they depend on the random numbers and the previous
// direction only), and what differs is rounding: at a crossing the photon is put on the
// interface and the rest of the flight is (τ - σs d1)/σs instead of τ/σs - d1, and the
// weight is folded as e^{-σa l1} e^{-σa l2} instead of e^{-σa (l1 + l2)}. So the results
// are NOT bit-identical, but positions differ by a few ulps of the distances walked and
// weights by a few ulps per crossing: a photon's contribution w = e^{-σa L} changes by
// σa δL + (crossings) ε relative, with δL ≲ (events) ε × (largest coordinate). With
// σa = 0.1 mm^-1, walks of ≲ 1e3 events and coordinates ≲ 1e2 mm (roulette ends a walk
// after ln(1e4)/σa = 92 mm of path on average), that is ≲ 1e-11 relative: the totals
// must agree to 1e-9 relative, far below their standard errors (~1e-2 relative).
// The discrete decisions (scatter or reach a face, roulette, the radial bin) see the same
// numbers up to that rounding; one of them could flip only if a compared pair fell within
// ~1e-11 relative of each other, which over the ~1e6 decisions here has a chance of
// order 1e-5 (a fixed seed decides it once and for all). The scattering-event counts
// must therefore be equal: a flight that resampled its depth at the interface (as a
// memoryless but different scheme would) changes them at once. Measured: R and T equal
// to the bit, absorbed within 1.1e-16 relative, the event counts equal.
TEST(LayeredMonteCarlo, SplitLayerWalksTheSamePaths) {
  const Coefficients c{0.1, 3.0, 0.6, 1.4};
  struct Split {
    double whole, first, second;
  };
  // 0.375 + 0.625 == 1.0 exactly, so the bottom face is at the same z.
  for (const Split& s : {Split{1.0, 0.375, 0.625}, Split{kInf, 0.5, kInf}}) {
    SCOPED_TRACE("thickness " + std::to_string(s.whole));
    MonteCarloOptions o = options(kMonteCarloChunkPhotons, 21);
    o.bin_edges_mm = log_bin_edges(0.05, 10.0, 6);
    const MonteCarloResult one = run_layered_monte_carlo({Layer{c, s.whole}}, o);
    const MonteCarloResult two = run_layered_monte_carlo({Layer{c, s.first}, Layer{c, s.second}}, o);
    const double tol = 1e-9;
    EXPECT_EQ(one.scattering_events, two.scattering_events);
    EXPECT_NEAR(two.reflectance.total, one.reflectance.total, tol * one.reflectance.total);
    EXPECT_NEAR(two.transmittance.total, one.transmittance.total, tol * one.transmittance.total);
    EXPECT_NEAR(two.absorbed, one.absorbed, tol * one.absorbed);
    for (std::size_t b = 0; b < one.reflectance.value.size(); ++b)
      EXPECT_NEAR(two.reflectance.value[b], one.reflectance.value[b], tol * one.reflectance.value[b])
          << "bin " << b;
  }
}

// ---------------------------------------------------------------------------------------
// c. Pure absorbers (σs = 0 in every layer) under normal incidence: the walk draws no
// random number and the beam goes straight down and up the stack, losing
// e^{-τ}, τ = Σk σa,k dk, per pass and splitting with F = ((η-1)/(η+1))² at each outer
// face (the interfaces between layers are index-matched: no reflection there):
//   T = (1-F) e^{-τ} Σj (F² e^{-2τ})^j = (1-F) e^{-τ} / (1 - F² e^{-2τ}),
//   R = (1-F) F e^{-2τ} Σj (F² e^{-2τ})^j = (1-F) F e^{-2τ} / (1 - F² e^{-2τ}),
//   A = 1 - R - T, every exit at r = 0,
// per unit power entered (R counts what leaves through the top after entering).
// Rounding: every photon's contribution is the same number, and summing N of them is
// exact to (N - 1) ε relative; the contribution itself carries a few ε per factor of its
// leading terms (one exp per layer per pass, the Fresnel factor, the escape product;
// later passes are damped by F² e^{-2τ} < 1e-3 each), and the formula a few more: the
// tolerance (N + 64) ε ≈ 2.4e-13 relative (N = 1000) covers both with room.
TEST(LayeredMonteCarlo, NonScatteringStackIsExact) {
  const std::vector<double> sigma_a{0.3, 1.2, 0.05}, thickness{0.5, 0.25, 2.0};
  const std::uint64_t n = 1000;
  for (double eta : {1.0, 1.5}) {
    SCOPED_TRACE("eta " + std::to_string(eta));
    std::vector<Layer> stack;
    double tau = 0.0;
    for (std::size_t k = 0; k < sigma_a.size(); ++k) {
      stack.push_back({{sigma_a[k], 0.0, 0.0, eta}, thickness[k]});
      tau += sigma_a[k] * thickness[k];
    }
    MonteCarloOptions o = options(n);
    o.bin_edges_mm = {0.0, 0.5, 1.0};
    const MonteCarloResult r = run_layered_monte_carlo(stack, o);
    const double f = std::pow((eta - 1.0) / (eta + 1.0), 2), e = std::exp(-tau);
    const double series = 1.0 / (1.0 - f * f * e * e);
    const double t = (1.0 - f) * e * series, rr = (1.0 - f) * f * e * e * series;
    const double tol = (n + 64) * kEps;
    EXPECT_NEAR(r.transmittance.total, t, tol * t);
    EXPECT_NEAR(r.reflectance.total, rr, tol * rr);  // eta 1: F = 0, so R = 0 exactly
    EXPECT_NEAR(r.absorbed, 1.0 - t - rr, tol);
    const double disc = std::numbers::pi * 0.25;  // every exit in the first bin, r in [0, 0.5)
    EXPECT_NEAR(r.transmittance.value[0], t / disc, tol * t / disc);
    EXPECT_EQ(r.transmittance.value[1], 0.0);
    EXPECT_EQ(r.scattering_events, 0u);
    EXPECT_EQ(r.truncated_photons, 0u);
  }
}

// ---------------------------------------------------------------------------------------
// Flights carry their optical depth across interfaces with each layer's σs. In an
// index-matched stack (η = 1: no Fresnel reflection anywhere) with one interaction
// allowed per photon (crossing an interface is not an interaction), a photon either
// crosses the whole stack unscattered, with probability p = e^{-Σk σs,k dk}, leaving
// weight e^{-Σk σa,k dk} through the bottom, or is truncated at its first scattering
// event. The middle layer is a pure absorber (σs = 0): flights cross it spending no depth.
// The truncated count is binomial(N, 1 - p): a 4σ Z test. Using one layer's σs for the
// whole flight instead would give p = e^{-2 × 1.7} = 0.033 or e^{-0.5 × 1.7} = 0.43
// instead of e^{-1.1} = 0.33 (σ = 0.0037 here: 80 and 26 σ away). The transmittance is
// then exactly the unscattered fraction times the weight, to (N + 16) ε relative
// (summing N equal weights, plus a few ε in the weight's three exp factors).
// Measured: 0.3 σ from p.
TEST(LayeredMonteCarlo, FlightsCarryTheirOpticalDepthAcrossLayers) {
  const std::vector<Layer> stack{{{0.1, 2.0, 0.3, 1.0}, 0.3},
                                 {{0.5, 0.0, 0.0, 1.0}, 0.4},
                                 {{0.2, 0.5, -0.4, 1.0}, 1.0}};
  const std::uint64_t n = 1 << 14;
  MonteCarloOptions o = options(n, 31);
  o.max_interactions_per_photon = 1;
  const MonteCarloResult r = run_layered_monte_carlo(stack, o);
  const double p = std::exp(-(2.0 * 0.3 + 0.5 * 1.0));
  const double weight = std::exp(-0.1 * 0.3) * std::exp(-0.5 * 0.4) * std::exp(-0.2 * 1.0);
  const double crossed = static_cast<double>(n - r.truncated_photons) / n;
  EXPECT_NEAR(crossed, p, kZ * std::sqrt(p * (1.0 - p) / n));
  EXPECT_NEAR(r.transmittance.total, crossed * weight, (n + 16) * kEps * crossed * weight);
  EXPECT_EQ(r.scattering_events, r.truncated_photons);  // each truncated photon scattered once
  EXPECT_EQ(r.reflectance.total, 0.0);
}

// ---------------------------------------------------------------------------------------
// d. Two really different layers: a thin, strongly absorbing, forward-scattering top
// layer over a bright scattering base, and a pure-absorbing layer between them.

// A thin strongly absorbing top layer, a pure absorber and a bright base (finite, so all
// three tallies are used), η = 1.4.
std::vector<Layer> two_material_stack(double base_thickness_mm) {
  return {{{2.0, 4.0, 0.8, 1.4}, 0.2}, {{0.5, 0.0, 0.0, 1.4}, 0.1},
          {{0.02, 5.0, 0.0, 1.4}, base_thickness_mm}};
}

// R + T + absorbed = 1 in expectation (roulette is unbiased; nothing is truncated). The
// three tallies are correlated, but SD(R + T + A) <= SD(R) + SD(T) + SD(A), so a 4 SE
// test against that bound fails by chance less often than a plain 4 SE test. (Measured:
// |sum - 1| < 0.01 of that bound: with absorption weighting each photon's R + T + A is 1
// but for roulette's gains and losses. Dropping the absorption at an interface crossing
// fails it at once.)
TEST(LayeredMonteCarlo, EnergyBalance) {
  for (double base : {1.0, kInf}) {
    SCOPED_TRACE("base " + std::to_string(base));
    const MonteCarloResult r = run_layered_monte_carlo(two_material_stack(base), options(1 << 14, 41));
    EXPECT_EQ(r.truncated_photons, 0u);
    const double sum = r.reflectance.total + r.transmittance.total + r.absorbed;
    const double se = r.reflectance.total_stderr + r.transmittance.total_stderr + r.absorbed_stderr;
    EXPECT_NEAR(sum, 1.0, kZ * se);
    EXPECT_GT(r.reflectance.total, 0.0);
    EXPECT_EQ(r.transmittance.total > 0.0, base < kInf);
  }
}

// The base matters, in the direction physics gives. Each check compares two independent
// runs (different seeds) and asks that the difference exceed 6 combined standard errors
// sqrt(SE1² + SE2²), in the sign derived below; the measured margins are quoted so that a
// false failure (a fluctuation of margin - 6 SE against the sign) is seen to be out of
// reach (at least 15σ for each).
//
// 1. With η = 1 (no Fresnel reflection at any face) a top layer of thickness t over a
// bright base against the same top layer alone as a slab of thickness t. Couple the walks
// photon by photon: they are the same walk until the photon first reaches z = t; the slab
// then loses it through its bottom face for good (nothing comes back through an
// index-matched face), while in the stack it enters the base, which sends a positive
// fraction of it back up (its albedo is 0.996), and some of that leaves through the top.
// So R_stack > R_slab in expectation; the excess is the light the base returns. Measured:
// R_stack 0.623, R_slab 0.072 (T_slab 0.82), 150 SE.
// 2. With η = 1.4: the walk samples paths with σs alone and weights them by
// e^{-Σk σa,k Lk}, so at fixed paths a higher σa in the base lowers every path's weight:
// the reflectance decreases strictly with the base's σa (0.02 vs 0.5 mm^-1, under the thin
// absorbing top and the pure absorber of two_material_stack). Measured: 0.148 vs 0.074,
// 34 SE.
// 3. The base's own g: at the same σs = 5 mm^-1, a base with g = 0.9 has a reduced
// scattering σs' = σs (1 - g) = 0.5 instead of 5 mm^-1 (similarity relation), a reduced
// albedo of 0.96 instead of 0.996, and the diffuse reflectance of a half-space increases
// strictly with the reduced albedo: the isotropic base reflects more. A walk that
// scattered with the top layer's g in the base would make the two equal. Measured:
// 0.148 vs 0.099, 21 SE (with the top's g = 0.8 used in the base: 0.117 vs 0.116, 0.8 SE).
void expect_more_reflective(const std::vector<Layer>& more, const std::vector<Layer>& less,
                            std::uint64_t seed) {
  const MonteCarloResult a = run_layered_monte_carlo(more, options(1 << 13, seed));
  const MonteCarloResult b = run_layered_monte_carlo(less, options(1 << 13, seed + 1));
  const double se = std::hypot(a.reflectance.total_stderr, b.reflectance.total_stderr);
  EXPECT_GT(a.reflectance.total - b.reflectance.total, 6.0 * se)
      << a.reflectance.total << " vs " << b.reflectance.total;
}

TEST(LayeredMonteCarlo, TheBaseShowsInTheReflectance) {
  const Coefficients top{0.3, 3.0, 0.7, 1.0}, base{0.02, 5.0, 0.0, 1.0};
  expect_more_reflective({{top, 0.3}, {base, kInf}}, {{top, 0.3}}, 51);

  const std::vector<Layer> bright = two_material_stack(kInf);
  std::vector<Layer> dark = bright, forward = bright;
  dark.back().c.sigma_a = 0.5;
  expect_more_reflective(bright, dark, 53);
  forward.back().c.g = 0.9;
  expect_more_reflective(bright, forward, 55);
}

// A top layer 30 reduced mean free paths deep hides any base: it is the top medium alone,
// semi-infinite. Top: σa 0.1, σs 3, g 0.7 (σt' = 1 mm^-1, so 30 mm = 30 mfp'), diffusion
// length 1/σtr = 1/√(3 σa σt') = 1.83 mm: light reaching the base is damped by about
// e^{-30 σtr} ≈ 7e-8 and what returns by its square, against standard errors ~2e-3. Two
// independent runs (different seeds), a 4 SE Z test on R, on a bright and on a dark base
// (2 checks). Measured: -1.2 and -0.02 SE; the transmittance through the bright base's
// bottom face was 7e-8, as estimated. A walk that used the base's g or σs in the top layer
// fails it.
TEST(LayeredMonteCarlo, DeepTopLayerHidesTheBase) {
  const Coefficients top{0.1, 3.0, 0.7, 1.4};
  MonteCarloOptions o = options(1 << 13, 61);
  const MonteCarloResult alone = run_monte_carlo(top, o);
  std::uint64_t seed = 62;
  for (const Coefficients& base : {Coefficients{0.005, 10.0, 0.0, 1.4}, Coefficients{5.0, 1.0, -0.5, 1.4}}) {
    o.seed = seed++;
    const MonteCarloResult stack = run_layered_monte_carlo({Layer{top, 30.0}, Layer{base, 1.0}}, o);
    const double se = std::hypot(alone.reflectance.total_stderr, stack.reflectance.total_stderr);
    EXPECT_NEAR(stack.reflectance.total, alone.reflectance.total, kZ * se) << "base sigma_a " << base.sigma_a;
  }
}

// ---------------------------------------------------------------------------------------
// e. Input errors: std::invalid_argument whose message starts with the layer and field;
// nothing else may escape.

void expect_error(const std::vector<Layer>& layers, const MonteCarloOptions& o, const std::string& start) {
  try {
    run_layered_monte_carlo(layers, o);
    ADD_FAILURE() << "no exception; expected " << start;
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(start, 0), 0u) << "message: " << what << "\nexpected start: " << start;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not std::invalid_argument: " << e.what();
  } catch (...) {
    ADD_FAILURE() << "not a std::exception";
  }
}

TEST(LayeredMonteCarlo, RejectsBadStacksNamingTheLayer) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Coefficients good{0.1, 1.0, 0.0, 1.4};
  const std::vector<Layer> ok{{good, 0.5}, {good, 1.0}, {good, kInf}};
  const MonteCarloOptions o = options(64);
  EXPECT_NO_THROW(run_layered_monte_carlo(ok, o));
  EXPECT_NO_THROW(run_layered_monte_carlo({{good, kInf}}, o));
  EXPECT_NO_THROW(run_layered_monte_carlo({{good, 0.5}, {good, 2.0}}, o));  // finite last layer

  expect_error({}, o, "layers: must not be empty");
  auto with = [&](std::size_t k, auto change) {
    std::vector<Layer> s = ok;
    change(s[k]);
    return s;
  };
  expect_error(with(1, [](Layer& l) { l.c.sigma_a = -1.0; }), o, "layers[1].sigma_a: ");
  expect_error(with(2, [](Layer& l) { l.c.sigma_a = 0.0; }), o, "layers[2].sigma_a: ");
  expect_error(with(2, [&](Layer& l) { l.c.sigma_s = nan; }), o, "layers[2].sigma_s: ");
  expect_error(with(0, [](Layer& l) { l.c.g = 1.0; }), o, "layers[0].g: ");
  expect_error(with(1, [](Layer& l) { l.c.eta = 3.0; }), o, "layers[1].eta: ");  // out of range
  expect_error(with(0, [](Layer& l) { l.c.eta = 3.0; }), o, "layers[0].eta: ");
  expect_error(with(2, [](Layer& l) { l.c.eta = 1.3; }), o,
               "layers[2].eta: must equal layers[0].eta (interfaces between layers are index-matched)");
  expect_error(with(0, [](Layer& l) { l.thickness_mm = kInf; }), o, "layers[0].thickness_mm: ");
  expect_error(with(1, [](Layer& l) { l.thickness_mm = 0.0; }), o, "layers[1].thickness_mm: ");
  expect_error(with(1, [&](Layer& l) { l.thickness_mm = nan; }), o, "layers[1].thickness_mm: ");
  expect_error(with(2, [](Layer& l) { l.thickness_mm = -1.0; }), o, "layers[2].thickness_mm: ");
  expect_error(with(2, [&](Layer& l) { l.thickness_mm = nan; }), o, "layers[2].thickness_mm: ");
  // The first bad layer is the one named.
  std::vector<Layer> two_bad = with(2, [](Layer& l) { l.c.g = 2.0; });
  two_bad[1].c.sigma_s = -1.0;
  expect_error(two_bad, o, "layers[1].sigma_s: ");

  // The options keep run_monte_carlo's checks; thickness_mm must stay at its default.
  MonteCarloOptions bad = o;
  bad.thickness_mm = 1.0;
  expect_error(ok, bad, "thickness_mm: ");
  bad.thickness_mm = nan;
  expect_error(ok, bad, "thickness_mm: ");
  bad = o;
  bad.photons = 0;
  expect_error(ok, bad, "photons: ");
  bad = o;
  bad.bin_edges_mm = {1.0};
  expect_error(ok, bad, "bin_edges_mm: ");
  bad = o;
  bad.max_scattering_order = 1;
  bad.min_scattering_order = 2;
  expect_error(ok, bad, "min_scattering_order: ");
  // A throwing progress callback is rethrown as it was thrown (not an input error).
  bad = o;
  bad.progress = [](double) { throw std::runtime_error("stop"); };
  EXPECT_THROW(run_layered_monte_carlo(ok, bad), std::runtime_error);
}

}  // namespace
}  // namespace sss::profiles
