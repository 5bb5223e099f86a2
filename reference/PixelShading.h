// What both CPU renderers (the diffusion reference and the random-walk ground truth) do
// alike at a pixel, so that their images differ only in how light crosses the medium:
//   * CameraRays: one ray through each pixel centre, with the projection the GPU uses
//     (scene::clip_from_view), in world mm;
//   * VisibleSurface: what the G-buffer and lighting passes know of the surface a ray
//     hits (Shading.h): shading normal, base colour, GGX specular, and the factor the
//     composite multiplies the scattered light by (shaders/composite.comp: base colour, or
//     its square root for pre/post albedo, times 1 - metallic).
#pragma once

#include "image/Image.h"
#include "reference/RayScene.h"
#include "reference/Shading.h"
#include "scene/Scene.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>

namespace sss::reference {

class CameraRays {
 public:
  CameraRays(const scene::Camera& camera, std::uint32_t width, std::uint32_t height, double mm_per_unit);
  struct Ray {
    glm::vec3 origin{0.0f}, direction{0.0f};  // world mm, unit direction
    float t_far = 0.0f;                       // the far plane
  };
  Ray pixel(std::uint32_t x, std::uint32_t y) const;
  // The unit direction towards the eye from a point the ray `direction` hit.
  glm::vec3 to_eye(const glm::vec3& direction) const { return ortho_ ? -forward_ : -direction; }

 private:
  glm::mat4 inv_view_proj_{1.0f};
  std::uint32_t width_, height_;
  float mm_;
  bool ortho_;
  glm::vec3 forward_{0.0f};
};

struct VisibleSurface {
  SurfacePoint point;
  const scene::Material* material = nullptr;
  glm::vec3 to_eye{0.0f};
  glm::vec3 normal{0.0f};     // shading normal, facing the eye
  glm::vec3 albedo{0.0f};     // base colour
  bool subsurface = false;    // the material scatters (sss.enabled)
  glm::dvec3 specular{0.0};   // GGX specular towards the eye (0 when not asked for); the
                              // diffusion references add S(1) to it (SingleScatter.h)
  glm::dvec3 irradiance{0.0}; // direct irradiance E (opaque surfaces only)
  glm::dvec3 scatter_factor{0.0};  // what multiplies the scattered light in the composite
  // Subsurface: the directional Fresnel exit factor F_t(η, n·v) / c per channel
  // (profiles::fresnel_exit_normalization; shaders/shared/composite.glsl exit_fresnel),
  // which the diffusion renderers apply with --fresnel on; 1 elsewhere. The ground truth
  // refracts at the face instead.
  glm::dvec3 exit_fresnel{1.0};
  // The pixel's radiance for an opaque surface: albedo (1 - metallic) E/π + specular.
  glm::dvec3 opaque_radiance() const;
};

// The surface `hit` of a camera ray travelling along `direction`. Specular is evaluated
// unless `diffuse_only`; irradiance only for opaque materials. `maps`: shadowed as the GPU
// shadows (direct_light).
VisibleSurface visible_surface(const scene::Scene& scene, const RayScene& rays, const CameraRays& camera,
                               const Hit& hit, const glm::vec3& direction, bool diffuse_only,
                               const ShadowMaps* maps = nullptr);

// Writes v's specular radiance (0 with diffuse_only) and alpha 1 into pixel (x, y) of
// `specular`: the part of the radiance the error budget takes apart from the scattered light.
void store_specular(image::Image& specular, std::uint32_t x, std::uint32_t y, const VisibleSurface& v,
                    bool diffuse_only);

}  // namespace sss::reference
