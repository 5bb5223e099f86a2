// Single scattering S⁽¹⁾ of a flat, semi-infinite, homogeneous medium under a smooth
// dielectric boundary (issue 18 part 2; Jensen, Marschner, Levoy & Hanrahan 2001, §2.3,
// "the single scattering term", with Hanrahan & Krueger 1993's planar closed form).
//
// What is integrated: a collimated beam of irradiance E (at normal incidence) meets the
// surface at outside cosine μi; the part F_t(η, μi) enters and travels along the refracted
// direction (inside cosine μi') with extinction σt = σa + σs (the real coefficients, not
// the reduced ones). At depth z the beam scatters once, with probability σs dz/μi' and the
// Henyey–Greenstein phase function p(g, cos θ) of the material's real g, toward the
// direction that refracts out to the camera (inside cosine μo'); on its way up it is
// attenuated over z/μo' and crosses the boundary with F_t(η, μo) and the 1/η² of radiance
// leaving a denser medium. The depth integral is closed:
//   ∫₀^∞ e^(−σt z/μi') e^(−σt z/μo') σs dz/(μi' μo') = α / (μi' + μo'),  α = σs/σt,
// so the once-scattered radiance toward ωo is L⁽¹⁾ = E μi f1 with
//   f1(ωi, ωo) = F_t(η, μi) F_t(η, μo) α p(g, cos θ) / (η² (μi' + μo')),
// cos θ = −μi'μo' + sin θi' sin θo' cos Δφ, the cosine between the refracted beam's
// direction (travelling in) and the exit direction (travelling out), Δφ the azimuth
// between their horizontal parts (Δφ = π: the light turns back toward its source). Light
// once scattered that meets the surface and reflects goes down and never leaves without
// scattering again, so nothing else is once-scattered. Checked against the analog walk's
// once-scattered exits binned by exit angle (tests/profiles/test_single_scattering.cpp).
#pragma once

#include "profiles/Medium.h"

namespace sss::profiles {

// The refracted (inside) cosine of a direction whose outside cosine is cos_outside, for a
// medium of relative index eta >= 1 (Snell).
double refracted_cosine(double cos_outside, double eta);

// Henyey–Greenstein phase function, normalised over the sphere (1/4π at g = 0); cos_theta
// between the propagation directions before and after the event.
double henyey_greenstein(double g, double cos_theta);

// f1 above, sr⁻¹: L⁽¹⁾ = E cos θi f1. cos_i, cos_o outside cosines in (0, 1];
// cos_dphi the cosine of the azimuth between the beam's and the exit's horizontal travel.
double single_scattering_brdf(const Coefficients& c, double cos_i, double cos_o, double cos_dphi);

// The once-scattered flux leaving per unit power that entered, per unit of outside exit
// cosine μo (the exit azimuth integrated, 64-point Gauss–Legendre in Δφ): what the analog
// walk's reflectance_by_exit_cosine tallies with max_scattering_order = 1. Its integral over
// μo in [0, 1] is the once-scattered total reflectance (α (1 − ln 2)/2 at g = 0, η = 1,
// normal incidence).
double single_scattering_exit_density(const Coefficients& c, double cos_i, double cos_o);

}  // namespace sss::profiles
