#include "profiles/ClassicalDipole.h"

#include "profiles/Fresnel.h"

#include <cmath>
#include <numbers>

namespace sss::profiles {

// Jensen, Marschner, Levoy, Hanrahan 2001, "A practical model for subsurface light
// transport", eq. 4 and 5: the real source at z_r = 1/σt', the virtual one at
// z_v = z_r + 4AD, A = (1 + Fdr)/(1 - Fdr), D = 1/(3σt'), σtr = √(3σa σt').
ClassicalDipole::ClassicalDipole(const Coefficients& c)
    : alpha_p_(c.albedo_reduced()), sigma_tr_(c.sigma_tr_classical()) {
  const double sigma_tp = c.sigma_t_reduced();
  const double fdr = fresnel_diffuse_reflectance_fit(c.eta);
  const double A = (1.0 + fdr) / (1.0 - fdr);
  const double D = 1.0 / (3.0 * sigma_tp);
  zr_ = 1.0 / sigma_tp;
  zv_ = zr_ + 4.0 * A * D;
}

double ClassicalDipole::reflectance(double r) const {
  const double r2 = r * r;
  const double dr = std::sqrt(r2 + zr_ * zr_);
  const double dv = std::sqrt(r2 + zv_ * zv_);
  const double real = zr_ * (1.0 + sigma_tr_ * dr) * std::exp(-sigma_tr_ * dr) / (dr * dr * dr);
  const double virt = zv_ * (1.0 + sigma_tr_ * dv) * std::exp(-sigma_tr_ * dv) / (dv * dv * dv);
  return alpha_p_ / (4.0 * std::numbers::pi) * (real + virt);
}

double ClassicalDipole::total_reflectance() const {
  // ∫2πr z(1+σ d)e^{-σd}/d³ dr = 2π e^{-σ z} for each pole, so
  // Rd = (α'/2)(e^{-σtr z_r} + e^{-σtr z_v}) — Jensen's eq. 5 in another form.
  return 0.5 * alpha_p_ * (std::exp(-sigma_tr_ * zr_) + std::exp(-sigma_tr_ * zv_));
}

double ClassicalDipole::support_radius() const {
  // Far out R ~ e^{-σtr r}/r²; e^{-20} ≈ 2e-9 of the scale. z_v bounds the near field.
  return 20.0 / sigma_tr_ + 10.0 * zv_;
}

}  // namespace sss::profiles
