// The response to a straight light edge: with irradiance 1 on x' < 0 and 0 on x' > 0,
// the exitant flux at signed distance x from the edge is
//   M(x) = ∫∫_{x'<0} R(√((x-x')² + y²)) dx' dy.
// M(-∞) is the total reflectance, M(0) half of it. This is the exact answer of the
// renderer's builtin:edge scene, and its differences give the 1D marginal kernel.
#pragma once

#include "profiles/GaussianFit.h"
#include "profiles/Profile.h"

namespace sss::profiles {

// For x >= 0, M(x) = ∫_x^∞ R(r) 2r acos(x/r) dr; for x < 0, M(x) = total - M(-x).
// Numerically (Gauss–Legendre on geometric panels from x), truncated at the profile's
// support radius (so M = 0 beyond it); M(0) = total/2 exactly, whatever R does at 0.
// `total` is the profile's closed-form total_reflectance().
double edge_response(const RadialProfile& profile, double x_mm);
Rgb edge_response(const RgbProfile& profile, double x_mm);
// Closed form for a sum of Gaussians: Σ w_i ½ erfc(x / √(2 v_i)).
Rgb edge_response(const GaussianFit& fit, double x_mm);

}  // namespace sss::profiles
