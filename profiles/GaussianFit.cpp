#include "profiles/GaussianFit.h"

#include "profiles/VariableProjection.h"
#include "profiles/VariableProjectionSearch.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace sss::profiles {

bool valid_gaussian_count(double n) { return n >= kMinGaussians && n <= kMaxGaussians && n == std::floor(n); }

std::string gaussian_count_rule() {
  return "must be an integer in [" + std::to_string(kMinGaussians) + ", " + std::to_string(kMaxGaussians) + "]";
}

namespace {

constexpr double kPi = 3.14159265358979323846;

void validate(const FitTarget& t, int n) {
  if (!valid_gaussian_count(n))
    throw std::invalid_argument("fit_gaussians: gaussians " + gaussian_count_rule() + ", got " + std::to_string(n));
  const std::size_t m = t.r_mm.size();
  if (m < static_cast<std::size_t>(n) + 1)
    throw std::invalid_argument("fit_gaussians: the target needs more samples than gaussians");
  if (t.R.size() != m || t.dr.size() != m)
    throw std::invalid_argument("fit_gaussians: r_mm, R and dr must have the same size");
  for (std::size_t j = 0; j < m; ++j) {
    if (!(t.r_mm[j] > 0.0) || !std::isfinite(t.r_mm[j]) || (j > 0 && !(t.r_mm[j] > t.r_mm[j - 1])))
      throw std::invalid_argument("fit_gaussians: radii must be positive, finite, ascending");
    if (!(t.dr[j] >= 0.0) || !std::isfinite(t.dr[j]))
      throw std::invalid_argument("fit_gaussians: dr must be finite and >= 0");
    for (double v : t.R[j])
      if (!std::isfinite(v)) throw std::invalid_argument("fit_gaussians: R must be finite");
  }
  if (!(t.prefilter_variance_mm2 >= 0.0) || !std::isfinite(t.prefilter_variance_mm2))
    throw std::invalid_argument("fit_gaussians: prefilter_variance_mm2 must be finite and >= 0");
  for (int c = 0; c < 3; ++c) {
    const double T = t.total_reflectance[c];
    if (!(T >= 0.0) || !std::isfinite(T))
      throw std::invalid_argument("fit_gaussians: total reflectance must be finite and >= 0");
    bool all_zero = true;
    for (std::size_t j = 0; j < m; ++j) all_zero = all_zero && t.R[j][c] == 0.0;
    if (all_zero && T > 0.0) {
      std::string msg = "fit_gaussians: R is zero on every sample of channel ";
      msg += kChannelNames[c];
      msg += " but its total is not";
      throw std::invalid_argument(msg);
    }
  }
}

// e^{-x} I0(x) for x >= 0: the polynomial approximations of Abramowitz & Stegun 9.8.1
// (|x| <= 3.75, relative error < 1.6e-7) and 9.8.2 (x >= 3.75, < 1.9e-7).
double scaled_bessel_i0(double x) {
  if (x <= 3.75) {
    const double t = (x / 3.75) * (x / 3.75);
    return std::exp(-x) *
           (1.0 + t * (3.5156229 + t * (3.0899424 + t * (1.2067492 +
                   t * (0.2659732 + t * (0.0360768 + t * 0.0045813))))));
  }
  const double t = 3.75 / x;
  return (0.39894228 + t * (0.01328592 + t * (0.00225319 + t * (-0.00157565 +
          t * (0.00916281 + t * (-0.02057706 + t * (0.02635537 + t * (-0.01647633 +
          t * 0.00392377)))))))) / std::sqrt(x);
}

// (R * G_v)(r) for a radial R: ∫0^∞ R(s) (s/v) exp(-(r-s)²/2v) e^{-rs/v} I0(rs/v) ds, the
// angular integral of the 2D convolution done in closed form. The integrand is negligible
// beyond 9 standard deviations from r; 24 panels of 8-point Gauss–Legendre.
Rgb blurred_reflectance(const RgbProfile& p, double r, double v) {
  static constexpr double x8[4] = {0.1834346424956498, 0.5255324099163290,
                                   0.7966664774136267, 0.9602898564975363};
  static constexpr double w8[4] = {0.3626837833783620, 0.3137066458778873,
                                   0.2223810344533745, 0.1012285362903763};
  const double sd = std::sqrt(v);
  const double lo = std::max(0.0, r - 9.0 * sd), hi = r + 9.0 * sd;
  constexpr int kPanels = 24;
  const double h = (hi - lo) / kPanels;
  Rgb sum{};
  for (int k = 0; k < kPanels; ++k) {
    const double mid = lo + (k + 0.5) * h;
    for (int q = 0; q < 8; ++q) {
      const double s = mid + (q < 4 ? -1.0 : 1.0) * x8[q % 4] * 0.5 * h;
      const double d = r - s;
      const double kernel = (s / v) * std::exp(-d * d / (2.0 * v)) * scaled_bessel_i0(r * s / v) *
                            w8[q % 4] * 0.5 * h;
      const Rgb R = p.reflectance(s);
      for (int c = 0; c < 3; ++c) sum[c] += kernel * R[c];
    }
  }
  return sum;
}

}  // namespace

