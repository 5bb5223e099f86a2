// Single scattering S(1) in the diffusion reference (issue 18 part 2): Jensen, Marschner,
// Levoy & Hanrahan 2001, §2.3 ("the single scattering term"), marched through the real
// geometry. What is integrated, per channel, at a visible subsurface point x_o seen along
// ω_o (unit, towards the eye) with shading normal n:
//
//   L(1)(x_o, ω_o) = F_t(η, μo)/η² ∫_0^{t_far} σs p(g, cos θ) Φ(x_s) e^(−σt s) ds,
//
//   * x_s = x_o + s ω_o', ω_o' the eye ray refracted into the medium (Snell, index η); the
//     march stops at t_far, where that ray leaves the object again (a thin part);
//   * Φ(x_s) = Σ_lights E V(x_i) μi F_t(η, μi)/μi' e^(−σt s_i'): each light's collimated
//     beam entering at x_i, the first surface point on the straight line from x_s towards
//     the light (distance s_i), with μi = n_i·l outside and μi' its refracted cosine inside.
//     μi E F_t/μi' is the beam's flux per unit area across its own direction inside;
//     s_i' = s_i μi/μi' is Jensen's estimate of the refracted path length (exact for a
//     plane); V(x_i) the light's visibility at x_i (shadow ray, or the GPU's shadow map);
//   * θ the angle between the refracted beam's travel direction at x_i and −ω_o';
//   * σs, σt, g, η the material's real coefficients (its effective medium: scale applied),
//     p Henyey–Greenstein.
//
// For a flat, semi-infinite medium this is exactly the closed form E μi f1 of
// profiles/SingleScattering.h (the depth integral is the one it solves analytically),
// which tests/reference checks. The depth integral is a deterministic quadrature: `samples`
// midpoints in the CDF of e^(−σt_min s) (σt_min the smallest σt over the channels that
// share η, which the others are weighted against), so the image has no noise and the
// flat-medium error falls as 1/samples².
//
// The result is radiance towards the eye per unit albedo (1 − metallic): the caller
// multiplies by the base colour as the GPU does (shaders/shared/shading.glsl).
#pragma once

#include "reference/PixelShading.h"
#include "reference/RayScene.h"
#include "reference/ShadowMaps.h"
#include "scene/Scene.h"

#include <glm/vec3.hpp>

namespace sss::reference {

inline constexpr int kSingleScatterSamples = 32;

glm::dvec3 marched_single_scattering(const scene::Scene& scene, const RayScene& rays, const VisibleSurface& v,
                                     const ShadowMaps* maps, int samples = kSingleScatterSamples);

// With single scattering on (ReferenceOptions::applies_single_scattering), what both
// diffusion estimators do at a subsurface pixel: adds the marched S(1) x base colour x
// (1 - metallic) to v.specular, the pixel's unblurred part, as the GPU adds its closed
// form to the specular target (shaders/shared/shading.glsl).
void add_single_scattering(const scene::Scene& scene, const RayScene& rays, VisibleSurface& v,
                           const ShadowMaps* maps);

}  // namespace sss::reference
