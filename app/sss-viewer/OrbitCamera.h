// OrbitCamera: the viewer's camera control. It starts as the scene's camera (so the first
// window frame equals the headless frame) and orbits around a target on that camera's
// view axis, at the depth of the scene's centre. Orbit and pan keep world +Y up.
#pragma once

#include "scene/Bounds.h"
#include "scene/Camera.h"

#include <glm/vec3.hpp>

namespace sss::app {

class OrbitCamera {
 public:
  OrbitCamera(const scene::Camera& initial, const scene::Bounds& bounds);

  void reset();                                  // back to the initial camera
  void orbit(float dx_pixels, float dy_pixels);  // left drag
  void pan(float dx_pixels, float dy_pixels, float viewport_width, float viewport_height);  // middle / shift+left
  void zoom(float wheel_steps);                  // > 0: closer
  // The home view of a window whose left `covered` pixels (of viewport_width) are under a
  // panel (issue 20 part 2: the panel hid the bunny's back-lit ear): the camera backs off
  // (orthographic: widens) by viewport_width / (viewport_width - covered), so what the
  // scene's camera showed across the window now fits the free part, and pans so that its
  // middle is the free part's middle. reset() (R) returns here from now on. Nothing for
  // covered <= 0 or >= viewport_width.
  void frame_free_area(float covered, float viewport_width, float viewport_height);

  scene::Camera camera() const;
  // Set by every change, cleared by take_changed(): set_camera only when it moved.
  bool take_changed() {
    const bool c = changed_;
    changed_ = false;
    return c;
  }

 private:
  glm::vec3 eye() const;

  scene::Camera initial_;
  float radius_;
  glm::vec3 initial_target_{0.0f};
  float initial_distance_ = 1.0f;
  glm::vec3 target_{0.0f};
  float distance_ = 1.0f;
  float yaw_ = 0.0f, pitch_ = 0.0f;
  float xmag_ = 1.0f;
  // Where reset() goes: the scene's camera, or the view frame_free_area made.
  glm::vec3 home_target_{0.0f};
  float home_distance_ = 1.0f, home_xmag_ = 1.0f;
  bool home_moved_ = false;  // false: home is exactly `initial_`
  bool moved_ = false;  // false: camera() is exactly `initial_`
  bool changed_ = false;
};

}  // namespace sss::app
