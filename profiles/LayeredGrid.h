// The Hankel-domain grid of the layered model, and the pieces of it that Layered.cpp,
// LayeredAdding.cpp and LayeredDiffusion.cpp share. Internal to profiles/.
//
// The transform. For a radially symmetric f(r) the 2-D Fourier transform is the Hankel
// transform of order 0, F(k) = 2π ∫0^∞ f(r) J0(kr) r dr, with inverse
// f(r) = (1/2π) ∫0^∞ F(k) J0(kr) k dk, and F(0) = ∫ 2πr f dr is the total. Convolution in
// the plane is a product of transforms.
//
// Sampling. Both f and F are sampled on one log-spaced grid x_j = 10^(-6 + j/128),
// j = 0..1280 (ten decades, 128 nodes a decade), in units of a length L of the stack
// (r = L x, k = x / L; L below). Between nodes the sampled function is taken to be linear
// in x² (and constant on the disc [0, x_0], zero beyond the last node). Then every piece
// integrates exactly against the Bessel kernel, however fast it oscillates:
//   ∫ x J0(yx) dx = x J1(yx)/y,      ∫ x³ J0(yx) dx = x³ J1(yx)/y - 2x² J2(yx)/y²
// (from d/dx[x^n J_n(x)] = x^n J_(n-1)(x)), so the transform is one fixed matrix M of
// node weights, the same for the forward and the inverse direction, computed once:
//   F(x_i / L) = 2π L² Σ_j M_ij f(L x_j),       f(L x_j) = 1/(2π L²) Σ_i M_ji F(x_i / L).
//
// Accuracy. Measured on the analytic pair pole_flux(r, z) <-> 2π e^{-z √(σ² + k²)}
// (Multipole.cpp; σ = 1/mm): the forward transform is within 2e-4 of F(0) everywhere; the
// inverse, over r in [0.25, 8] mm where the function falls by 10^5-10^7, within 0.02% RMS
// for z = 2 mm and 0.1% RMS (1.2% at worst, at 8 mm) for z = 0.3 mm. 32 nodes a decade
// were 200% off there: the resolution is what the dynamic range needs. Sampling error
// comes from where a function is not smooth on the grid, so the top medium's own profile
// (mc-table's 1/r, the dipoles' steep core) is kept exactly in r and only what the stack
// adds to it goes through the inverse: it has crossed the top layer twice, so its
// transform falls off at least like e^{-k d}, negligible long before the last frequency
// node (x = 10^4 / L with L <= d). T of a stack has crossed every layer. The inverse's
// interpolant in k leaves a weak oscillating tail in r: integrated, the profiles lose
// 0.2% (R) and 0.5% (T) of the diffusion solution's exact totals on a skin-like stack.
//
// L is the smallest length of the stack (the smallest reduced mean free path and the
// thinnest layer), raised if needed so that the largest support radius stays within
// 10^4 L: the grid then reaches from 10^-6 of the finest detail out to the widest support,
// and its lowest frequency, 10^-6 / L, is below 10^-2 / (widest support), where every
// transform is its total to 2.5e-5 relative (1 - J0(kr) <= (kr)²/4).
#pragma once

#include "profiles/ClassicalDipole.h"
#include "profiles/Layered.h"
#include "profiles/Multipole.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

namespace sss::profiles::layered {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
inline constexpr int kPerDecade = 128;
inline constexpr int kDecades = 10;
inline constexpr double kLogLo = -6.0;
inline constexpr int kNodes = kPerDecade * kDecades + 1;

inline double grid_x(int j) { return std::pow(10.0, kLogLo + static_cast<double>(j) / kPerDecade); }

// M_ij = ∫ (hat function of node j, linear in x²) J0(x_i x) x dx over the grid. The
// antiderivatives at node j for row i are
//   a1 = x_j J1(x_i x_j) / x_i,    a3 = x_j³ J1(x_i x_j) / x_i - 2 x_j² J2(x_i x_j) / x_i²,
// and x_i x_j = 10^(2 kLogLo + (i + j)/kPerDecade) depends on i + j alone: 2 kNodes - 1
// Bessel values build the whole matrix.
struct HankelMatrix {
  std::vector<double> x;
  std::vector<double> m;  // [i][j]
  HankelMatrix() : x(kNodes), m(static_cast<std::size_t>(kNodes) * kNodes, 0.0) {
    for (int j = 0; j < kNodes; ++j) x[j] = grid_x(j);
    std::vector<double> j1(2 * kNodes - 1), j2(2 * kNodes - 1);
    for (int k = 0; k < 2 * kNodes - 1; ++k) {
      const double u = std::pow(10.0, 2.0 * kLogLo + static_cast<double>(k) / kPerDecade);
      j1[k] = std::cyl_bessel_j(1.0, u);
      j2[k] = std::cyl_bessel_j(2.0, u);
    }
    for (int i = 0; i < kNodes; ++i) {
      const double y = x[i];
      double* row = m.data() + static_cast<std::size_t>(i) * kNodes;
      const auto a1 = [&](int j) { return x[j] * j1[i + j] / y; };
      const auto a3 = [&](int j) {
        return x[j] * x[j] * (x[j] * j1[i + j] / y - 2.0 * j2[i + j] / (y * y));
      };
      // The disc [0, x0] carries the value of node 0 (a1 vanishes at 0).
      double prev1 = a1(0), prev3 = a3(0);
      row[0] += prev1;
      for (int j = 0; j + 1 < kNodes; ++j) {
        const double xa = x[j], xb = x[j + 1];
        const double n1 = a1(j + 1), n3 = a3(j + 1);
        const double A = n1 - prev1, B = n3 - prev3;
        // f = α + β x² through (xa, fa), (xb, fb): fa A + (fb - fa) (B - xa² A) / (xb² - xa²).
        const double C = (B - xa * xa * A) / (xb * xb - xa * xa);
        row[j] += A - C;
        row[j + 1] += C;
        prev1 = n1, prev3 = n3;
      }
    }
  }
};

inline const HankelMatrix& hankel() {
  static const HankelMatrix h;
  return h;
}

// Σ_j M_ij v_j, times `scale`.
inline std::vector<double> apply(const std::vector<double>& v, double scale) {
  const auto& h = hankel();
  std::vector<double> out(kNodes, 0.0);
  for (int i = 0; i < kNodes; ++i) {
    const double* row = h.m.data() + static_cast<std::size_t>(i) * kNodes;
    double acc = 0.0;
    for (int j = 0; j < kNodes; ++j) acc += row[j] * v[j];
    out[i] = scale * acc;
  }
  return out;
}

// Samples f(L x_j) -> F(x_i / L).
inline std::vector<double> forward(const std::vector<double>& f, double L) {
  return apply(f, 2.0 * std::numbers::pi * L * L);
}
// F(x_i / L) -> f(L x_j).
inline std::vector<double> inverse(const std::vector<double>& F, double L) {
  return apply(F, 1.0 / (2.0 * std::numbers::pi * L * L));
}

// One finite layer's profiles (one channel): reflectance from above and from below, and
// transmittance. Reflectance is the base model's semi-infinite profile times the
// multipole's finite-thickness factor R_multipole / R_dipole (the multipole's i = 0 pair
// is the classical dipole with the same lit face): near the axis, where a layer thicker
// than a mean free path does not yet feel its far face, that is the semi-infinite model
// (mc-table: within 1-2% of Monte Carlo, where the classical dipole is off by 20-70%);
// far out, the light the far face lets through is missing as the multipole says. With
// base = dipole it is the multipole itself. Transmittance is the multipole's.
struct FiniteLayer {
  Multipole down, up;  // lit from above (faces top, bottom) and from below (swapped)
  ClassicalDipole dipole_down, dipole_up;
  std::unique_ptr<RadialProfile> semi_down, semi_up;
  bool pure = false;  // base = dipole: the multipole alone

