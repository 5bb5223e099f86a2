// The spline through mc-table's fluxes per annulus, from which McTableProfile evaluates
// R(r): how it is built and why is McTableSpline.cpp's comment "Histopolation". Internal
// to profiles/.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace sss::profiles {

struct McTableSpline {
  std::size_t K = 0;           // the last enforced annulus: nodes 0..K
  double dx = 0.0;             // the annuli's width in x = ln r (optical units)
  std::vector<double> centre;  // node k at the centre c_k of bin k (x)
  std::vector<double> phi;     // φ_k = ln q at c_k
  std::vector<double> seg;     // segment k: a0..a3 of φ in t ∈ [0, 1] over [c_k, c_k+1]
  double s0 = 1.5;             // the slope of φ at c_0 (the law below it)
  double kappa = 0.0;          // the tail's decay rate (per optical unit)
  double rK = 0.0;             // e^{c_K}
  int iterations = 0;
  double residual = 0.0;
};

// Fits the spline to the fluxes `target` (per annulus; 0 where not enforced) over the
// annuli `enforced` among the first `bins_used` of a table with these `r_edges` (optical
// units), for a medium of reduced albedo `alpha`; `apart`: the multiply-scattered part
// alone (the log law below c_0). Throws std::invalid_argument (starting with `too_few`)
// when fewer than two annuli are enforced, std::runtime_error when the fixed point
// diverges; `medium` ("albedo A, eta E") names the medium in both.
McTableSpline fit_mc_table_spline(const std::vector<double>& r_edges, std::size_t bins_used,
                                  const std::vector<double>& target, const std::vector<char>& enforced,
                                  double alpha, bool apart, const std::string& too_few,
                                  const std::string& medium);

// The radius (optical units) past which r R(r) stays below 1e-8 of its peak.
double mc_table_support_mfp(const McTableSpline& spline);

}  // namespace sss::profiles
