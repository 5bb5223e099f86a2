// The real-time frame's shadow maps, rebuilt on the CPU, so the reference can be lit as
// the GPU lights its frame (`sss-reference --shadows shadow-map`): the budget's
// "lighting" link (DESIGN.md §1) is the difference between this and ray-traced shadows.
//
// Each shadowed light (directional, spot: scene::shadow_frustum, the matrices and biases
// renderer/LightSetup uploads) gets a size x size depth map. A texel holds what the
// rasterizer writes there: the depth of the nearest surface through the texel centre
// (an Embree ray from the frustum's near to far plane through every mesh, no culling, as
// the shadow pass draws them), plus the pass's slope-scaled depth bias 1.5·m, m the
// triangle's larger depth slope per texel (max(|∂z/∂x|, |∂z/∂y|), as llvmpipe computes
// it); 1.0 (the clear value) where no surface is met. The lookup is
// shaders/shared/shading.glsl's shadow_visibility: the point moved along the shading
// normal by the normal offset, projected, its depth less the depth bias compared
// (LESS_OR_EQUAL) with the 4x4 texels around it weighted (1-f, 1, 1, f)/3 per axis (the
// 3x3 bilinear PCF), clamped to the map's edge; 1 outside the map. Point lights have no
// map on the GPU, so no shadow here either; lights past SSS_MAX_LIGHTS are not shaded.
//
// Thickness (`--thickness-from shadow-map`): the GPU's transmission reads a second map of each
// light without the slope-scaled bias (targets.light_depth) and turns it into the path
// from P back to the surface nearest the light on P's texel, the texel's depth moved to
// P's own position along the gradient of its neighbours (shaders/shared/thickness.glsl's
// shadow_thickness, ported here line for line). Against the ray-cast thickness that is the
// budget's thickness link: a texel's footprint and the gradient's plane instead of the
// exact last surface on the light's line through P.
#pragma once

#include "reference/RayScene.h"
#include "scene/Scene.h"
#include "scene/ShadowFrustum.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace sss::reference {

class ShadowMaps {
 public:
  // Builds every shadowed light's map (parallel over rows with TBB, in the caller's arena).
  // Throws std::invalid_argument for a size outside 1..16384.
  ShadowMaps(const scene::Scene& scene, const RayScene& rays, std::uint32_t size);

  // Whether light `index` (into Scene::lights) is shaded at all: the GPU shades the first
  // SSS_MAX_LIGHTS.
  bool shaded(std::size_t index) const { return index < maps_.size(); }
  // The filtered visibility of light `index` at p (world mm) with shading normal n (unit):
  // 1 for a light without a map.
  double visibility(std::size_t index, const glm::vec3& p_mm, const glm::vec3& n) const;
  // The path through the geometry from p (world mm) towards light `index`, as the GPU
  // reads it from the unbiased map (above), in mm: 0 where nothing lies between p and the
  // light; -1 where p is outside the map or the light has no map (the GPU then transmits
  // nothing from it).
  double thickness_mm(std::size_t index, const glm::vec3& p_mm) const;
  // The stored depth of texel (x, y) of light `index`'s map (tests).
  float depth(std::size_t index, std::uint32_t x, std::uint32_t y) const;
  std::uint32_t size() const { return size_; }

 private:
  struct Map {
    scene::ShadowFrustum frustum;
    std::vector<float> depth;  // size², row y = NDC y from -1 up; empty without a map
    std::vector<float> raw;    // the same without the slope-scaled bias (thickness)
  };
  std::vector<Map> maps_;
  std::uint32_t size_ = 0;
  float mm_per_unit_ = 1000.0f;
};

}  // namespace sss::reference
