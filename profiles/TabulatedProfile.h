// A profile tabulated at radii (log-log interpolation between nodes): used to fit and
// plot Monte Carlo results like any analytic model.
#pragma once

#include "profiles/MonteCarlo.h"
#include "profiles/Profile.h"

#include <vector>

namespace sss::profiles {

class TabulatedProfile final : public RadialProfile {
 public:
  // Nodes must be ascending in r with R > 0 where possible; zero entries are dropped.
  TabulatedProfile(std::vector<double> r_mm, std::vector<double> R, double total,
                   double total_transmittance = 0.0);
  // From a Monte Carlo run: one node per bin (at the bin's area-weighted centre).
  static TabulatedProfile from_monte_carlo(const MonteCarloResult& mc);
  double reflectance(double r_mm) const override;
  double total_reflectance() const override { return total_; }
  double total_transmittance() const override { return total_t_; }
  double support_radius() const override;
  double inner_radius() const override;

 private:
  std::vector<double> log_r_, log_R_;
  double total_, total_t_;
};

}  // namespace sss::profiles
