#include "profiles/QuantizedDiffusion.h"

#include "profiles/Medium.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace sss::profiles {

double erfcx(double x) {
  if (!(x >= 0.0)) throw std::invalid_argument("erfcx: expected x >= 0, got " + message_number(x));
  if (x < 26.0) return std::exp(x * x) * std::erfc(x);
  // erfcx(x) ~ 1/(x√π) Σ_k (-1)^k (2k-1)!! / (2x²)^k (Abramowitz & Stegun 7.1.23); at
  // x >= 26 the term after k = 5 is 10395 / 1352^6 < 2e-15 of the sum.
  const double inv = 1.0 / (2.0 * x * x);
  double term = 1.0, sum = 1.0;
  for (int k = 1; k <= 5; ++k) {
    term *= -double(2 * k - 1) * inv;
    sum += term;
  }
  return sum / (x * std::sqrt(std::numbers::pi));
}

QuantizedDiffusion::QuantizedDiffusion(const Coefficients& c, const QdSchedule& schedule)
    : dipole_(DipoleTerms::make(c)), sigma_tp_(c.sigma_t_reduced()) {
  if (auto e = c.validate()) throw std::invalid_argument(e->what());
  if (!(c.sigma_s > 0.0))
    throw std::invalid_argument("sigma_s: quantized diffusion needs scattering (sigma_s > 0), got " +
                                message_number(c.sigma_s));
  if (!(schedule.ratio > 1.0) || !std::isfinite(schedule.ratio))
    throw std::invalid_argument("qd schedule: ratio must be a finite number > 1, got " +
                                message_number(schedule.ratio));
  if (schedule.max_terms < 1 || schedule.fixed_terms < 0)
    throw std::invalid_argument("qd schedule: max_terms must be >= 1 and fixed_terms >= 0");
  if (!(schedule.first_step_scale > 0.0) || !std::isfinite(schedule.first_step_scale))
    throw std::invalid_argument("qd schedule: first_step_scale must be a finite number > 0, got " +
                                message_number(schedule.first_step_scale));
  const double D = dipole_.D, sa = c.sigma_a, s = sigma_tp_;
  const double alpha_p = c.albedo_reduced();
  const double d_e = 2.0 * dipole_.z_e;  // the image's offset below the source, 4AD
  // f(v, d) and g(v, d): the beam α'σ e^{-σz'} integrated against N₁(v; z' + d) and
  // against (z' + d)/v N₁ (header). erfcx's argument is >= 0 since d >= 0.
  const auto f = [&](double v, double d) {
    return 0.5 * alpha_p * s * std::exp(-d * d / (2.0 * v)) * erfcx((d + s * v) / std::sqrt(2.0 * v));
  };
  const auto g = [&](double v, double d) {
    return s * (alpha_p * std::exp(-d * d / (2.0 * v)) / std::sqrt(2.0 * std::numbers::pi * v) - f(v, d));
  };
  // The first step (d'Eon & Irving's v0, on the unreduced albedo and σs), then geometric.
  const double a = c.albedo();
  const double v0 = schedule.first_step_scale * 5.0 * std::pow(10.0, 6.11 * a * a - 1.168 * a - 7.94) /
                    (c.sigma_s * c.sigma_s);
  double t0 = 0.0, t1 = v0 / D;
  const int cap = schedule.fixed_terms > 0 ? schedule.fixed_terms : schedule.max_terms;
  for (int i = 0; i < cap; ++i) {
    // w_i = ∫ e^{-σa τ} dτ over [t0, t1], written to keep its digits when σa t is small.
    const double w = std::exp(-sa * t0) * -std::expm1(-sa * (t1 - t0)) / sa;
    const double v = D * (t0 + t1);
    const double phi = f(v, 0.0) - f(v, d_e);
    const double flux = g(v, 0.0) + g(v, d_e);
    const double coefficient = alpha_p * w * (dipole_.c_phi * phi + dipole_.c_e * D * flux);
    terms_.push_back({v, coefficient});
    peak_.push_back(coefficient / (2.0 * std::numbers::pi * v));
    inv_two_var_.push_back(1.0 / (2.0 * v));
    total_ += coefficient;
    if (schedule.fixed_terms == 0 && sa * t1 >= kTimeMass) break;
    t0 = t1;
    t1 *= schedule.ratio;
  }
}

double QuantizedDiffusion::reflectance(double r) const {
  const double r2 = r * r;
  double sum = 0.0;
  for (std::size_t i = 0; i < peak_.size(); ++i) sum += peak_[i] * std::exp(-r2 * inv_two_var_[i]);
  return sum;
}

double QuantizedDiffusion::support_radius() const {
  // As the better dipole's: the profile falls as e^{-σtr r} beyond the source depths. The
  // widest Gaussian (σa v ≈ 2 D kTimeMass) reaches √(90 D/σa) ≈ 9.5/σtr: within it.
  return 20.0 / dipole_.sigma_tr + 10.0 * (1.0 / sigma_tp_ + 2.0 * dipole_.z_e);
}

}  // namespace sss::profiles
