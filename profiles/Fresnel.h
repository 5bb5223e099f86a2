// Fresnel reflectance of a smooth dielectric boundary and its angular moments.
#pragma once

namespace sss::profiles {

// Unpolarized Fresnel reflectance for light arriving with cosine cos_i (> 0) at a boundary
// whose relative index is eta_rel = n_transmitted / n_incident. Total internal
// reflection gives 1.
double fresnel_dielectric(double cos_i, double eta_rel);

// The i-th angular moment of the reflectance seen from *inside* a medium of index eta
// (relative to the outside), ∫_0^1 Fr(μ) μ^i dμ, by numerical integration: the part under
// the critical angle in closed form, the rest with Gauss–Legendre in a variable that
// removes the square-root kink. i = 1 or 2. In d'Eon's notation this is C1 = 2·m1/2 ...;
// the boundary constant of the better dipole is A = (1 + 3 m2) / (1 - 2 m1).
double fresnel_moment(int i, double eta);

// The same moments from the published polynomial fits (d'Eon 2012, "A better dipole",
// for 2C1 and 3C2; the halves/thirds as in pbrt-v3's FresnelMoment1/2).
double fresnel_moment1_fit(double eta);
double fresnel_moment2_fit(double eta);

// Internal diffuse Fresnel reflectance, Groenhuis et al. 1983 fit used by Jensen et al.
// 2001: Fdr = -1.440/η² + 0.710/η + 0.668 + 0.0636 η.
double fresnel_diffuse_reflectance_fit(double eta);

}  // namespace sss::profiles
