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
// Tabulated per channel at construction (the profile is evaluated once, not per pixel).
// Quadrature (ScatterKernel.cpp): the θ = π part is a cumulative ∫ 2πs R ds over
// geometric panels; the band |a − d| < s < a + d is integrated in u, s = c − h cos u
// (c, h the band's centre and half-width), which absorbs θ's square-root ends, on
// Gauss–Legendre panels between geometric break points (R's own scales, and the scale
// |a − d| near the kink d = a). PBD's and the multipole's R and T (~4 µs and ~1 µs a
// call) are first tabulated on 64 nodes per decade (cubic in log-log, ~1e-6).
// Table: K has a kink at d = a, where the disc's rim crosses x_o (for profiles with a
// 1/r peak, PBD and Burley, K' is logarithmically singular there). So the table is in
// y = |d/a − 1|, one part inside the rim and one outside, each with cells uniform
// within every octave of y, 16 per octave (edges 2^e (1 + k/16), found from the bits of
// y without a logarithm): log-spaced towards the kink from both sides and log-spaced in
// d far from it. Each cell holds the cubic through K at t = 0, 1/3, 2/3, 1; closer than
// 2^-20 a to the kink K is K(a). The table agrees with the integral above to 1e-3
// relative wherever K > 1e-6 K(0) (measured: 2e-5 against an independent polar
// integral, tests/reference/test_scatter_kernel.cpp); about 800 cells (50 KB) a table
// (its cost: reference/README.md, "Performance").
// R is taken as 0 beyond the profile's support radius S, so K is exactly 0 beyond
// support_radius() = S + a.
//
// Transmission (slabs): transmit(ρ) is the same disc average of the profile's
// transmittance T (RadialProfile::transmittance), ρ the lateral distance. It is 0 when
// the profile has no transmittance (semi-infinite models): has_transmittance() is true
// when some channel's total transmittance is > 0.
#pragma once

#include "profiles/Profile.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace sss::reference {

class ScatterKernel {
 public:
  // Throws std::invalid_argument for a point area that is not finite and > 0.
  // far_side_dark: points on the far side (n_i · n_o < 0) contribute nothing, whatever the
  // profile (transmit() is 0 and has_transmittance() true, so that the octree keeps the
  // sides apart): the real-time renderers' view, which blurs only the surface it sees and
  // brings light through thin parts by a local term instead (Transmission::Local/Off).
  ScatterKernel(const profiles::RgbProfile& profile, double point_area_mm2, bool far_side_dark = false);

  glm::dvec3 reflect(double d_mm) const;     // K(d), mm^-2
  glm::dvec3 transmit(double rho_mm) const;  // disc-averaged T(ρ), mm^-2
  // K with its first and second derivatives in d (mm^-3, mm^-4), from the same cubic
  // cells (so only as smooth as the table: derivatives good to ~1e-2 relative), for
  // the octree's second-order estimate of a node. Zero derivatives closer than 2^-20 a
  // to the kink at d = a, and beyond the support.
  struct Jet {
    glm::dvec3 value{0.0}, first{0.0}, second{0.0};
  };
  Jet reflect_jet(double d_mm) const;
  Jet transmit_jet(double rho_mm) const;
  bool has_transmittance() const { return has_transmittance_; }
  bool far_side_dark() const { return far_side_dark_; }
  double support_radius() const { return support_mm_; }
  // The near field of the octree's ratio estimate (PointOctree.h): points closer than
  // near_radius() = kNearSpacings · √A (4: about 50 points), and ∫_0^ρ 2πd K(d) dd over that disc, what the
  // near points' Σ K A would be for a perfectly even point density on a flat surface.
  static constexpr double kNearSpacings = 4.0;
  double near_radius() const { return near_radius_; }
  const glm::dvec3& near_integral() const { return near_integral_; }
  double point_area() const { return point_area_mm2_; }

 private:
  // Cubic per cell; coefficients c0..c3 for R, G, B, padded to one 64-byte line.
  struct Table {
    double inv_a = 1.0;                // 1/a: cells are in y = |d/a − 1|
    double end = 0.0;                  // (S + a)/a: K = 0 from there on
    std::uint64_t base = 0;            // key of the first cell edge, y = 2^-20
    std::uint32_t inner_cells = 0;     // cells of y = 1 − d/a; then those of d/a − 1
    std::vector<float> coef;           // 16 per cell: c_k of channel c at [4k + c]
    glm::dvec3 at_kink{0.0};           // K(a), for |d/a − 1| < 2^-20
    glm::dvec3 eval(double d) const;
    Jet jet(double d) const;
  };
  static Table build_table(const profiles::RgbProfile& profile, bool transmit, double a,
                           double support_mm);
  glm::dvec3 near_disc_integral(double a) const;
  Table reflect_, transmit_;
  bool has_transmittance_ = false;
  bool far_side_dark_ = false;
  double support_mm_ = 0.0;
  double near_radius_ = 0.0;
  glm::dvec3 near_integral_{0.0};
  double point_area_mm2_ = 0.0;
};

}  // namespace sss::reference
