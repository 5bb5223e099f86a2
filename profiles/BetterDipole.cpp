#include "profiles/BetterDipole.h"

#include "profiles/Fresnel.h"

#include <cmath>
#include <numbers>

namespace sss::profiles {

// d'Eon 2012, "A better dipole": Grosjean's D, the boundary constant from the Fresnel
// moments (here the published fits, tested against numerical integration), and the
// exitant flux Cφ φ + CE E (also Habel et al. 2013, eq. 5–7).
DipoleTerms DipoleTerms::make(const Coefficients& c) {
  DipoleTerms t{};
  const double sigma_tp = c.sigma_t_reduced();
  t.D = (2.0 * c.sigma_a + c.sigma_s_reduced()) / (3.0 * sigma_tp * sigma_tp);
  t.sigma_tr = std::sqrt(c.sigma_a / t.D);
  const double m1 = fresnel_moment1_fit(c.eta);
  const double m2 = fresnel_moment2_fit(c.eta);
  const double A = (1.0 + 3.0 * m2) / (1.0 - 2.0 * m1);
  t.z_e = 2.0 * A * t.D;
  t.c_phi = 0.25 * (1.0 - 2.0 * m1);
  t.c_e = 0.5 * (1.0 - 3.0 * m2);
  return t;
}

double DipoleTerms::flux(double r, double z_r) const {
  // Unit-power source at depth z_r; negative image mirrored about z = -z_e.
  const double z_v = -z_r - 2.0 * z_e;
  const double r2 = r * r;
  const double dr = std::sqrt(r2 + z_r * z_r);
  const double dv = std::sqrt(r2 + z_v * z_v);
  const double er = std::exp(-sigma_tr * dr);
  const double ev = std::exp(-sigma_tr * dv);
  const double inv4pi = 0.25 / std::numbers::pi;
  // Fluence φ and normal flux E = -D ∂φ/∂z·n at z = 0.
  const double phi = inv4pi / D * (er / dr - ev / dv);
  const double E = inv4pi * (z_r * (1.0 + sigma_tr * dr) * er / (dr * dr * dr) -
                             z_v * (1.0 + sigma_tr * dv) * ev / (dv * dv * dv));
  return c_phi * phi + c_e * E;
}

BetterDipole::BetterDipole(const Coefficients& c)
    : terms_(DipoleTerms::make(c)), alpha_p_(c.albedo_reduced()), zr_(1.0 / c.sigma_t_reduced()) {}

double BetterDipole::reflectance(double r) const { return alpha_p_ * terms_.flux(r, zr_); }

double BetterDipole::total_reflectance() const {
  // ∫2πr e^{-σd}/d dr = 2π e^{-σ z}/σ and ∫2πr z(1+σd)e^{-σd}/d³ dr = 2π e^{-σz}.
  const double s = terms_.sigma_tr;
  const double zv = zr_ + 2.0 * terms_.z_e;  // |z_v|
  const double er = std::exp(-s * zr_), ev = std::exp(-s * zv);
  const double phi_total = (er - ev) / (2.0 * terms_.D * s);
  const double e_total = 0.5 * (er + ev);
  return alpha_p_ * (terms_.c_phi * phi_total + terms_.c_e * e_total);
}

double BetterDipole::support_radius() const {
  return 20.0 / terms_.sigma_tr + 10.0 * (zr_ + 2.0 * terms_.z_e);
}

}  // namespace sss::profiles
