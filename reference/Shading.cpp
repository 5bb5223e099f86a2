#include "reference/Shading.h"

#include "profiles/Fresnel.h"
#include "profiles/Random.h"

#include "image/Image.h"
#include "scene/SplitSum.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace sss::reference {

namespace {

constexpr double kPi = 3.14159265358979323846;

float wrap_coord(float u, scene::Wrap wrap) {
  switch (wrap) {
    case scene::Wrap::ClampToEdge: return std::clamp(u, 0.0f, 1.0f);
    case scene::Wrap::MirroredRepeat: {
      const float f = u - 2.0f * std::floor(0.5f * u);  // [0, 2)
      return f > 1.0f ? 2.0f - f : f;
    }
    case scene::Wrap::Repeat: break;
  }
  return u - std::floor(u);
}

int wrap_texel(int i, int n, scene::Wrap wrap) {
  if (wrap == scene::Wrap::Repeat) return ((i % n) + n) % n;
  if (wrap == scene::Wrap::MirroredRepeat) {
    const int period = 2 * n;
    int m = ((i % period) + period) % period;
    return m < n ? m : period - 1 - m;
  }
  return std::clamp(i, 0, n - 1);
}

// Bilinear (or nearest) lookup at level 0; `srgb` decodes each texel before filtering,
// as an sRGB image view does.
glm::vec4 sample(const scene::Texture& t, glm::vec2 uv, bool srgb) {
  const scene::ImageRgba8& img = *t.image;
  const int w = int(img.width), h = int(img.height);
  auto texel = [&](int x, int y) {
    x = wrap_texel(x, w, t.sampler.wrap_s);
    y = wrap_texel(y, h, t.sampler.wrap_t);
    const std::uint8_t* p = &img.pixels[(std::size_t(y) * w + x) * 4];
    glm::vec4 c;
    for (int k = 0; k < 4; ++k) {
      const float v = float(p[k]) / 255.0f;
      c[k] = (srgb && k < 3) ? image::srgb_decode(v) : v;
    }
    return c;
  };
  const float u = wrap_coord(uv.x, t.sampler.wrap_s) * float(w) - 0.5f;
  const float v = wrap_coord(uv.y, t.sampler.wrap_t) * float(h) - 0.5f;
  if (t.sampler.mag == scene::Filter::Nearest)
    return texel(int(std::floor(u + 0.5f)), int(std::floor(v + 0.5f)));
  const int x0 = int(std::floor(u)), y0 = int(std::floor(v));
  const float fx = u - float(x0), fy = v - float(y0);
  return (texel(x0, y0) * (1.0f - fx) + texel(x0 + 1, y0) * fx) * (1.0f - fy) +
         (texel(x0, y0 + 1) * (1.0f - fx) + texel(x0 + 1, y0 + 1) * fx) * fy;
}

}  // namespace

SurfacePoint surface_at(const scene::Scene& s, const RayScene& rays, std::uint32_t instance,
                        std::uint32_t triangle, const glm::vec2& b) {
  const scene::Instance& inst = s.instances[instance];
  const scene::Mesh& mesh = s.meshes[inst.mesh];
  const std::uint32_t i0 = mesh.indices[3 * triangle], i1 = mesh.indices[3 * triangle + 1],
                      i2 = mesh.indices[3 * triangle + 2];
  const float w0 = 1.0f - b.x - b.y;
  const std::vector<glm::vec3>& world = rays.world_positions(instance);
  SurfacePoint p;
  p.material = mesh.material;
  p.position_mm = world[i0] * w0 + world[i1] * b.x + world[i2] * b.y;
  const glm::vec3 gn = glm::cross(world[i1] - world[i0], world[i2] - world[i0]);
  const float gl = glm::length(gn);
  p.geometric_normal = gl > 0.0f ? gn / gl : glm::vec3(0.0f, 0.0f, 1.0f);
  const glm::mat3& nm = rays.normal_matrix(instance);
  const glm::vec3 n = nm * (mesh.normals[i0] * w0 + mesh.normals[i1] * b.x + mesh.normals[i2] * b.y);
  const float nl = glm::length(n);
  p.normal = nl > 0.0f ? n / nl : p.geometric_normal;
  if (!mesh.uv0.empty()) {
    p.has_uv = true;
    p.uv = mesh.uv0[i0] * w0 + mesh.uv0[i1] * b.x + mesh.uv0[i2] * b.y;
  }
  if (!mesh.tangents.empty()) {
    const glm::vec4 t = mesh.tangents[i0] * w0 + mesh.tangents[i1] * b.x + mesh.tangents[i2] * b.y;
    p.tangent = glm::vec4(glm::mat3(inst.world) * glm::vec3(t), mesh.tangents[i0].w);
  }
  if (const std::vector<SkyTransfer>* sky = rays.sky_transfers(instance))
    for (int k = 0; k < 9; ++k)
      p.sky_blocked[k] = (*sky)[i0][k] * w0 + (*sky)[i1][k] * b.x + (*sky)[i2][k] * b.y;
  return p;
}

