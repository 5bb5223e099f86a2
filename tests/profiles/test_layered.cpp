// Model `layered` (profiles/Layered.h): the limits it must reproduce exactly or to the
// accuracy of its sampled transforms, each against something computed independently of
// the adding code:
//  - one finite layer over nothing is the multipole (with base = dipole, the pure Donner &
//    Jensen model) and one semi-infinite layer is the base model itself;
//  - a top layer much deeper than its diffusion length hides whatever lies below it;
//  - at zero frequency the sampled transforms give the scalar adding formula of the
//    layers' closed-form totals, and the profile integrates to those totals;
//  - the stack's inputs are checked, and the errors name the layer and field.
// The model against the layered Monte Carlo walk is in test_layered_accuracy.cpp.
#include "profiles/ClassicalDipole.h"
#include "profiles/Layered.h"
#include "profiles/McTableProfile.h"
#include "profiles/Multipole.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace sss::profiles {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The relative error of an integral through the sampled transforms (LayeredGrid.h): the
// samples are interpolated linearly in u = r² between nodes 10^(1/128) apart, Δu/u = 3.6%,
// which misses a function's integral over a step by (Δu/u)²/8 = 1.6e-4 per unit of its
// relative curvature u² f''/f in u. The profiles here bend by at most a few units
// (the near-axis 1/r of mc-table is u^(-1/2): 3/4; e^(-σr) at σr = 4: 3.5), so 1e-3.
// The lowest frequency adds at most 2.5e-5 (LayeredGrid.h).
constexpr double kSampledIntegral = 1e-3;

// Two skin-like layers (σ in mm^-1; the test needs media, not a measured skin).
const Coefficients kEpi{0.3, 8.0, 0.0, 1.4};
const Coefficients kDerm{0.02, 2.0, 0.0, 1.4};

// ∫ 2πr f(r) dr by the midpoint rule on 4000 log-spaced steps a decade from 1e-7 mm to
// `outer`: the relative step 5.8e-4 makes the rule's error ~ (5.8e-4)²/24 of the integral
// where f is smooth, and the part below 1e-7 mm is at most π (1e-7)² max f.
double integrate(const std::function<double(double)>& f, double outer) {
  double sum = 0.0, prev = 1e-7;
  const double q = std::pow(10.0, 1.0 / 4000.0);
  for (double r = prev * q; prev < outer; prev = r, r *= q) {
    const double m = 0.5 * (r + prev);
    sum += 2.0 * std::numbers::pi * m * f(m) * (r - prev);
  }
  return sum;
}

// The sampled transform pair against a closed form: a pole of the dipoles,
// f(r) = z (1 + σρ) e^{-σρ} / ρ³ (ρ² = r² + z²), has F(k) = 2π e^{-z √(σ² + k²)} (the
// k = 0 case is Multipole.cpp's pole_total). Linear-in-x² interpolation on nodes 10^(1/128)
// apart misses by (Δu/u)²/8 = 1.6e-4 per unit of relative curvature: the forward map is
// held to 1e-3 of F(0) (kSampledIntegral). The inverse is held to 1e-3 of (the value +
// 1e-4 of the peak) wherever the function is within 10^4 of its peak: the relative bound
// where it is large, an absolute floor in its far tail.
TEST(LayeredTransform, ReproducesTheDipolePolePair) {
  const auto& x = detail::hankel_grid();
  const double sigma = 1.0, L = 0.1;
  for (double z : {0.3, 2.0}) {
    auto f = [&](double r) {
      const double rho = std::sqrt(r * r + z * z);
      return z * (1.0 + sigma * rho) * std::exp(-sigma * rho) / (rho * rho * rho);
    };
    auto F = [&](double k) {
      return 2.0 * std::numbers::pi * std::exp(-z * std::sqrt(sigma * sigma + k * k));
    };
    std::vector<double> fs(x.size()), Fs(x.size());
    for (std::size_t j = 0; j < x.size(); ++j) fs[j] = f(L * x[j]), Fs[j] = F(x[j] / L);
    const auto fwd = detail::hankel_forward(fs, L);
    for (std::size_t i = 0; i < x.size(); ++i)
      ASSERT_NEAR(fwd[i], Fs[i], kSampledIntegral * Fs[0]) << z << " k " << x[i] / L;
    const auto inv = detail::hankel_inverse(Fs, L);
    const double peak = f(0.0);
    for (std::size_t j = 0; j < x.size(); ++j) {
      const double r = L * x[j];
      if (f(r) < 1e-4 * peak) break;
      ASSERT_NEAR(inv[j], f(r), kSampledIntegral * (f(r) + 1e-4 * peak)) << z << " r " << r;
    }
  }
}