double default_fit_resolution(Model model) {
  // A layered profile is its top medium's mc-table profile near the axis, 1/r peak included.
  return model == Model::McTable || model == Model::Layered ? 0.25 : 0.0;
}

double gaussian_2d(double variance_mm2, double r_mm) {
  return std::exp(-r_mm * r_mm / (2.0 * variance_mm2)) / (2.0 * kPi * variance_mm2);
}

Rgb GaussianFit::evaluate(double r_mm) const {
  Rgb out{};
  for (std::size_t i = 0; i < variances_mm2.size(); ++i) {
    const double g = gaussian_2d(variances_mm2[i], r_mm);
    for (int c = 0; c < 3; ++c) out[c] += weights[i][c] * g;
  }
  return out;
}

FitTarget make_fit_target(const RgbProfile& profile, int samples, double resolution) {
  if (samples < 2) {
    std::string msg = "make_fit_target: samples must be >= 2, got ";
    msg += std::to_string(samples);
    throw std::invalid_argument(msg);
  }
  FitTarget t;
  const double r0 = 1e-3 * profile.inner_radius();
  const double r1 = profile.support_radius();
  if (!(r0 > 0.0) || !(r1 > r0) || !std::isfinite(r1))
    throw std::invalid_argument("make_fit_target: the profile's radii are not usable");
  if (resolution < 0.0) resolution = default_fit_resolution(profile.model());
  if (!std::isfinite(resolution) || resolution > 10.0)
    throw std::invalid_argument("resolution: must lie in [0, 10] inner radii, got " +
                                std::to_string(resolution));
  const double blur_sd = resolution * profile.inner_radius();
  t.prefilter_variance_mm2 = blur_sd * blur_sd;
  const double h = std::log(r1 / r0) / (samples - 1);
  t.r_mm.resize(samples);
  t.R.resize(samples);
  t.dr.resize(samples);
  for (int j = 0; j < samples; ++j) {
    const double r = j == samples - 1 ? r1 : r0 * std::exp(h * j);
    t.r_mm[j] = r;
    t.R[j] = t.prefilter_variance_mm2 > 0.0
                 ? blurred_reflectance(profile, r, t.prefilter_variance_mm2)
                 : profile.reflectance(r);
    // Trapezoid rule in u = ln r: ∫ f dr = ∫ f(e^u) e^u du.
    t.dr[j] = (j == 0 || j == samples - 1 ? 0.5 : 1.0) * h * r;
  }
  t.total_reflectance = profile.total_reflectance();
  return t;
}

GaussianFit fit_gaussians(const FitTarget& target, const FitOptions& opt) {
  const int n = opt.gaussians;
  validate(target, n);
  // The log-variances: variable projection (VariableProjection.h) searched by
  // Levenberg–Marquardt with restarts (VariableProjectionSearch.h).
  detail::VarPro vp(target, n);
  const detail::SearchResult search = detail::search_log_variances(vp, target, opt);
  const detail::Point& best = search.best;
  GaussianFit fit;
  fit.iterations = search.iterations;

  // Sort by variance, rescale each channel to the exact total, measure the error.
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int x, int y) { return best.theta[x] < best.theta[y]; });
  fit.variances_mm2.resize(n);
  fit.weights.assign(n, Rgb{});
  for (int c = 0; c < 3; ++c) {
    const double sum = best.W.col(c).sum();
    const double T = target.total_reflectance[c];
    for (int i = 0; i < n; ++i) {
      const double w = best.W(order[i], c);
      fit.weights[i][c] = (sum > 0.0 ? w * (T / sum) : 0.0);
    }
  }
  Eigen::MatrixXd Adata(vp.samples(), n);
  Eigen::MatrixXd Wfinal(n, 3);
  for (int i = 0; i < n; ++i) {
    fit.variances_mm2[i] = std::exp(best.theta[order[i]]);
    vp.column(best.theta[order[i]], Adata.col(i));
    for (int c = 0; c < 3; ++c) Wfinal(i, c) = fit.weights[i][c];
  }
  const Eigen::MatrixXd residual = vp.targets() - Adata * Wfinal;
  for (int c = 0; c < 3; ++c) {
    for (int i = 0; i < n; ++i) fit.total_reflectance[c] += fit.weights[i][c];
    const double norm = vp.targets().col(c).norm();
    fit.relative_error[c] = norm > 0.0 ? residual.col(c).norm() / norm : 0.0;
  }
  // A blurred target: the kernel is the fit with the blur's variance taken off. A fitted
  // variance below the blur's (the fit asking for detail finer than the resolution) keeps
  // 1% of it rather than going to zero; the relative error above is then that of a
  // kernel slightly wider than the one returned, at a scale the target does not resolve.
  const double v0 = target.prefilter_variance_mm2;
  fit.prefilter_variance_mm2 = v0;
  if (v0 > 0.0)
    for (double& v : fit.variances_mm2) v = std::max(v - v0, 0.01 * v0);
  return fit;
}

}  // namespace sss::profiles
