// Model mc-table (profiles/McTableProfile.h): the lookup's own properties on a small table
// generated here (its accuracy against an independent Monte Carlo is tested elsewhere).
#include "profiles/ArtistMapping.h"
#include "profiles/Integrate.h"
#include "profiles/McTable.h"
#include "profiles/HFunction.h"
#include "profiles/McTableProfile.h"
#include "profiles/MonteCarlo.h"

#include "profiles/Profile.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

using namespace sss::profiles;

namespace {

constexpr double kPi = std::numbers::pi;

// A small table: η {1, 1.2, 1.4}, 8 albedos uniform in u = √(1 - α') from 0.99 down to
// 0.01 (as the shipped grid is), the disc [0, 0.01) and 30 log-uniform annuli to 64 mfp,
// 2^15 walks on one thread (about 0.3 s).
const McTableData& small_table() {
  static const McTableData table = [] {
    McTableOptions o;
    o.eta = {1.0, 1.2, 1.4};
    const double u_lo = 0.1, u_hi = std::sqrt(0.99);
    for (int i = 7; i >= 0; --i) {
      const double u = u_lo + (u_hi - u_lo) * i / 7.0;
      o.albedo.push_back(i == 0 ? 0.99 : i == 7 ? 0.01 : 1.0 - u * u);
    }
    o.r_edges = log_bin_edges(0.01, 64.0, 30);
    o.photons = 1u << 15;
    o.chunk_photons = 4096;
    o.threads = 1;
    return generate_mc_table(o);
  }();
  return table;
}

// A medium in optical units with reduced albedo α'.
Coefficients optical(double alpha, double eta, double sigma_tp = 1.0) {
  return {(1.0 - alpha) * sigma_tp, alpha * sigma_tp, 0.0, eta};
}

// ∫ 2π r R over [r0, r1] (mm) by an independent quadrature: composite Gauss-Legendre in
// x = ln r (dr = r dx) with `panels` panels of 16 points. On an annulus (64 panels) it
// converges to ~1e-13 (measured: 256 panels agree to 1e-15).
double annulus(const RadialProfile& p, double r0, double r1, int panels = 64) {
  return integrate([&](double x) {
                     const double r = std::exp(x);
                     return 2.0 * kPi * r * r * p.reflectance(r);
                   },
                   std::log(r0), std::log(r1), panels, 16);
}

// The flux of table bin b of a profile in optical units (σt' = 1). The disc [0, r_1) is
// integrated from min_radius() (where R is clamped) over its 7 decades with 256 panels;
// what lies below min_radius = 1e-9 is q(r_min)/s <= (r_min/r_1) F_0 = 1e-7 F_0 for the
// shipped and the small table (r_1 >= 1e-3... 1e-2; q ∝ r^s, s >= 1 there).
double bin_flux(const McTableProfile& p, const McTableData& t, std::size_t b) {
  if (b == 0) return annulus(p, p.min_radius(), t.r_edges[1], 256);
  return annulus(p, t.r_edges[b], t.r_edges[b + 1]);
}

// ∫ 2π r R over [0, ∞): the table's bins, then to 100 support radii (far past where R has
// underflowed).
double integral(const McTableProfile& p, const McTableData& t) {
  double sum = 0.0;
  for (std::size_t b = 0; b < t.bins(); ++b) sum += bin_flux(p, t, b);
  return sum + annulus(p, t.r_edges.back(), std::max(100.0 * p.support_radius(), 2.0 * t.r_edges.back()), 256);
}

}  // namespace

TEST(McTableProfile, DecayRateSolvesTheDispersionRelation) {
  // κ0 = 1 - 2e^{-2/α} + ... as α → 0 (artanh κ = 1/α): 1 to double precision at 0.01.
  EXPECT_EQ(transport_decay_rate(0.01), 1.0);
  for (double a : {0.3, 0.9, 0.999, 0.9999}) {
    const double k = transport_decay_rate(a);
    ASSERT_GT(k, 0.0);
    ASSERT_LT(k, 1.0);
    // The defining equation holds to rounding (bisection to the last bit).
    EXPECT_NEAR(a * std::atanh(k) / k, 1.0, 1e-12) << a;
  }
  // Diffusion limit: κ0² = 3(1-α)(1 - (4/5)(1-α) + O((1-α)²)) (the series of
  // artanh(κ)/κ = 1 + κ²/3 + κ⁴/5 + ...), so at 1-α = 1e-4 κ0 = √3e-4 (1 - 4e-5).
  EXPECT_NEAR(transport_decay_rate(0.9999), std::sqrt(3e-4) * (1.0 - 0.4e-4), 1e-9);
  EXPECT_THROW(transport_decay_rate(1.0), std::invalid_argument);
}

