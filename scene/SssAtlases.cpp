// The atlases texture space asks for (ensure_sss_atlases), their padding and gutter sized
// by the material's reach (reflectance_reach_mm).
#include "scene/UvAtlas.h"

#include "scene/Scene.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <cstdint>
#include <deque>
#include <exception>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <vector>

namespace sss::scene {

double reflectance_reach_mm(const profiles::RgbProfile& profile, double fraction) {
  const double step = std::log(1.02), r0 = 1e-4;
  const double r_max = std::min(1e4, std::max(profile.support_radius(), 1e-3));
  std::vector<double> r, dm;  // midpoints and their share of ∫ R 2πr dr (dr = r d ln r)
  for (double lo = r0; lo < r_max; lo *= 1.02) r.push_back(lo * std::sqrt(1.02));
  double reach = 0.0;
  for (int c = 0; c < 3; ++c) {
    const profiles::RadialProfile& p = profile.channel(c);
    dm.assign(r.size(), 0.0);
    double total = 0.0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      dm[i] = std::max(p.reflectance(r[i]), 0.0) * 2.0 * std::numbers::pi * r[i] * r[i] * step;
      total += dm[i];
    }
    if (!(total > 0.0)) continue;
    double sum = 0.0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      sum += dm[i];
      if (sum >= fraction * total) {
        reach = std::max(reach, r[i] * std::sqrt(1.02));
        break;
      }
    }
  }
  return reach;
}

std::size_t ensure_sss_atlases(Scene& scene, const AtlasOptions& options) {
  std::size_t generated = 0;
  for (Mesh& mesh : scene.meshes) {
    if (mesh.material >= scene.materials.size() || !scene.materials[mesh.material].sss.enabled)
      continue;
    if (!mesh.uv_atlas.empty()) continue;
    const UvCheck check = check_uvs(mesh);
    if (check.usable) continue;
    // The padding the material's reach asks for, at the scale a first layout gives (more
    // padding packs the charts smaller, so the gutter then reaches further still).
    AtlasOptions o = options;
    double reach_mm = 0.0;
    try {
      reach_mm = reflectance_reach_mm(scene.materials[mesh.material].sss.profile(), kGutterReflectanceShare);
    } catch (const std::exception&) {
      reach_mm = 0.0;  // a profile that cannot be made: the renderer reports it
    }
    if (reach_mm > 0.0) {
      o.max_gutter_reach = kGutterReachInReaches * reach_mm / scene.mm_per_unit;
      const double s = build_atlas(mesh, o).stats.uv_per_unit;  // UV per scene unit
      const double needed = reach_mm / scene.mm_per_unit * s * options.resolution / kGutterReachInPaddings;
      const double cap = double(kMaxPaddingTexels) * options.resolution / 1024.0;
      o.padding_texels = std::uint32_t(std::max(double(options.padding_texels), std::ceil(std::min(needed, cap))));
    }
    const AtlasStats stats = generate_atlas(mesh, o);
    char detail[160];
    std::snprintf(detail, sizeof detail,
                  "%zu charts, %.0f%% of the texture used, %u texels of padding for a %.1f mm reach",
                  stats.charts, 100.0 * stats.utilization, o.padding_texels, reach_mm);
    scene.texture_notes.push_back("mesh " + mesh.name + ": generated a UV atlas (" + check.reason +
                             "; " + detail + ")");
    ++generated;
  }
  return generated;
}

}  // namespace sss::scene
