// A glTF with no extras.sss, as a user's own file is: two boxes, "plastic" (metallic 0)
// and "metal" (metallic 1, the glTF default). Shared by the --sss-material tests of the
// overrides (MaterialOverridesTest) and of the executables (ViewerAppTest).
#pragma once

#include "scene/GltfTestWriter.h"

#include <cstdint>
#include <filesystem>
#include <vector>

namespace sss::testing {

// Two unit cubes side by side, `size_m` metres wide, in a file with no extras.sss: mesh 0
// wears "plastic" (metallic 0), mesh 1 "metal" (metallic 1, the glTF default). Flat
// normals, no UVs (so a subsurface material needs a generated atlas).
inline void write_two_boxes(const std::filesystem::path& path, float size_m) {
  scene::testing::GltfTestWriter w;
  std::vector<float> pos, nrm;
  std::vector<std::uint16_t> idx;
  const float h = 0.5f * size_m;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const auto base = std::uint16_t(pos.size() / 3);
      for (int k = 0; k < 4; ++k) {
        float p[3];
        p[axis] = float(sign) * h;
        p[u] = (k == 1 || k == 2) ? h : -h;
        p[v] = (k >= 2) ? h : -h;
        float n[3] = {0, 0, 0};
        n[axis] = float(sign);
        pos.insert(pos.end(), p, p + 3);
        nrm.insert(nrm.end(), n, n + 3);
      }
      // Counter-clockwise seen from outside.
      const std::uint16_t a = base, b = std::uint16_t(base + 1), c = std::uint16_t(base + 2),
                          d = std::uint16_t(base + 3);
      if (sign > 0) idx.insert(idx.end(), {a, b, c, a, c, d});
      else idx.insert(idx.end(), {a, c, b, a, d, c});
    }
  const int p = w.floats(pos, "VEC3", 3);
  w.doc["accessors"][p]["min"] = {-h, -h, -h};
  w.doc["accessors"][p]["max"] = {h, h, h};
  const int n = w.floats(nrm, "VEC3", 3);
  const int i = w.indices(idx);
  w.push("materials", {{"name", "plastic"},
                       {"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.8, 1.0}},
                                                 {"metallicFactor", 0.0}}}});
  w.push("materials", {{"name", "metal"}});
  for (int m = 0; m < 2; ++m) {
    nlohmann::json primitive = {{"attributes", {{"POSITION", p}, {"NORMAL", n}}},
                                {"indices", i}, {"material", m}};
    w.push("meshes", {{"primitives", nlohmann::json::array({primitive})}});
    w.push("nodes", {{"mesh", m}, {"translation", {m * 1.5 * size_m, 0.0, 0.0}}});
  }
  w.push("scenes", {{"nodes", {0, 1}}});
  w.doc["scene"] = 0;
  w.write_glb(path);
}

}  // namespace sss::testing