// R_mm(r) = σt'² R_t(σt' r): a medium 7.3 times denser is the same profile shrunk 7.3
// times. Only the folding of ln σt' into the coefficients differs between the two, so
// they agree to rounding: |ψ| ε with ψ = ln R up to ~40, i.e. ~1e-14; asserted 1e-12.
TEST(McTableProfile, ScalesWithTheReducedExtinction) {
  const McTableData& t = small_table();
  for (double a : {0.005, 0.3, 0.9, 0.99}) {
    const McTableProfile unit(optical(a, 1.1), t), dense(optical(a, 1.1, 7.3), t);
    EXPECT_NEAR(dense.total_reflectance(), unit.total_reflectance(), 1e-14);
    EXPECT_NEAR(dense.support_radius(), unit.support_radius() / 7.3, 1e-12 * unit.support_radius());
    for (double r : {0.0, 1e-4, 0.0123, 0.3, 1.0, 3.7, 20.0, 70.0, 500.0}) {
      const double want = 7.3 * 7.3 * unit.reflectance(7.3 * r);
      EXPECT_NEAR(dense.reflectance(r), want, 1e-12 * want) << a << " " << r;
    }
  }
}

// Similarity: a g = 0.8 medium is looked up as its reduced g = 0 medium (σs' = σs (1-g)),
// so the two profiles are the same up to the rounding of σs (1 - g) (a few ulps in α'
// and σt', moving R by ~1e-15 relative); asserted 1e-12.
TEST(McTableProfile, AnisotropicMediumIsItsReducedMedium) {
  const McTableData& t = small_table();
  const double sigma_a = 0.05, sigma_s_reduced = 1.7;
  const McTableProfile reduced({sigma_a, sigma_s_reduced, 0.0, 1.3}, t);
  const McTableProfile forward({sigma_a, sigma_s_reduced / 0.2, 0.8, 1.3}, t);
  EXPECT_NEAR(forward.total_reflectance(), reduced.total_reflectance(), 1e-12);
  for (double r : {0.0, 0.01, 0.2, 1.0, 5.0, 30.0}) {
    const double want = reduced.reflectance(r);
    EXPECT_NEAR(forward.reflectance(r), want, 1e-12 * want) << r;
  }
}

// At a table node the interpolation weights are exactly (1, 0, ...): the total, its error
// and every annulus flux the reconstruction is fitted to are the node's own (rounding of
// exp(ln(F/α')) α': ~1e-15; asserted 1e-13).
TEST(McTableProfile, LookupAtANodeIsTheNode) {
  const McTableData& t = small_table();
  for (std::size_t e = 0; e < t.eta.size(); ++e)
    for (std::size_t a = 0; a < t.albedo.size(); ++a) {
      const McTableProfile p(optical(t.albedo[a], t.eta[e]), t);
      const std::size_t node = t.node(e, a);
      EXPECT_NEAR(p.total_reflectance(), t.total[node], 1e-13 * t.total[node]) << e << " " << a;
      EXPECT_NEAR(p.total_stderr(), t.total_se[node], 1e-13 * t.total_se[node]);
      int enforced = 0;
      for (std::size_t b = 0; b < t.bins(); ++b) {
        if (!p.enforced()[b]) continue;
        ++enforced;
        const double f = t.flux[t.slot(e, a, b)];
        EXPECT_NEAR(p.target_flux()[b], f, 1e-13 * f) << e << " " << a << " bin " << b;
      }
      // The peak and its neighbours at least are measured well even with 2^15 walks.
      EXPECT_GE(enforced, 10) << e << " " << a;
    }
}