glm::vec3 base_colour(const scene::Scene& s, const SurfacePoint& p) {
  const scene::Material& m = s.materials[p.material];
  glm::vec3 c(m.base_color);
  if (m.base_color_texture && p.has_uv)
    c *= glm::vec3(sample(s.textures[*m.base_color_texture], p.uv, true));
  return glm::clamp(c, glm::vec3(0.0f), glm::vec3(1.0f));
}

glm::vec3 shading_normal(const scene::Scene& s, const SurfacePoint& p, const glm::vec3& to_eye) {
  glm::vec3 n = p.normal;
  const float facing = glm::dot(n, to_eye) < 0.0f ? -1.0f : 1.0f;
  n *= facing;
  const scene::Material& m = s.materials[p.material];
  if (m.normal_texture && p.has_uv && glm::dot(glm::vec3(p.tangent), glm::vec3(p.tangent)) > 0.0f) {
    const glm::vec3 tan(p.tangent);
    const glm::vec3 t = glm::normalize(tan - n * glm::dot(n, tan));
    const glm::vec3 bt = glm::cross(n, t) * p.tangent.w * facing;
    glm::vec3 mn = glm::vec3(sample(s.textures[*m.normal_texture], p.uv, false)) * 2.0f - 1.0f;
    mn.x *= m.normal_scale;
    mn.y *= m.normal_scale;
    n = glm::normalize(t * mn.x + bt * mn.y + n * std::max(mn.z, 1e-4f));
  }
  return n;
}

std::optional<LightArrival> light_arrival(const scene::Scene& s, std::size_t index, const glm::vec3& p_mm,
                                         const ShadowMaps* maps) {
  const scene::Light& light = s.lights[index];
  if (maps && !maps->shaded(index)) return std::nullopt;
  const float mm_per_unit = float(s.mm_per_unit);
  if (!light.reaches(p_mm / mm_per_unit)) return std::nullopt;
  LightArrival a;
  a.radiance = glm::dvec3(light.color) * double(light.intensity);
  if (light.type == scene::LightType::Directional) {
    a.l = -light.direction();
    return a;
  }
  const glm::vec3 d = light.position() * mm_per_unit - p_mm;  // mm
  a.distance_mm = glm::length(d);
  if (!(a.distance_mm > 0.0f)) return std::nullopt;
  a.l = d / a.distance_mm;
  const double d_units = double(a.distance_mm) / double(mm_per_unit);
  a.radiance /= std::max(d_units * d_units, 1e-8);
  if (light.type == scene::LightType::Spot) {
    const double lo = std::cos(light.outer_cone), hi = std::cos(light.inner_cone);
    const double c = glm::dot(-a.l, light.direction());
    const double t = std::clamp((c - lo) / std::max(hi - lo, 1e-9), 0.0, 1.0);
    a.radiance *= t * t * (3.0 - 2.0 * t);  // GLSL smoothstep
  }
  return a;
}

double light_visibility(const RayScene& rays, std::size_t index, const SurfacePoint& p, const glm::vec3& n,
                        const LightArrival& a, const ShadowMaps* maps) {
  if (maps) return maps->visibility(index, p.position_mm, n);
  // Shadow rays leave from just off the surface, on the side the light is on.
  const float offset = 1e-4f * std::max(1.0f, glm::length(p.position_mm)) + 1e-4f;
  const glm::vec3 side = glm::dot(p.geometric_normal, a.l) >= 0.0f ? p.geometric_normal : -p.geometric_normal;
  return rays.occluded(p.position_mm + side * offset, a.l, 0.0f, a.distance_mm - 2.0f * offset) ? 0.0 : 1.0;
}

