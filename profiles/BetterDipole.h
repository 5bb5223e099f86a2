// The better dipole of d'Eon 2012 ("A better dipole"): Grosjean's diffusion coefficient
// D = (2σa + σs')/(3σt'²), the extrapolation distance 2AD with A = (1+3m2)/(1-2m1) from
// the Fresnel moments, and the exitant flux R = Cφ φ + CE E with Cφ = (1-2m1)/4,
// CE = (1-3m2)/2.
#pragma once

#include "profiles/Profile.h"

namespace sss::profiles {

// The dipole's response at the surface, shared by the better dipole and PBD: the
// exitant flux at distance r from the axis for a unit-power isotropic point source at
// depth z_r, with the negative image at z_v (< 0), both seen from the surface z = 0.
struct DipoleTerms {
  double D, sigma_tr, c_phi, c_e, z_e;  // z_e: extrapolation distance 2AD
  // Cφ φ(r) + CE E(r) for a unit source at depth z_r (its image is at -z_r - 2 z_e).
  double flux(double r, double z_r) const;
  static DipoleTerms make(const Coefficients& c);
};

class BetterDipole final : public RadialProfile {
 public:
  explicit BetterDipole(const Coefficients& c);
  double reflectance(double r_mm) const override;
  // Closed form: α'[Cφ (e^{-σtr zr} - e^{-σtr|zv|})/(2Dσtr) + CE (e^{-σtr zr} + e^{-σtr|zv|})/2].
  double total_reflectance() const override;
  double support_radius() const override;
  double inner_radius() const override { return zr_; }

 private:
  DipoleTerms terms_;
  double alpha_p_, zr_;
};

}  // namespace sss::profiles