// Both lookups' fluxes (apart: the multiply-scattered part) over the media below: the
// reconstruction integrates over every enforced annulus to its target flux (1e-6).
void expect_reproduces_the_annulus_fluxes(const McTableData& t, bool apart) {
  const std::pair<double, double> media[] = {
      {t.albedo[4], t.eta[1]}, {t.albedo[7], t.eta[0]}, {0.3, 1.1}, {0.9, 1.37}, {0.97, 1.0}, {0.004, 1.2}};
  for (const auto& [a, eta] : media) {
    const McTableProfile p(optical(a, eta), t, apart);
    EXPECT_LT(p.residual(), 1e-12) << a << " " << eta;
    for (std::size_t b = 0; b < t.bins(); ++b) {
      if (!p.enforced()[b]) continue;
      const double f = p.target_flux()[b];
      EXPECT_NEAR(bin_flux(p, t, b), f, 1e-6 * f) << "albedo " << a << " eta " << eta << " bin " << b;
    }
  }
}

// ∫ 2π r R = total_reflectance() at every node, within one standard error.
void expect_integral_is_the_total_at_nodes(const McTableData& t, bool apart) {
  for (std::size_t e = 0; e < t.eta.size(); ++e)
    for (std::size_t a = 0; a < t.albedo.size(); ++a) {
      const McTableProfile p(optical(t.albedo[a], t.eta[e]), t, apart);
      EXPECT_NEAR(integral(p, t), p.total_reflectance(), p.total_stderr())
          << "albedo " << t.albedo[a] << " eta " << t.eta[e];
    }
}

// Histopolation: the reconstructed R integrates over every enforced annulus to the flux it
// was fitted to, at a node and between nodes. The fixed point stops at |ln(F/I)| < 1e-12,
// its 6-point Gauss-Legendre per half bin is exact to ~1e-13 on exp(cubic), and the test's
// quadrature adds ~1e-13 (annuli) or 1e-7 (the disc, see bin_flux): asserted 1e-6.
TEST(McTableProfile, ReconstructionReproducesTheAnnulusFluxes) {
  expect_reproduces_the_annulus_fluxes(small_table(), false);
}

// ∫ 2π r R over [0, ∞) against total_reflectance(), the interpolated tabulated total. The
// enforced annuli hold their fluxes exactly, so at a node the two differ only by what the
// reconstruction puts where it enforces nothing (unreliable annuli, past the last edge)
// against what the walks put there: a part of the total measured with less than the
// total's standard error. Asserted within one standard error (measured: <= 0.01 se).
// Between nodes the small table's coarse grid adds interpolation error; the shipped
// table's test below covers that.
TEST(McTableProfile, IntegralOfTheProfileIsTheTotalAtNodes) {
  expect_integral_is_the_total_at_nodes(small_table(), false);
}

// A brighter medium (higher α', same η and σt') reflects more: the total rises strictly
// along a fine sweep of α' across every node interval, the extension below 0.01 included.
// (R(r) at a fixed radius rises too, but near r = 0 only by ~α' itself, less than the
// small table's noise between neighbouring sweep steps: the shipped table's test checks
// it.)
TEST(McTableProfile, BrighterMediumReflectsMore) {
  const McTableData& t = small_table();
  for (double eta : {1.0, 1.15, 1.4}) {
    double last_total = 0.0;
    for (int i = 0; i <= 400; ++i) {
      const double u = std::sqrt(1.0 - 0.001) + (std::sqrt(1.0 - 0.99) - std::sqrt(1.0 - 0.001)) * i / 400.0;
      const double a = 1.0 - u * u;
      const McTableProfile p(optical(a, eta), t);
      EXPECT_GT(p.total_reflectance(), last_total) << "albedo " << a << " eta " << eta;
      last_total = p.total_reflectance();
    }
  }
}

