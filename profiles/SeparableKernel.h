// A Jimenez-style separable 1D kernel (Jimenez et al. 2015, "Separable subsurface
// scattering") built from any profile.
#pragma once

#include "profiles/Profile.h"

#include <vector>

namespace sss::profiles {

// A separable kernel: taps at offsets (mm, ascending, symmetric about 0, one tap at 0)
// with RGB weights that sum to 1 per channel. Applied horizontally then vertically, it is
// exact for irradiance that varies along one axis only (an edge): each weight is the
// profile's 1D marginal integrated over the tap's cell, i.e. a difference of the edge
// response. Multiply the result by total_reflectance.
struct SeparableKernel {
  std::vector<double> offsets_mm;
  std::vector<Rgb> weights;
  Rgb total_reflectance{};
  double range_mm = 0.0;
};

// `taps` odd, >= 3. Offsets follow Jimenez's quadratic spacing x = range·sign(t)·t², t
// uniform in [-1, 1], so taps crowd where the profile is sharp; the centre tap's offset
// is +0.0. range_mm <= 0 picks the radius holding 99.9% of the marginal's energy in the
// widest channel (M(range) = 5e-4·T).
// Tap i owns the cell between the midpoints to its neighbours (the outermost cells reach
// ±∞), so its weight is (M(lower boundary) − M(upper boundary)) / T. Convolving a step
// edge with the taps therefore gives M exactly at the cell boundaries; at a tap itself
// (counting the tap on the edge as ½) it gives the mean of M at its two boundaries.
// Throws std::invalid_argument for a bad tap count or a non-finite range.
//
// Quadrature: every M above is an edge_response() integral (~1200 evaluations of R), and
// the range alone takes ~30 bisection steps per channel, so a kernel costs ~1.4e5
// evaluations of R: cheap for the closed-form models, not for pbd, whose R(r) is itself a
// 64-sample beam integral (docs/PROFILES.md, "Benchmarks", has both). Tabulated evaluates
// each channel's R once on a log grid (kTabulatedNodesPerDecade nodes per decade from
// 1e-4·inner_radius to the support, cubic log-log interpolation, the exact R outside the
// grid) and integrates the table, and the weights differ from Exact's by < 4e-7
// (absolute; they sum to 1, and the GPU stores them as floats), the range by < 1e-5
// relative (tests/profiles/test_separable_kernel_quadrature.cpp, pbd and multipole).
// Auto picks Tabulated for the models whose R is costly (pbd, multipole, qd) and Exact for
// the closed forms (dipole, better-dipole, burley) and tabulated Monte Carlo, where it is
// already cheap.
enum class KernelQuadrature { Auto, Exact, Tabulated };
inline constexpr int kTabulatedNodesPerDecade = 32;

SeparableKernel make_separable_kernel(const RgbProfile& profile, int taps,
                                      double range_mm = 0.0,
                                      KernelQuadrature quadrature = KernelQuadrature::Auto);

}  // namespace sss::profiles
