// KHR_mesh_quantization and KHR_texture_transform (issue 21): quantized attributes decode
// by glTF's normalized-integer formulas, a texture transform is applied to the UVs, what
// the extensions do not allow is refused naming the field; and files written by Debian's
// gltfpack (quantized, texture-transformed) load as the originals within the
// quantization's own step.
#include "renderer/scene/GltfLoader.h"

#include "GltfTestWriter.h"
#include "LoadExpect.h"
#include "tests/common/CliRun.h"

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

namespace sss::scene {
namespace {

using testing::GltfTestWriter;
using testing::TempDir;
using testing::load_error;
using testing::load_ok;
using testing::tiny_png;


// A triangle with quantized POSITION (SHORT, not normalized, stride 8), NORMAL (BYTE
// normalized, stride 4), TEXCOORD_0 (UNSIGNED_SHORT normalized) and a textured material;
// `transform` goes on the base colour texture. gltfpack's way: the node's scale
// dequantizes the positions. Accessors: 0 POSITION, 1 NORMAL, 2 TEXCOORD_0.
GltfTestWriter quantized_triangle(bool declare_extension, const nlohmann::json& transform = nullptr) {
  GltfTestWriter w;
  const std::vector<std::int16_t> pos = {0, 0, 0, 0, 1000, 0, 0, 0, 0, -2000, 0, 0};
  const std::vector<std::int8_t> nrm = {0, 0, 127, 0, 0, 0, 127, 0, -128, 0, 0, 0};
  const std::vector<std::uint16_t> uv = {0, 0, 65535, 0, 0, 32768};
  const int p = w.accessor(w.view(pos.data(), pos.size() * 2, 8), 5122, 3, "VEC3");
  const int n = w.accessor(w.view(nrm.data(), nrm.size(), 4), 5120, 3, "VEC3", true);
  const int t = w.accessor(w.view(uv.data(), uv.size() * 2), 5123, 3, "VEC2", true);
  const auto png = tiny_png();
  w.push("images", {{"bufferView", w.view(png.data(), png.size())}, {"mimeType", "image/png"}});
  w.push("textures", {{"source", 0}});
  nlohmann::json info = {{"index", 0}};
  if (!transform.is_null()) info["extensions"] = {{"KHR_texture_transform", transform}};
  w.push("materials", {{"pbrMetallicRoughness", {{"baseColorTexture", info}}}});
  w.push("meshes", {{"primitives", {{{"attributes", {{"POSITION", p}, {"NORMAL", n}, {"TEXCOORD_0", t}}},
                                     {"material", 0}}}}});
  w.push("nodes", {{"mesh", 0}, {"scale", {0.001, 0.001, 0.001}}});
  w.doc["scenes"] = {{{"nodes", {0}}}};
  if (declare_extension) {
    w.doc["extensionsUsed"] = {"KHR_mesh_quantization", "KHR_texture_transform"};
    w.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
  }
  return w;
}

}  // namespace

// glTF 2.0's decoding: BYTE normalized max(c/127, -1), UNSIGNED_SHORT normalized c/65535,
// integers as themselves (then the node's scale); normals renormalised.
TEST(MeshQuantization, QuantizedAttributesDecodeByTheSpecsFormulas) {
  const TempDir dir("quantized");
  GltfTestWriter w = quantized_triangle(true);
  w.write_gltf(dir / "q.gltf");
  const Scene s = load_ok(dir / "q.gltf");
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& m = s.meshes[0];
  EXPECT_EQ(m.positions[1], glm::vec3(1000, 0, 0));  // the node's scale is the instance's
  EXPECT_EQ(m.positions[2], glm::vec3(0, -2000, 0));
  EXPECT_EQ(m.normals[0], glm::vec3(0, 0, 1));
  EXPECT_EQ(m.normals[2], glm::vec3(-1, 0, 0));  // -128/127 clamps to -1
  EXPECT_FLOAT_EQ(m.uv0[1].x, 1.0f);
  EXPECT_FLOAT_EQ(m.uv0[2].y, 32768.0f / 65535.0f);

  // Without the extension in extensionsUsed the same accessors are refused, and the
  // message says what would make them legal.
  w.doc.erase("extensionsUsed");
  w.doc.erase("extensionsRequired");
  w.write_gltf(dir / "plain.gltf");
  const std::string e = load_error(dir / "plain.gltf");
  EXPECT_NE(e.find("KHR_mesh_quantization"), std::string::npos) << e;
  EXPECT_NE(e.find("accessors[0]"), std::string::npos) << e;

  // NORMAL may not be an unnormalized integer even with the extension.
  w.doc["extensionsUsed"] = {"KHR_mesh_quantization"};
  w.doc["accessors"][1].erase("normalized");
  w.write_gltf(dir / "bad_normal.gltf");
  const std::string b = load_error(dir / "bad_normal.gltf");
  EXPECT_NE(b.find("accessors[1].componentType: NORMAL cannot be BYTE"), std::string::npos) << b;

}

// KHR_texture_transform's matrix T·R·S, computed here as a complex rotation: u + iv
// scaled, turned by -rotation, then offset.
TEST(TextureTransform, TheUvsAreTransformedAsTheExtensionSays) {
  const TempDir dir("texture_transform");
  const double rot = 0.7, sx = 2.0, sy = 0.5, ox = 0.25, oy = -1.5;
  GltfTestWriter w = quantized_triangle(
      true, {{"offset", {ox, oy}}, {"rotation", rot}, {"scale", {sx, sy}}});
  w.write_gltf(dir / "t.gltf");
  const Scene s = load_ok(dir / "t.gltf");
  ASSERT_EQ(s.meshes.size(), 1u);
  const float raw[3][2] = {{0, 0}, {1, 0}, {0, 32768.0f / 65535.0f}};
  for (int i = 0; i < 3; ++i) {
    const std::complex<double> scaled(sx * raw[i][0], sy * raw[i][1]);
    const std::complex<double> turned = scaled * std::polar(1.0, -rot) + std::complex<double>(ox, oy);
    EXPECT_NEAR(s.meshes[0].uv0[std::size_t(i)].x, turned.real(), 1e-6) << i;
    EXPECT_NEAR(s.meshes[0].uv0[std::size_t(i)].y, turned.imag(), 1e-6) << i;
  }
  // A texCoord override to a set the renderer does not read: the texture is not drawn, as
  // for a textureInfo naming it.
  GltfTestWriter w2 = quantized_triangle(true, {{"texCoord", 1}});
  w2.write_gltf(dir / "t2.gltf");
  const Scene s2 = load_ok(dir / "t2.gltf");
  EXPECT_FALSE(s2.materials[0].base_color_texture.has_value());
  // Bad values name the field.
  for (const auto& [tf, field] : std::vector<std::pair<nlohmann::json, std::string>>{
           {{{"scale", {1.0}}}, "KHR_texture_transform.scale"},
           {{{"offset", {"a", 0}}}, "KHR_texture_transform.offset"},
           {{{"rotation", "x"}}, "KHR_texture_transform.rotation"},
           {{{"texCoord", -1}}, "KHR_texture_transform.texCoord"},
           {nlohmann::json::array({1}), "KHR_texture_transform"}}) {
    GltfTestWriter b = quantized_triangle(true, tf);
    b.write_gltf(dir / "bad.gltf");
    const std::string e = load_error(dir / "bad.gltf");
    EXPECT_NE(e.find("materials[0].pbrMetallicRoughness.baseColorTexture.extensions." + field),
              std::string::npos) << e;

  }
}

// Debian's gltfpack (its defaults: positions 14 bits, normals 8, texcoords 12, the UVs'
// range in KHR_texture_transform, the positions' in the node; vertices reordered for the
// cache) writes files the loader reads as the originals: every original triangle's
// world-space vertices are found in the packed mesh within half a quantization step of the
// largest extent, 0.5 / (2^14 - 1), and its UVs within half a 12-bit step of their range.
TEST(MeshQuantization, GltfpackFilesLoadAsTheOriginals) {
  const TempDir dir("gltfpack");
  for (const char* asset : {"bunny.glb", "textured_tile.glb"}) {
    SCOPED_TRACE(asset);
    const std::filesystem::path in = std::filesystem::path(SSS_SOURCE_DIR) / "assets" / asset;
    const std::filesystem::path out = dir / (std::string("packed_") + asset);
    const auto run = sss::testing::run_shell("gltfpack -ke -i '" + in.string() + "' -o '" + out.string() + "' 2>&1");
    ASSERT_EQ(run.code, 0) << run.out;
    const Scene a = load_ok(in), b = load_ok(out);
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    ASSERT_EQ(a.instances.size(), 1u);
    ASSERT_EQ(b.instances.size(), 1u);
    EXPECT_EQ(b.materials[0].sss.enabled, a.materials[0].sss.enabled);  // -ke kept extras.sss
    const auto world = [](const Scene& s, std::size_t i) {
      return glm::vec3(s.instances[0].world * glm::vec4(s.meshes[0].positions[i], 1.0f));
    };
    const Bounds box = a.bounds();
    const glm::vec3 ext = box.max - box.min;
    const float extent = std::max({ext.x, ext.y, ext.z});
    const float tol = 0.5f * extent / 16383.0f + 1e-6f * extent;
    // Match each original vertex to the packed one nearest to it (a grid-free O(n²) is
    // fine at these sizes), then require every triangle's corners to match.
    const Mesh& ma = a.meshes[0];
    const Mesh& mb = b.meshes[0];
    ASSERT_EQ(ma.indices.size(), mb.indices.size());
    float worst = 0.0f, worst_uv = 0.0f;
    for (std::size_t i = 0; i < ma.positions.size(); ++i) {
      const glm::vec3 p = world(a, i);
      // The nearest packed vertex, and among those at the same place (a UV seam
      // duplicates positions) the one whose UV is nearest.
      float best = std::numeric_limits<float>::infinity(), best_uv = best;
      for (std::size_t j = 0; j < mb.positions.size(); ++j) {
        const glm::vec3 d = glm::abs(world(b, j) - p);
        best = std::min(best, std::max({d.x, d.y, d.z}));
      }
      worst = std::max(worst, best);
      if (!ma.uv0.empty()) {
        ASSERT_FALSE(mb.uv0.empty());
        for (std::size_t j = 0; j < mb.positions.size(); ++j) {
          const glm::vec3 d = glm::abs(world(b, j) - p);
          if (std::max({d.x, d.y, d.z}) > tol) continue;
          const glm::vec2 du = glm::abs(ma.uv0[i] - mb.uv0[j]);
          best_uv = std::min(best_uv, std::max(du.x, du.y));
        }
        worst_uv = std::max(worst_uv, best_uv);
      }
    }
    EXPECT_LE(worst, tol) << "extent " << extent;
    if (!ma.uv0.empty()) {
      float lo = std::numeric_limits<float>::infinity(), hi = -lo;
      for (const glm::vec2& uv : ma.uv0) {
        lo = std::min({lo, uv.x, uv.y});
        hi = std::max({hi, uv.x, uv.y});
      }
      EXPECT_LE(worst_uv, 0.5f * (hi - lo) / 4095.0f + 1e-6f);
    }
    std::printf("[ gltfpack ] %s: worst position error %.3g of tolerance %.3g; worst uv error %.3g\n",
                asset, worst, tol, worst_uv);
  }
}

}  // namespace sss::scene