// Outside the table: η beyond its axis is refused with the field named; α' above the
// last node and below the first are extended (not refused).
TEST(McTableProfile, OutOfRangeMediaAreRefusedByName) {
  const McTableData& t = small_table();
  auto message = [&](const sss::profiles::Coefficients& c) {
    try {
      McTableProfile p(c, t);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message(optical(0.5, 1.5)), "eta: mc-table covers eta in [1, 1.4], got 1.5");
  EXPECT_EQ(message(optical(0.995, 1.2)), "accepted");
  // A medium that does not scatter reflects nothing (it was NaN before: ln of a zero flux).
  {
    const McTableProfile dark({1.0, 0.0, 0.0, 1.3}, t);
    EXPECT_EQ(dark.total_reflectance(), 0.0);
    for (double r : {0.0, 1e-3, 1.0, 10.0, std::nan("")}) EXPECT_EQ(dark.reflectance(r), 0.0) << r;
  }
  EXPECT_EQ(message(optical(1.0 - 1e-11, 1.2)), "accepted");
  // Coefficients::validate still comes first (a NaN is named as itself).
  EXPECT_EQ(message({std::nan(""), 1.0, 0.0, 1.2}).rfind("sigma_a", 0), 0u);
  for (const auto& c : {optical(0.99, 1.4), optical(0.01, 1.0), optical(1e-6, 1.2), optical(0.5, 1.0)})
    EXPECT_EQ(message(c), "accepted");
}

// Below the first α' node the first slice is scaled by α'/α'_0: continuous at α'_0 (a
// medium 1e-9 darker differs by the factor 1 - 1e-9: asserted 1e-8 relative) and linear
// in α' below it (half the albedo, half the profile: rounding only, 1e-14).
TEST(McTableProfile, DarkExtensionIsContinuous) {
  const McTableData& t = small_table();
  const double a0 = t.albedo.front();
  for (double eta : {1.0, 1.3}) {
    const McTableProfile at(optical(a0, eta), t), below(optical(a0 * (1.0 - 1e-9), eta), t),
        half(optical(0.5 * a0, eta), t);
    EXPECT_NEAR(below.total_reflectance(), at.total_reflectance(), 1e-8 * at.total_reflectance());
    EXPECT_NEAR(half.total_reflectance(), 0.5 * at.total_reflectance(), 1e-14);
    for (double r : {0.0, 0.001, 0.05, 0.5, 2.0, 8.0}) {
      const double v = at.reflectance(r);
      EXPECT_NEAR(below.reflectance(r), v, 1e-8 * v) << r;
      EXPECT_NEAR(half.reflectance(r), 0.5 * v, 1e-13 * v) << r;
    }
  }
}

// R grows like 1/r towards the source; it is clamped at min_radius() = 1e-9 mfp, so R(0)
// is finite, equals R(min_radius), and R stays positive and finite everywhere.
TEST(McTableProfile, FiniteAtTheOriginAndEverywhere) {
  const McTableData& t = small_table();
  for (double a : {0.001, 0.5, 0.99}) {
    const McTableProfile p(optical(a, 1.2, 3.0), t);
    EXPECT_EQ(p.reflectance(0.0), p.reflectance(p.min_radius()));
    EXPECT_EQ(p.reflectance(1e-300), p.reflectance(0.0));
    for (double r : {0.0, 1e-12, 1e-6, 1e-3, 1.0, 10.0, 1e3, 1e300}) {
      const double v = p.reflectance(r);
      EXPECT_TRUE(std::isfinite(v) && v >= 0.0) << a << " " << r << " " << v;
    }
    EXPECT_GT(p.reflectance(0.0), p.reflectance(0.001));
  }
}

// Single scattering apart (McTableProfile.h): the same lookup of the multiply-scattered
// part flux - α' q, total - α' q_total. At a node it is the node's own part: total, its
// stored error, and every enforced annulus (as LookupAtANodeIsTheNode, 1e-13).
TEST(McTableProfile, ApartLookupAtANodeIsTheNodesMultipleScattering) {
  const McTableData& t = small_table();
  for (std::size_t e = 0; e < t.eta.size(); ++e)
    for (std::size_t a = 0; a < t.albedo.size(); ++a) {
      const McTableProfile p(optical(t.albedo[a], t.eta[e]), t, true);
      const std::size_t node = t.node(e, a);
      const double ms = t.multiple_total(e, a);
      EXPECT_NEAR(p.total_reflectance(), ms, 1e-13 * ms) << e << " " << a;
      EXPECT_NEAR(p.total_stderr(), t.multiple_total_se[node], 1e-13 * t.multiple_total_se[node]);
      EXPECT_NEAR(ms, t.total[node] - t.albedo[a] * t.single_total[e], 1e-15);
      int enforced = 0;
      for (std::size_t b = 0; b < t.bins(); ++b) {
        if (!p.enforced()[b]) continue;
        ++enforced;
        const double f = t.multiple_flux(e, a, b);
        EXPECT_NEAR(p.target_flux()[b], f, 1e-13 * f) << e << " " << a << " bin " << b;
      }
      EXPECT_GE(enforced, 10) << e << " " << a;
    }
}

// The apart reconstruction reproduces its enforced fluxes (as
// ReconstructionReproducesTheAnnulusFluxes, 1e-6) and integrates to its total at the nodes
// within one standard error (as IntegralOfTheProfileIsTheTotalAtNodes); the disc's share
// below min_radius is smaller still than with single scattering (q ∝ r² ln(1/r)).
TEST(McTableProfile, ApartReconstructionReproducesTheFluxesAndTheTotal) {
  expect_reproduces_the_annulus_fluxes(small_table(), true);
  expect_integral_is_the_total_at_nodes(small_table(), true);
}

// The apart total rises with α' along the fine sweep of BrighterMediumReflectsMore, the
// extension below the first node (∝ α'²) included, and stays below the full total.
TEST(McTableProfile, ApartBrighterMediumReflectsMore) {
  const McTableData& t = small_table();
  for (double eta : {1.0, 1.15, 1.4}) {
    double last_total = 0.0;
    for (int i = 0; i <= 400; ++i) {
      const double u = std::sqrt(1.0 - 0.001) + (std::sqrt(1.0 - 0.99) - std::sqrt(1.0 - 0.001)) * i / 400.0;
      const double a = 1.0 - u * u;
      const McTableProfile p(optical(a, eta), t, true);
      EXPECT_GT(p.total_reflectance(), last_total) << "albedo " << a << " eta " << eta;
      EXPECT_LT(p.total_reflectance(), McTableProfile(optical(a, eta), t).total_reflectance());
      last_total = p.total_reflectance();
    }
  }
}

// Not asserted: the constructor's and one R(r)'s cost (the lead's bench measures them
// properly in a Release build).
TEST(McTableProfile, Timing) {
  const McTableData& t = small_table();
  const int n = 300;
  const auto t0 = std::chrono::steady_clock::now();
  double sink = 0.0;
  for (int i = 0; i < n; ++i)
    sink += McTableProfile(optical(0.2 + 0.7 * i / n, 1.0 + 0.4 * i / n), t).total_reflectance();
  const auto t1 = std::chrono::steady_clock::now();
  const McTableProfile p(optical(0.9, 1.3), t);
  const int m = 1 << 20;
  for (int i = 0; i < m; ++i) sink += p.reflectance(1e-3 + 20.0 * i / m);
  const auto t2 = std::chrono::steady_clock::now();
  std::printf("mc-table (small table, %zu bins): constructor %.1f us, R(r) %.1f ns (sink %g)\n",
              t.bins(), std::chrono::duration<double, std::micro>(t1 - t0).count() / n,
              std::chrono::duration<double, std::nano>(t2 - t1).count() / m, sink);
}



// --- The shipped table (profiles/data/mc_table.bin, compiled in) ---

// Between nodes too, the integral of the profile is the interpolated total: the enforced
// fluxes are normalised to it (McTableProfile.cpp), so what remains is the unenforced
// annuli's share, measured with less than the total's error. Asserted within one standard
// error (measured: at most 0.2 se, at α' = 0.999 where the far annuli carry most flux).
TEST(McTableProfile, ShippedIntegralIsTheTotalBetweenNodes) {
  const McTableData& t = shipped_mc_table();
  for (double eta : {1.0, 1.025, 1.33, 1.4, 1.62, 2.5})
    for (double a : {0.005, 0.1, 0.3, 0.5, 0.8, 0.9, 0.99, 0.995, 0.999, 0.9995, 0.9999}) {
      const McTableProfile p(optical(a, eta), t);
      EXPECT_NEAR(integral(p, t), p.total_reflectance(), p.total_stderr())
          << "albedo " << a << " eta " << eta;
    }
}

// R(r) rises with α' at every radius where the table is measured (inside the enforced
// annuli, before the exponential tail), at radii from 0.01 to 30 mfp: from one α' node to
// the next (no interpolation involved; the walks are shared by every node, so their
// differences are measured far better than the ~1e-3 noise of a value), and along a
// fine sweep in u once the normalisation to the interpolated total is divided out
// (flux_scale(): it scales every flux, hence R, and it is 1 at the nodes; between the
// last two nodes it reaches ~1.003, more than R near the source changes with α' there,
// so R itself may dip by that much; the factor is asserted within 1% of 1). In the tail
// R need not rise: when the last reliable annulus moves to the next one, the tail's start
// and rate move with it (seen at 10 mfp for α' ~ 0.16, where r R is 1e-8 of its peak).
TEST(McTableProfile, ShippedProfileRisesWithAlbedo) {
  const McTableData& t = shipped_mc_table();
  const double radii[] = {0.01, 0.1, 0.5, 1.0, 3.0, 10.0, 30.0};
  auto sweep = [&](double eta, const std::vector<double>& albedos, const char* what) {
    std::array<double, 7> last{};
    double last_total = 0.0, last_tail = 0.0;
    for (double a : albedos) {
      const McTableProfile p(optical(a, eta), t);
      EXPECT_GT(p.total_reflectance(), last_total) << what << " albedo " << a << " eta " << eta;
      last_total = p.total_reflectance();
      EXPECT_NEAR(p.flux_scale(), 1.0, 0.01) << what << " albedo " << a << " eta " << eta;
      for (std::size_t k = 0; k < 7; ++k) {
        const double v = p.reflectance(radii[k]) / p.flux_scale();
        if (radii[k] < std::min(p.tail_start_mfp(), last_tail)) {
          EXPECT_GT(v, last[k]) << what << " albedo " << a << " eta " << eta << " r " << radii[k];
        }
        last[k] = v;
      }
      last_tail = p.tail_start_mfp();
    }
  };
  std::vector<double> fine;
  for (int i = 0; i <= 300; ++i) {
    const double u = std::sqrt(1.0 - 0.01) + (0.01 - std::sqrt(1.0 - 0.01)) * i / 300.0;
    fine.push_back(std::min(1.0 - u * u, t.albedo.back()));
  }
  for (std::size_t e = 0; e < t.eta.size(); e += 5) sweep(t.eta[e], t.albedo, "nodes");
  for (double eta : {1.0, 1.4, 2.0}) sweep(eta, fine, "sweep");
}

// The model is wired in: by name, through make_profile (the shipped table, thickness
// ignored as by the other semi-infinite models: the same profile), and its errors.
TEST(McTableProfile, ShippedModelByName) {
  ASSERT_EQ(parse_model("mc-table"), Model::McTable);
  EXPECT_EQ(model_name(Model::McTable), "mc-table");
  EXPECT_NE(model_names().find("mc, mc-table"), std::string::npos) << model_names();
  const Coefficients skin{0.032, 0.74, 0.0, 1.4};
  const McTableProfile direct(skin, shipped_mc_table());
  const auto semi = make_profile(Model::McTable, skin, std::numeric_limits<double>::infinity(), {});
  const auto slab = make_profile(Model::McTable, skin, 2.0, {});
  for (double r : {0.0, 0.1, 1.0, 10.0}) {
    EXPECT_EQ(semi->reflectance(r), direct.reflectance(r));
    EXPECT_EQ(slab->reflectance(r), direct.reflectance(r));
  }
  EXPECT_EQ(slab->total_transmittance(), 0.0);
  try {
    make_profile(Model::McTable, {0.01, 1.0, 0.0, 2.6}, std::numeric_limits<double>::infinity(), {});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("eta: ", 0), 0u) << e.what();
  }
}

