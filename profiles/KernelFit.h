// The real-time kernel of one material, as the GPU receives it and as the CPU reference
// can sum it (`sss-reference --kernel fit`, the budget's "exact profile -> Gaussian fit"
// link): the profile's sum-of-Gaussians fit and, for a slab, its transmittance T(r) as a
// sum of the same Gaussians. One function makes both, so the reference sums exactly the
// kernel that renderer/MaterialTable uploads.
#pragma once

#include "profiles/GaussianFit.h"
#include "profiles/Profile.h"

#include <optional>
#include <vector>

namespace sss::profiles {

// A slab's transmittance T(r) (the multipole's) as a sum of the reflectance fit's own
// Gaussians: T_c(r) ≈ Σ_i weights[i]_c G(v_i, r), non-negative weights for the fixed
// variances (NNLS with the energy row Σ_i w_ic = total, as fit_gaussians does for R).
struct TransmittanceFit {
  std::vector<Rgb> weights;  // one per fit.variances_mm2
  Rgb total{};               // Σ_i weights[i] == the profile's total transmittance
  Rgb relative_error{};      // ‖r(T − T̃)‖₂ / ‖r T‖₂ on the fit's samples
};
// The fitted transmittance of `rgb` for fixed `variances_mm2` (ascending, > 0), on the
// samples of `target` (make_fit_target(rgb), the reflectance fit's own).
TransmittanceFit fit_transmittance(const RgbProfile& rgb, const FitTarget& target,
                                   const std::vector<double>& variances_mm2);

struct KernelFit {
  GaussianFit fit;
  std::optional<TransmittanceFit> transmittance;  // slabs only
};

// The material kernel: fit_gaussians(make_fit_target(rgb), {gaussians}) at the model's
// default resolution, and for a slab (`slab`: Medium::is_slab) the transmittance with the
// same variances. Throws what fit_gaussians throws (a gaussian count outside 1..8).
KernelFit fit_kernel(const RgbProfile& rgb, int gaussians, bool slab);

}  // namespace sss::profiles
