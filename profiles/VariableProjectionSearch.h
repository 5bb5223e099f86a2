// Internal to the Gaussian fit (GaussianFit.cpp): the search over the log-variances of
// the variable-projection functional (VariableProjection.h). Levenberg–Marquardt with
// the exact variable-projection Jacobian, from three starting spreads placed by the
// target's energy, then re-seeding of Gaussians whose weights vanish.
#pragma once

#include "profiles/GaussianFit.h"
#include "profiles/VariableProjection.h"

namespace sss::profiles::detail {

// Projected Levenberg–Marquardt on Φ from p.theta, with θ kept in
// [vp.theta_min(), vp.theta_max()], for at most max_iterations. p ends at the best point
// found, evaluated. Returns the number of iterations.
int levenberg_marquardt(VarPro& vp, Point& p, int max_iterations);

struct SearchResult {
  Point best;          // evaluated; W before the energy rescale
  int iterations = 0;  // Levenberg–Marquardt iterations, all runs summed
};

// The restarts of fit_gaussians (GaussianFit.h): three probed starts, the best of them
// run to convergence, then up to two rounds of re-seeding. opt.gaussians must equal the
// n that vp was built with.
SearchResult search_log_variances(VarPro& vp, const FitTarget& target, const FitOptions& opt);

}  // namespace sss::profiles::detail
