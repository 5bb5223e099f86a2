#include "profiles/EdgeResponse.h"

#include "profiles/Integrate.h"

#include <algorithm>
#include <cmath>

namespace sss::profiles {

double edge_response(const RadialProfile& profile, double x_mm) {
  const double total = profile.total_reflectance();
  if (x_mm == 0.0) return 0.5 * total;  // exact, and the profile may be singular at 0
  if (x_mm < 0.0) return total - edge_response(profile, -x_mm);
  const double x = x_mm;
  const double outer = profile.support_radius() - x;
  if (!(outer > 0.0)) return 0.0;
  // A circle of radius r about the point crosses the lit half-plane in an arc of angle
  // 2 acos(x/r). With r = x + s the arc is 2 atan2(√(s(2x + s)), x), which keeps its
  // precision as s → 0, where it behaves like √s: the geometric panels of
  // integrate_log, starting at 1e-6·min(x, inner radius), resolve that and the profile's
  // own structure on the scale of its inner radius.
  const auto integrand = [&](double s) {
    const double r = x + s;
    return profile.reflectance(r) * 2.0 * r * std::atan2(std::sqrt(s * (2.0 * x + s)), x);
  };
  const double inner = std::min(x, profile.inner_radius());
  return integrate_log(integrand, inner, outer, 8, 16);
}

Rgb edge_response(const RgbProfile& profile, double x_mm) {
  Rgb out{};
  for (int c = 0; c < 3; ++c) out[c] = edge_response(profile.channel(c), x_mm);
  return out;
}

Rgb edge_response(const GaussianFit& fit, double x_mm) {
  // The 1D marginal of G(v, ·) is the normal density of variance v, so the lit half-plane
  // contributes P(X > x) = ½ erfc(x / √(2v)).
  Rgb out{};
  for (std::size_t i = 0; i < fit.variances_mm2.size(); ++i) {
    const double m = 0.5 * std::erfc(x_mm / std::sqrt(2.0 * fit.variances_mm2[i]));
    for (int c = 0; c < 3; ++c) out[c] += fit.weights[i][c] * m;
  }
  return out;
}

}  // namespace sss::profiles
