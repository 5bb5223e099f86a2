// A profile tabulated at radii (log-log interpolation between nodes): used to fit and
// plot Monte Carlo results like any analytic model.
//
// Between nodes, log R is linear in log r (power laws are reproduced exactly). Inside the
// first node R is held constant at its value; past the last node it decays exponentially,
// R(r) = R_n exp(-k (r - r_n)), with k = ln(R_{n-1}/R_n) / (r_n - r_{n-1}) from the last
// two nodes (pure exponential tails are reproduced exactly); if those two nodes do not
// decay (Monte Carlo noise in a sparse tail), k = 1/(r_n - r_{n-1}) instead.
#pragma once

#include "profiles/MonteCarlo.h"
#include "profiles/Profile.h"

#include <vector>

namespace sss::profiles {

class TabulatedProfile final : public RadialProfile {
 public:
  // Nodes must be ascending in r with R > 0 where possible; zero entries are dropped.
  // Throws std::invalid_argument (naming "r_mm", "R" or "total") for mismatched sizes,
  // radii that are not finite, > 0 and strictly ascending, negative or non-finite R,
  // fewer than two nodes with R > 0, or a non-finite total.
  TabulatedProfile(std::vector<double> r_mm, std::vector<double> R, double total,
                   double total_transmittance = 0.0);
  // From a Monte Carlo run: one node per non-empty bin, at the bin's area-weighted centre
  // r̄ = √((r0² + r1²)/2) (the radius that halves the annulus' area; r1/√2 for the disc
  // [0, r1]). Empty bins are dropped. The totals are the run's totals, which include
  // exits beyond the last bin. If the run has at least two non-empty transmittance bins
  // they become the transmittance profile (otherwise transmittance(r) is 0, though
  // total_transmittance() is still the run's total).
  static TabulatedProfile from_monte_carlo(const MonteCarloResult& mc);
  // Adds a transmittance profile (same rules as the constructor's nodes).
  void set_transmittance(std::vector<double> r_mm, std::vector<double> T);

  double reflectance(double r_mm) const override { return reflectance_.eval(r_mm); }
  double transmittance(double r_mm) const override { return transmittance_.eval(r_mm); }
  double total_reflectance() const override { return total_; }
  double total_transmittance() const override { return total_t_; }
  double support_radius() const override;  // the last node's radius
  double inner_radius() const override;    // the first node's radius

 private:
  struct Table {
    std::vector<double> log_r, log_v;
    double tail_rate = 0.0;  // k of the exponential tail, mm^-1
    // Empty table: 0 everywhere.
    double eval(double r_mm) const;
    static Table build(std::vector<double> r_mm, std::vector<double> v, const char* what);
  };
  Table reflectance_, transmittance_;
  double total_, total_t_;
};

}  // namespace sss::profiles