// Past the last α' node (0.9999) the table extrapolates in u = √(1 - α') with the
// parabola through its last three nodes. At η = 1 the exact total is 1 - H(1)√(1 - α')
// (Chandrasekhar; HFunction.h): measured within 2.7e-5 relative at α' = 0.99997 (the
// preset cream's red) and 5.3e-5 as α' -> 1 - 1e-11 (the secant alone was 1.2e-3 low).
// Bound 2e-4: the last node's own standard error (6e-5 relative) times 3, rounded up.
// The extension is continuous at the last node (a medium 1e-12 brighter: 1e-9).
TEST(McTableProfile, ShippedExtrapolationPastTheLastAlbedoFollowsTheExactTotal) {
  const double last = shipped_mc_table().albedo.back();
  for (double a : {0.99995, 0.99997, 0.99999, 1.0 - 1e-6, 1.0 - 1e-9, 1.0 - 1e-11}) {
    const McTableProfile p(optical(a, 1.0), shipped_mc_table());
    const double exact = sss::profiles::exact_total_reflectance_index_matched(a);
    EXPECT_NEAR(p.total_reflectance(), exact, 2e-4 * exact) << "albedo " << a;
    EXPECT_TRUE(std::isfinite(p.reflectance(1.0)) && p.reflectance(1.0) > 0.0) << a;
  }
  const McTableProfile at(optical(last, 1.3), shipped_mc_table());
  const McTableProfile past(optical(last + 1e-12, 1.3), shipped_mc_table());
  EXPECT_NEAR(past.total_reflectance(), at.total_reflectance(), 1e-9);
  EXPECT_NEAR(past.reflectance(1.0), at.reflectance(1.0), 1e-9 * at.reflectance(1.0));
}

