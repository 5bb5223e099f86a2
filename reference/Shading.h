// What the reference renderer knows about a surface point, computed as the real-time
// G-buffer and lighting passes compute it (shaders/gbuffer.*, shaders/lighting.comp), so
// the two images differ only where an approximation differs:
//   * the interpolated vertex normal, turned to face the viewer, perturbed by the normal
//     map; base colour = factor × texture (sRGB decoded, bilinear, level 0: the GPU's
//     mipmaps blur minified textures a little more);
//   * direct light from every scene light: irradiance E = radiance · max(n·l, 0) · V,
//     with V from a shadow ray (hard, exact) where the GPU filters a shadow map, and the
//     half-space light masks; GGX specular (Smith height-correlated visibility, Schlick
//     Fresnel, F0 = mix(0.04·specular, base colour, metallic)), as the GPU evaluates it.
#pragma once

#include "reference/RayScene.h"
#include "reference/ShadowMaps.h"
#include "scene/Scene.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <limits>
#include <optional>

namespace sss::reference {

struct SurfacePoint {
  glm::vec3 position_mm{0.0f};
  glm::vec3 geometric_normal{0.0f, 0.0f, 1.0f};  // unit, the triangle's winding
  glm::vec3 normal{0.0f, 0.0f, 1.0f};            // unit interpolated vertex normal
  glm::vec2 uv{0.0f};
  glm::vec4 tangent{0.0f};  // xyz world, w sign; zero when the mesh has none
  bool has_uv = false;
  std::uint32_t material = 0;
  // The GPU's sky occlusion at the point, its vertices' transfers interpolated as the
  // G-buffer does (RayScene::sky_transfers; zero without them): what the GPU-shadow mode
  // takes from the harmonics' irradiance.
  SkyTransfer sky_blocked{};
};

SurfacePoint surface_at(const scene::Scene& scene, const RayScene& rays, std::uint32_t instance,
                        std::uint32_t triangle, const glm::vec2& barycentric);

// Base colour (linear RGB, clamped to [0, 1]) at the point, factor × texture.
glm::vec3 base_colour(const scene::Scene& scene, const SurfacePoint& p);

// The shading normal seen from `to_eye`: the interpolated normal flipped to face the
// viewer, then the material's normal map if it has one (and the mesh has tangents).
glm::vec3 shading_normal(const scene::Scene& scene, const SurfacePoint& p, const glm::vec3& to_eye);

// The environment's irradiance at p with normal n (unit). as_gpu: as the GPU lights it
// (scene::Environment::irradiance: spherical harmonics less blocked_irradiance of
// p.sky_blocked, clamped at 0, as shading.glsl; the GPU-shadow mode of direct_light). Otherwise the true one: kEnvironmentStrata² stratified cosine-weighted
// directions with shadow rays and the full-resolution radiance, deterministic per point.
// entry_eta (per channel; directional Fresnel on a subsurface material): only the part
// that enters, each direction times F_t(η, n.w), or as the GPU takes it, times
// c = profiles::fresnel_exit_normalization(η), F_t's cosine-weighted mean.
inline constexpr int kEnvironmentStrata = 8;
glm::dvec3 environment_irradiance(const scene::Environment& env, const RayScene& rays, const SurfacePoint& p,
                                  const glm::vec3& n, bool as_gpu, const glm::dvec3* entry_eta = nullptr);

struct SpecularInputs;
// The environment's specular radiance towards spec.to_eye at p (normal n): as_gpu, the
// split sum the GPU evaluates (scene/SplitSum.h, no occlusion); otherwise the true
// integral of L V f n.l, kEnvironmentStrata² stratified GGX-distributed normals with
// shadow rays and the full-resolution radiance, deterministic per point.
glm::dvec3 environment_specular(const scene::Environment& env, const RayScene& rays, const SurfacePoint& p,
                                const glm::vec3& n, const SpecularInputs& spec, bool as_gpu);

struct DirectLight {
  glm::dvec3 irradiance{0.0};  // E, before any albedo
  glm::dvec3 specular{0.0};    // radiance towards the eye (zero when not asked)
};

struct SpecularInputs {
  glm::vec3 to_eye{0.0f};  // unit
  glm::vec3 f0{0.04f};
  float roughness = 1.0f;
};

// Light `index` (into Scene::lights) arriving at p_mm, before any visibility: the unit
// direction l towards it, its irradiance at normal incidence (distance falloff and spot
// cone applied) and its distance (infinite for directional lights). Empty where its
// half-space mask leaves p dark, or (maps non-null) where the GPU does not shade it.
struct LightArrival {
  glm::vec3 l{0.0f, 0.0f, 1.0f};
  glm::dvec3 radiance{0.0};
  float distance_mm = std::numeric_limits<float>::infinity();
};
std::optional<LightArrival> light_arrival(const scene::Scene& scene, std::size_t index, const glm::vec3& p_mm,
                                         const ShadowMaps* maps);
// Its visibility at p (shading normal n): a shadow ray from just off the surface, or the
// GPU's filtered shadow map when `maps` is set.
double light_visibility(const RayScene& rays, std::size_t index, const SurfacePoint& p, const glm::vec3& n,
                        const LightArrival& arrival, const ShadowMaps* maps);

// Direct light at p with normal n (unit). `specular` null: irradiance only. `maps` null:
// ray-traced shadows from every light; else the lights are shadowed as the GPU shadows
// them (ShadowMaps.h: its filtered shadow maps, no shadow from point lights, only the
// lights the GPU shades). `entry_eta` non-null: a subsurface point with directional
// Fresnel, each light's irradiance times F_t(η, n·l) per channel (the part that enters;
// shaders/shared/shading.glsl does the same), the specular lobe unchanged.
DirectLight direct_light(const scene::Scene& scene, const RayScene& rays, const SurfacePoint& p,
                         const glm::vec3& n, const SpecularInputs* specular,
                         const ShadowMaps* maps = nullptr, const glm::dvec3* entry_eta = nullptr);

}  // namespace sss::reference
