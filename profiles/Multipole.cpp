#include "profiles/Multipole.h"

#include "profiles/Fresnel.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace sss::profiles {

namespace {

// Normal flux at the plane z = 0 (z down) at distance r from the axis, from a pole of
// unit strength at signed depth z:  -∂/∂z [e^{-σρ}/ρ] = z (1 + σρ) e^{-σρ} / ρ³,
// ρ = √(r² + z²). A pole on the plane (z = 0) contributes nothing at r > 0, and by that
// limit nothing at r = 0 either (where the expression would be 0/0).
double pole_flux(double r, double z, double sigma) {
  if (z == 0.0) return 0.0;
  const double rho = std::sqrt(r * r + z * z);
  return z * (1.0 + sigma * rho) * std::exp(-sigma * rho) / (rho * rho * rho);
}

// ∫_0^∞ 2πr pole_flux(r, z) dr = 2π sgn(z) e^{-σ|z|}: the integrand is
// -2πz d/dr[e^{-σρ}/ρ] since dρ/dr = r/ρ, so the integral is 2πz e^{-σ|z|}/|z|.
double pole_total(double z, double sigma) {
  if (z == 0.0) return 0.0;
  return 2.0 * std::numbers::pi * std::copysign(std::exp(-sigma * std::fabs(z)), z);
}

}  // namespace

// Donner & Jensen 2005, §2.2 (eq. 8–11), for a slab 0 ≤ z ≤ d in air with the same
// boundary on both faces. The extrapolated boundaries lie at z = -z_b and z = d + z_b.
// Mirroring about the first maps z to -2z_b - z, about the second to 2(d + z_b) - z; their
// composition translates by 2(d + 2 z_b). Starting from the real source at ℓ = 1/σt' and
// its image -ℓ - 2z_b this gives, for i in [-n, n],
//     z_{+,i} = 2i(d + 2z_b) + ℓ,       z_{-,i} = 2i(d + 2z_b) - ℓ - 2z_b,
// and the fluence φ = (α'/4πD) Σ_i [e^{-σtr ρ+}/ρ+ - e^{-σtr ρ-}/ρ-] vanishes on both
// extrapolated planes (exactly for n → ∞). With the classical constants of Jensen et al.
// 2001 (D = 1/(3σt'), σtr = √(3σa σt'), z_b = 2AD, A = (1 + Fdr)/(1 - Fdr)) the i = 0 pair
// is the classical dipole.
Multipole::Multipole(const Coefficients& c, double thickness_mm, int pairs)
    : Multipole(c, thickness_mm, pairs, c.eta, c.eta) {}

// Different faces (Donner & Jensen 2005 §3 give each boundary of a layer its own A): the
// mirror about the lit face's extrapolated plane z = -z_b still maps ℓ to -ℓ - 2z_b, the
// one about the far face's plane z = d + z_b' maps z to 2(d + z_b') - z, and their
// composition translates by 2(d + z_b + z_b'): the same lattice with that period.
Multipole::Multipole(const Coefficients& c, double thickness_mm, int pairs, double eta_top,
                     double eta_bottom) {
  if (auto e = c.validate()) throw std::invalid_argument("Multipole: " + e->what());
  for (double eta : {eta_top, eta_bottom})
    if (!(eta >= kEtaMin && eta <= kEtaMax))
      throw std::invalid_argument("Multipole: a face's relative index must lie in [" +
                                  message_number(kEtaMin) + ", " + message_number(kEtaMax) +
                                  "], got " + message_number(eta));
  if (!std::isfinite(thickness_mm) || !(thickness_mm > 0.0))
    throw std::invalid_argument("Multipole: thickness must be a finite number > 0 mm, got " +
                                std::to_string(thickness_mm));
  if (pairs < 0 && pairs != kAutoPairs)
    throw std::invalid_argument("Multipole: pairs must be >= 0 (or kAutoPairs), got " +
                                std::to_string(pairs));
  alpha_p_ = c.albedo_reduced();
  sigma_tr_ = c.sigma_tr_classical();
  thickness_ = thickness_mm;
  const double sigma_tp = c.sigma_t_reduced();
  const double D = 1.0 / (3.0 * sigma_tp);
  const auto z_b = [D](double eta) {
    const double fdr = fresnel_diffuse_reflectance_fit(eta);
    return 2.0 * (1.0 + fdr) / (1.0 - fdr) * D;  // 2AD, A = (1 + Fdr)/(1 - Fdr)
  };
  ell_ = 1.0 / sigma_tp;
  z_b_ = z_b(eta_top);
  z_b_far_ = z_b(eta_bottom);
  period_ = 2.0 * (thickness_ + z_b_ + z_b_far_);
  // Pole i weighs about e^{-σtr |i| P} in the totals (and less in R(r)).
  n_ = pairs != kAutoPairs
           ? pairs
           : static_cast<int>(std::clamp(std::ceil(25.0 / (sigma_tr_ * period_)), 10.0, 1e6));
}

