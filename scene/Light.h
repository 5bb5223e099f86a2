// Light: a KHR_lights_punctual light placed in the world. It shines along its local -Z
// (directional, spot); `world` is the node's world matrix without scale.
//
// Units follow KHR_lights_punctual, read radiometrically by both renderers: a
// directional light's `intensity` is the irradiance E it delivers to a surface facing
// it (colour × intensity per channel), so a white Lambertian surface under it has exitant
// flux π·L = E. Point and spot intensities are radiant intensity I (E = I / d² at
// normal incidence). builtin:edge uses a directional light with intensity 1: E = 1.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <optional>
#include <string>

namespace sss::scene {

enum class LightType { Directional, Point, Spot };

struct Light {
  std::string name;
  LightType type = LightType::Directional;
  glm::vec3 color{1.0f};   // linear RGB, >= 0
  float intensity = 1.0f;  // see above
  float range = 0.0f;      // 0 = infinite
  float inner_cone = 0.0f;           // spot, radians, 0 <= inner < outer
  float outer_cone = 0.7853981634f;  // spot, radians, <= π/2
  glm::mat4 world{1.0f};
  // Half-space mask (scene units): the light reaches only points p with
  // dot(mask->xyz, p) + mask->w < 0. It is a sharp, resolution-independent edge that
  // both renderers apply analytically (builtin:edge lights x < 0 with (1, 0, 0, 0)).
  std::optional<glm::vec4> mask;

  glm::vec3 position() const { return glm::vec3(world[3]); }
  glm::vec3 direction() const;  // world direction the light travels (local -Z), unit
  // Whether the mask lets the light reach p (true when there is no mask).
  bool reaches(const glm::vec3& p) const;
};

// A directional light travelling along `direction` (world, need not be unit).
Light directional_light(const std::string& name, const glm::vec3& direction, float irradiance,
                        const glm::vec3& color = glm::vec3(1.0f));

}  // namespace sss::scene
