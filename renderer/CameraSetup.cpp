#include "renderer/CameraSetup.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>

namespace sss::renderer {

CameraSetup make_camera_setup(const scene::Camera& camera, std::uint32_t width,
                              std::uint32_t height) {
  CameraSetup c;
  c.view = camera.view();
  c.position = camera.position();
  c.forward = camera.forward();
  c.orthographic = camera.projection == scene::Projection::Orthographic;
  // Reversed depth: P rebuilt from the depth buffer (lighting.comp) stays within ~1e-7 of
  // its distance whatever the camera's znear. With the usual mapping a glTF camera's
  // znear of 0.05 and zfar of 1e6 (2CylinderEngine.glb) left one float step of depth a
  // whole scene unit deep at 1000 units, more than the shadow test's bias: the shadow map
  // then shadowed lit faces in stripes (shadow acne that no bias scaled to the scene
  // removes; issue 20).
  c.proj = scene::clip_from_view(camera, width, height, /*reversed_depth=*/true);
  return c;
}

shader::mat4 to_shader(const glm::mat4& m) {
  shader::mat4 out;
  for (int c = 0; c < 4; ++c) out.c[c] = {m[c][0], m[c][1], m[c][2], m[c][3]};
  return out;
}

shader::FrameUniforms make_frame_uniforms(const CameraSetup& camera, std::uint32_t width,
                                          std::uint32_t height, double mm_per_unit,
                                          float exposure, std::uint32_t light_count,
                                          SssTechnique technique) {
  shader::FrameUniforms u;
  const glm::mat4 view_proj = camera.proj * camera.view;
  u.view_proj = to_shader(view_proj);
  // Inverted in double: its entries span the scene's distances and their reciprocals.
  u.inv_view_proj = to_shader(glm::mat4(glm::inverse(glm::dmat4(camera.proj) * glm::dmat4(camera.view))));
  u.inv_proj = to_shader(glm::inverse(camera.proj));
  u.camera = {camera.position.x, camera.position.y, camera.position.z,
              camera.orthographic ? 1.0f : 0.0f};
  u.forward = {camera.forward.x, camera.forward.y, camera.forward.z, 0.0f};
  u.viewport = {float(width), float(height), 1.0f / float(width), 1.0f / float(height)};
  u.scale = {float(mm_per_unit), camera.proj[0][0], std::abs(camera.proj[1][1]), exposure};
  u.options = {float(light_count), float(static_cast<int>(technique)), 0.0f, 0.0f};
  return u;
}

std::optional<ScreenRect> projected_rect(const glm::mat4& view_proj, const scene::Bounds& bounds,
                                         std::uint32_t width, std::uint32_t height) {
  if (bounds.empty()) return std::nullopt;
  ScreenRect r{1e30, 1e30, -1e30, -1e30};
  for (int i = 0; i < 8; ++i) {
    const glm::vec4 clip = view_proj * glm::vec4(bounds.corner(i), 1.0f);
    if (!(clip.w > 1e-6f)) return std::nullopt;  // behind the camera plane (perspective)
    const double px = (double(clip.x) / clip.w + 1.0) * 0.5 * width;
    const double py = (double(clip.y) / clip.w + 1.0) * 0.5 * height;
    r.x0 = std::min(r.x0, px), r.x1 = std::max(r.x1, px);
    r.y0 = std::min(r.y0, py), r.y1 = std::max(r.y1, py);
  }
  return r;
}

PixelRect geometry_rect(const CameraSetup& camera, const scene::Bounds& bounds,
                        std::uint32_t width, std::uint32_t height) {
  const PixelRect full{0, 0, width, height};
  const std::optional<ScreenRect> box = projected_rect(camera.proj * camera.view, bounds, width, height);
  if (!box) return full;
  const double x_min = box->x0, y_min = box->y0, x_max = box->x1, y_max = box->y1;
  const auto clamp_to = [](double v, std::uint32_t size) {
    return static_cast<std::uint32_t>(std::clamp(v, 0.0, double(size)));
  };
  PixelRect r{clamp_to(std::floor(x_min) - 2.0, width), clamp_to(std::floor(y_min) - 2.0, height),
              clamp_to(std::ceil(x_max) + 2.0, width), clamp_to(std::ceil(y_max) + 2.0, height)};
  if (r.x1 <= r.x0 || r.y1 <= r.y0) r = {0, 0, 1, 1};  // nothing in view: one pixel
  return r;
}

float surface_key_stride(const CameraSetup& camera, const scene::Bounds& bounds,
                         double mm_per_unit) {
  double far_mm = 0.0;
  if (!bounds.empty())
    far_mm = (double(glm::dot(bounds.center() - camera.position, camera.forward)) +
              double(bounds.radius())) * mm_per_unit;
  const double needed = 2.0 * std::max(far_mm, 0.0) + 1024.0;
  return float(std::exp2(std::ceil(std::log2(needed))));
}

}  // namespace sss::renderer
