// One channel of a material's real-time kernel (KernelFit.h) as a RadialProfile, so the
// CPU references can sum the Gaussian fit in place of the exact R(r) (`sss-reference
// --kernel fit`): R(r) = Σ_i w_i G(v_i, r), T(r) = Σ_i u_i G(v_i, r) for a slab's
// transmittance fit (0 otherwise), with G the unit-integral 2D Gaussian (DESIGN.md §3).
// The totals are the weights' sums, exactly (each G integrates to 1).
#pragma once

#include "profiles/KernelFit.h"
#include "profiles/Profile.h"

#include <memory>
#include <vector>

namespace sss::profiles {

class GaussianSumProfile : public RadialProfile {
 public:
  // variances > 0 (mm²), weights >= 0, transmit_weights empty or as many as variances.
  // Throws std::invalid_argument otherwise, or for no Gaussian at all.
  GaussianSumProfile(std::vector<double> variances_mm2, std::vector<double> weights,
                     std::vector<double> transmit_weights = {});

  double reflectance(double r_mm) const override;
  double total_reflectance() const override { return total_; }
  double transmittance(double r_mm) const override;
  double total_transmittance() const override { return total_transmit_; }
  // Where exp(-r²/2v) of the widest Gaussian falls below 1e-9: r = √(2 ln 1e9 · v_max).
  double support_radius() const override;
  // The narrowest Gaussian's standard deviation.
  double inner_radius() const override;

 private:
  std::vector<double> v_, w_, u_;
  double total_ = 0.0, total_transmit_ = 0.0;
};

// The kernel as an RgbProfile (one GaussianSumProfile per channel), labelled with the
// model it was fitted to.
RgbProfile make_kernel_profile(const KernelFit& kernel, Model fitted_model);

}  // namespace sss::profiles
