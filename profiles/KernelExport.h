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
// radius holding 99.9% of the marginal's energy in the widest channel.
SeparableKernel make_separable_kernel(const RgbProfile& profile, int taps,
                                      double range_mm = 0.0);

// What the exports record about where a kernel came from.
struct KernelInfo {
  std::string model;        // model_name()
  std::string medium;       // a human-readable description of the medium
};

// {"model", "medium", "variances_mm2", "weights", "total_reflectance", "relative_error"
//  [, "separable": {"offsets_mm", "weights", "total_reflectance"}]}
std::string kernel_to_json(const GaussianFit& fit, const KernelInfo& info,
                           const SeparableKernel* separable = nullptr);
// A C99 header: `static const float PREFIX_variances_mm2[N]`, `PREFIX_weights[N][3]`,
// counts as #defines, and the separable kernel when given.
std::string kernel_to_c_header(const GaussianFit& fit, const KernelInfo& info,
                               const SeparableKernel* separable = nullptr,
                               const std::string& prefix = "sss_kernel");

}  // namespace sss::profiles
