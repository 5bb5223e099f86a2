// The multipole of Donner & Jensen 2005 ("Light diffusion in multi-layered translucent
// materials") for one slab of thickness d in air: dipole pairs mirrored about both
// extrapolated boundaries, giving reflectance and transmittance profiles. With the
// classical dipole's source depth and boundary constant, so a thick slab becomes the
// classical dipole.
//
// Limits of the model (measured in tests/profiles/test_multipole.cpp):
// - For d < ℓ = 1/σt' the real source lies below the slab: T(r) turns negative near the
//   axis (total T ≈ -0.3 at d = 0.5 mfp). At d = ℓ it sits on the far face and adds
//   nothing to T. Results are meaningful for d > ℓ.
// - The pole series converges like e^{-σtr P |i|}, P = 2(d + 2 z_b). For bright thin slabs
//   (σtr P ≲ 1, e.g. α' = 0.999, d = 0.5 mfp: 0.43) ten pairs miss R by 7e-4 relative at
//   3 mfp and get the tail beyond 10 mfp wrong by orders of magnitude (there R has fallen
//   below 1e-5 of R(0)). As α' → 1 the truncated totals even tend to R → α', T → 0,
//   whereas the series tends to R = α'(d + z_b - ℓ)/(d + 2z_b): kAutoPairs sizes n
//   from σtr P instead.
#pragma once

#include "profiles/Profile.h"

#include <vector>

namespace sss::profiles {

class Multipole final : public RadialProfile {
 public:
  // `pairs` = n: the poles i in [-n, n]. kAutoPairs picks n = max(10, ⌈25/(σtr P)⌉),
  // capped at 10⁶, so that the omitted poles weigh ≲ e^{-25}. Throws
  // std::invalid_argument for invalid coefficients, a thickness that is not a finite
  // positive number, or pairs < 0 other than kAutoPairs.
  static constexpr int kAutoPairs = -1;
  Multipole(const Coefficients& c, double thickness_mm, int pairs = 10);
  // A slab whose two faces see different relative indices (a layer of a stack,
  // profiles/Layered.h): eta_top at the lit face z = 0, eta_bottom at z = d; c.eta is not
  // used. Each face gets its own extrapolation distance z_b = 2 A(η) D; with equal
  // indices this is the constructor above.
  Multipole(const Coefficients& c, double thickness_mm, int pairs, double eta_top,
            double eta_bottom);
  double reflectance(double r_mm) const override;
  double transmittance(double r_mm) const override;
  double total_reflectance() const override;    // closed form, summed over the pairs
  double total_transmittance() const override;  // closed form, summed over the pairs
  double support_radius() const override;
  double inner_radius() const override;
  int pairs() const { return n_; }
  // Pole depths (z down from the lit face), i = -n..n in order.
  std::vector<double> positive_poles() const;
  std::vector<double> negative_poles() const;

 private:
  double z_pos(int i) const { return i * period_ + ell_; }
  double z_neg(int i) const { return i * period_ - ell_ - 2.0 * z_b_; }
  double alpha_p_, sigma_tr_, thickness_;
  // Source depth 1/σt', the extrapolation distances 2AD of the lit and the far face, and
  // the period 2(d + z_b + z_b_far) of the pole lattice.
  double ell_, z_b_, z_b_far_, period_;
  int n_;
};

}  // namespace sss::profiles
