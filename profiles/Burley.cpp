#include "profiles/Burley.h"

#include "profiles/BetterDipole.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace sss::profiles {

// The scale s(A) of Christensen & Burley 2015 (Pixar Technical Memo 15-04), eq. 5: the fit
// for perpendicular incidence (the "searchlight configuration") with the profile's width
// given by the mean free path ℓ, d = ℓ/s:
//     s = 1.85 - A + 7 |A - 0.8|³.
// Their Monte Carlo references were run with mean free path 1 and isotropic scattering
// (g = 0; Christensen, SIGGRAPH 2015 talk "An approximate reflectance profile for
// efficient subsurface scattering"), so ℓ = 1/σt = 1/σt'. The memo's two other fits are
// not used here: eq. 6, s = 1.9 - A + 3.5 (A - 0.8)², for diffuse surface transmission,
// and eq. 8, s = 3.5 + 100 (A - 0.33)⁴, with ℓ replaced by the diffuse mean free path.
double burley_scale(double A) {
  const double x = std::fabs(A - 0.8);
  return 1.85 - A + 7.0 * x * x * x;
}

namespace {

double checked_scale_length(double A, double mfp) {
  if (!std::isfinite(A) || !(A >= 0.0) || !(A <= 1.0))
    throw std::invalid_argument("Burley: surface albedo must lie in [0, 1], got " +
                                std::to_string(A));
  if (!std::isfinite(mfp) || !(mfp > 0.0))
    throw std::invalid_argument("Burley: mean free path must be > 0 mm, got " +
                                std::to_string(mfp));
  return mfp / burley_scale(A);
}

// From a medium: the surface albedo is the better dipole's total diffuse reflectance (the
// physically based model the fit is meant to stand in for, with the same η), and the mean
// free path is the reduced one, 1/σt': the references behind s(A) scattered isotropically,
// where 1/σt' = 1/σt, and by the similarity relation (Wyman et al. 1989) a medium with
// g ≠ 0 diffuses like an isotropic one with σs' = σs (1 - g).
double medium_albedo(const Coefficients& c) {
  if (auto e = c.validate()) throw std::invalid_argument("Burley: " + e->what());
  return BetterDipole(c).total_reflectance();
}

}  // namespace

Burley::Burley(const Coefficients& c)
    : A_(medium_albedo(c)), d_(checked_scale_length(A_, c.mfp_reduced())) {}

Burley::Burley(double albedo, double mfp_mm)
    : A_(albedo), d_(checked_scale_length(albedo, mfp_mm)) {}

// R(r) = A (e^{-r/d} + e^{-r/3d}) / (8π d r)  (Christensen & Burley 2015, eq. 2–3).
// ∫2πr R dr = A (d + 3d)/(4d) = A exactly, and 2πr R(r) = A(e^{-r/d} + e^{-r/3d})/(4d) is
// bounded, so the 1/r singularity is integrable. R is evaluated at max(r, ε), ε = 1e-9 d:
// the disc r < ε holds A ε/(2d) = 5e-10 A, of which the clamp misses half (2πr R(ε) is
// linear there), so no integral moves by more than 2.5e-10 A; R(0) = R(ε) ≈
// A/(4π ε d) ≈ 8e7 A/d² is finite.
double Burley::reflectance(double r) const {
  r = std::max(r, 1e-9 * d_);
  const double x = r / d_;
  return A_ * (std::exp(-x) + std::exp(-x / 3.0)) / (8.0 * std::numbers::pi * d_ * r);
}

double Burley::support_radius() const {
  // r R(r) ∝ e^{-r/3d} dominates the tail; past 70 d the lost fraction of A is
  // ¼e^{-70} + ¾e^{-70/3} ≈ 5e-11, and r R has fallen below 1e-10 of its scale.
  return 70.0 * d_;
}

}  // namespace sss::profiles
