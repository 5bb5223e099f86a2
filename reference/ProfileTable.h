// One channel's R(r) (or T(r)) as the CPU reference reads it: the profile itself, or, for
// the models whose profile is costly to evaluate, a table. Shared by the disc-averaged
// kernel of the point-octree reference (ScatterKernel.h) and the per-pixel profile
// sampling of the probe reference (ProbeReference.h), so both integrate the same R.
#pragma once

#include "profiles/Profile.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace sss::reference {

// R (or T) as the quadrature sees it: the profile itself, or for the costly models
// (photon beam diffusion: ~4 µs a call) a cubic interpolant of ln R in ln r on 64 nodes
// per decade from 1e-7 min(ℓ, a) to the support, Lagrange through the 4 nearest nodes.
// ln R of a diffusion profile is smooth in ln r, with derivatives of the order of σr,
// so the interpolation error is ~(ln 10/64)^4 σr/24 ~ 1e-6 (measured through the
// kernel: its PBD and multipole tables match the polar integral of the profile itself
// to 2e-5, as those of the directly evaluated models do). Nodes at or below 0 (the
// multipole's T near the axis of a thin slab) fall back to linear interpolation in R;
// below the first node the profile is evaluated directly.
class ProfileTable {
 public:
  ProfileTable(const profiles::RadialProfile& p, bool transmit, bool interpolate, double r0,
                 double support)
      : p_(p), transmit_(transmit) {
    if (!interpolate) return;
    log_r0_ = std::log(r0);
    inv_step_ = kNodesPerDecade / std::log(10.0);
    const int n = int(std::ceil(std::log(support / r0) * inv_step_)) + 4;
    for (int k = -1; k <= n; ++k) {
      const double v = direct(std::exp(log_r0_ + k / inv_step_));
      value_.push_back(v);
      log_value_.push_back(v > 0.0 ? std::log(v) : -std::numeric_limits<double>::infinity());
    }
  }
  double operator()(double r) const {
    if (value_.empty()) return direct(r);
    const double x = (std::log(std::max(r, 1e-300)) - log_r0_) * inv_step_;
    // Nodes k - 1 .. k + 2 around x (node j at index j + 1).
    const double k = std::clamp(std::floor(x), 0.0, double(value_.size() - 4));
    const double t = x - k;
    const std::size_t i = std::size_t(k);
    const double* lv = &log_value_[i];
    if (std::isfinite(lv[0]) && std::isfinite(lv[1]) && std::isfinite(lv[2]) &&
        std::isfinite(lv[3]) && t >= 0.0 && t <= 1.0) {
      // Lagrange weights at nodes -1, 0, 1, 2 for t in [0, 1].
      const double w0 = -t * (t - 1.0) * (t - 2.0) / 6.0, w1 = (t + 1.0) * (t - 1.0) * (t - 2.0) / 2.0;
      const double w2 = -(t + 1.0) * t * (t - 2.0) / 2.0, w3 = (t + 1.0) * t * (t - 1.0) / 6.0;
      return std::exp(w0 * lv[0] + w1 * lv[1] + w2 * lv[2] + w3 * lv[3]);
    }
    if (t < 0.0 || t > 1.0) return direct(r);  // outside the nodes
    return value_[i + 1] + t * (value_[i + 2] - value_[i + 1]);
  }

 private:
  static constexpr double kNodesPerDecade = 64.0;
  double direct(double r) const { return transmit_ ? p_.transmittance(r) : p_.reflectance(r); }
  const profiles::RadialProfile& p_;
  bool transmit_;
  double log_r0_ = 0.0, inv_step_ = 0.0;
  std::vector<double> value_, log_value_;
};

}  // namespace sss::reference
