#include "OrbitCamera.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace sss::app {

OrbitCamera::OrbitCamera(const scene::Camera& initial, const scene::Bounds& bounds)
    : initial_(initial), radius_(std::max(bounds.empty() ? 1.0f : bounds.radius(), 1e-3f)) {
  const glm::vec3 center = bounds.empty() ? glm::vec3(0.0f) : bounds.center();
  const glm::vec3 f = initial_.forward();
  initial_distance_ = std::max(glm::dot(center - initial_.position(), f), 0.1f * radius_);
  initial_target_ = initial_.position() + f * initial_distance_;
  home_target_ = initial_target_;
  home_distance_ = initial_distance_;
  home_xmag_ = initial_.xmag;
  reset();
  changed_ = false;
}

void OrbitCamera::reset() {
  const glm::vec3 back = -initial_.forward();
  pitch_ = std::asin(std::clamp(back.y, -1.0f, 1.0f));
  yaw_ = std::atan2(back.x, back.z);
  xmag_ = home_xmag_;
  target_ = home_target_;
  distance_ = home_distance_;
  changed_ = changed_ || moved_ || home_moved_;
  moved_ = home_moved_;
}

void OrbitCamera::frame_free_area(float covered, float viewport_width, float viewport_height) {
  if (!(covered > 0.0f && covered < viewport_width)) return;
  reset();
  const float widen = viewport_width / (viewport_width - covered);
  distance_ *= widen;  // the target's depth: the scene's centre
  xmag_ *= widen;
  moved_ = true;
  // The view's middle moves right by covered / 2 pixels: the subject with it.
  pan(0.5f * covered, 0.0f, viewport_width, viewport_height);
  home_target_ = target_;
  home_distance_ = distance_;
  home_xmag_ = xmag_;
  home_moved_ = true;
  changed_ = true;
}

glm::vec3 OrbitCamera::eye() const {
  const glm::vec3 back(std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_),
                       std::cos(pitch_) * std::cos(yaw_));
  return target_ + back * distance_;
}

void OrbitCamera::orbit(float dx, float dy) {
  if (dx == 0.0f && dy == 0.0f) return;
  constexpr float kRadiansPerPixel = 0.008f;
  yaw_ -= dx * kRadiansPerPixel;
  pitch_ = std::clamp(pitch_ + dy * kRadiansPerPixel, -1.5f, 1.5f);
  moved_ = changed_ = true;
}

void OrbitCamera::pan(float dx, float dy, float viewport_width, float viewport_height) {
  if (dx == 0.0f && dy == 0.0f) return;
  const scene::Camera c = camera();
  // World units per pixel at the target's depth.
  const float span = c.projection == scene::Projection::Orthographic
                         ? 2.0f * xmag_ * viewport_height / std::max(viewport_width, 1.0f)
                         : 2.0f * distance_ * std::tan(0.5f * c.yfov);
  const float scale = span / std::max(viewport_height, 1.0f);
  const glm::vec3 right = glm::vec3(c.world[0]);
  const glm::vec3 up = glm::vec3(c.world[1]);
  target_ += (-dx * right + dy * up) * scale;
  moved_ = changed_ = true;
}

void OrbitCamera::zoom(float steps) {
  if (steps == 0.0f) return;
  const float factor = std::pow(0.9f, steps);
  distance_ = std::clamp(distance_ * factor, 0.01f * radius_, 100.0f * radius_);
  xmag_ = std::clamp(xmag_ * factor, 1e-4f * radius_, 100.0f * radius_);
  moved_ = changed_ = true;
}

scene::Camera OrbitCamera::camera() const {
  if (!moved_) return initial_;
  scene::Camera c = initial_;
  const glm::vec3 e = eye();
  c.world = scene::look_at_world(e, target_, glm::vec3(0.0f, 1.0f, 0.0f));
  c.xmag = xmag_;
  // Near and far bracket the scene's sphere around the target, as frame_bounds does.
  c.znear = std::max(distance_ - 2.0f * radius_, 0.01f * radius_);
  c.zfar = distance_ + 2.0f * radius_;
  return c;
}

}  // namespace sss::app
