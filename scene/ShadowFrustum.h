// The shadow map of one light as the real-time frame renders it: its view-projection
// (scene units -> Vulkan clip space, depth 0..1), the normal offset applied to the shaded
// point and the depth bias subtracted from its depth before the comparison. Directional
// lights get an orthographic fit to the scene's bounding sphere, spot lights a
// perspective frustum of their outer cone; point lights have none (no cube maps).
//
// One function, so that renderer/LightSetup (the GPU's light block) and the CPU
// reference's shadow-map mode (reference/ShadowMaps.h, the budget's "lighting"
// link) use the same matrices and biases.
#pragma once

#include "scene/Bounds.h"
#include "scene/Light.h"

#include <glm/mat4x4.hpp>

#include <cstdint>

namespace sss::scene {

struct ShadowFrustum {
  bool shadowed = false;        // false: no shadow map (point lights)
  glm::mat4 view_proj{1.0f};    // scene units -> clip
  glm::mat4 inverse{1.0f};      // its inverse
  float normal_offset = 0.0f;   // scene units, along the shading normal
  float depth_bias = 0.0f;      // NDC depth subtracted from the point's depth
};

// The rasterizer's slope-scaled depth bias of the shadow pass (vkCmdSetDepthBias(0, 0,
// 1.5) in renderer/ShadowPass.cpp): the stored depth is z + kShadowSlopeBias · m, m the
// triangle's largest depth slope per texel.
inline constexpr float kShadowSlopeBias = 1.5f;

ShadowFrustum shadow_frustum(const Light& light, const Bounds& bounds, std::uint32_t shadow_map_size);

}  // namespace sss::scene