// The artist mapping inverts mc-table's own total: the medium it returns has, under
// mc-table, the colour asked for (bisection to 1e-15 in u, total Lipschitz ~3 in u:
// asserted 1e-9), a thickness changes nothing (semi-infinite), and a colour brighter than
// the brightest total (α' = 1 - 1e-10, as for every model) is refused naming the model and
// that bound.
TEST(McTableProfile, ShippedArtistMappingInvertsTheTable) {
  ArtistParameters ap{{0.6, 0.4, 0.2}, {1.0, 0.5, 0.25}, 1.4, 0.0};
  const auto m = medium_from_artist(Model::McTable, ap);
  ASSERT_TRUE(std::holds_alternative<sss::profiles::Medium>(m)) << std::get<sss::FieldError>(m).what();
  const RgbProfile rgb(Model::McTable, std::get<sss::profiles::Medium>(m));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgb.channel(c).total_reflectance(), ap.color[c], 1e-9) << c;
  ap.thickness_mm = 3.0;
  const auto slab = medium_from_artist(Model::McTable, ap);
  ASSERT_TRUE(std::holds_alternative<sss::profiles::Medium>(slab));
  for (int c = 0; c < 3; ++c)
    EXPECT_EQ(std::get<sss::profiles::Medium>(slab).sigma_a[c], std::get<sss::profiles::Medium>(m).sigma_a[c]);
  ap.thickness_mm = std::numeric_limits<double>::infinity();
  // A colour past the table's last node (its total at η = 1.4 is 0.950) but within reach.
  ap.color = {0.97, 0.5, 0.5};
  const auto past = medium_from_artist(Model::McTable, ap);
  ASSERT_TRUE(std::holds_alternative<sss::profiles::Medium>(past)) << std::get<sss::FieldError>(past).what();
  EXPECT_GT(std::get<sss::profiles::Medium>(past).channel(0).albedo_reduced(), shipped_mc_table().albedo.back());
  ap.color = {0.9999, 0.5, 0.5};
  const auto bright = medium_from_artist(Model::McTable, ap);
  ASSERT_TRUE(std::holds_alternative<sss::FieldError>(bright));
  const auto& e = std::get<sss::FieldError>(bright);
  EXPECT_EQ(e.field, "color[R]");
  const double reach = mc_table_total(optical(1.0 - 1e-10, 1.4), shipped_mc_table()).total;
  EXPECT_EQ(e.message, "0.9999 is brighter than model mc-table can reach (" + sss::message_number(reach) +
                           " at this eta and thickness)");
}

