#include "reference/PixelShading.h"

#include "profiles/Fresnel.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>

namespace sss::reference {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

CameraRays::CameraRays(const scene::Camera& cam, std::uint32_t width, std::uint32_t height, double mm_per_unit)
    : inv_view_proj_(glm::inverse(scene::clip_from_view(cam, width, height) * cam.view())),
      width_(width),
      height_(height),
      mm_(float(mm_per_unit)),
      ortho_(cam.projection == scene::Projection::Orthographic),
      forward_(cam.forward()) {}

CameraRays::Ray CameraRays::pixel(std::uint32_t x, std::uint32_t y) const {
  const glm::vec2 ndc((float(x) + 0.5f) / float(width_) * 2.0f - 1.0f, (float(y) + 0.5f) / float(height_) * 2.0f - 1.0f);
  const glm::vec4 a = inv_view_proj_ * glm::vec4(ndc, 0.0f, 1.0f);
  const glm::vec4 b = inv_view_proj_ * glm::vec4(ndc, 1.0f, 1.0f);
  const glm::vec3 near = glm::vec3(a) / a.w * mm_, far = glm::vec3(b) / b.w * mm_;
  Ray r;
  r.origin = near;
  r.direction = glm::normalize(far - near);
  r.t_far = glm::length(far - near);
  return r;
}

glm::dvec3 VisibleSurface::opaque_radiance() const { return scatter_factor * irradiance / kPi + specular; }

VisibleSurface visible_surface(const scene::Scene& s, const RayScene& rays, const CameraRays& camera, const Hit& hit,
                               const glm::vec3& direction, bool diffuse_only, const ShadowMaps* maps) {
  VisibleSurface v;
  v.point = surface_at(s, rays, hit.instance, hit.triangle, hit.barycentric);
  const scene::Material& m = s.materials[v.point.material];
  v.material = &m;
  v.subsurface = m.sss.enabled;
  v.to_eye = camera.to_eye(direction);
  v.normal = shading_normal(s, v.point, v.to_eye);
  v.albedo = base_colour(s, v.point);
  SpecularInputs spec;
  spec.to_eye = v.to_eye;
  spec.f0 = glm::mix(glm::vec3(0.04f * m.specular), v.albedo, m.metallic);
  spec.roughness = m.roughness;
  const bool want_specular = !diffuse_only && std::max({spec.f0.x, spec.f0.y, spec.f0.z}) > 0.0f;
  if (v.subsurface) {
    if (want_specular) v.specular = direct_light(s, rays, v.point, v.normal, &spec, maps).specular;
  } else if (!diffuse_only) {
    const DirectLight d = direct_light(s, rays, v.point, v.normal, want_specular ? &spec : nullptr, maps);
    v.irradiance = d.irradiance;
    v.specular = d.specular;
  }
  const bool pre_post = v.subsurface && m.sss.albedo_mode == scene::AlbedoMode::PrePost;
  const glm::dvec3 albedo(v.albedo);
  v.scatter_factor = (pre_post ? glm::sqrt(albedo) : albedo) * (1.0 - double(m.metallic));
  if (v.subsurface) {
    const auto eta = m.sss.medium.eta;  // the scale leaves η alone
    const double cos_o = std::clamp(double(glm::dot(v.normal, v.to_eye)), 0.0, 1.0);
    for (int c = 0; c < 3; ++c)
      v.exit_fresnel[c] =
          profiles::fresnel_transmittance(cos_o, eta[c]) / profiles::fresnel_exit_normalization(eta[c]);
  }
  return v;
}

void store_specular(image::Image& specular, std::uint32_t x, std::uint32_t y, const VisibleSurface& v,
                    bool diffuse_only) {
  float* sp = specular.pixel(int(x), int(y));
  for (int c = 0; c < 3; ++c) sp[c] = diffuse_only ? 0.0f : float(v.specular[c]);
  sp[3] = 1.0f;
}

}  // namespace sss::reference
