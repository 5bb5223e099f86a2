// Burley's normalized diffusion (Christensen & Burley 2015, "Approximate reflectance
// profiles for efficient subsurface scattering"): R(r) = A s (e^{-sr/ℓ} + e^{-sr/3ℓ})/(8πℓr),
// whose integral is exactly A, with the scale s(A) of their searchlight fit.
#pragma once

#include "profiles/Profile.h"

namespace sss::profiles {

// s(A) = 1.85 - A + 7|A - 0.8|³ (Christensen & Burley 2015, eq. 5: perpendicular
// incidence, width measured in mean free paths ℓ); d = ℓ/s.
double burley_scale(double surface_albedo);

class Burley final : public RadialProfile {
 public:
  // From a medium: A is the medium's total diffuse reflectance (taken from the better
  // dipole's closed form) and ℓ its mean free path; see Burley.cpp for the choice.
  explicit Burley(const Coefficients& c);
  // Directly from the surface albedo A in [0, 1] and the mean free path ℓ (mm).
  // Throws std::invalid_argument outside those ranges.
  Burley(double albedo, double mfp_mm);
  // R(r) in mm^-2; r is clamped to 1e-9 d (the 1/r singularity is integrable).
  double reflectance(double r_mm) const override;
  double total_reflectance() const override { return A_; }
  double support_radius() const override;
  double inner_radius() const override { return d_; }
  double scale_d() const { return d_; }  // d = ℓ / s

 private:
  double A_, d_;
};

}  // namespace sss::profiles
