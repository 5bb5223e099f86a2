// RayScene: every instance of a Scene, flattened to world space in mm, in one Embree 3
// BVH. Primary rays find the visible surface of each pixel; shadow rays decide whether a
// light reaches a point. The geometry is the same triangles the real-time renderer
// rasterizes (no culling: back faces are hit, as the G-buffer draws them).
#pragma once

#include "reference/SkyOcclusion.h"
#include "scene/Scene.h"

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

namespace sss::reference {

struct Hit {
  std::uint32_t instance = 0;   // Scene::instances
  std::uint32_t triangle = 0;   // in the instance's mesh
  glm::vec2 barycentric{0.0f};  // weights of corners 1 and 2
  float t = 0.0f;               // ray parameter (mm for a unit direction)
};

class RayScene {
 public:
  // Throws std::runtime_error if Embree cannot create its device or scene. `threads` > 0
  // caps Embree's own build threads.
  explicit RayScene(const scene::Scene& scene, int threads = 0);
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  // Origin and direction in world mm (direction need not be unit; t is in its units).
  std::optional<Hit> intersect(const glm::vec3& origin, const glm::vec3& direction,
                               float t_near = 0.0f,
                               float t_far = std::numeric_limits<float>::infinity()) const;
  bool occluded(const glm::vec3& origin, const glm::vec3& direction, float t_near,
                float t_far) const;

  // World-mm positions of an instance's vertices (what the BVH holds), and its normal
  // matrix (inverse transpose of the world matrix's 3x3).
  const std::vector<glm::vec3>& world_positions(std::uint32_t instance) const;
  const glm::mat3& normal_matrix(std::uint32_t instance) const;
  double mm_per_unit() const { return mm_per_unit_; }

  // The GPU's sky occlusion (sky_occlusion(): per instance, per vertex), for the GPU-shadow
  // mode's environment light: surface_at() interpolates it into SurfacePoint::sky_blocked.
  // Null for an instance without one (none set: the sky is not occluded on those terms).
  void set_sky_transfers(std::vector<std::vector<SkyTransfer>> transfers) { sky_ = std::move(transfers); }
  const std::vector<SkyTransfer>* sky_transfers(std::uint32_t instance) const {
    return instance < sky_.size() && !sky_[instance].empty() ? &sky_[instance] : nullptr;
  }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double mm_per_unit_ = 1000.0;
  std::vector<std::vector<SkyTransfer>> sky_;
};

}  // namespace sss::reference
