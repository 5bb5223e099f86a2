// Quantized diffusion (d'Eon & Irving 2011, "A quantized-diffusion model for rendering
// translucent materials", ACM TOG 30(4)): the time-resolved Green's function of the
// diffusion equation, G(r, τ) = e^{-σa τ} N₃(2Dτ; r) (τ = c t, a normalised 3-D Gaussian of
// variance 2Dτ per axis), is integrated over time in intervals [τ_i, τ_{i+1}], each
// replaced by one Gaussian of variance v_i = D(τ_i + τ_{i+1}) and weight
// w_i = ∫ e^{-σa τ} dτ over it. The source is the refracted beam's first scattering,
// α'σt' e^{-σt' z'} at depth z' (the reduced coefficients, as PBD's beam), with the
// negative image of the improved boundary condition d_e = 2 z_b = 4AD below it (A from the
// Fresnel moments, as the better dipole: DipoleTerms). Integrated over the beam in closed
// form per Gaussian, the profile is a sum of 2-D Gaussians in r:
//
//   R(r) = α' Σ_i w_i [Cφ Φ_i + CE D E_i] N₂(v_i; r),   N₂(v; r) = e^{-r²/2v} / (2π v),
//   f(v, d) = (α'σ/2) e^{-d²/2v} erfcx((d + σv)/√(2v)),        σ = σt',
//   g(v, d) = σ [α' e^{-d²/2v} / √(2πv) − f(v, d)],
//   Φ_i = f(v_i, 0) − f(v_i, d_e),   E_i = g(v_i, 0) + g(v_i, d_e)
//
// (the per-Gaussian integrals re-derived in ../shared/research/missing-models.md §1.3; α'
// twice, as PBD's multiple scattering, so QD and PBD share a normalisation). No single
// scattering: the beam's once-scattered light is not in this R(r).
//
// The time steps: τ_1 = v_1/D with v_1 a multiple (first_step_scale) of d'Eon & Irving's
// first variance v0 = 5·10^{6.11α² − 1.168α − 7.94} / σs² (unreduced α = σs/σt; the schedule
// of the one open implementation, research §1.2), then geometric, τ_{i+1} = ratio·τ_i,
// until σa τ reaches kTimeMass (the time mass left, e^{-45}, is below any double's
// resolution) or max_terms. Quantizing loses a little of the continuous model, whose total
// has a closed form (the extended beam source with the improved boundary): with v0 itself,
// the golden ratio and 45 terms (that implementation's choice) the totals are 1.3-2.3% low;
// the default, v0/100 and ratio 1.2 (~100 terms), is 0.2-0.3% low at α' = 0.5-0.99; ratio
// 1.01 and v0/10⁴ reach 0.006% (tests/profiles/test_quantized_diffusion.cpp).
#pragma once

#include "profiles/BetterDipole.h"
#include "profiles/Profile.h"

#include <vector>

namespace sss::profiles {

// exp(x²) erfc(x), the scaled complementary error function, for x >= 0 (x < 0 is refused:
// QD needs none). erfc alone underflows past x ≈ 26.5 and 1 - erf(x) cancels to nothing in
// float near x ≈ 4 (research §1.5); here exp(x²)·std::erfc(x) below x = 26 (glibc's erfc
// keeps its relative accuracy in the tail) and the asymptotic series beyond, whose first
// omitted term there is below 2e-15 relative. Throws std::invalid_argument for x < 0 or NaN.
double erfcx(double x);

struct QdSchedule {
  double ratio = 1.2;    // τ_{i+1} / τ_i after the first step, > 1
  int max_terms = 1024;  // a cap on the Gaussians (the stop is normally σa τ = kTimeMass)
  // 0: stop at σa τ >= kTimeMass; > 0: exactly this many Gaussians (tests reproduce the
  // published 45-term values).
  int fixed_terms = 0;
  // The first step's variance as a multiple of d'Eon & Irving's v0 (tests refine it to show
  // that the sum converges to the continuous model), > 0.
  double first_step_scale = 0.01;
};

class QuantizedDiffusion final : public RadialProfile {
 public:
  static constexpr double kTimeMass = 45.0;
  struct Term {
    double variance_mm2;  // v_i
    double coefficient;   // c_i: R(r) = Σ c_i N₂(v_i; r), and the total is Σ c_i
  };
  // Throws std::invalid_argument for invalid coefficients, σs = 0 (no beam to scatter) or a
  // schedule with ratio <= 1 or no terms.
  explicit QuantizedDiffusion(const Coefficients& c, const QdSchedule& schedule = {});
  double reflectance(double r_mm) const override;
  double total_reflectance() const override { return total_; }  // Σ c_i, exact for the sum
  double support_radius() const override;
  double inner_radius() const override { return 1.0 / sigma_tp_; }
  const std::vector<Term>& terms() const { return terms_; }

 private:
  DipoleTerms dipole_;
  double sigma_tp_;
  double total_ = 0.0;
  std::vector<Term> terms_;
  // Per term, what reflectance() evaluates: c_i / (2π v_i) and 1 / (2 v_i).
  std::vector<double> peak_, inv_two_var_;
};

}  // namespace sss::profiles