std::vector<double> Multipole::positive_poles() const {
  std::vector<double> z;
  for (int i = -n_; i <= n_; ++i) z.push_back(z_pos(i));
  return z;
}

std::vector<double> Multipole::negative_poles() const {
  std::vector<double> z;
  for (int i = -n_; i <= n_; ++i) z.push_back(z_neg(i));
  return z;
}

// R(r): the flux leaving through z = 0, whose outward normal is -z. By Fick's law
// J = -D∇φ that is J·(-ẑ) = D ∂φ/∂z at z = 0, and for a pole at depth z_s,
// ∂/∂z [e^{-σρ}/ρ] at z = 0 is z_s (1 + σρ) e^{-σρ}/ρ³ = pole_flux(r, z_s). So
//     R(r) = (α'/4π) Σ_i [pole_flux(r, z_{+,i}) - pole_flux(r, z_{-,i})].
double Multipole::reflectance(double r) const {
  double sum = 0.0;
  for (int i = -n_; i <= n_; ++i)
    sum += pole_flux(r, z_pos(i), sigma_tr_) - pole_flux(r, z_neg(i), sigma_tr_);
  return alpha_p_ / (4.0 * std::numbers::pi) * sum;
}

// T(r): the flux leaving through z = d (outward normal +z), -D ∂φ/∂z at z = d. There
// ∂/∂z [e^{-σρ}/ρ] = -(d - z_s)(1 + σρ) e^{-σρ}/ρ³ with ρ = √(r² + (d - z_s)²), so
//     (α'/4π) Σ_i [pole_flux(r, d - z_{+,i}) - pole_flux(r, d - z_{-,i})].
double Multipole::transmittance(double r) const {
  double sum = 0.0;
  for (int i = -n_; i <= n_; ++i)
    sum += pole_flux(r, thickness_ - z_pos(i), sigma_tr_) -
           pole_flux(r, thickness_ - z_neg(i), sigma_tr_);
  return alpha_p_ / (4.0 * std::numbers::pi) * sum;
}

double Multipole::total_reflectance() const {
  double sum = 0.0;
  for (int i = -n_; i <= n_; ++i)
    sum += pole_total(z_pos(i), sigma_tr_) - pole_total(z_neg(i), sigma_tr_);
  return alpha_p_ / (4.0 * std::numbers::pi) * sum;
}

double Multipole::total_transmittance() const {
  double sum = 0.0;
  for (int i = -n_; i <= n_; ++i)
    sum += pole_total(thickness_ - z_pos(i), sigma_tr_) -
           pole_total(thickness_ - z_neg(i), sigma_tr_);
  return alpha_p_ / (4.0 * std::numbers::pi) * sum;
}

double Multipole::support_radius() const {
  // As for the classical dipole: every pole decays as e^{-σtr ρ}/ρ² with ρ ≥ r, e^{-20}
  // ≈ 2e-9 of the scale at 20/σtr; the near field extends to the image depth ℓ + 2 z_b.
  return 20.0 / sigma_tr_ + 10.0 * (ell_ + 2.0 * std::max(z_b_, z_b_far_));
}

double Multipole::inner_radius() const { return std::min(ell_, thickness_); }

}  // namespace sss::profiles
