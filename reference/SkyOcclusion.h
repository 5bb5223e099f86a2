// Sky occlusion: per vertex of every instance, the part of an environment's irradiance
// that the scene blocks, as 9 transfer coefficients in the spherical-harmonic basis the
// GPU lights with (precomputed radiance transfer, Sloan, Kautz & Snyder 2002, "Precomputed
// Radiance Transfer for Real-Time Rendering in Dynamic, Low-Frequency Lighting
// Environments", SIGGRAPH; here only the blocked part, so that a vertex that sees the
// whole sky gets exactly zero and an unoccluded surface is lit as before).
//
// For a vertex at p with unit normal n and a sky of radiance L(w) = sum_k L_k Y_k(w), the
// irradiance that the scene hides is
//   E_blocked = integral over the blocked directions of L(w) (n.w) dw
//             = sum_k L_k B_k,   B_k = integral over the blocked directions of Y_k(w) (n.w) dw.
// The GPU holds the sky as the irradiance's coefficients e_k = A_l L_k (A_0 = pi,
// A_1 = 2 pi / 3, A_2 = pi / 4; Ramamoorthi & Hanrahan 2001, "An Efficient Representation
// for Irradiance Environment Maps", eq. 8), so each vertex stores T_k = B_k / A_l and the
// shaders form E_blocked = sum_k e_k T_k (shaders/shared/surface.glsl). B_k is estimated
// from kSkyOcclusionStrata² stratified cosine-weighted directions w_s (density n.w / pi):
// B_k ~ (pi / N) sum over the blocked w_s of Y_k(w_s). Within the harmonics' band limit of
// the sky this is what the references' shadow rays sample (reference/Shading.cpp).
//
// World space (a floor under an object occludes it, and its instances differ), so the
// bake is per instance; Embree rays (RayScene), hence here and not in the Vulkan renderer
// that uploads it.
#pragma once

#include "scene/Scene.h"

#include <array>
#include <atomic>
#include <vector>

namespace sss::reference {

class RayScene;

inline constexpr int kSkyOcclusionStrata = 12;  // 144 directions per vertex

using SkyTransfer = std::array<float, 9>;

// One SkyTransfer per vertex of each instance's mesh (scene.instances order; empty for an
// instance whose mesh has no triangles). A vertex whose normal is not usable gets zeros.
// Each ray starts a thousandth of the way from the vertex toward the mean centroid of its
// triangles (off the plane of a neighbouring face at a concave crease), then 1e-4 x the
// scene's bounding diagonal along the normal, and counts a hit at any distance; a convex
// object alone gets exactly zero (no ray that leaves a vertex into its normal's
// hemisphere re-enters a convex polyhedron whose vertex normals are positive sums of the
// face normals around them). Deterministic: each vertex's directions are seeded by its
// world position and normal, so copies of one vertex agree. `cancel` (optional) stops the
// bake early; what it returns then is incomplete and must not be used.
std::vector<std::vector<SkyTransfer>> sky_occlusion(const scene::Scene& scene,
                                                   const std::atomic<bool>* cancel = nullptr);
// The same with the scene's rays already built (RayScene(scene)).
std::vector<std::vector<SkyTransfer>> sky_occlusion(const scene::Scene& scene, const RayScene& rays,
                                                   const std::atomic<bool>* cancel = nullptr);

// E_blocked = sum_k sh[k] T_k for a sky whose irradiance coefficients are `sh`
// (scene::Environment::irradiance_sh): what the shaders subtract.
glm::vec3 blocked_irradiance(const std::array<glm::vec3, 9>& sh, const SkyTransfer& t);

}  // namespace sss::reference