TEST(LayeredAdding, OneFiniteLayerWithTheDipoleBaseIsTheMultipole) {
  // base = dipole: the layer's reflectance is the multipole's own (LayeredGrid.h, FiniteLayer::pure).
  for (double d : {0.6, 3.0}) {
    const LayeredProfile one({{kDerm, d}}, {}, Model::Dipole, LayerCoupling::Adding);
    const Multipole mp(kDerm, d, Multipole::kAutoPairs);
    for (double r : {0.0, 0.01, 0.3, 1.0, 4.0}) {
      EXPECT_EQ(one.reflectance(r), mp.reflectance(r)) << d << " " << r;
      EXPECT_EQ(one.transmittance(r), mp.transmittance(r)) << d << " " << r;
    }
    EXPECT_EQ(one.total_reflectance(), mp.total_reflectance());
    EXPECT_EQ(one.total_transmittance(), mp.total_transmittance());
  }
}

TEST(Layered, OneSemiInfiniteLayerIsTheBaseModel) {
  const LayeredProfile one({{kDerm, kInf}}, {}, Model::McTable);
  const McTableProfile table(kDerm);
  for (double r : {0.0, 0.01, 0.3, 1.0, 4.0}) EXPECT_EQ(one.reflectance(r), table.reflectance(r));
  EXPECT_EQ(one.total_reflectance(), table.total_reflectance());
  EXPECT_EQ(one.total_transmittance(), 0.0);
}

TEST(Layered, FaceWithTheSameIndexOnBothSidesIsTheSymmetricMultipole) {
  // The two-index constructor with equal indices is the one-index multipole: the pole
  // lattice period 2(d + z_b + z_b') is 2(d + 2 z_b).
  const Multipole a(kDerm, 2.0, Multipole::kAutoPairs);
  const Multipole b(kDerm, 2.0, Multipole::kAutoPairs, kDerm.eta, kDerm.eta);
  for (double r : {0.0, 0.5, 2.0}) {
    EXPECT_EQ(a.reflectance(r), b.reflectance(r));
    EXPECT_EQ(a.transmittance(r), b.transmittance(r));
  }
}

TEST(Layered, ADeepTopLayerHidesWhatLiesBelow) {
  // A top layer d deep: what reaches the base and comes back has crossed it twice, and
  // diffusion attenuates it by ~e^{-σtr d} each way; the multipole's finite-thickness
  // factor differs from 1 by the same order. At σtr d = 40 both are below e^-40 ≈ 4e-18
  // of the top medium's own semi-infinite profile: the two must agree to rounding
  // (1e-12 relative, far above double rounding and far below any physics).
  const double sigma_tr = kEpi.sigma_tr_classical();
  const double d = 40.0 / sigma_tr;
  for (const Coefficients& base : {kDerm, Coefficients{2.0, 1.0, 0.0, 1.4}}) {
    const LayeredProfile deep({{kEpi, d}, {base, kInf}}, {}, Model::McTable);
    const McTableProfile semi(kEpi);
    for (double r : {0.01, 0.1, 0.5, 1.0, 2.0}) {
      const double want = semi.reflectance(r);
      EXPECT_NEAR(deep.reflectance(r), want, 1e-12 * want) << r;
    }
    // The total of a corrected (mc-table) layer is the integral of its profile through the
    // sampled transform: kSampledIntegral of it.
    EXPECT_NEAR(deep.total_reflectance(), semi.total_reflectance(),
                kSampledIntegral * semi.total_reflectance());
  }
}

