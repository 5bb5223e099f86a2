// The multipole of Donner & Jensen 2005 ("Light diffusion in multi-layered translucent
// materials") for one slab of thickness d in air: dipole pairs mirrored about both
// extrapolated boundaries, giving reflectance and transmittance profiles. With the
// classical dipole's source depth and boundary constant, so a thick slab becomes the
// classical dipole.
#pragma once

#include "profiles/Profile.h"

#include <vector>

namespace sss::profiles {

class Multipole final : public RadialProfile {
 public:
  // Throws std::invalid_argument for invalid coefficients, a thickness that is not a
  // finite positive number, or pairs < 0. `pairs` = n: the poles i in [-n, n].
  Multipole(const Coefficients& c, double thickness_mm, int pairs = 10);
  double reflectance(double r_mm) const override;
  double transmittance(double r_mm) const override;
  double total_reflectance() const override;    // closed form, summed over the pairs
  double total_transmittance() const override;  // closed form, summed over the pairs
  double support_radius() const override;
  double inner_radius() const override;
  // Pole depths (z down from the lit face), i = -n..n in order.
  const std::vector<double>& positive_poles() const { return z_pos_; }
  const std::vector<double>& negative_poles() const { return z_neg_; }

 private:
  double alpha_p_, sigma_tr_, thickness_;
  double ell_, z_b_;                   // source depth 1/σt', extrapolation distance 2AD
  std::vector<double> z_pos_, z_neg_;  // source depths of the positive and negative poles
};

}  // namespace sss::profiles
