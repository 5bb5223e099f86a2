// The classical dipole of Jensen et al. 2001 ("A practical model for subsurface light
// transport"): one positive source at depth 1/σt', its mirror image about the
// extrapolated boundary z = -2AD, A from the Groenhuis Fdr fit, D = 1/(3σt').
#pragma once

#include "profiles/Profile.h"

namespace sss::profiles {

class ClassicalDipole final : public RadialProfile {
 public:
  explicit ClassicalDipole(const Coefficients& c);
  double reflectance(double r_mm) const override;
  // Rd = (α'/2)(1 + exp(-4/3 A √(3(1-α')))) exp(-√(3(1-α'))) (Jensen et al. 2001, eq. 5).
  double total_reflectance() const override;
  double support_radius() const override;
  double inner_radius() const override { return zr_; }

 private:
  double alpha_p_, sigma_tr_, zr_, zv_;
};

}  // namespace sss::profiles
