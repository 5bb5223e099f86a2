// Every analytic model against independent transport: the project's Monte Carlo (a
// random walk with the real phase function and Fresnel boundary, tested on its own
// against Chandrasekhar's exact totals) and, at η = 1, the exact H-function total.
//
// The tolerances are the model's accuracy, not noise. They were measured with the same
// photon counts and seeds (numbers in the comments, `sss-fit validate` prints the same
// table) and set with a margin. The Monte Carlo's own noise at these counts is ≤ 0.5% of
// a total and 1–3% per annulus, far below the margins, so a test fails when a model
// gets worse, not by chance. Why each model deviates:
//  - classical dipole: one source at depth 1/σt' and the P1 boundary; the lecture's
//    "off by 12x near the incident light". Good totals at high albedo, shape off by
//    20–70% RMS.
//  - better dipole: Grosjean's D and the Cφ/CE boundary flux improve the total at high
//    albedo, not the shape near the source.
//  - PBD: integrates the beam and adds single scattering, so the shape is right to
//    3–12% RMS; but it double-counts part of the first scattering and overestimates the
//    total by 2–10% at η = 1.3 and 8–15% at η = 1 (measured against the H-function).
//  - Burley: takes the better dipole's total (exactly) and a fitted shape whose tail is
//    far shorter than diffusion's at high albedo: 40–80% RMS on [0.25, 8] mfp.
//  - multipole: the classical dipole's approximations for a finite slab.
//  - qd: diffusion of the beam's first scattering (no single scattering): short of the
//    total by the once-scattered light at low albedo, converging at high albedo.
#include "profiles/HFunction.h"
#include "profiles/Presets.h"
#include "profiles/Validation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>

using namespace sss::profiles;

namespace {

struct Bounds {
  double total;  // |relative error of the total reflectance|
  double rms;    // RMS relative error of R(r) over [0.25, 8] mfp
  double max;    // max relative error over the same annuli
};

struct Case {
  const char* preset;
  int channel;
  std::uint64_t photons;
  double thickness_mm;
};

ValidationReport run(const Case& c, Medium& m) {
  m = preset_medium(*find_preset(c.preset));
  m.thickness_mm = c.thickness_mm;
  ValidationOptions o;
  o.photons = c.photons;
  o.seed = 7;
  o.channels = {false, false, false};
  o.channels[c.channel] = true;
  return validate_against_monte_carlo(m, o);
}

void check(const Case& c, const std::map<Model, Bounds>& bounds) {
  Medium m;
  const ValidationReport rep = run(c, m);
  const auto& mc = rep.monte_carlo[c.channel];
  ASSERT_LT(mc.reflectance.total_stderr, 0.005 * mc.reflectance.total);
  for (const ModelComparison& mm : rep.models) {
    const auto it = bounds.find(mm.model);
    if (it == bounds.end()) continue;
    const ChannelComparison& ch = mm.channels[c.channel];
    SCOPED_TRACE(std::string(c.preset) + "[" + sss::kChannelNames[c.channel] + "] " +
                 std::string(model_name(mm.model)));
    EXPECT_LT(std::fabs(ch.total_rel_error), it->second.total);
    EXPECT_LT(ch.rms_rel_error, it->second.rms);
    EXPECT_LT(ch.max_rel_error, it->second.max);
    if (mm.model == Model::Pbd) {
      EXPECT_GT(ch.total_rel_error, 0.0) << "PBD overestimates";
    }
  }
  // Burley's total is the better dipole's by construction.
  double bd = -1, burley = -2;
  for (const ModelComparison& mm : rep.models) {
    if (mm.model == Model::BetterDipole) bd = mm.channels[c.channel].total;
    if (mm.model == Model::Burley) burley = mm.channels[c.channel].total;
  }
  EXPECT_NEAR(burley, bd, 1e-12);
}

constexpr double kSemiInfinite = std::numeric_limits<double>::infinity();

}  // namespace

// High albedo (α' ≥ 0.95). Measured (total, RMS, max) in %:
//  skin1 R  α' .959: dipole -0.6/26/49, better -3.7/29/63, pbd +5.6/6.7/11, burley 40/71
//  skin2 R  α' .988: dipole -1.7/22/40, better -1.2/26/61, pbd +4.9/6.6/10, burley 40/59
//  marble G α' .998: dipole -1.4/29/55, better -0.8/23/60, pbd +2.3/4.1/9.7, burley 77/137
const std::map<Model, Bounds> kHighAlbedo = {
    {Model::Dipole, {0.03, 0.40, 0.70}},
    {Model::BetterDipole, {0.05, 0.40, 0.80}},
    {Model::Pbd, {0.08, 0.10, 0.16}},
    {Model::Burley, {0.05, 0.90, 1.60}},
};
// Lower albedo (0.67 ≤ α' < 0.95). Measured:
//  skin1 G α' .838: dipole +6.5/44/83, better -9.0/41/65, pbd +7.0/8.2/12.5, burley 49/93
//  skin1 B α' .678: dipole +13.3/73/128, better -10.4/70/101, pbd +9.1/12.2/19, burley 50/96
//  ketchup R α' .747: dipole +11.3/59/107, better -9.8/56/74, pbd +8.8/10.4/14, burley 51/95
const std::map<Model, Bounds> kLowerAlbedo = {
    {Model::Dipole, {0.16, 0.85, 1.45}},
    {Model::BetterDipole, {0.13, 0.85, 1.20}},
    {Model::Pbd, {0.12, 0.16, 0.25}},
    {Model::Burley, {0.13, 0.65, 1.20}},
};

