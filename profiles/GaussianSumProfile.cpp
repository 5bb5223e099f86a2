#include "profiles/GaussianSumProfile.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace sss::profiles {

namespace {

double sum_of(const std::vector<double>& v, const std::vector<double>& w, double r) {
  double s = 0.0;
  for (std::size_t i = 0; i < w.size(); ++i) s += w[i] * gaussian_2d(v[i], r);
  return s;
}

}  // namespace

GaussianSumProfile::GaussianSumProfile(std::vector<double> variances_mm2, std::vector<double> weights,
                                       std::vector<double> transmit_weights)
    : v_(std::move(variances_mm2)), w_(std::move(weights)), u_(std::move(transmit_weights)) {
  if (v_.empty()) throw std::invalid_argument("Gaussian kernel: no Gaussians");
  if (w_.size() != v_.size())
    throw std::invalid_argument("Gaussian kernel: " + std::to_string(w_.size()) + " weights for " +
                                std::to_string(v_.size()) + " variances");
  if (!u_.empty() && u_.size() != v_.size())
    throw std::invalid_argument("Gaussian kernel: " + std::to_string(u_.size()) +
                                " transmittance weights for " + std::to_string(v_.size()) + " variances");
  for (std::size_t i = 0; i < v_.size(); ++i) {
    if (!(std::isfinite(v_[i]) && v_[i] > 0.0))
      throw std::invalid_argument("Gaussian kernel: variance " + std::to_string(i) + " must be finite and > 0");
    if (!(std::isfinite(w_[i]) && w_[i] >= 0.0))
      throw std::invalid_argument("Gaussian kernel: weight " + std::to_string(i) + " must be finite and >= 0");
    if (!u_.empty() && !(std::isfinite(u_[i]) && u_[i] >= 0.0))
      throw std::invalid_argument("Gaussian kernel: transmittance weight " + std::to_string(i) +
                                  " must be finite and >= 0");
    total_ += w_[i];
    if (!u_.empty()) total_transmit_ += u_[i];
  }
}

double GaussianSumProfile::reflectance(double r_mm) const { return sum_of(v_, w_, r_mm); }

double GaussianSumProfile::transmittance(double r_mm) const { return u_.empty() ? 0.0 : sum_of(v_, u_, r_mm); }

double GaussianSumProfile::support_radius() const {
  const double v_max = *std::max_element(v_.begin(), v_.end());
  return std::sqrt(2.0 * std::log(1e9) * v_max);
}

double GaussianSumProfile::inner_radius() const {
  return std::sqrt(*std::min_element(v_.begin(), v_.end()));
}

RgbProfile make_kernel_profile(const KernelFit& kernel, Model fitted_model) {
  const GaussianFit& f = kernel.fit;
  std::array<std::unique_ptr<RadialProfile>, 3> channels;
  for (int c = 0; c < 3; ++c) {
    std::vector<double> w, u;
    for (std::size_t i = 0; i < f.variances_mm2.size(); ++i) {
      w.push_back(f.weights[i][c]);
      if (kernel.transmittance) u.push_back(kernel.transmittance->weights[i][c]);
    }
    channels[c] = std::make_unique<GaussianSumProfile>(f.variances_mm2, std::move(w), std::move(u));
  }
  return RgbProfile(fitted_model, std::move(channels));
}

}  // namespace sss::profiles
