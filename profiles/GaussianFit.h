// Sum-of-Gaussians fit of an RGB diffusion profile (DESIGN.md §3):
//   R_c(r) ≈ Σ_i w_ic G(v_i, r),   G(v, r) = exp(-r²/2v) / (2πv)   (unit integral in 2D)
// with variances v_i shared by R, G and B and weights w_ic >= 0 per channel, so one blur
// per Gaussian serves all three channels. Σ_i w_ic equals the profile's total reflectance
// exactly (energy is preserved). The error is the relative L2 error of r·R(r) with the
// linear measure dr:  e_c = ‖r(R_c - R̃_c)‖₂ / ‖r R_c‖₂.
//
// Optimiser: variable projection (Golub & Pereyra 1973). For fixed variances the weights
// are a non-negative least-squares problem (Lawson–Hanson) with the energy equality;
// Levenberg–Marquardt moves the log-variances.
#pragma once

#include "profiles/Medium.h"
#include "profiles/Profile.h"

#include <string>
#include <vector>

namespace sss::profiles {

inline constexpr int kMinGaussians = 1;
inline constexpr int kMaxGaussians = 8;  // = SSS_MAX_GAUSSIANS (tests/vk/ShaderConfigTest.cpp)
inline constexpr int kDefaultGaussians = 6;

// The one range check of a Gaussian count, wherever one comes in (the fit, glTF extras,
// the CLIs' options and material specs, the editor): an integer in [kMinGaussians,
// kMaxGaussians]. The rule reads "must be an integer in [1, 8]"; callers add ", got X"
// as their input shows it.
bool valid_gaussian_count(double n);
std::string gaussian_count_rule();

// G(v, r) above.
double gaussian_2d(double variance_mm2, double r_mm);

// Samples of the profile to fit: radii (ascending, log-spaced), R at each, quadrature
// weights for ∫ · dr, and the totals that the weights must sum to.
struct FitTarget {
  std::vector<double> r_mm;
  std::vector<Rgb> R;
  std::vector<double> dr;  // quadrature weight of each sample for ∫ f(r) dr
  Rgb total_reflectance{};
  // The fit's resolution: R holds the profile blurred by G(v, ·) with this variance (0:
  // the profile itself). fit_gaussians fits the blurred samples and then takes v off every
  // variance, so the kernel it returns, blurred by the same G(v, ·), matches the blurred
  // profile to its relative_error (a blur of Gaussians adds variances).
  double prefilter_variance_mm2 = 0.0;
};

// The default resolution of a fit, as a fraction of the RgbProfile's inner_radius() (the
// smallest over its channels; for mc-table and the dipoles one reduced mean free path
// 1/σt', for Burley d = ℓ/s, for the tabulated mc its first node): 0.25 for mc-table and for
// layered (near the axis it is the top medium's mc-table profile), 0 (the profile itself)
// for the others. mc-table's R(r) has the true 1/r peak of single
// scattering at the source, which no finite sum of Gaussians follows (the L2 error of r·R
// is then dominated by radii below 0.02 mean free paths, which hold under 1% of the
// energy); 0.25 mean free paths is where `sss-fit validate` starts comparing profiles
// with Monte Carlo. docs/PROFILES.md has the measurements.
double default_fit_resolution(Model model);

// Samples `profile` on a log grid from 1e-3·inner_radius to support_radius. dr holds the
// trapezoid weights in ln r times r (∫ f dr = ∫ f r d ln r). With a resolution ρ > 0
// (a fraction of inner_radius(); < 0: default_fit_resolution(profile.model())) the samples
// are of R blurred by a 2D Gaussian of standard deviation ρ·inner_radius (the radial
// convolution ∫ R(s) (s/v) exp(-(r-s)²/2v) e^{-rs/v} I0(rs/v) ds, Gauss–Legendre on
// panels). Throws std::invalid_argument for samples < 2.
FitTarget make_fit_target(const RgbProfile& profile, int samples = 96,
                          double resolution = -1.0);

struct GaussianFit {
  std::vector<double> variances_mm2;  // ascending
  std::vector<Rgb> weights;           // one RGB weight per variance, each >= 0
  Rgb total_reflectance{};            // Σ_i weights[i] per channel (== the profile's)
  Rgb relative_error{};               // e_c above, on the target's samples (blurred ones
                                      // when the target has a prefilter variance)
  double prefilter_variance_mm2 = 0.0;  // the target's (see FitTarget)
  int iterations = 0;                 // Levenberg–Marquardt iterations, all starts summed

  Rgb evaluate(double r_mm) const;
};

struct FitOptions {
  int gaussians = 6;  // 1 .. kMaxGaussians
  // Cap on each Levenberg–Marquardt run: the final one from the best start, and each
  // re-seeding; the three starts are probed with min(5, max_iterations) each.
  int max_iterations = 60;
};

// For fixed variances each channel's weights solve min Σ_j dr_j r_j²(R_j − R̃_j)² with
// w >= 0 and Σw = total: NNLS on the system augmented by a heavily weighted row Σw = total,
// then a rescale that makes the sum exact to rounding (|Σw − total| <= 1e-15·total; the
// rescale changes each weight by the row's residual, measured below 5e-9 relative on the
// dipole presets). The outer
// Levenberg–Marquardt minimises Σ_c e_c² over the log-variances with the exact
// variable-projection Jacobian, from three starting spreads placed by the radii that
// hold a fraction of the target's energy, and re-seeds Gaussians whose weights vanish
// in every channel.
// Throws std::invalid_argument for a gaussian count outside [1, kMaxGaussians] or an
// empty/invalid target (sizes differ, fewer samples than gaussians + 1, radii not
// positive and ascending, non-finite values, negative totals).
GaussianFit fit_gaussians(const FitTarget& target, const FitOptions& opt = {});

}  // namespace sss::profiles
