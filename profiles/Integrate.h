// Deterministic quadrature shared by every model, the fit and the tests.
#pragma once

#include <functional>
#include <vector>

namespace sss::profiles {

struct GaussLegendreRule {
  std::vector<double> nodes;    // on [-1, 1], ascending
  std::vector<double> weights;
};

// The n-point Gauss–Legendre rule (Newton iteration on P_n; cached, thread-safe).
const GaussLegendreRule& gauss_legendre(int n);

// ∫_a^b f, composite Gauss–Legendre with `panels` equal panels of `order` points.
double integrate(const std::function<double(double)>& f, double a, double b, int panels = 16,
                 int order = 16);

// ∫_0^r_outer f(r) dr for functions with structure near 0 and long tails: one panel on
// [0, r_inner] then geometric panels (`per_decade` per factor of 10) up to r_outer.
double integrate_log(const std::function<double(double)>& f, double r_inner, double r_outer,
                     int per_decade = 6, int order = 16);

// ∫_0^r_outer 2π r R(r) dr with integrate_log.
double integrate_radial(const std::function<double(double)>& R, double r_inner,
                        double r_outer);

}  // namespace sss::profiles
