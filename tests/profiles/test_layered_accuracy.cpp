// Model `layered` against the layered analog Monte Carlo walk (run_layered_monte_carlo,
// an independent computation: real transport, no diffusion), for the stacks issue 19
// names: a thin absorbing layer over a scattering base, a scattering layer over an
// absorbing base, and two skin-like layers (over a semi-infinite and over a 2 mm dermis).
//
// What is asserted, and why:
//  - the total reflectance within the 3% goal, with the Monte Carlo's own noise
//    allowed at 4 standard errors (family-wise false-failure probability < 4 x 6.3e-5);
//  - on skin, the default coupling (diffusion through the stack) against Donner &
//    Jensen's adding (LayerCoupling::Adding), the same walk judging both: its total and
//    its R(r) are closer. Measured (2^18 walks; README "Layered materials"): totals
//    +0.7% / +1.6% against +29% / +28%, R(r) RMS 12% / 15% against 58% / 61%.
// Not asserted: the 10% RMS goal for R(r) over [0.25, 8] mm, which the model
// misses (11-15% RMS, README), nor its 3% on the slab's total transmittance (-8.9%; the
// single-slab multipole alone is -9%). Both need Monte Carlo slab tables (issue 19).
//
// Scattering is isotropic (g = 0) so that what is measured is the layering, not the
// similarity relation (mc-table's g error is issue 18 part 4).
#include "profiles/Layered.h"
#include "profiles/MonteCarlo.h"
#include "profiles/Validation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace sss::profiles {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTotalGoal = 0.03;  // issue 19
constexpr double kZ = 4.0;           // two-sided 6.3e-5 per comparison

struct Stack {
  const char* name;
  std::vector<Layer> layers;
};

const std::vector<Stack>& stacks() {
  static const std::vector<Stack> s = {
      {"absorbing-over-scattering",
       {{{1.0, 5.0, 0.0, 1.4}, 0.5}, {{0.01, 2.0, 0.0, 1.4}, kInf}}},
      {"scattering-over-absorbing",
       {{{0.01, 3.0, 0.0, 1.4}, 1.0}, {{1.0, 1.0, 0.0, 1.4}, kInf}}},
      {"skin", {{{0.3, 8.0, 0.0, 1.4}, 0.25}, {{0.02, 2.0, 0.0, 1.4}, kInf}}},
      {"skin-slab", {{{0.3, 8.0, 0.0, 1.4}, 0.25}, {{0.02, 2.0, 0.0, 1.4}, 2.0}}},
  };
  return s;
}

const std::vector<double>& edges() {
  static const std::vector<double> e = log_bin_edges(0.25, 8.0, 24);
  return e;
}

// One walk per stack, shared by the tests (2^16 walks: 0.3-1.2 s each on one core).
const MonteCarloResult& walk(std::size_t i) {
  static std::vector<MonteCarloResult> runs = [] {
    std::vector<MonteCarloResult> out;
    for (const Stack& s : stacks()) {
      MonteCarloOptions o;
      o.photons = 1u << 16;
      o.seed = 19;
      o.threads = 1;
      o.bin_edges_mm = edges();
      out.push_back(run_layered_monte_carlo(s.layers, o));
    }
    return out;
  }();
  return runs[i];
}

// RMS of the relative error of the model's annulus averages over [0.25, 8] mm (the disc
// [0, 0.25) is the walk's first bin and is left out).
double rms_error(const RadialProfile& p, const MonteCarloResult& mc) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t b = 1; b + 1 < edges().size(); ++b) {
    const double model = annulus_average(p, edges()[b], edges()[b + 1]);
    const double e = model / mc.reflectance.value[b] - 1.0;
    sum += e * e;
    ++n;
  }
  return std::sqrt(sum / n);
}

TEST(LayeredAccuracy, TotalReflectanceWithinThreePercentOfMonteCarlo) {
  for (std::size_t i = 0; i < stacks().size(); ++i) {
    const auto& mc = walk(i);
    const LayeredProfile p(stacks()[i].layers, {});
    const double want = mc.reflectance.total;
    EXPECT_NEAR(p.total_reflectance(), want, kTotalGoal * want + kZ * mc.reflectance.total_stderr)
        << stacks()[i].name;
  }
}

TEST(LayeredAccuracy, DiffusionCouplingBeatsTheAddingEquationsOnSkin) {
  for (std::size_t i = 0; i < stacks().size(); ++i) {
    if (std::string(stacks()[i].name).rfind("skin", 0) != 0) continue;
    const auto& mc = walk(i);
    const LayeredProfile diffusion(stacks()[i].layers, {});
    const LayeredProfile adding(stacks()[i].layers, {}, kDefaultModel, LayerCoupling::Adding);
    const double want = mc.reflectance.total;
    // The two errors differ by 25% of the total, 40x the walk's 4-SE noise.
    EXPECT_LT(std::fabs(diffusion.total_reflectance() - want) + kZ * mc.reflectance.total_stderr,
              std::fabs(adding.total_reflectance() - want))
        << stacks()[i].name;
    // R(r): the walk's noise enters both RMS the same way (same bins); their measured gap,
    // 12-15% against 58-61%, is 20x the walk's per-bin noise at 2^16 walks (~3%).
    EXPECT_LT(rms_error(diffusion, mc), rms_error(adding, mc)) << stacks()[i].name;
  }
}

}  // namespace
}  // namespace sss::profiles