TEST(LayeredAdding, ZeroFrequencyIsTheScalarAddingOfTheTotals) {
  // The totals: the scalar adding formula over the layers' closed-form totals, written out
  // here for two layers from the layer profiles themselves (not from LayeredProfile).
  const double d1 = 0.25, d2 = 2.0;
  const Coefficients top = kEpi;
  Coefficients matched = kDerm;
  matched.eta = 1.0;  // the base under a layer is index-matched
  {  // finite over semi-infinite, base = dipole (pure multipole layers)
    const Multipole down(top, d1, Multipole::kAutoPairs, top.eta, 1.0);
    const Multipole up(top, d1, Multipole::kAutoPairs, 1.0, top.eta);
    const ClassicalDipole base(matched);
    const double t = down.total_transmittance(), r2 = base.total_reflectance();
    const double want = down.total_reflectance() + t * t * r2 / (1.0 - r2 * up.total_reflectance());
    const LayeredProfile p({{top, d1}, {kDerm, kInf}}, {}, Model::Dipole, LayerCoupling::Adding);
    EXPECT_NEAR(p.total_reflectance(), want, 1e-14);
    // The profile integrates to its total: R1 exactly, the added part through the sampled
    // transforms (kSampledIntegral).
    EXPECT_NEAR(integrate([&](double r) { return p.reflectance(r); }, p.support_radius()),
                want, kSampledIntegral * want);
  }
  {  // two finite layers: R and T
    const Multipole d_top(top, d1, Multipole::kAutoPairs, top.eta, 1.0);
    const Multipole u_top(top, d1, Multipole::kAutoPairs, 1.0, top.eta);
    const Multipole bottom(kDerm, d2, Multipole::kAutoPairs, 1.0, kDerm.eta);
    const double t1 = d_top.total_transmittance(), r2 = bottom.total_reflectance();
    const double denom = 1.0 - r2 * u_top.total_reflectance();
    const double want_r = d_top.total_reflectance() + t1 * t1 * r2 / denom;
    const double want_t = t1 * bottom.total_transmittance() / denom;
    const LayeredProfile p({{top, d1}, {kDerm, d2}}, {}, Model::Dipole, LayerCoupling::Adding);
    EXPECT_NEAR(p.total_reflectance(), want_r, 1e-14);
    EXPECT_NEAR(p.total_transmittance(), want_t, 1e-14);
    EXPECT_NEAR(integrate([&](double r) { return p.reflectance(r); }, p.support_radius()),
                want_r, kSampledIntegral * want_r);
    EXPECT_NEAR(integrate([&](double r) { return p.transmittance(r); }, p.support_radius()),
                want_t, kSampledIntegral * want_t);
  }
}

// LayerCoupling::Diffusion (the default). Its frequency-domain solution for identical
// layers is, in exact arithmetic, the one for the homogeneous medium (the interfaces carry
// φ and D ∂φ/∂z across unchanged), so what the stack adds to the top medium's own profile
// is zero up to the rounding of the two solves (~1e-16 of R(k)) spread by the inverse
// transform: 1e-9 of the profile's peak bounds it with room for the 1281-term sums.
TEST(LayeredDiffusion, IdenticalLayersAreTheHomogeneousMedium) {
  for (Model base : {Model::Dipole, Model::McTable}) {
    const LayeredProfile split({{kDerm, 0.7}, {kDerm, 1.3}, {kDerm, kInf}}, {}, base);
    const auto alone = make_profile(base, kDerm, kInf, {});
    const double peak = alone->reflectance(0.01);
    for (double r : {0.01, 0.1, 0.5, 1.0, 3.0, 10.0})
      EXPECT_NEAR(split.reflectance(r), alone->reflectance(r), 1e-9 * peak)
          << model_name(base) << " " << r;
  }
}

// One finite layer in the diffusion solution is the image series, i.e. the multipole with
// the same faces: its totals exactly (the k = 0 solve against the closed-form sums, which
// differ by the multipole's truncated poles, e^-25 ≈ 1e-11), its profiles through the
// sampled inverse transform of (multipole - dipole), whose interpolation error is
// kSampledIntegral of that difference's scale (its value near the axis), and the
// transmittance's likewise of its own scale.
TEST(LayeredDiffusion, OneFiniteLayerIsTheMultipole) {
  for (double d : {0.6, 3.0}) {
    const LayeredProfile one({{kDerm, d}}, {}, Model::Dipole);
    const Multipole mp(kDerm, d, Multipole::kAutoPairs);
    const ClassicalDipole dip(kDerm);
    EXPECT_NEAR(one.diffusion_total_reflectance(), mp.total_reflectance(), 1e-10) << d;
    EXPECT_NEAR(one.diffusion_total_transmittance(), mp.total_transmittance(), 1e-10) << d;
    const double scale_r = std::fabs(mp.reflectance(0.0) - dip.reflectance(0.0));
    const double scale_t = mp.transmittance(0.0);
    for (double r : {0.0, 0.05, 0.3, 1.0, 3.0, 8.0}) {
      EXPECT_NEAR(one.reflectance(r), mp.reflectance(r), kSampledIntegral * scale_r) << d << " " << r;
      EXPECT_NEAR(one.transmittance(r), mp.transmittance(r), kSampledIntegral * scale_t) << d << " " << r;
    }
  }
}

