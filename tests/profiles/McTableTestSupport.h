// Statistics and radial-grid helpers shared by the mc-table tests
// (test_mc_table_data.cpp, test_mc_table_accuracy.cpp).
#pragma once

#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

namespace sss::profiles::test {

// The z with one-sided tail probability p: P(Z > z) = erfc(z/√2)/2 = p (bisection).
inline double z_one_sided(double p) {
  double lo = 0.0, hi = 40.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(mid / std::numbers::sqrt2) > p ? lo : hi) = mid;
  }
  return hi;
}

// The z for a two-sided test at family-wise false-failure probability p over n checks
// (Bonferroni: p/n per check, p/(2n) per tail). Valid however the checks are correlated.
inline double z_family(double p, std::size_t n) {
  return z_one_sided(p / (2.0 * static_cast<double>(n)));
}

// The upper p-quantile of χ²_k / k, by the Wilson–Hilferty cube-root normal approximation
// (Wilson & Hilferty 1931, PNAS 17:684): χ²_k/k ≈ (1 - 2/(9k) + z_p √(2/(9k)))³. For
// k >= 10 and p >= 1e-5 it lies within 1.2% above the exact quantile (checked against the
// inverted regularized gamma function: k = 16, p = 1.7e-5: 3.210 vs 3.179; k = 25,
// p = 1e-3: 2.109 vs 2.105), far less than the margins the tests use.
inline double chi2_over_k_quantile(double k, double p) {
  const double a = 2.0 / (9.0 * k), z = z_one_sided(p);
  return std::pow(1.0 - a + z * std::sqrt(a), 3);
}

// The table's annuli covering r in [lo, hi] mfp: from the last edge <= lo to the first
// edge >= hi (for [0.25, 8] with 16 annuli per decade: 0.237 .. 8.66, 25 annuli).
struct EdgeRange {
  std::size_t first = 0, last = 0;  // edge indices; annuli first .. last - 1
};
inline EdgeRange annuli_covering(const std::vector<double>& edges, double lo, double hi) {
  EdgeRange e;
  while (e.first + 1 < edges.size() && edges[e.first + 1] <= lo) ++e.first;
  e.last = e.first;
  while (e.last + 1 < edges.size() && edges[e.last] < hi) ++e.last;
  return e;
}

}  // namespace sss::profiles::test
