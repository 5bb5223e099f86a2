// Single scattering apart (issue 18 part 2, "nothing counted twice"): the renderers add
// S(1) in closed form (profiles/SingleScattering.h), so the profiles can leave the once-
// scattered light out (ModelOptions::single_scattering_apart). Checked here against
// computations that share nothing with what they check:
//  (a) the mc-table's stored once-scattered totals q_total(η) against the closed form;
//  (b) its once-scattered flux per annulus q(η, b) against an independent quadrature of
//      the once-scattered radial flux of a pencil beam;
//  (c) model mc-table with single scattering apart against the analog walk's exits after
//      two or more scattering events (MonteCarloOptions::min_scattering_order = 2): the
//      total between nodes and the stored multiply-scattered fluxes per annulus at nodes;
//  (d) models pbd and mc with single scattering apart: pbd against the analog walk within
//      PBD's known accuracy, mc and pbd wired through make_profile.
// Statistical bounds are in the stored or run-time standard errors; each says where its
// false-failure probability comes from.
#include "profiles/Fresnel.h"
#include "profiles/Integrate.h"
#include "profiles/McTable.h"
#include "profiles/McTableProfile.h"
#include "profiles/MonteCarlo.h"
#include "profiles/PhotonBeamDiffusion.h"
#include "profiles/Presets.h"
#include "profiles/Profile.h"
#include "profiles/SingleScattering.h"
#include "profiles/Validation.h"

