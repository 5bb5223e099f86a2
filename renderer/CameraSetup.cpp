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
  c.proj = scene::clip_from_view(camera, width, height);
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
                                          int sss_mode) {
  shader::FrameUniforms u;
  const glm::mat4 view_proj = camera.proj * camera.view;
  u.view_proj = to_shader(view_proj);
  u.inv_view_proj = to_shader(glm::inverse(view_proj));
  u.inv_proj = to_shader(glm::inverse(camera.proj));
  u.camera = {camera.position.x, camera.position.y, camera.position.z,
              camera.orthographic ? 1.0f : 0.0f};
  u.forward = {camera.forward.x, camera.forward.y, camera.forward.z, 0.0f};
  u.viewport = {float(width), float(height), 1.0f / float(width), 1.0f / float(height)};
  u.scale = {float(mm_per_unit), camera.proj[0][0], std::abs(camera.proj[1][1]), exposure};
  u.options = {float(light_count), float(sss_mode), 0.0f, 0.0f};
  return u;
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