// The diffusion totals are the integrals of the profiles (checked against this file's own
// quadrature to kQuadrature), and they agree with the diffusion solution's exact totals at
// k = 0 up to what the sampled inverse transform loses (LayeredGrid.h: a weak oscillating
// tail beyond the support). 1% of the total is not derived: it guards that loss, measured
// at 0.2% of R and 0.5% of T here, an order below the model's own error against Monte
// Carlo (test_layered_accuracy.cpp).
TEST(LayeredDiffusion, TotalsAreTheProfilesIntegrals) {
  constexpr double kQuadrature = 1e-5;  // both midpoint rules: (0.009)²/24 and (6e-4)²/24
  for (Model base : {Model::Dipole, Model::McTable}) {
    const LayeredProfile p({{kEpi, 0.25}, {kDerm, 2.0}}, {}, base);
    const double rt = p.total_reflectance(), tt = p.total_transmittance();
    EXPECT_NEAR(integrate([&](double r) { return p.reflectance(r); }, p.support_radius()), rt,
                kQuadrature * rt) << model_name(base);
    EXPECT_NEAR(integrate([&](double r) { return p.transmittance(r); }, p.support_radius()), tt,
                kQuadrature * tt) << model_name(base);
    EXPECT_NEAR(tt, p.diffusion_total_transmittance(), 1e-2 * tt);
    if (base == Model::Dipole) {
      EXPECT_NEAR(rt, p.diffusion_total_reflectance(), 1e-2 * rt);
    }
  }
}

TEST(Layered, ProfilesArePositiveAndFinite) {
  const LayeredProfile p({{kEpi, 0.25}, {kDerm, 1.5}, {Coefficients{0.5, 3.0, 0.0, 1.4}, kInf}},
                         {}, Model::McTable);
  for (double r = 1e-6; r < p.support_radius(); r *= 1.1) {
    const double v = p.reflectance(r);
    ASSERT_TRUE(std::isfinite(v) && v > 0.0) << r;
    EXPECT_EQ(p.transmittance(r), 0.0);  // semi-infinite base
  }
}

TEST(Layered, BadStacksNameTheLayerAndField) {
  auto message = [](const LayerStack& s) {
    try {
      (void)make_layered_rgb_profile(s);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  Medium epi = Medium::from_reduced({0.3, 0.4, 0.5}, {8, 8, 8}, 1.4);
  epi.thickness_mm = 0.25;
  Medium derm = Medium::from_reduced({0.02, 0.03, 0.05}, {2, 2, 2}, 1.4);
  EXPECT_EQ(message({}).rfind("layers: ", 0), 0u) << message({});
  {
    Medium open_top = epi;
    open_top.thickness_mm = kInf;
    EXPECT_EQ(message({open_top, derm}).rfind("layers[0].thickness_mm: ", 0), 0u);
  }
  {
    Medium bad = derm;
    bad.sigma_a[1] = -1.0;
    EXPECT_EQ(message({epi, bad}).rfind("layers[1].sigma_a[G]: ", 0), 0u) << message({epi, bad});
  }
  {
    Medium other = derm;
    other.eta = {1.5, 1.5, 1.5};
    EXPECT_EQ(message({epi, other}).rfind("layers[1].eta[R]: ", 0), 0u) << message({epi, other});
  }
  {
    Medium thin = epi;
    thin.thickness_mm = 0.05;  // under one reduced mean free path (1/8.3 mm)
    EXPECT_EQ(message({thin, derm}).rfind("layers[0].thickness_mm[R]: ", 0), 0u)
        << message({thin, derm});
  }
  EXPECT_EQ(message(LayerStack(kMaxLayers + 1, epi)).rfind("layers: ", 0), 0u);
  EXPECT_EQ(message({epi, derm}), "no error");
}

}  // namespace
}  // namespace sss::profiles
