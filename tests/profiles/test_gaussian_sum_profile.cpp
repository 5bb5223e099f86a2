// The material's real-time kernel as a profile (GaussianSumProfile.h, KernelFit.h): what
// `sss-reference --kernel fit` sums, issue 17's "Gaussian fit" link.
#include "profiles/GaussianSumProfile.h"
#include "profiles/Integrate.h"
#include "profiles/KernelFit.h"
#include "profiles/Presets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sss::profiles {
namespace {

// ∫ 2πr R dr by the library's radial quadrature (geometric panels) against the weights'
// sum, which is the total by construction (each G integrates to 1): the quadrature's own
// error on Gaussians is far below 1e-6 relative.
TEST(GaussianSumProfile, IntegratesToItsWeightsAndTransmitsItsOwnWeights) {
  const GaussianSumProfile p({0.01, 0.3, 4.0}, {0.2, 0.3, 0.1}, {0.0, 0.05, 0.02});
  EXPECT_DOUBLE_EQ(p.total_reflectance(), 0.6);
  EXPECT_DOUBLE_EQ(p.total_transmittance(), 0.07);
  const double r_total =
      integrate_radial([&](double r) { return p.reflectance(r); }, 1e-4 * p.inner_radius(), p.support_radius());
  const double t_total =
      integrate_radial([&](double r) { return p.transmittance(r); }, 1e-4 * p.inner_radius(), p.support_radius());
  EXPECT_NEAR(r_total, 0.6, 1e-6);
  EXPECT_NEAR(t_total, 0.07, 1e-7);
  // R(0) = Σ w / (2π v).
  EXPECT_NEAR(p.reflectance(0.0), (0.2 / 0.01 + 0.3 / 0.3 + 0.1 / 4.0) / (2.0 * 3.14159265358979323846), 1e-12);
  EXPECT_DOUBLE_EQ(p.inner_radius(), 0.1);
  // Beyond the support the widest Gaussian has fallen below 1e-9 of its peak.
  EXPECT_LT(std::exp(-p.support_radius() * p.support_radius() / 8.0), 1.01e-9);
}

TEST(GaussianSumProfile, RefusesWhatIsNotAKernel) {
  EXPECT_THROW(GaussianSumProfile({}, {}), std::invalid_argument);
  EXPECT_THROW(GaussianSumProfile({1.0}, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(GaussianSumProfile({0.0}, {1.0}), std::invalid_argument);
  EXPECT_THROW(GaussianSumProfile({1.0}, {-1.0}), std::invalid_argument);
  EXPECT_THROW(GaussianSumProfile({1.0}, {std::nan("")}), std::invalid_argument);
  EXPECT_THROW(GaussianSumProfile({1.0}, {1.0}, {1.0, 1.0}), std::invalid_argument);
}

// The kernel profile of a material is its fit, channel by channel, and a slab's keeps the
// fitted transmittance (the multipole's total, as renderer/MaterialTable uploads it).
TEST(GaussianSumProfile, KernelProfileIsTheMaterialsFit) {
  Medium slab = preset_medium(*find_preset("skin1"));
  slab.thickness_mm = 2.0;
  const RgbProfile exact(Model::Multipole, slab);
  const KernelFit k = fit_kernel(exact, 6, true);
  ASSERT_TRUE(k.transmittance.has_value());
  const RgbProfile p = make_kernel_profile(k, Model::Multipole);
  EXPECT_EQ(p.model(), Model::Multipole);
  for (double r : {0.0, 0.05, 0.5, 2.0, 9.0}) {
    const Rgb want = k.fit.evaluate(r), got = p.reflectance(r);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1e-12 * std::max(1.0, want[c])) << r;
  }
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(p.total_reflectance()[c], exact.total_reflectance()[c], 1e-12);
    EXPECT_NEAR(p.total_transmittance()[c], exact.total_transmittance()[c], 1e-12);
  }
}

}  // namespace
}  // namespace sss::profiles
