// The exact diffusion profile of one material as the reference sums it: R averaged over
// the disc that one irradiance point stands for (area A, radius a = sqrt(A/π)),
//
//   K(d) = 1/(πa²) ∫_disc R(|d e_x + u|) du
//        = 1/(πa²) ∫_0^∞ R(s) 2s θ(s) ds,   θ(s) = the half-angle of the circle of radius
//          s about x_o that lies inside the disc: π for s ≤ a − d, 0 for s ≤ d − a or
//          s ≥ a + d, else acos((s² + d² − a²) / (2sd)).
//
// For d ≫ a, K(d) = R(d)(1 + O(a²/d²)); near d = 0 it integrates R's peak (and the 1/r
// singularity of PBD and Burley) instead of sampling it, so a point set of spacing s
// reproduces ∫ R dA without needing s ≪ the mean free path. Σ_i K(|x_o − x_i|) A over a
// plane of points tends to the total reflectance.
//
// Tabulated per channel at construction (the profile is evaluated once, not per pixel):
// log-spaced nodes in d with log-log interpolation, dense enough that the table agrees
// with the integral above to 1e-3 relative wherever K > 1e-6 K(0). Beyond the profile's
// support radius K is 0.
//
// Transmission (slabs): transmit(ρ) is the same disc average of the profile's
// transmittance T (RadialProfile::transmittance), ρ the lateral distance. It is 0 when
// the profile has no transmittance (semi-infinite models).
#pragma once

#include "profiles/Profile.h"

#include <glm/vec3.hpp>

#include <vector>

namespace sss::reference {

class ScatterKernel {
 public:
  // Throws std::invalid_argument for a point area that is not finite and > 0.
  ScatterKernel(const profiles::RgbProfile& profile, double point_area_mm2);

  glm::dvec3 reflect(double d_mm) const;     // K(d), mm^-2
  glm::dvec3 transmit(double rho_mm) const;  // disc-averaged T(ρ), mm^-2
  bool has_transmittance() const { return has_transmittance_; }
  double support_radius() const { return support_mm_; }
  double point_area() const { return point_area_mm2_; }

 private:
  struct Table {
    double log_d0 = 0.0, inv_step = 0.0;  // nodes at exp(log_d0 + i / inv_step)
    std::vector<glm::dvec3> log_value;    // log K per channel (-inf as a large negative)
    glm::dvec3 at_zero{0.0};              // K(d) for d below the first node
    glm::dvec3 eval(double d, double support) const;
  };
  Table reflect_, transmit_;
  bool has_transmittance_ = false;
  double support_mm_ = 0.0;
  double point_area_mm2_ = 0.0;
};

}  // namespace sss::reference