namespace {

// Stratified directions about a point's normal n for the environment's estimates: n's
// tangent frame, a generator seeded from the point's position and a salt (the same point
// always gets the same estimate, neighbours independent ones), and whether the sky is
// open along a direction, from just off the surface on its side.
class PointSky {
 public:
  PointSky(const RayScene& rays, const SurfacePoint& p, const glm::vec3& n, std::uint64_t salt)
      : rays_(rays), p_(p), n_(n), rng_(seed(p, salt)) {
    const glm::vec3 t = std::fabs(n.x) > 0.9f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    b1_ = glm::normalize(glm::cross(t, n));
    b2_ = glm::cross(n, b1_);
    offset_ = 1e-4f * std::max(1.0f, glm::length(p.position_mm)) + 1e-4f;
  }
  // A jittered point of stratum (i, j) of kEnvironmentStrata² over the unit square.
  glm::dvec2 stratum(int i, int j) {
    const double k = kEnvironmentStrata;
    const double u1 = (i + rng_.uniform()) / k;
    return {u1, (j + rng_.uniform()) / k};
  }
  // The unit direction with cosine `cos_n` to n at azimuth phi.
  glm::vec3 direction(double cos_n, double phi) const {
    const double s = std::sqrt(std::max(0.0, 1.0 - cos_n * cos_n));
    return glm::normalize(b1_ * float(s * std::cos(phi)) + b2_ * float(s * std::sin(phi)) + n_ * float(cos_n));
  }
  bool open(const glm::vec3& w) const {
    const glm::vec3 side = glm::dot(p_.geometric_normal, w) >= 0.0f ? p_.geometric_normal : -p_.geometric_normal;
    return !rays_.occluded(p_.position_mm + side * offset_, w, 0.0f, std::numeric_limits<float>::infinity());
  }

 private:
  static std::uint64_t seed(const SurfacePoint& p, std::uint64_t salt) {
    for (int c = 0; c < 3; ++c) {
      std::uint32_t bits = 0;
      std::memcpy(&bits, &p.position_mm[c], sizeof(bits));
      salt = profiles::SplitMix64(salt ^ bits).next();
    }
    return salt;
  }
  const RayScene& rays_;
  const SurfacePoint& p_;
  glm::vec3 n_, b1_{0.0f}, b2_{0.0f};
  profiles::Xoshiro256ss rng_;
  float offset_ = 0.0f;
};

}  // namespace

glm::dvec3 environment_irradiance(const scene::Environment& env, const RayScene& rays, const SurfacePoint& p,
                                  const glm::vec3& n, bool as_gpu, const glm::dvec3* entry_eta) {
  if (as_gpu) {
    // As shade() takes it: the harmonics' irradiance less what the bake says is blocked.
    glm::dvec3 e(glm::max(env.irradiance(n) - blocked_irradiance(env.irradiance_sh, p.sky_blocked), glm::vec3(0.0f)));
    // The GPU's entry factor for a sky: c, the cosine-weighted mean of F_t over the
    // hemisphere (shading.glsl), exact for a uniform sky.
    if (entry_eta)
      for (int c = 0; c < 3; ++c) e[c] *= profiles::fresnel_exit_normalization((*entry_eta)[c]);
    return e;
  }
  // E = integral of L(w) V(w) cos over the hemisphere = pi E_cos[L V] for w drawn with
  // density cos / pi (cos = sqrt(1 - u1), azimuth 2 pi u2): kEnvironmentStrata^2
  // stratified samples (Shirley & Chiu's map of the square to the disc would do as well;
  // these strata are compact enough at this count).
  PointSky sky(rays, p, n, 0x5EEDu);
  const int k = kEnvironmentStrata;
  glm::dvec3 sum(0.0);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      const glm::dvec2 u = sky.stratum(i, j);
      const glm::vec3 w = sky.direction(std::sqrt(std::max(0.0, 1.0 - u.x)), 2.0 * kPi * u.y);
      if (!sky.open(w)) continue;
      glm::dvec3 l(env.radiance(w));
      if (entry_eta)  // the part that enters at this direction's cosine
        for (int c = 0; c < 3; ++c) l[c] *= profiles::fresnel_transmittance(glm::dot(n, w), (*entry_eta)[c]);
      sum += l;
    }
  return sum * (kPi / double(k * k));
}