  double corrected(const RadialProfile& semi, const ClassicalDipole& dip, const Multipole& mp,
                   double r) const {
    const double m = mp.reflectance(r);
    if (pure) return m;
    const double d = dip.reflectance(r);
    if (!(d > 0.0)) return 0.0;
    return semi.reflectance(r) * std::clamp(m / d, 0.0, 1.0);
  }
  double reflectance_down(double r) const { return corrected(*semi_down, dipole_down, down, r); }
  double reflectance_up(double r) const { return corrected(*semi_up, dipole_up, up, r); }
  // The layer's totals: closed forms for the pure multipole; otherwise ∫ 2πr R dr of the
  // corrected profile (its transform at the lowest frequency, set by LayeredProfile).
  double tot_down = 0.0, tot_up = 0.0;
  double total_down() const { return pure ? down.total_reflectance() : tot_down; }
  double total_up() const { return pure ? up.total_reflectance() : tot_up; }
};

inline Coefficients with_eta(Coefficients c, double eta) {
  c.eta = eta;
  return c;
}

inline std::string layer_field(std::size_t k, const std::string& field) {
  return "layers[" + std::to_string(k) + "]." + field;
}

// Linear interpolation of samples on the grid at r = L x, in log x; 0 beyond the last
// node, the first node's value on the disc.
inline double at_grid(const std::vector<double>& v, double L, double r) {
  const auto& x = hankel().x;
  const double t = r / L;
  if (!(t > x.front())) return v.front();
  if (t >= x.back()) return 0.0;
  const double u = (std::log10(t) - kLogLo) * kPerDecade;
  const int j = std::min(static_cast<int>(u), kNodes - 2);
  const double w = u - j;
  return v[j] + w * (v[j + 1] - v[j]);
}

// The sampled inverse transform's floor (LayeredTransform test: 1e-3 of the value plus
// 1e-7 of the peak): beyond where a decaying profile first falls under 1e-6 of its peak,
// what is left is the interpolant's weak oscillating tail, not light. Cut it there.
inline void cut_tail(std::vector<double>& v) {
  std::size_t peak = 0;
  for (std::size_t j = 1; j < v.size(); ++j)
    if (std::fabs(v[j]) > std::fabs(v[peak])) peak = j;
  const double floor = 1e-6 * std::fabs(v[peak]);
  for (std::size_t j = peak; j < v.size(); ++j)
    if (std::fabs(v[j]) < floor) {
      std::fill(v.begin() + static_cast<std::ptrdiff_t>(j), v.end(), 0.0);
      break;
    }
}

// ∫ 2πr f dr from 0 to `outer`: f(lo) on the disc [0, lo), lo = 10^-6 L, then the
// midpoint rule on 256 log steps a decade (relative step 0.9%: the rule's error is
// ~ (0.009)²/24 = 3e-6 of the integral where f is smooth).
template <class F>
inline double integrate_profile(F&& f, double L, double outer) {
  const double lo = 1e-6 * L;
  double sum = std::numbers::pi * lo * lo * f(0.0);
  const double q = std::pow(10.0, 1.0 / 256.0);
  for (double a = lo, b = lo * q; a < outer; a = b, b *= q) {
    const double m = 0.5 * (a + b);
    sum += 2.0 * std::numbers::pi * m * f(m) * (b - a);
  }
  return sum;
}

}  // namespace sss::profiles::layered
