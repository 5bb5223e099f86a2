// Cameras and KHR_lights_punctual lights referenced by nodes: every parameter checked
// against the glTF and extension specs, placed with the node's rigid world transform.
#include "scene/GltfContext.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <limits>
#include <numbers>

namespace sss::scene {

namespace {

constexpr double kFloatMax = std::numeric_limits<float>::max();

// The rotation and translation of `world`: cameras and lights ignore scale.
std::variant<glm::mat4, std::string> rigid(const glm::dmat4& world) {
  glm::dmat4 r = world;
  for (int c = 0; c < 3; ++c) {
    const double len = glm::length(glm::dvec3(r[c]));
    if (!(len > 1e-12) || !std::isfinite(len)) return std::string("has a degenerate world transform");
    r[c] /= len;
  }
  return glm::mat4(r);
}

}  // namespace

Status add_camera(GltfContext& ctx, int index, const glm::dmat4& world, const std::string& node) {
  if (auto e = out_of_range("cameras", index, ctx.model.cameras.size()))
    return ctx.fail(node, "camera", *e);
  const tinygltf::Camera& gc = ctx.model.cameras[std::size_t(index)];
  const std::string object = indexed("cameras", std::size_t(index));
  Camera cam;
  cam.name = gc.name.empty() ? object : gc.name;
  const auto bad = [&](const char* field, double v, const char* rule) {
    return ctx.fail(object, field, std::string("must be ") + rule + ", got " + number_text(v));
  };
  if (gc.type == "perspective") {
    const auto& p = gc.perspective;
    if (!(p.yfov > 0.0 && p.yfov < std::numbers::pi)) return bad("perspective.yfov", p.yfov, "in (0, pi)");
    if (!(p.aspectRatio >= 0.0 && p.aspectRatio < 1e6)) return bad("perspective.aspectRatio", p.aspectRatio, ">= 0");
    if (!(p.znear > 0.0 && p.znear < kFloatMax)) return bad("perspective.znear", p.znear, "> 0");
    if (!(p.zfar == 0.0 || (p.zfar > p.znear && p.zfar < kFloatMax)))
      return bad("perspective.zfar", p.zfar, "> znear (or absent for infinite)");
    cam.projection = Projection::Perspective;
    cam.yfov = float(p.yfov);
    cam.aspect = float(p.aspectRatio);
    cam.znear = float(p.znear);
    cam.zfar = float(p.zfar);
  } else if (gc.type == "orthographic") {
    const auto& o = gc.orthographic;
    if (!(std::isfinite(o.xmag) && o.xmag != 0.0 && std::fabs(o.xmag) < kFloatMax)) return bad("orthographic.xmag", o.xmag, "finite and not 0");
    if (!(std::isfinite(o.ymag) && o.ymag != 0.0 && std::fabs(o.ymag) < kFloatMax)) return bad("orthographic.ymag", o.ymag, "finite and not 0");
    if (!(o.znear >= 0.0 && o.znear < kFloatMax)) return bad("orthographic.znear", o.znear, ">= 0");
    if (!(o.zfar > o.znear && o.zfar < kFloatMax)) return bad("orthographic.zfar", o.zfar, "> znear");
    cam.projection = Projection::Orthographic;
    cam.xmag = float(std::fabs(o.xmag));
    cam.ymag = float(std::fabs(o.ymag));
    cam.znear = float(o.znear);
    cam.zfar = float(o.zfar);
  } else {
    return ctx.fail(object, "type", "must be \"perspective\" or \"orthographic\", got \"" + gc.type + "\"");
  }
  auto r = rigid(world);
  if (auto* msg = std::get_if<std::string>(&r)) return ctx.fail(node, "", "camera node " + *msg);
  cam.world = std::get<glm::mat4>(r);
  ctx.scene.cameras.push_back(cam);
  return std::nullopt;
}

Status add_light(GltfContext& ctx, const tinygltf::Value& ext, const glm::dmat4& world,
                 const std::string& node) {
  const char* field = "extensions.KHR_lights_punctual.light";
  if (!ext.IsObject() || !ext.Get("light").IsInt())
    return ctx.fail(node, field, "must be an integer light index");
  const int index = ext.Get("light").GetNumberAsInt();
  if (auto e = out_of_range("KHR_lights_punctual.lights", index, ctx.model.lights.size()))
    return ctx.fail(node, field, *e);
  const tinygltf::Light& gl = ctx.model.lights[std::size_t(index)];
  const std::string object = "extensions.KHR_lights_punctual.lights[" + std::to_string(index) + "]";
  Light l;
  l.name = gl.name.empty() ? object : gl.name;
  if (gl.type == "directional") l.type = LightType::Directional;
  else if (gl.type == "point") l.type = LightType::Point;
  else if (gl.type == "spot") l.type = LightType::Spot;
  else return ctx.fail(object, "type", "must be directional, point or spot, got \"" + gl.type + "\"");
  if (!gl.color.empty()) {
    if (gl.color.size() != 3) return ctx.fail(object, "color", "must have 3 numbers");
    for (int c = 0; c < 3; ++c) {
      const double v = gl.color[std::size_t(c)];
      if (!(v >= 0.0 && v <= 1e6))
        return ctx.fail(object, "color[" + std::to_string(c) + "]", "must be >= 0 and finite, got " + number_text(v));
      l.color[c] = float(v);
    }
  }
  if (!(gl.intensity >= 0.0 && gl.intensity < kFloatMax))
    return ctx.fail(object, "intensity", "must be >= 0 and finite, got " + number_text(gl.intensity));
  if (!(gl.range >= 0.0 && gl.range < kFloatMax))
    return ctx.fail(object, "range", "must be > 0 and finite (or absent), got " + number_text(gl.range));
  l.intensity = float(gl.intensity);
  l.range = float(gl.range);
  if (l.type == LightType::Spot) {
    const double inner = gl.spot.innerConeAngle, outer = gl.spot.outerConeAngle;
    if (!(outer > 0.0 && outer <= std::numbers::pi / 2))
      return ctx.fail(object, "spot.outerConeAngle", "must lie in (0, pi/2], got " + number_text(outer));
    if (!(inner >= 0.0 && inner < outer))
      return ctx.fail(object, "spot.innerConeAngle", "must lie in [0, outerConeAngle), got " + number_text(inner));
    l.inner_cone = float(inner);
    l.outer_cone = float(outer);
  }
  auto r = rigid(world);
  if (auto* msg = std::get_if<std::string>(&r)) return ctx.fail(node, "", "light node " + *msg);
  l.world = std::get<glm::mat4>(r);
  ctx.scene.lights.push_back(l);
  return std::nullopt;
}

}  // namespace sss::scene
