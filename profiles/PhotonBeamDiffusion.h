// Photon beam diffusion (Habel, Christensen and Jarosz 2013): the multiple-scattering
// profile is the better dipole integrated along the refracted beam, estimated with both
// exponential and equiangular sampling of the depth combined by multiple importance
// sampling (balance heuristic), plus the single-scattering term integrated along the
// beam. Deterministic stratified samples make R(r) smooth in r.
#pragma once

#include "profiles/BetterDipole.h"
#include "profiles/Profile.h"

#include <vector>

namespace sss::profiles {

// How the depth along the beam is sampled, for both the multiple- and the
// single-scattering integral: exponentially in depth, equiangularly about the exit point,
// or both combined with the balance heuristic (the default; see docs/PBD_CONVERGENCE.md).
enum class BeamSampling { Exponential, Equiangular, Mis };

class PhotonBeamDiffusion final : public RadialProfile {
 public:
  // `samples`: depth samples per strategy (MIS uses `samples` of each). Throws
  // std::invalid_argument for invalid coefficients or samples < 1.
  // single_scattering_apart (ModelOptions::single_scattering_apart): R(r) and its total
  // are the multiple-scattering term alone; the renderer adds single scattering apart.
  PhotonBeamDiffusion(const Coefficients& c, int samples,
                      BeamSampling sampling = BeamSampling::Mis,
                      bool single_scattering_apart = false);
  double reflectance(double r_mm) const override {
    return single_scattering_apart_ ? multiple_scattering(r_mm)
                                    : multiple_scattering(r_mm) + single_scattering(r_mm);
  }
  double multiple_scattering(double r_mm) const;
  double single_scattering(double r_mm) const;
  // Numerical: ∫2πr R dr over [0, support_radius] (computed once in the constructor), of
  // whatever reflectance() returns (without the single-scattering term when it is apart).
  double total_reflectance() const override { return total_; }
  double support_radius() const override;
  double inner_radius() const override;

  // The exact integrands the estimators sample, exposed so that tests and the convergence
  // study can integrate them by an independent quadrature (r > 0):
  //   multiple_scattering(r) ≈ ∫_0^∞ ms_integrand(r, z) dz,
  //   single_scattering(r)   ≈ ∫_0^∞ ss_integrand(r, t) dt (zero for t < critical_depth(r)).
  double ms_integrand(double r_mm, double z_mm) const;
  double ss_integrand(double r_mm, double t_mm) const;
  // The shallowest beam depth whose exit ray towards r is inside the critical cone.
  double critical_depth(double r_mm) const { return r_mm * tan_crit_; }
  // R is evaluated at max(r, min_radius()): the profile has an integrable singularity
  // at r = 0 (1/r from single scattering, log r from multiple scattering).
  double min_radius() const { return r_min_; }
  int samples() const { return samples_; }
  bool single_scattering_apart() const { return single_scattering_apart_; }
  BeamSampling sampling() const { return sampling_; }

 private:
  Coefficients c_;
  DipoleTerms terms_;
  int samples_;
  BeamSampling sampling_;
  bool single_scattering_apart_ = false;
  double total_ = 0.0;
  // Derived constants (see the .cpp for their sources).
  double sigma_t_, sigma_tp_, albedo_, alpha_p_, tan_crit_, theta_crit_, r_min_;
  // Stratified sample positions u_i = (i + 1/2)/N mapped once: exponential depths (in
  // units of the respective mean free path) and equiangular tangents.
  std::vector<double> exp_depth_;   // -ln(1 - u_i)
  std::vector<double> exp_weight_;  // 1 - u_i = e^{-exp_depth_i}
  std::vector<double> tan_ms_;      // tan(u_i π/2)
  std::vector<double> tan_ss_;      // tan(θc + u_i (π/2 - θc))
};

}  // namespace sss::profiles