// Not asserted: the constructor's and one R(r)'s cost with the shipped table.
TEST(McTableProfile, ShippedTiming) {
  const McTableData& t = shipped_mc_table();
  const int n = 200;
  const auto t0 = std::chrono::steady_clock::now();
  double sink = 0.0;
  for (int i = 0; i < n; ++i)
    sink += McTableProfile(optical(0.2 + 0.79 * i / n, 1.0 + 0.6 * i / n), t).total_reflectance();
  const auto t1 = std::chrono::steady_clock::now();
  for (int i = 0; i < n * 64; ++i) sink += mc_table_total(optical(0.2 + 0.79 * i / (64 * n), 1.3), t).total;
  const auto t2 = std::chrono::steady_clock::now();
  const McTableProfile p(optical(0.9, 1.3), t);
  const int m = 1 << 22;
  for (int i = 0; i < m; ++i) sink += p.reflectance(1e-3 + 20.0 * i / m);
  const auto t3 = std::chrono::steady_clock::now();
  std::printf("mc-table (shipped, %zu bins): constructor %.1f us, mc_table_total %.2f us, R(r) %.1f ns (sink %g)\n",
              t.bins(), std::chrono::duration<double, std::micro>(t1 - t0).count() / n,
              std::chrono::duration<double, std::micro>(t2 - t1).count() / (64 * n),
              std::chrono::duration<double, std::nano>(t3 - t2).count() / m, sink);
}
