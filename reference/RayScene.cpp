#include "reference/RayScene.h"

#include <embree3/rtcore.h>

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace sss::reference {

struct RayScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<std::vector<glm::vec3>> positions;  // per instance, world mm
  std::vector<glm::mat3> normal_matrices;
  std::vector<std::uint32_t> instance_of_geometry;

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {
[[noreturn]] void embree_failure(RTCDevice device, const char* what) {
  const RTCError e = device ? rtcGetDeviceError(device) : RTC_ERROR_UNKNOWN;
  throw std::runtime_error(std::string("Embree: ") + what + " failed (error " +
                           std::to_string(int(e)) + ")");
}
}  // namespace

RayScene::RayScene(const scene::Scene& s, int threads) : impl_(std::make_unique<Impl>()), mm_per_unit_(s.mm_per_unit) {
  Impl& m = *impl_;
  m.device = rtcNewDevice(threads > 0 ? ("threads=" + std::to_string(threads)).c_str() : nullptr);
  if (!m.device) embree_failure(nullptr, "rtcNewDevice");
  m.scene = rtcNewScene(m.device);
  if (!m.scene) embree_failure(m.device, "rtcNewScene");
  rtcSetSceneBuildQuality(m.scene, RTC_BUILD_QUALITY_HIGH);
  // Watertight traversal: one ray per pixel must not slip between two triangles.
  rtcSetSceneFlags(m.scene, RTC_SCENE_FLAG_ROBUST);
  const float mm = float(s.mm_per_unit);
  m.positions.resize(s.instances.size());
  m.normal_matrices.resize(s.instances.size());
  for (std::uint32_t i = 0; i < s.instances.size(); ++i) {
    const scene::Instance& inst = s.instances[i];
    const scene::Mesh& mesh = s.meshes.at(inst.mesh);
    std::vector<glm::vec3>& world = m.positions[i];
    world.reserve(mesh.positions.size());
    for (const glm::vec3& p : mesh.positions) world.push_back(glm::vec3(inst.world * glm::vec4(p, 1.0f)) * mm);
    m.normal_matrices[i] = glm::transpose(glm::inverse(glm::mat3(inst.world)));
    if (mesh.triangle_count() == 0) continue;
    RTCGeometry g = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (!g) embree_failure(m.device, "rtcNewGeometry");
    // Embree reads 16 bytes past the last vertex: the buffer it allocates is padded.
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                          RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                          world.size()));
    auto* idx = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), mesh.triangle_count()));
    if (!v || !idx) {
      rtcReleaseGeometry(g);
      embree_failure(m.device, "rtcSetNewGeometryBuffer");
    }
    for (std::size_t k = 0; k < world.size(); ++k) {
      v[3 * k] = world[k].x;
      v[3 * k + 1] = world[k].y;
      v[3 * k + 2] = world[k].z;
    }
    std::copy(mesh.indices.begin(), mesh.indices.end(), idx);
    rtcCommitGeometry(g);
    const unsigned id = rtcAttachGeometry(m.scene, g);
    rtcReleaseGeometry(g);
    if (m.instance_of_geometry.size() <= id) m.instance_of_geometry.resize(id + 1, 0);
    m.instance_of_geometry[id] = i;
  }
  rtcCommitScene(m.scene);
  if (rtcGetDeviceError(m.device) != RTC_ERROR_NONE) embree_failure(m.device, "rtcCommitScene");
}

RayScene::~RayScene() = default;

std::optional<Hit> RayScene::intersect(const glm::vec3& o, const glm::vec3& d, float t_near,
                                       float t_far) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  rh.ray.org_x = o.x;
  rh.ray.org_y = o.y;
  rh.ray.org_z = o.z;
  rh.ray.dir_x = d.x;
  rh.ray.dir_y = d.y;
  rh.ray.dir_z = d.z;
  rh.ray.tnear = t_near;
  rh.ray.tfar = t_far;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  Hit h;
  h.instance = impl_->instance_of_geometry[rh.hit.geomID];
  h.triangle = rh.hit.primID;
  h.barycentric = {rh.hit.u, rh.hit.v};
  h.t = rh.ray.tfar;
  return h;
}

bool RayScene::occluded(const glm::vec3& o, const glm::vec3& d, float t_near, float t_far) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray{};
  ray.org_x = o.x;
  ray.org_y = o.y;
  ray.org_z = o.z;
  ray.dir_x = d.x;
  ray.dir_y = d.y;
  ray.dir_z = d.z;
  ray.tnear = t_near;
  ray.tfar = t_far;
  ray.mask = 0xFFFFFFFFu;
  rtcOccluded1(impl_->scene, &context, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

const std::vector<glm::vec3>& RayScene::world_positions(std::uint32_t instance) const {
  return impl_->positions.at(instance);
}
const glm::mat3& RayScene::normal_matrix(std::uint32_t instance) const {
  return impl_->normal_matrices.at(instance);
}

}  // namespace sss::reference