#include "McTableTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace sss::profiles {
namespace {

using test::annuli_covering;
using test::chi2_over_k_quantile;
using test::EdgeRange;
using test::z_family;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = std::numbers::pi;

// A medium in optical units: σt' = 1, reduced albedo α', g = 0.
Coefficients optical(double alpha, double eta) { return {1.0 - alpha, alpha, 0.0, eta}; }

std::size_t index_of(const std::vector<double>& axis, double x) {
  const auto it = std::find(axis.begin(), axis.end(), x);
  return static_cast<std::size_t>(it - axis.begin());
}

// ---------------------------------------------------------------------------------------
// The once-scattered light of the table's walk, computed independently.

// (a) The closed form: the once-scattered flux per unit power entered per unit outside
// exit cosine (SingleScattering.h, normal incidence), integrated over μo in [0, 1] by
// 64 × 16-point Gauss-Legendre panels (the integrand is smooth in μo: F_t and the refracted
// cosine are; 128 panels agree to 1e-13). The density is α times a function of g and η
// alone (f1 ∝ α), so per unit albedo it is the density of any medium divided by its α:
// 0.5 here, exactly representable.
double closed_form_single_total(double eta) {
  const Coefficients c{0.5, 0.5, 0.0, eta};
  return integrate([&](double mu) { return single_scattering_exit_density(c, 1.0, mu); }, 0.0,
                   1.0, 64, 16) /
         0.5;
}

// (b) The once-scattered flux through the annulus [r0, r1) per unit albedo, in optical units
// (σt' = σt = 1, isotropic, the beam entering straight down). The beam reaches depth z with
// e^{-z} and scatters there (density e^{-z} dz per unit albedo); an isotropic event sends
// it up with cosine μ = cos θ with density 1/2 per unit μ; it reaches the surface at
// r = z tan θ after the path z/μ and leaves with T(μ) = 1 - F(μ, η) (Fresnel.h, seen from
// inside: relative index 1/η; 0 past the critical angle):
//   Φ(r0, r1) = ∫0^∞ dz e^{-z} ∫_{μ: z tan θ ∈ [r0, r1)} ½ e^{-z/μ} T(μ) dμ.
// Changing (z, μ) to (r, θ) with z = r cot θ (dz dμ = cot θ sin θ dr dθ = cos θ dr dθ), the
// exponent is -r cot θ (1 + 1/cos θ) = -r cot(θ/2), and the r-integral is closed:
//   Φ(r0, r1) = ∫0^θc ½ T(cos θ) cos θ tan(θ/2) (e^{-r0 cot(θ/2)} - e^{-r1 cot(θ/2)}) dθ,
// θc the critical angle (π/2 at η = 1). One smooth integral per annulus, checked against
// (a) below: over [0, ∞) it is the closed-form total (at η = 1, (1 - ln 2)/2).
// Quadrature: [0, θc/2] geometrically in θ (8 panels per decade from 1e-14; the integrand
// varies on the scale θ ~ r0 near 0 and is ~θ/4 below, so [0, 1e-14] holds < 1e-28), and
// [θc/2, θc] with θ = θc - (θc/2) v², which removes T's square-root kink at θc.
double single_annulus_flux(double r0, double r1, double eta) {
  const double theta_c = eta > 1.0 ? std::asin(1.0 / eta) : 0.5 * kPi;
  auto f = [&](double theta) {
    const double mu = std::cos(theta);
    const double t = 1.0 - fresnel_dielectric(mu, 1.0 / eta);
    const double tan_half = std::tan(0.5 * theta);
    const double cot_half = 1.0 / tan_half;
    const double e0 = r0 > 0.0 ? std::exp(-r0 * cot_half) : 1.0;
    const double e1 = std::isfinite(r1) ? std::exp(-r1 * cot_half) : 0.0;
    return 0.5 * t * mu * tan_half * (e0 - e1);
  };
  const double half = 0.5 * theta_c;
  const double near = integrate_log(f, 1e-14, half, 8, 16);
  const double far = integrate([&](double v) { return f(theta_c - half * v * v) * 2.0 * half * v; },
                               0.0, 1.0, 32, 16);
  return near + far;
}

const double kEtas[] = {1.0, 1.4, 2.0, 2.5};

// The quadrature of (b) is the closed form of (a) over the whole surface (two different
// integrals of the same once-scattered light: 1e-9 covers both quadratures), and at η = 1
// both are (1 - ln 2)/2.
TEST(McTableSingleScattering, QuadratureAndClosedFormAgree) {
  EXPECT_NEAR(closed_form_single_total(1.0), (1.0 - std::numbers::ln2) / 2.0, 1e-12);
  for (double eta : kEtas) {
    EXPECT_NEAR(single_annulus_flux(0.0, kInf, eta), closed_form_single_total(eta), 1e-9) << eta;
    // Annuli add up: [0, 1) + [1, ∞).
    EXPECT_NEAR(single_annulus_flux(0.0, 1.0, eta) + single_annulus_flux(1.0, kInf, eta),
                closed_form_single_total(eta), 1e-9) << eta;
  }
}

// (a) q_total(η) against the closed form, by the stored (batch-means) standard error:
// |z| <= 4 at each of 4 η, a two-sided 6.3e-5 each, so a false alarm has probability
// below 2.5e-4 (Bonferroni) for a correct table.
TEST(McTableSingleScattering, StoredTotalsMatchTheClosedForm) {
  const McTableData& t = shipped_mc_table();
  for (double eta : kEtas) {
    const std::size_t e = index_of(t.eta, eta);
    ASSERT_LT(e, t.eta.size()) << "eta " << eta << " is not a table node";
    const double q = t.single_total[e], se = t.single_total_se[e];
    const double exact = closed_form_single_total(eta);
    ASSERT_GT(se, 0.0);
    const double z = (q - exact) / se;
    EXPECT_LE(std::fabs(z), 4.0) << "eta " << eta << ": table " << q << " +- " << se
                                 << ", closed form " << exact;
    RecordProperty("z_eta_" + std::to_string(eta), std::to_string(z));
    std::printf("eta %.1f: q_total %.6f +- %.2g, closed form %.6f, z %+.2f (%+.3f%%)\n", eta, q,
                se, exact, z, 100.0 * (q / exact - 1.0));
  }
}

// (b) q(η, b) per annulus against the quadrature, over the annuli that each hold at least
// 1e-3 of the once-scattered total (together 97-99% of it; the rest are many small annuli
// at the ends whose flux is too small for a normal approximation of their counts): the sum
// of z_b² = ((q_b - Φ_b) / se_b)² over k annuli against the 99.9% quantile of χ²_k
// (Wilson-Hilferty, McTableTestSupport.h; 4 η, so a false alarm below 4e-3). One walk leaves
// once-scattered through one annulus at most, so the annuli are nearly independent (a
// multinomial's small negative correlations, which only narrow the spread of Σz²).
TEST(McTableSingleScattering, StoredAnnuliMatchTheQuadrature) {
  const McTableData& t = shipped_mc_table();
  for (double eta : kEtas) {
    const std::size_t e = index_of(t.eta, eta);
    ASSERT_LT(e, t.eta.size());
    const double total = closed_form_single_total(eta);
    double chi2 = 0.0, covered = 0.0, worst = 0.0;
    int k = 0;
    for (std::size_t b = 0; b < t.bins(); ++b) {
      const double expect = single_annulus_flux(t.r_edges[b], t.r_edges[b + 1], eta);
      if (expect < 1e-3 * total) continue;
      const double q = t.single_flux[t.single_slot(e, b)], se = t.single_flux_se[t.single_slot(e, b)];
      ASSERT_GT(se, 0.0) << "eta " << eta << " bin " << b;
      const double z = (q - expect) / se;
      chi2 += z * z;
      worst = std::max(worst, std::fabs(z));
      covered += expect;
      ++k;
    }
    ASSERT_GE(k, 20) << eta;
    const double bound = k * chi2_over_k_quantile(k, 1e-3);
    EXPECT_LT(chi2, bound) << "eta " << eta << ": chi-square " << chi2 << " over " << k << " annuli";
    EXPECT_GT(covered, 0.95 * total) << eta;
    RecordProperty("chi2_eta_" + std::to_string(eta), std::to_string(chi2));
    std::printf("eta %.1f: %d annuli (%.1f%% of the once-scattered flux), chi-square %.1f "
                "(99.9%% quantile %.1f), worst |z| %.2f\n",
                eta, k, 100.0 * covered / total, chi2, bound, worst);
  }
}

// ---------------------------------------------------------------------------------------
// (c) Model mc-table with single scattering apart against the analog walk.

// The analog walk (MonteCarlo.h: σs flights, absorption weighting, per-photon errors)
// leaving out exits after fewer than two scattering events. Roulette at 5% of the entry
// weight, as the table's walks (unbiased: MonteCarlo.RouletteIsUnbiased).
MonteCarloResult analog_apart(const Coefficients& c, std::uint64_t photons, std::uint64_t seed,
                              std::vector<double> edges = {}) {
  MonteCarloOptions o;
  o.photons = photons;
  o.seed = seed;
  o.threads = 1;  // ctest runs tests side by side
  o.roulette_weight = 0.05;
  o.min_scattering_order = 2;
  o.bin_edges_mm = std::move(edges);
  return run_monte_carlo(c, o);
}

// The α' halfway in u = √(1 - α') between the two table nodes around `near`.
double albedo_midpoint(const McTableData& t, double near) {
  std::size_t i = 0;
  while (i + 2 < t.albedo.size() && t.albedo[i + 1] < near) ++i;
  const double u = 0.5 * (std::sqrt(1.0 - t.albedo[i]) + std::sqrt(1.0 - t.albedo[i + 1]));
  return 1.0 - u * u;
}

struct OffNode {
  double alpha_near, eta;
  std::uint64_t photons;
};

// Off-node media (α' a u-midpoint, η a midpoint of the 0.05 steps). The lookup's total
// and its error bound (Σ|w| se of the multiply-scattered totals over the stencil) against
// the analog run's, two-sided at z_family(1e-4, 4) = 4.1 on the combined SE. Photons give
// the analog run a relative SE of 0.1-0.3% (measured while writing this); 4.6 s on one
// core for all four.
TEST(McTableApart, TotalMatchesTheAnalogWalkWithoutOnceScatteredLightBetweenNodes) {
  const McTableData& t = shipped_mc_table();
  const OffNode media[] = {{0.3, 1.325, 1u << 21}, {0.8, 1.025, 1u << 19},
                           {0.95, 1.475, 1u << 18}, {0.995, 1.325, 1u << 16}};
  const double z = z_family(1e-4, std::size(media));
  for (const OffNode& m : media) {
    const double alpha = albedo_midpoint(t, m.alpha_near);
    const Coefficients c = optical(alpha, m.eta);
    const McTableProfile p(c, t, true);
    const McTableTotal lookup = mc_table_total(c, t, true);
    EXPECT_EQ(p.total_reflectance(), lookup.total);
    const MonteCarloResult r = analog_apart(c, m.photons, 77 + static_cast<std::uint64_t>(1e4 * alpha));
    ASSERT_EQ(r.truncated_photons, 0u);
    const double se = std::hypot(lookup.stderr_, r.reflectance.total_stderr);
    EXPECT_NEAR(lookup.total, r.reflectance.total, z * se) << "alpha' " << alpha << " eta " << m.eta;
    // And it is what the full lookup minus its once-scattered light gives: the full total
    // is larger by about α' q_total (not exactly: the two are interpolated separately).
    const double full = McTableProfile(c, t).total_reflectance();
    EXPECT_GT(full, lookup.total);
    std::printf("alpha' %.5f eta %.3f: mc-table apart %.6f +- %.2g, analog (order >= 2) %.6f +- %.2g "
                "(%+.3f%%, z %+.2f); full %.6f, once-scattered share %.1f%%\n",
                alpha, m.eta, lookup.total, lookup.stderr_, r.reflectance.total,
                r.reflectance.total_stderr, 100.0 * (lookup.total / r.reflectance.total - 1.0),
                (lookup.total - r.reflectance.total) / se, full, 100.0 * (1.0 - lookup.total / full));
  }
}

// At table nodes, per annulus over [0.25, 8] mfp (the table's own annuli, so the analog
// bins are the same annuli): the stored multiply-scattered flux flux - α' q, which is what
// the apart lookup enforces there (target_flux, to rounding), against the analog walk's
// exits after two or more events. The mean of z² over k annuli against the quantile of
// χ²_k'/k' with k' = 2k/3 at 1e-4 / 3 (3 nodes), as McTableVsAnalog does: the analog
// run's annuli are correlated at η > 1 (a walk leaves through several), which widens the
// spread by up to 1.2x (measured there).
TEST(McTableApart, StoredMultipleScatteringAgreesWithTheAnalogWalkAtNodes) {
  const McTableData& t = shipped_mc_table();
  const EdgeRange er = annuli_covering(t.r_edges, 0.25, 8.0);
  const std::vector<double> edges(t.r_edges.begin() + static_cast<std::ptrdiff_t>(er.first),
                                  t.r_edges.begin() + static_cast<std::ptrdiff_t>(er.last) + 1);
  struct Node {
    double alpha_near, eta;
    std::uint64_t photons;
  };
  const Node nodes[] = {{0.3, 1.4, 1u << 21}, {0.9, 1.0, 1u << 19}, {0.99, 1.6, 1u << 17}};
  for (const Node& n : nodes) {
    std::size_t a = 0;
    while (a + 1 < t.albedo.size() && t.albedo[a] < n.alpha_near) ++a;
    const std::size_t e = index_of(t.eta, n.eta);
    ASSERT_LT(e, t.eta.size());
    const double alpha = t.albedo[a];
    const Coefficients c = optical(alpha, n.eta);
    const McTableProfile p(c, t, true);
    const MonteCarloResult r = analog_apart(c, n.photons, 500 + a, edges);
    double sum_z2 = 0.0, sum_rel2 = 0.0;
    int k = 0;
    for (std::size_t b = er.first; b < er.last; ++b) {
      const double r0 = t.r_edges[b], r1 = t.r_edges[b + 1];
      const double area = kPi * (r1 * r1 - r0 * r0);
      const double mc = r.reflectance.value[b - er.first] * area;
      const double mc_se = r.reflectance.stderr_[b - er.first] * area;
      const double tab = t.multiple_flux(e, a, b), tab_se = t.multiple_flux_se[t.slot(e, a, b)];
      if (p.enforced()[b]) {
        EXPECT_NEAR(p.target_flux()[b], tab, 1e-12 * tab) << "bin " << b;
      }
      const double zb = (tab - mc) / std::hypot(tab_se, mc_se);
      sum_z2 += zb * zb;
      sum_rel2 += (tab / mc - 1.0) * (tab / mc - 1.0);
      ++k;
    }
    const double mean_z2 = sum_z2 / k;
    const double bound = chi2_over_k_quantile(std::max(1, 2 * k / 3), 1e-4 / std::size(nodes));
    EXPECT_LT(mean_z2, bound) << "alpha' " << alpha << " eta " << n.eta;
    std::printf("node alpha' %.5f eta %.2f: %d annuli, mean z^2 %.2f (bound %.2f), RMS %.2f%%\n",
                alpha, n.eta, k, mean_z2, bound, 100.0 * std::sqrt(sum_rel2 / k));
  }
}

// ---------------------------------------------------------------------------------------
// The apart lookup's own properties on the shipped table.

// The integral of the reconstruction is the interpolated multiply-scattered total (the
// enforced annuli are normalised to it, as in the full lookup: within one SE), R is finite
// and positive, the histopolation converged, and R grows towards the source only like
// ln(1/r): inside the disc's node c_0 it is exactly R(c_0)(1 + (2 - s0)(ln c_0 - ln r))
// down to min_radius (rounding: 1e-12), so from 1e-3 mfp to the clamp at 1e-9 by at most
// 1 + 7 ln 10 = 17 (s0 >= 1), where the full profile's 1/r grows by up to 1e6.
TEST(McTableApart, ReconstructionIsConsistentAndLogarithmicAtTheSource) {
  const McTableData& t = shipped_mc_table();
  for (double eta : {1.0, 1.33, 1.6, 2.5})
    for (double a : {0.005, 0.05, 0.3, 0.8, 0.99, 0.9999}) {
      const McTableProfile p(optical(a, eta), t, true);
      SCOPED_TRACE("albedo " + std::to_string(a) + " eta " + std::to_string(eta));
      EXPECT_LT(p.residual(), 1e-12);
      EXPECT_TRUE(p.single_scattering_apart());
      const double integral =
          integrate_log([&](double r) { return 2.0 * kPi * r * p.reflectance(r); }, p.min_radius(),
                        100.0 * p.support_radius(), 8, 16) +
          kPi * p.min_radius() * p.min_radius() * p.reflectance(0.0);
      EXPECT_NEAR(integral, p.total_reflectance(), std::max(p.total_stderr(), 1e-9 * p.total_reflectance()));
      const double s = p.inner_slope();
      EXPECT_GE(s, 1.0);
      EXPECT_LE(s, 2.0);
      const double c0 = std::log(t.r_edges[1]) - 0.5 * std::log(t.r_edges[2] / t.r_edges[1]);
      const double r_c0 = p.reflectance(std::exp(c0)), at0 = p.reflectance(0.0);
      EXPECT_TRUE(std::isfinite(at0) && at0 > 0.0);
      EXPECT_NEAR(at0, r_c0 * (1.0 + (2.0 - s) * (c0 - std::log(p.min_radius()))), 1e-12 * at0);
      EXPECT_LE(at0, p.reflectance(1e-3) * (1.0 + 7.0 * std::log(10.0)));
      // Less light than the full profile, by the once-scattered share.
      const McTableProfile full(optical(a, eta), t);
      EXPECT_LT(p.total_reflectance(), full.total_reflectance());
    }
}

// Below the first α' node the multiply-scattered part scales like α'² (every path scatters
// at least twice, each event a factor α'): half the albedo, a quarter of the profile.
TEST(McTableApart, DarkExtensionIsQuadraticInAlbedo) {
  const McTableData& t = shipped_mc_table();
  const double a0 = t.albedo.front();
  for (double eta : {1.0, 1.3}) {
    const McTableProfile at(optical(a0, eta), t, true), half(optical(0.5 * a0, eta), t, true);
    EXPECT_NEAR(half.total_reflectance(), 0.25 * at.total_reflectance(), 1e-13);
    for (double r : {0.0, 0.001, 0.05, 0.5, 2.0}) {
      const double v = at.reflectance(r);
      EXPECT_NEAR(half.reflectance(r), 0.25 * v, 1e-12 * v) << r;
    }
  }
}

// ---------------------------------------------------------------------------------------
// (d) pbd and mc with single scattering apart.

// Wiring: make_profile and RgbProfile pass the option on. pbd apart is its multiple-
// scattering term alone (and its total is that term's integral, so it is the full total
// minus the single-scattering term's integral); mc apart tallies what run_monte_carlo
// with min_scattering_order = 2 tallies (the same walks: the same total to the bit);
// mc-table apart is McTableProfile(c, true).
TEST(SingleScatteringApart, EveryModelTakesTheOption) {
  const Coefficients skin{0.032, 0.74, 0.44, 1.3};  // skin1 red, real g
  ModelOptions apart;
  apart.single_scattering_apart = true;
  apart.mc_photons = 1u << 14;
  apart.mc_seed = 3;
  apart.mc_threads = 1;
  ModelOptions full = apart;
  full.single_scattering_apart = false;

  const PhotonBeamDiffusion pbd(skin, 32);
  const auto pbd_apart = make_profile(Model::Pbd, skin, kInf, apart);
  for (double r : {0.01, 0.3, 1.0, 5.0}) EXPECT_EQ(pbd_apart->reflectance(r), pbd.multiple_scattering(r)) << r;
  const double ss_total = integrate_log([&](double r) { return 2.0 * kPi * r * pbd.single_scattering(r); },
                                        pbd.inner_radius(), pbd.support_radius(), 2, 12);
  EXPECT_NEAR(pbd_apart->total_reflectance(), pbd.total_reflectance() - ss_total, 1e-9);
  EXPECT_LT(pbd_apart->total_reflectance(), make_profile(Model::Pbd, skin, kInf, full)->total_reflectance());

  const auto mc_apart = make_profile(Model::MonteCarlo, skin, kInf, apart);
  const auto mc_full = make_profile(Model::MonteCarlo, skin, kInf, full);
  MonteCarloOptions o;
  o.photons = apart.mc_photons;
  o.seed = apart.mc_seed;
  o.threads = 1;
  o.min_scattering_order = 2;
  const MonteCarloResult r = run_monte_carlo(skin, o);
  EXPECT_EQ(mc_apart->total_reflectance(), r.reflectance.total);
  EXPECT_NEAR(mc_full->total_reflectance(), r.reflectance.total + r.low_order_exits, 1e-12);

  // make_profile passes the option to the lookup over the g axis (skin's g is between the
  // isotropic table and the first anisotropic layer).
  const auto table_apart = make_profile(Model::McTable, skin, kInf, apart);
  const auto direct = make_mc_table_profile(skin, true);
  for (double r0 : {0.0, 0.1, 1.0, 10.0}) EXPECT_EQ(table_apart->reflectance(r0), direct->reflectance(r0));
  EXPECT_EQ(table_apart->total_reflectance(), direct->total_reflectance());
  EXPECT_LT(table_apart->total_reflectance(),
            make_profile(Model::McTable, skin, kInf, full)->total_reflectance());

  // The diffusion models have no single scattering: the option changes nothing.
  for (Model m : {Model::Dipole, Model::BetterDipole, Model::Burley, Model::Qd})
    EXPECT_EQ(make_profile(m, skin, kInf, apart)->total_reflectance(),
              make_profile(m, skin, kInf, full)->total_reflectance())
        << model_name(m);

  const Medium medium = preset_medium(*find_preset("skin1"));
  const RgbProfile rgb(Model::McTable, medium, apart);
  for (int c = 0; c < 3; ++c)
    EXPECT_EQ(rgb.channel(c).total_reflectance(), McTableProfile(medium.channel(c), true).total_reflectance());
}

// PBD apart against the analog walk's exits after two or more events (validate_against_
// monte_carlo with the option: its reference leaves the once-scattered exits out too), on
// the media and with the photons of test_models_vs_mc.cpp. Bounds, derived from the full
// PBD's known accuracy there (test_models_vs_mc.cpp: total 8% at high albedo, 12% at lower
// albedo) and from its single-scattering term's: apart = full - ss, so
//   |PBD_ms - MC_ms| <= |PBD_full - MC_full| + |PBD_ss - MC_ss|
//                    <= b_full MC_full + b_ss MC_ss + 4 SE,
// with b_ss = 3%, the bound PBD's ss term is held to on its own below. That 3% is not
// derived: PBD's 32-sample beam quadrature is 1% by docs/PBD_CONVERGENCE.md, and the rest
// of its measured 1.3-2.2% gap to the walk's once-scattered exits is not pinned down; it
// guards the term from getting worse. Relative to MC_ms that is larger than b_full where the once-scattered share
// is large (38-44% at α' 0.68-0.75): measured apart skin1 B +16.3% against the derived
// 23.8%, ketchup R +13.2% against 21.1%. The radial RMS and max keep the full PBD's bounds
// at high albedo (measured apart: skin1 R +6.2/6.6/9.9%, marble G +2.8/5.0/12.3% against
// 10%, 16%); at lower albedo they are printed, not bounded: where R_ss dominates the ms
// part is small and a relative per-annulus error of the full profile does not carry over.
// The finding behind it: PBD's ms term alone overestimates the walk more than the full
// PBD does (its α'² Grosjean source counts part of the first scattering again), so with
// single scattering on, pbd's excess shows. mc-table apart must stay within its own
// accuracy (total 1%, RMS 5%, as test_mc_table_accuracy.cpp).
struct ApartCase {
  const char* preset;
  int channel;
  std::uint64_t photons;
  double full_total;  // the full PBD's total bound there (test_models_vs_mc.cpp)
  bool high_albedo;   // the radial RMS and max bounds apply
};

TEST(SingleScatteringApart, PbdAgreesWithTheAnalogWalkWithinItsKnownAccuracy) {
  const ApartCase cases[] = {{"skin1", 0, 300000, 0.08, true},
                             {"marble", 1, 40000, 0.08, true},
                             {"skin1", 2, 300000, 0.12, false},
                             {"ketchup", 0, 300000, 0.12, false}};
  for (const ApartCase& k : cases) {
    const Medium m = preset_medium(*find_preset(k.preset));
    ValidationOptions o;
    o.photons = k.photons;
    o.seed = 7;
    o.threads = 1;
    o.channels = {k.channel == 0, k.channel == 1, k.channel == 2};
    o.models = {Model::Pbd, Model::McTable};
    o.model_options.single_scattering_apart = true;
    const ValidationReport rep = validate_against_monte_carlo(m, o);
    const MonteCarloResult& mc = rep.monte_carlo[k.channel];
    ASSERT_LT(mc.reflectance.total_stderr, 0.005 * mc.reflectance.total);
    EXPECT_GT(mc.low_order_exits, 0.0);
    const ChannelComparison& pbd = rep.models[0].channels[k.channel];
    const ChannelComparison& tab = rep.models[1].channels[k.channel];
    SCOPED_TRACE(std::string(k.preset) + "[" + kChannelNames[k.channel] + "]");
    const double ms = mc.reflectance.total, ss = mc.low_order_exits;
    const double bound = (k.full_total * (ms + ss) + 0.03 * ss + 4.0 * mc.reflectance.total_stderr) / ms;
    EXPECT_LT(std::fabs(pbd.total_rel_error), bound);
    EXPECT_GT(pbd.total_rel_error, 0.0) << "PBD's ms term overestimates";
    if (k.high_albedo) {
      EXPECT_LT(pbd.rms_rel_error, 0.10);
      EXPECT_LT(pbd.max_rel_error, 0.16);
    }
    EXPECT_LT(std::fabs(tab.total_rel_error), 0.01);
    EXPECT_LT(tab.rms_rel_error, 0.05);
    // PBD's own single-scattering total (its full total less its apart one) against the
    // walk's once-scattered exits: printed, to show where PBD's excess lies.
    const double pbd_ss = make_profile(Model::Pbd, m.channel(k.channel), kInf, {})->total_reflectance() -
                          pbd.total;
    EXPECT_NEAR(pbd_ss, mc.low_order_exits, 0.03 * mc.low_order_exits + 4.0 * mc.low_order_exits_stderr)
        << "PBD's single-scattering term";
    std::printf("%s[%c] alpha' %.3f, once-scattered share %.1f%% (pbd's single scattering %.5f, "
                "walk's %.5f +- %.5f): pbd apart total %+.1f%%, RMS %.1f%%, "
                "max %.1f%%; mc-table apart total %+.2f%%, RMS %.1f%% (MC median annulus SE %.1f%%)\n",
                k.preset, kChannelNames[k.channel][0], m.channel(k.channel).albedo_reduced(),
                100.0 * mc.low_order_exits / (mc.low_order_exits + mc.reflectance.total), pbd_ss,
                mc.low_order_exits, mc.low_order_exits_stderr,
                100.0 * pbd.total_rel_error, 100.0 * pbd.rms_rel_error, 100.0 * pbd.max_rel_error,
                100.0 * tab.total_rel_error, 100.0 * tab.rms_rel_error,
                100.0 * rep.median_bin_rel_stderr[k.channel]);
  }
}

}  // namespace
}  // namespace sss::profiles