glm::dvec3 environment_specular(const scene::Environment& env, const RayScene& rays, const SurfacePoint& p,
                                const glm::vec3& n, const SpecularInputs& spec, bool as_gpu) {
  const glm::vec3& v = spec.to_eye;
  const float n_dot_v = std::max(glm::dot(n, v), 1e-4f);
  const glm::dvec3 f0(spec.f0);
  if (as_gpu) {
    // The split sum, as lighting.comp evaluates it (no occlusion).
    const glm::vec3 r = glm::reflect(-v, n);
    const glm::vec2 ab = scene::dfg_lookup(n_dot_v, spec.roughness);
    return glm::dvec3(env.specular_radiance(r, spec.roughness)) * (f0 * double(ab.x) + double(ab.y));
  }
  // integral of L(l) V(l) f(v, l) n.l dl with l = reflect(-v, h), h drawn from
  // D(h) n.h: each sample weighs L V F vis 4 (v.h) (n.l) / (n.h) (D cancels).
  // kEnvironmentStrata² stratified samples, seeded from the point as the irradiance is.
  PointSky sky(rays, p, n, 0x5BEC0u);
  const double alpha = scene::ggx_alpha(spec.roughness), a2 = alpha * alpha;
  const int k = kEnvironmentStrata;
  glm::dvec3 sum(0.0);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      const glm::dvec2 u = sky.stratum(i, j);
      const double cos_h = scene::ggx_normal_cosine(u.x, a2);
      const glm::vec3 h = sky.direction(cos_h, 2.0 * kPi * u.y);
      const double vh = glm::dot(v, h);
      if (vh <= 0.0) continue;
      const glm::vec3 l = glm::normalize(2.0f * float(vh) * h - v);
      const double nl = glm::dot(n, l);
      if (nl <= 0.0 || !sky.open(l)) continue;
      const glm::dvec3 F = f0 + (1.0 - f0) * std::pow(1.0 - vh, 5.0);
      sum += glm::dvec3(env.radiance(l)) * F * (scene::smith_visibility(nl, n_dot_v, a2) * 4.0 * vh * nl / cos_h);
    }
  return sum / double(k * k);
}

DirectLight direct_light(const scene::Scene& s, const RayScene& rays, const SurfacePoint& p,
                         const glm::vec3& n, const SpecularInputs* spec, const ShadowMaps* maps,
                         const glm::dvec3* entry_eta) {
  DirectLight out;
  // The environment: with directional Fresnel (entry_eta), the part that enters; its
  // specular is sampled (or, with the GPU's shadow maps, the GPU's split sum).
  if (s.environment) {
    out.irradiance += environment_irradiance(*s.environment, rays, p, n, maps != nullptr, entry_eta);
    if (spec) out.specular += environment_specular(*s.environment, rays, p, n, *spec, maps != nullptr);
  }
  for (std::size_t index = 0; index < s.lights.size(); ++index) {
    const std::optional<LightArrival> a = light_arrival(s, index, p.position_mm, maps);
    if (!a) continue;
    const glm::vec3 l = a->l;
    const float n_dot_l = glm::dot(n, l);
    if (n_dot_l <= 0.0f) continue;
    const double visibility = light_visibility(rays, index, p, n, *a, maps);
    if (!(visibility > 0.0)) continue;
    const glm::dvec3 radiance = a->radiance;
    const glm::dvec3 incident = radiance * double(n_dot_l) * visibility;
    if (entry_eta) {
      for (int c = 0; c < 3; ++c)
        out.irradiance[c] += incident[c] * profiles::fresnel_transmittance(n_dot_l, (*entry_eta)[c]);
    } else {
      out.irradiance += incident;
    }
    if (spec) {
      const glm::vec3& v = spec->to_eye;
      const double n_dot_v = std::max(double(glm::dot(n, v)), 1e-4);
      const double alpha = std::max(double(spec->roughness) * spec->roughness, 1e-3);
      const double a2 = alpha * alpha;
      const glm::vec3 h = glm::normalize(l + v);
      const double n_dot_h = std::max(double(glm::dot(n, h)), 0.0);
      const double v_dot_h = std::max(double(glm::dot(v, h)), 0.0);
      const double dd = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
      const double D = a2 / (kPi * dd * dd);
      const double vis = scene::smith_visibility(n_dot_l, n_dot_v, a2);
      const glm::dvec3 f0(spec->f0);
      const glm::dvec3 F = f0 + (1.0 - f0) * std::pow(1.0 - v_dot_h, 5.0);
      out.specular += D * vis * F * incident;
    }
  }
  return out;
}

}  // namespace sss::reference