TEST(ModelsVsMonteCarlo, Skin1Red) { check({"skin1", 0, 300000, kSemiInfinite}, kHighAlbedo); }
TEST(ModelsVsMonteCarlo, Skin2Red) { check({"skin2", 0, 100000, kSemiInfinite}, kHighAlbedo); }
TEST(ModelsVsMonteCarlo, MarbleGreen) { check({"marble", 1, 40000, kSemiInfinite}, kHighAlbedo); }
TEST(ModelsVsMonteCarlo, Skin1Green) { check({"skin1", 1, 300000, kSemiInfinite}, kLowerAlbedo); }
TEST(ModelsVsMonteCarlo, Skin1Blue) { check({"skin1", 2, 300000, kSemiInfinite}, kLowerAlbedo); }
TEST(ModelsVsMonteCarlo, KetchupRed) { check({"ketchup", 0, 300000, kSemiInfinite}, kLowerAlbedo); }

TEST(ModelsVsMonteCarlo, MultipoleSlabs) {
  // skin1 red slabs of 2 and 4 mm (1.5 and 3.1 reduced mfp). Measured (R total, T total,
  // RMS of R(r)) in %: 2 mm +8.4/-8.7/39, 4 mm +1.0/-7.9/26. The semi-infinite models
  // miss the transmitted light entirely (R off by +28…+40% at 2 mm): not checked here.
  struct Slab {
    double mm, r_total, t_total, rms;
  };
  for (const Slab& s : {Slab{2.0, 0.12, 0.12, 0.50}, Slab{4.0, 0.04, 0.12, 0.40}}) {
    Medium m;
    const ValidationReport rep =
        run({"skin1", 0, 300000, s.mm}, m);
    const auto& mc = rep.monte_carlo[0];
    ASSERT_GT(mc.transmittance.total, 0.1);
    ASSERT_LT(mc.transmittance.total_stderr, 0.005 * mc.transmittance.total);
    bool found = false;
    for (const ModelComparison& mm : rep.models) {
      if (mm.model != Model::Multipole) continue;
      found = true;
      const ChannelComparison& ch = mm.channels[0];
      SCOPED_TRACE("slab " + std::to_string(s.mm) + " mm");
      EXPECT_LT(std::fabs(ch.total_rel_error), s.r_total);
      EXPECT_LT(std::fabs(ch.total_transmittance_rel_error), s.t_total);
      EXPECT_LT(ch.rms_rel_error, s.rms);
    }
    EXPECT_TRUE(found) << "validate must include the multipole for slabs";
  }
}

TEST(ModelsVsExactTransport, IndexMatchedTotals) {
  // η = 1, isotropic: the exact total is 1 - H(1)√(1-α) (no noise at all). Measured
  // relative errors (%):
  //   α      dipole  better   pbd
  //   0.3    -29.6   -21.7    +7.6
  //   0.5    -23.9   -20.0   +11.2
  //   0.8    -12.4   -12.8   +14.4
  //   0.9     -7.2    -7.9   +14.4
  //   0.95    -3.9    -4.5   +13.7
  //   0.99    -0.8    -1.0   +11.8
  //   0.999   -0.05   -0.06  +10.3
  // Diffusion converges to exact transport as α → 1; PBD's double counting does not.
  struct Row {
    double albedo, dipole, better, pbd_lo, pbd_hi;
  };
  const Row rows[] = {{0.3, 0.33, 0.25, 0.05, 0.10}, {0.5, 0.27, 0.23, 0.08, 0.14},
                      {0.8, 0.15, 0.15, 0.11, 0.17}, {0.9, 0.09, 0.10, 0.11, 0.17},
                      {0.95, 0.05, 0.06, 0.11, 0.16}, {0.99, 0.012, 0.015, 0.09, 0.14},
                      {0.999, 0.002, 0.002, 0.08, 0.13}};
  const ModelOptions opt;
  for (const Row& r : rows) {
    const Coefficients k{1.0 - r.albedo, r.albedo, 0.0, 1.0};
    const double exact = exact_total_reflectance_index_matched(r.albedo);
    auto err = [&](Model m) {
      return make_profile(m, k, kSemiInfinite, opt)->total_reflectance() / exact - 1.0;
    };
    SCOPED_TRACE("albedo " + std::to_string(r.albedo));
    EXPECT_LT(std::fabs(err(Model::Dipole)), r.dipole);
    EXPECT_LT(std::fabs(err(Model::BetterDipole)), r.better);
    EXPECT_GT(err(Model::Pbd), r.pbd_lo);
    EXPECT_LT(err(Model::Pbd), r.pbd_hi);
  }
  // Quantized diffusion has no single scattering (QuantizedDiffusion.h), which the exact
  // total counts: it is short by -66% at α = 0.3 and -17% at 0.8 (measured), and must
  // converge as the once-scattered share vanishes: |error| falls with α, and at α >= 0.99
  // it is within 1%: the default schedule's quantization (<= 0.5%, the bound
  // test_quantized_diffusion.cpp holds it to) plus the better dipole's own error there
  // (0.96% at 0.99, 0.06% at 0.999: the same diffusion with the same boundary).
  double previous = 1.0;
  for (const Row& r : rows) {
    const Coefficients k{1.0 - r.albedo, r.albedo, 0.0, 1.0};
    const double exact = exact_total_reflectance_index_matched(r.albedo);
    const double e = std::fabs(make_profile(Model::Qd, k, kSemiInfinite, opt)->total_reflectance() / exact - 1.0);
    EXPECT_LT(e, previous) << "qd, albedo " << r.albedo;
    previous = e;
    if (r.albedo >= 0.99) {
      const double better = std::fabs(make_profile(Model::BetterDipole, k, kSemiInfinite, opt)->total_reflectance() / exact - 1.0);
      EXPECT_LT(e, 0.005 + better) << "qd, albedo " << r.albedo;
    }
  }
}
