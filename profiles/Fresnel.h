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

// The directional factors of the separable BSSRDF (Jensen et al. 2001; pbrt-v3's
// SeparableBSSRDF, pbrt-v4's NormalizedFresnelBxDF), S_d = (1/π) F_t(η, ωi) R(r)
// F_t(η, ωo) / c:
// - fresnel_transmittance: F_t = 1 - Fr for light meeting the surface of a medium of
//   index eta (relative to the outside) from outside with cosine cos_outside. By the
//   reciprocity of the Fresnel equations it is also the transmittance of light leaving the
//   medium into that outside direction, so one function serves entry and exit.
// - fresnel_exit_normalization: c = ∫ F_t(η, ω) cos θ dω / π over the outside
//   hemisphere, = 1 - 2 m1(1/η) (m1 the first moment of the reflectance seen from outside;
//   fresnel_moment's "inside a medium of index 1/η" is outside a medium of index η). The
//   exitant radiance M F_t(η, θo) / (c π) then carries exactly the exitance M out, as
//   M / π (Lambert) does. c(1.4) = 0.92321 (pbrt-v3's 1 - 2 FresnelMoment1(1/η)).
double fresnel_transmittance(double cos_outside, double eta);
double fresnel_exit_normalization(double eta);

// Internal diffuse Fresnel reflectance, Groenhuis et al. 1983 fit used by Jensen et al.
// 2001: Fdr = -1.440/η² + 0.710/η + 0.668 + 0.0636 η.
double fresnel_diffuse_reflectance_fit(double eta);

}  // namespace sss::profiles
