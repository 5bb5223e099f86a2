// The directional albedo of the project's specular lobe (GGX D, Smith height-correlated
// visibility, Schlick's Fresnel weight Fc = (1 - v.h)^5) by a plain midpoint rule over the
// outgoing hemisphere in (theta_l, phi_l): no importance sampling and no code shared with
// scene::dfg_integrate, so the split-sum tests have an independent value.
//   A = integral f/F (1 - Fc) n.l dl,  B = integral f/F Fc n.l dl,  f/F = D vis.
// A uniform grid of n_theta x n_phi cells; phi over [0, pi], doubled (the lobe is
// symmetric about the plane of n and v).
#pragma once

#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>

namespace sss::testing {

inline glm::dvec2 ggx_albedo_quadrature(double n_dot_v, double roughness, int n_theta, int n_phi) {
  constexpr double kPi = 3.14159265358979323846;
  const double alpha = std::max(roughness * roughness, 1e-3), a2 = alpha * alpha;
  const double nv = n_dot_v, sv = std::sqrt(std::max(0.0, 1.0 - nv * nv));
  const double dt = 0.5 * kPi / n_theta, dp = kPi / n_phi;
  glm::dvec2 sum(0.0);
  for (int i = 0; i < n_theta; ++i) {
    const double t = (i + 0.5) * dt, nl = std::cos(t), sl = std::sin(t);
    for (int j = 0; j < n_phi; ++j) {
      const double p = (j + 0.5) * dp;
      // v = (sv, 0, nv), l = (sl cos p, sl sin p, nl), h = (v + l) / |v + l|
      const double hx = sv + sl * std::cos(p), hy = sl * std::sin(p), hz = nv + nl;
      const double hl = std::sqrt(hx * hx + hy * hy + hz * hz);
      const double nh = hz / hl, vh = (sv * hx + nv * hz) / hl;
      const double dd = nh * nh * (a2 - 1.0) + 1.0;
      const double d = a2 / (kPi * dd * dd);
      const double vis = 0.5 / (nl * std::sqrt(nv * nv * (1.0 - a2) + a2) + nv * std::sqrt(nl * nl * (1.0 - a2) + a2));
      const double fc = std::pow(1.0 - vh, 5.0);
      const double w = d * vis * nl * sl * dt * dp * 2.0;  // dl = sin t dt dp, both halves
      sum += glm::dvec2(w * (1.0 - fc), w * fc);
    }
  }
  return sum;
}

}  // namespace sss::testing
