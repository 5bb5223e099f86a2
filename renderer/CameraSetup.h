// CameraSetup: the scene camera as the frame sees it: Vulkan projection (depth 0..1,
// image y down), view, and the frame uniforms built from them.
#pragma once

#include "renderer/RenderOptions.h"
#include "scene/Bounds.h"
#include "scene/Camera.h"
#include "shaders/shared/frame.h"

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <optional>

namespace sss::renderer {

struct CameraSetup {
  glm::mat4 view{1.0f};
  glm::mat4 proj{1.0f};  // Vulkan clip space: y flipped, z in [0, 1] reversed (1 at the near plane)
  bool orthographic = false;
  glm::vec3 position{0.0f};
  glm::vec3 forward{0.0f, 0.0f, -1.0f};
};

CameraSetup make_camera_setup(const scene::Camera& camera, std::uint32_t width,
                              std::uint32_t height);

shader::mat4 to_shader(const glm::mat4& m);

shader::FrameUniforms make_frame_uniforms(const CameraSetup& camera, std::uint32_t width,
                                          std::uint32_t height, double mm_per_unit,
                                          float exposure, std::uint32_t light_count,
                                          SssTechnique technique);

// The screen rectangle of `bounds`' eight corners under `view_proj` (Vulkan clip space) in
// an image of width x height, in pixels (x right, y down; pixel = (ndc + 1) / 2 x size, as
// pixel_ndc() in common.glsl inverts it), not clamped. nullopt when a corner is behind the
// camera plane (perspective) or the bounds are empty. geometry_rect and the viewer's
// object labels use it.
struct ScreenRect {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
};
std::optional<ScreenRect> projected_rect(const glm::mat4& view_proj, const scene::Bounds& bounds,
                                         std::uint32_t width, std::uint32_t height);

// The pixels the screen passes must cover: the projection of `bounds`' eight corners,
// grown by 2 pixels (so that the rect's border pixels are background: taps clamped to the
// rect read background there, as they would outside it), clamped to the image. The whole
// image when a corner is behind the camera plane or the bounds are empty. x1, y1 exclusive.
struct PixelRect {
  std::uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  std::uint32_t width() const { return x1 - x0; }
  std::uint32_t height() const { return y1 - y0; }
};
PixelRect geometry_rect(const CameraSetup& camera, const scene::Bounds& bounds,
                        std::uint32_t width, std::uint32_t height);

// The separable SSS pass's surface key stride (FrameUniforms::options.z, sss.glsl): a power
// of two >= 2 x the farthest view depth of `bounds` in mm + 1024 mm, so that keys of two
// materials never come within 1024 mm (more than any kernel range) of each other.
float surface_key_stride(const CameraSetup& camera, const scene::Bounds& bounds,
                         double mm_per_unit);

}  // namespace sss::renderer
