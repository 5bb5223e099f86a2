// Chandrasekhar's H-function for isotropic scattering, and the exact total reflectance
// of an index-matched semi-infinite medium under a normally incident beam,
// R = 1 - H(1) √(1 - α) (Chandrasekhar 1960, "Radiative Transfer", ch. V). This is
// exact transport, independent of every diffusion model and of the Monte Carlo code.
#pragma once

namespace sss::profiles {

// H(μ) for single-scattering albedo α in (0, 1], μ in [0, 1].
double chandrasekhar_h(double mu, double albedo);

// 1 - H(1) √(1 - α): e.g. 0.41495 at α = 0.9 and 0.75272 at α = 0.99.
double exact_total_reflectance_index_matched(double albedo);

}  // namespace sss::profiles
