#include "profiles/KernelFit.h"

#include "profiles/Nnls.h"

#include <Eigen/Core>

#include <cmath>

namespace sss::profiles {

TransmittanceFit fit_transmittance(const RgbProfile& rgb, const FitTarget& target,
                                   const std::vector<double>& variances_mm2) {
  const auto rows = static_cast<Eigen::Index>(target.r_mm.size());
  const auto n = static_cast<Eigen::Index>(variances_mm2.size());
  TransmittanceFit out;
  out.weights.assign(variances_mm2.size(), Rgb{});
  const Rgb total = rgb.total_transmittance();
  Eigen::MatrixXd A(rows + 1, n);
  Eigen::VectorXd b(rows + 1);
  // Rows weighted by √dr·r: the least squares of r(T − T̃) in dr, the fit's own norm. The
  // Gaussian rows are the same for every channel; only the energy row and b change.
  for (Eigen::Index j = 0; j < rows; ++j) {
    const double s = std::sqrt(target.dr[j]) * target.r_mm[j];
    for (Eigen::Index i = 0; i < n; ++i)
      A(j + 1, i) = s * gaussian_2d(variances_mm2[i], target.r_mm[j]);
  }
  for (int c = 0; c < 3; ++c) {
    double norm2 = 0.0;
    for (Eigen::Index j = 0; j < rows; ++j) {
      const double s = std::sqrt(target.dr[j]) * target.r_mm[j];
      b(j + 1) = s * rgb.channel(c).transmittance(target.r_mm[j]);
      norm2 += b(j + 1) * b(j + 1);
    }
    if (!(total[c] > 0.0) || !(norm2 > 0.0)) continue;  // nothing transmitted
    // The energy row Σ_i u_i = total, weighted far above the rest (then made exact).
    const double k = 1e4 * std::sqrt(norm2) / total[c];
    A.row(0).setConstant(k);
    b(0) = k * total[c];
    const Eigen::VectorXd u = nnls(A, b);
    const double sum = u.sum();
    if (!(sum > 0.0)) continue;
    double err2 = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) out.weights[i][c] = u(i) * total[c] / sum;
    for (Eigen::Index j = 0; j < rows; ++j) {
      double fitted = 0.0;
      for (Eigen::Index i = 0; i < n; ++i) fitted += out.weights[i][c] * A(j + 1, i);
      err2 += (fitted - b(j + 1)) * (fitted - b(j + 1));
    }
    out.total[c] = total[c];
    out.relative_error[c] = std::sqrt(err2 / norm2);
  }
  return out;
}

KernelFit fit_kernel(const RgbProfile& rgb, int gaussians, bool slab) {
  FitOptions options;
  options.gaussians = gaussians;
  const FitTarget target = make_fit_target(rgb);
  KernelFit out{fit_gaussians(target, options), std::nullopt};
  if (slab) out.transmittance = fit_transmittance(rgb, target, out.fit.variances_mm2);
  return out;
}

}  // namespace sss::profiles
