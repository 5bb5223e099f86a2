#include "profiles/Integrate.h"

#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>
#include <stdexcept>

namespace sss::profiles {

namespace {

// Nodes are the roots of the Legendre polynomial P_n, found by Newton's method from the
// Tricomi initial guess cos(π(i - 1/4)/(n + 1/2)); weights 2/((1 - x²) P_n'(x)²)
// (Abramowitz & Stegun 25.4.29).
GaussLegendreRule build_rule(int n) {
  GaussLegendreRule rule;
  rule.nodes.resize(n);
  rule.weights.resize(n);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 0.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      const double pn = (n == 1) ? x : p1;
      const double pn1 = (n == 1) ? 1.0 : p0;
      dp = n * (x * pn - pn1) / (x * x - 1.0);
      const double dx = pn / dp;
      x -= dx;
      if (std::fabs(dx) < 1e-16) break;
    }
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);
    rule.nodes[i] = -x;
    rule.nodes[n - 1 - i] = x;
    rule.weights[i] = w;
    rule.weights[n - 1 - i] = w;
  }
  if (n == 1) {
    rule.nodes[0] = 0.0;
    rule.weights[0] = 2.0;
  }
  return rule;
}

}  // namespace

const GaussLegendreRule& gauss_legendre(int n) {
  if (n < 1 || n > 512) throw std::invalid_argument("gauss_legendre: order must be in [1, 512]");
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<GaussLegendreRule>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[n];
  if (!slot) slot = std::make_unique<GaussLegendreRule>(build_rule(n));
  return *slot;
}

double integrate(const std::function<double(double)>& f, double a, double b, int panels,
                 int order) {
  const GaussLegendreRule& rule = gauss_legendre(order);
  const double h = (b - a) / panels;
  double sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    const double mid = a + (p + 0.5) * h;
    double s = 0.0;
    for (int k = 0; k < order; ++k) s += rule.weights[k] * f(mid + 0.5 * h * rule.nodes[k]);
    sum += 0.5 * h * s;
  }
  return sum;
}

double integrate_log(const std::function<double(double)>& f, double r_inner, double r_outer,
                     int per_decade, int order) {
  if (!(r_inner > 0.0) || !(r_outer > r_inner))
    return r_outer > 0.0 ? integrate(f, 0.0, r_outer, 8, order) : 0.0;
  // [0, r_inner] is itself split geometrically down to 1e-6 r_inner: profiles with an
  // integrable 1/r singularity (PBD single scattering, Burley) keep their accuracy.
  const double inner_floor = r_inner * 1e-6;
  double sum = integrate(f, 0.0, inner_floor, 1, order);
  const double ratio = std::pow(10.0, 1.0 / per_decade);
  double a = inner_floor;
  while (a < r_outer) {
    const double b = std::min(a * ratio, r_outer);
    sum += integrate(f, a, b, 1, order);
    a = b;
  }
  return sum;
}

double integrate_radial(const std::function<double(double)>& R, double r_inner,
                        double r_outer) {
  return integrate_log([&](double r) { return 2.0 * std::numbers::pi * r * R(r); }, r_inner,
                       r_outer);
}

}  // namespace sss::profiles
