#include "ScatterScale.h"

#include "scene/Material.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace sss::scene {

ScatterScale scatter_scale(const SssMaterial& sss, double object_mm, double pixel_min_mm) {
  ScatterScale out;
  out.object_mm = object_mm;
  out.pixel_min_mm = pixel_min_mm;
  if (!sss.enabled) return out;
  const profiles::Medium m = sss.effective_medium();
  out.mfp_min_mm = out.diffusion_min_mm = std::numeric_limits<double>::infinity();
  for (int c = 0; c < 3; ++c) {
    const profiles::Coefficients k = m.channel(c);
    const double mfp = k.mfp_reduced();
    const double diffusion = 1.0 / k.sigma_tr_classical();
    out.mfp_min_mm = std::min(out.mfp_min_mm, mfp);
    out.mfp_max_mm = std::max(out.mfp_max_mm, mfp);
    out.diffusion_min_mm = std::min(out.diffusion_min_mm, diffusion);
    out.diffusion_max_mm = std::max(out.diffusion_max_mm, diffusion);
  }
  return out;
}

ScatterScale scatter_scale(const Scene& scene, std::size_t material, std::uint32_t height) {
  if (material >= scene.materials.size()) return {};
  Bounds b;
  for (const Instance& inst : scene.instances)
    if (inst.mesh < scene.meshes.size() && scene.meshes[inst.mesh].material == material)
      b.extend(scene.meshes[inst.mesh].bounds.transformed(inst.world));
  const ScatterScale medium_only = scatter_scale(scene.materials[material].sss, 0.0);
  if (b.empty()) return medium_only;
  const double object_mm = double(glm::length(b.extent())) * scene.mm_per_unit;
  double pixel_mm = 0.0;
  if (height != 0 && !scene.cameras.empty()) {
    const Camera& cam = scene.cameras.front();
    const glm::vec3 eye = cam.position();
    const glm::vec3 nearest = glm::clamp(eye, b.min, b.max);
    const double distance = double(glm::length(nearest - eye)) * scene.mm_per_unit;
    if (cam.projection == Projection::Orthographic)
      pixel_mm = 2.0 * double(cam.ymag) * scene.mm_per_unit / double(height);
    else if (distance > 0.0)
      pixel_mm = 2.0 * distance * std::tan(0.5 * double(cam.yfov)) / double(height);
  }
  return scatter_scale(scene.materials[material].sss, object_mm, pixel_mm);
}

std::string scatter_scale_readout(const ScatterScale& s) {
  if (s.object_mm <= 0.0 || !(s.mfp_max_mm > 0.0)) return {};
  std::ostringstream o;
  // Two significant digits, without an exponent from 100 to 10^6 mm (a metre is "1000").
  const auto num = [&](double v) {
    if (v >= 100.0 && v < 1e6) o << std::llround(v);
    else o << std::setprecision(2) << v;
  };
  const auto range = [&](double lo, double hi) {
    num(lo);
    if (hi - lo > 0.005 * hi) o << "-", num(hi);
  };
  o << "mfp ";
  range(s.mfp_min_mm, s.mfp_max_mm);
  o << " mm, diffusion ";
  range(s.diffusion_min_mm, s.diffusion_max_mm);
  o << " mm; object ";
  num(s.object_mm);
  o << " mm (";
  num(100.0 * s.diffusion_max_mm / s.object_mm);
  o << "%)";
  return o.str();
}

std::optional<std::string> scatter_scale_warning(const Scene& scene, std::size_t material,
                                                 std::uint32_t height) {
  if (material >= scene.materials.size()) return std::nullopt;
  return scatter_scale_warning(scene.materials[material], scatter_scale(scene, material, height));
}

std::optional<std::string> scatter_scale_warning(const Material& mat, const ScatterScale& s) {
  if (s.object_mm <= 0.0 || !mat.sss.enabled) return std::nullopt;
  std::ostringstream w;
  w.precision(3);
  w << "material '" << mat.name << "' (scale " << mat.sss.scale << "): ";
  if (s.pixel_min_mm > 0.0 && 3.0 * s.diffusion_max_mm < s.pixel_min_mm) {
    w << "scatters below one pixel everywhere: 3 diffusion lengths are " << 3.0 * s.diffusion_max_mm
      << " mm, a pixel covers at least " << s.pixel_min_mm << " mm of the " << s.object_mm
      << " mm object. Lower its scale (a distance d on the object scatters as d x scale; "
      << mat.sss.scale * 3.0 * s.diffusion_max_mm / s.pixel_min_mm
      << " reaches one pixel), or check the units: σ are per mm, mfp in mm";
    return w.str();
  }
  if (s.diffusion_min_mm > s.object_mm) {
    w << "scatters wider than the object: its shortest diffusion length, " << s.diffusion_min_mm
      << " mm, is longer than the object's " << s.object_mm
      << " mm diameter, so light spreads through all of it. Raise its scale (a distance d on the "
         "object scatters as d x scale), or check the units: σ are per mm, mfp in mm";
    return w.str();
  }
  return std::nullopt;
}

}  // namespace sss::scene
