// Exporting a fit for use in other engines: JSON (the `sss-fit fit --json` schema, see
// DESIGN.md §4) and a self-contained C header, each optionally with a separable kernel
// (SeparableKernel.h, included here for the exports' callers).
#pragma once

#include "profiles/GaussianFit.h"
#include "profiles/Profile.h"
#include "profiles/SeparableKernel.h"

#include <string>
#include <vector>

namespace sss::profiles {

// What the exports record about where a kernel came from.
struct KernelInfo {
  std::string model;        // model_name()
  std::string medium;       // a human-readable description of the medium
};

// {"model", "medium", "variances_mm2", "weights", "total_reflectance", "relative_error",
//  "resolution_mm" [, "separable": {"offsets_mm", "weights", "total_reflectance"}]}
// (resolution_mm: the fit's resolution, GaussianFit::prefilter_variance_mm2 as a standard
// deviation; 0 when the fit is of the profile itself)
// Numbers are written with %.17g (doubles round-trip); a non-finite one as null.
std::string kernel_to_json(const GaussianFit& fit, const KernelInfo& info,
                           const SeparableKernel* separable = nullptr);
// A C99 header: `static const float PREFIX_variances_mm2[N]`, `PREFIX_weights[N][3]`,
// `PREFIX_total_reflectance[3]`, `PREFIX_relative_error[3]`, `PREFIX_resolution_mm`,
// PREFIX_COUNT (upper-cased)
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
