// Camera: a glTF camera placed in the world. It looks down its local -Z with +Y up
// (glTF 2.0 §3.10); `world` is the node's world matrix without scale.
//
// Aspect. A perspective camera keeps its vertical field of view; with aspect 0 it takes
// the image's aspect. An orthographic camera keeps its horizontal half-width xmag and
// takes ymag = xmag / image aspect, so pixels stay square and the width is exact
// (builtin:edge relies on this). Distances are in scene units (metres for glTF).
#pragma once

#include "scene/Bounds.h"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <string>

namespace sss::scene {

enum class Projection { Perspective, Orthographic };

struct Camera {
  std::string name;
  Projection projection = Projection::Perspective;
  float yfov = 0.6f;    // perspective: vertical field of view, radians, in (0, π)
  float aspect = 0.0f;  // perspective: width / height; 0 = the image's
  float xmag = 1.0f;    // orthographic: half-width of the view
  float ymag = 1.0f;    // orthographic: half-height as written in the file
  float znear = 0.01f;  // > 0 (perspective), >= 0 (orthographic)
  float zfar = 100.0f;  // > znear; 0 = infinite (perspective only)
  glm::mat4 world{1.0f};

  glm::vec3 position() const { return glm::vec3(world[3]); }
  glm::vec3 forward() const;  // world direction of local -Z, unit
  glm::vec3 up() const;       // world direction of local +Y, unit
  glm::mat4 view() const;     // inverse(world)
  // Orthographic half extents for an image of this aspect (width / height).
  glm::vec2 ortho_half_extent(float image_aspect) const { return {xmag, xmag / image_aspect}; }
};

// The projection both renderers use for an image of width x height pixels: Vulkan clip
// space (image y down, depth in [0, 1]; an infinite far plane becomes znear * 1e5).
// Pixel (x, y) of the image covers NDC [2x/w - 1, 2(x+1)/w - 1] x [2y/h - 1, ...].
// reversed_depth: depth 1 at the near plane and 0 at the far one (the GPU's depth buffer,
// renderer/CameraSetup.h: a float depth then keeps ~2^-24 of relative precision at every
// distance, where the usual mapping crowds it at the near plane); x, y and w are the same.
glm::mat4 clip_from_view(const Camera& camera, std::uint32_t width, std::uint32_t height,
                         bool reversed_depth = false);

// A rigid transform at `eye` looking at `target`; `up` must not be parallel to the view.
glm::mat4 look_at_world(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up);

// A perspective camera looking along `direction` (world, need not be unit) at the
// centre of `bounds`, far enough that the bounding sphere, scaled by `margin`, fits the
// vertical field of view (so the whole box is seen, for any image at least as wide as
// tall, when margin >= 1). Near and far planes bracket the sphere.
Camera frame_bounds(const Bounds& bounds, const glm::vec3& direction = {-0.4f, -0.35f, -1.0f},
                    float yfov = 0.6f, float margin = 1.1f);

}  // namespace sss::scene
