// Exporting a fit for use in other engines: JSON (the `sss-fit fit --json` schema, see
// DESIGN.md §4) and a self-contained C header; and a Jimenez-style separable 1D kernel
// (Jimenez et al. 2015, "Separable subsurface scattering") built from any profile.
#pragma once

#include "profiles/GaussianFit.h"
#include "profiles/Profile.h"

#include <string>
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
// uniform in [-1, 1], so taps crowd where the profile is sharp. range_mm <= 0 picks the
// radius holding 99.9% of the marginal's energy in the widest channel (M(range) = 5e-4·T).
// Tap i owns the cell between the midpoints to its neighbours (the outermost cells reach
// ±∞), so its weight is (M(lower boundary) − M(upper boundary)) / T. Convolving a step
// edge with the taps therefore gives M exactly at the cell boundaries; at a tap itself
// (counting the tap on the edge as ½) it gives the mean of M at its two boundaries.
// Throws std::invalid_argument for a bad tap count or a non-finite range.
SeparableKernel make_separable_kernel(const RgbProfile& profile, int taps,
                                      double range_mm = 0.0);

// What the exports record about where a kernel came from.
struct KernelInfo {
  std::string model;        // model_name()
  std::string medium;       // a human-readable description of the medium
};

// {"model", "medium", "variances_mm2", "weights", "total_reflectance", "relative_error"
//  [, "separable": {"offsets_mm", "weights", "total_reflectance"}]}
// Numbers are written with %.17g (doubles round-trip); a non-finite one as null.
std::string kernel_to_json(const GaussianFit& fit, const KernelInfo& info,
                           const SeparableKernel* separable = nullptr);
// A C99 header: `static const float PREFIX_variances_mm2[N]`, `PREFIX_weights[N][3]`,
// `PREFIX_total_reflectance[3]`, `PREFIX_relative_error[3]`, PREFIX_COUNT (upper-cased)
// as a #define, an include guard PREFIX_H, a comment block with the model, medium,
// error, units and how to evaluate R(r); with a separable kernel also
// PREFIX_SEPARABLE_TAPS, `PREFIX_separable_offsets_mm`, `PREFIX_separable_weights` and
// `PREFIX_separable_total_reflectance`. Floats are printed with 9 significant digits
// (they round-trip). Throws std::invalid_argument if the prefix is not a C identifier
// or a value is not finite.
std::string kernel_to_c_header(const GaussianFit& fit, const KernelInfo& info,
                               const SeparableKernel* separable = nullptr,
                               const std::string& prefix = "sss_kernel");

}  // namespace sss::profiles
