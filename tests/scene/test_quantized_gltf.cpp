// KHR_mesh_quantization, KHR_texture_transform, EXT_meshopt_compression and
// KHR_draco_mesh_compression (issue 21): quantized attributes decode by glTF's
// normalized-integer formulas, a texture transform is applied to the UVs, what the
// extensions do not allow is refused naming the field; and files written by tools not ours
// (Debian's gltfpack; glTF-Transform from npm, tools/node/variants.mjs) load as the
// originals within the quantization's own step, or bit for bit where the compression is
// lossless.
#include "scene/GltfLoader.h"

#include "GltfTestWriter.h"
#include "LoadExpect.h"
#include "tests/common/CliRun.h"

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <fstream>
#include <functional>
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

// Tangents follow a texture transform: for a triangle whose tangent and bitangent are
// its UV derivatives (unit, conformal), the loaded tangent is ∂P/∂u' computed here from
// the positions and the transformed UVs by the usual triangle formula, and its handedness
// the sign of (N × T)·∂P/∂v'; a rotation with unequal scales, and a mirror, included.
TEST(TextureTransform, TangentsFollowTheTransformedUvs) {
  const TempDir dir("texture_transform_tangents");
  for (const nlohmann::json& tf : {nlohmann::json{{"rotation", 0.7}, {"scale", {2.0, 0.5}}},
                                   nlohmann::json{{"scale", {-1.0, 1.0}}, {"offset", {0.3, 0.0}}},
                                   nlohmann::json{{"rotation", -2.0}}}) {
    SCOPED_TRACE(tf.dump());
    GltfTestWriter w;
    const std::vector<float> pos = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const std::vector<float> nrm = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    const std::vector<float> tan = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
    const std::vector<float> uv = {0, 0, 1, 0, 0, 1};
    const int p = w.accessor(w.view(pos.data(), pos.size() * 4), 5126, 3, "VEC3");
    const int n = w.accessor(w.view(nrm.data(), nrm.size() * 4), 5126, 3, "VEC3");
    const int t = w.accessor(w.view(tan.data(), tan.size() * 4), 5126, 3, "VEC4");
    const int u = w.accessor(w.view(uv.data(), uv.size() * 4), 5126, 3, "VEC2");
    const auto png = tiny_png();
    w.push("images", {{"bufferView", w.view(png.data(), png.size())}, {"mimeType", "image/png"}});
    w.push("textures", {{"source", 0}});
    const nlohmann::json info = {{"index", 0}, {"extensions", {{"KHR_texture_transform", tf}}}};
    w.push("materials", {{"pbrMetallicRoughness", {{"baseColorTexture", info}}}, {"normalTexture", info}});
    w.push("meshes", {{"primitives", {{{"attributes", {{"POSITION", p}, {"NORMAL", n}, {"TANGENT", t}, {"TEXCOORD_0", u}}},
                                       {"material", 0}}}}});
    w.push("nodes", {{"mesh", 0}});
    w.doc["scenes"] = {{{"nodes", {0}}}};
    w.doc["extensionsUsed"] = {"KHR_texture_transform"};
    w.write_gltf(dir / "t.gltf");
    const Scene s = load_ok(dir / "t.gltf");
    ASSERT_EQ(s.meshes.size(), 1u);
    const Mesh& m = s.meshes[0];
    ASSERT_EQ(m.tangents.size(), 3u);
    const glm::vec3 e1 = m.positions[1] - m.positions[0], e2 = m.positions[2] - m.positions[0];
    const glm::vec2 d1 = m.uv0[1] - m.uv0[0], d2 = m.uv0[2] - m.uv0[0];
    const float r = 1.0f / (d1.x * d2.y - d2.x * d1.y);
    const glm::vec3 dpdu = (e1 * d2.y - e2 * d1.y) * r, dpdv = (e2 * d1.x - e1 * d2.x) * r;
    const glm::vec3 expected = glm::normalize(dpdu);
    const float handedness = glm::dot(glm::cross(glm::vec3(0, 0, 1), expected), dpdv) < 0.0f ? -1.0f : 1.0f;
    for (const glm::vec4& got : m.tangents) {
      EXPECT_LT(glm::length(glm::vec3(got) - expected), 1e-5f) << got.x << " " << got.y << " " << got.z;
      EXPECT_EQ(got.w, handedness);
    }
  }
}

namespace {

// How far a loaded file `b` is from the original `a` (one mesh, one instance each):
// every original vertex is matched to the nearest vertex of b in world space (a grid-free
// O(n²) is fine at these sizes); `position` is the worst such distance (max-norm), `uv`
// the worst UV distance among the vertices of b at that place within `tol` (a UV seam
// duplicates positions), `normal` the worst |n_a - n_b| likewise. `uv_range` is the
// range of a's UVs over both components.
struct VertexError {
  float position = 0.0f, uv = 0.0f, normal = 0.0f, extent = 0.0f, uv_range = 0.0f;
};
VertexError vertex_error(const Scene& a, const Scene& b, float tol) {
  VertexError r;
  EXPECT_EQ(a.meshes.size(), 1u);
  EXPECT_EQ(b.meshes.size(), 1u);
  EXPECT_EQ(a.instances.size(), 1u);
  EXPECT_EQ(b.instances.size(), 1u);
  if (a.meshes.size() != 1 || b.meshes.size() != 1 || a.instances.size() != 1 || b.instances.size() != 1)
    return r;
  const auto world = [](const Scene& s, std::size_t i) {
    return glm::vec3(s.instances[0].world * glm::vec4(s.meshes[0].positions[i], 1.0f));
  };
  const glm::mat3 na = glm::inverse(glm::transpose(glm::mat3(a.instances[0].world)));
  const glm::mat3 nb = glm::inverse(glm::transpose(glm::mat3(b.instances[0].world)));
  const Bounds box = a.bounds();
  const glm::vec3 ext = box.max - box.min;
  r.extent = std::max({ext.x, ext.y, ext.z});
  const Mesh& ma = a.meshes[0];
  const Mesh& mb = b.meshes[0];
  EXPECT_EQ(ma.indices.size(), mb.indices.size());
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  for (const glm::vec2& uv : ma.uv0) {
    lo = std::min({lo, uv.x, uv.y});
    hi = std::max({hi, uv.x, uv.y});
  }
  r.uv_range = ma.uv0.empty() ? 0.0f : hi - lo;
  for (std::size_t i = 0; i < ma.positions.size(); ++i) {
    const glm::vec3 p = world(a, i);
    const glm::vec3 n = glm::normalize(na * ma.normals[i]);
    float best = std::numeric_limits<float>::infinity(), best_uv = best, best_n = best;
    for (std::size_t j = 0; j < mb.positions.size(); ++j) {
      const glm::vec3 d = glm::abs(world(b, j) - p);
      best = std::min(best, std::max({d.x, d.y, d.z}));
    }
    r.position = std::max(r.position, best);
    for (std::size_t j = 0; j < mb.positions.size(); ++j) {
      const glm::vec3 d = glm::abs(world(b, j) - p);
      if (std::max({d.x, d.y, d.z}) > tol) continue;
      best_n = std::min(best_n, glm::length(glm::normalize(nb * mb.normals[j]) - n));
      if (!ma.uv0.empty() && !mb.uv0.empty()) {
        const glm::vec2 du = glm::abs(ma.uv0[i] - mb.uv0[j]);
        best_uv = std::min(best_uv, std::max(du.x, du.y));
      }
    }
    r.normal = std::max(r.normal, best_n);
    if (!ma.uv0.empty()) r.uv = std::max(r.uv, best_uv);
  }
  EXPECT_EQ(ma.uv0.empty(), mb.uv0.empty());
  return r;
}

// Half a quantization step of `bits` over `range`, the most rounding can move a value,
// with float rounding of the dequantized value (a few ulps of the extent) on top.
float half_step(float range, int bits, float extent) {
  return 0.5f * range / float((1 << bits) - 1) + 1e-6f * extent;
}

// Octahedral normals (Draco's and meshopt's filter) with `bits` per coordinate: the two
// coordinates u, v in [-1, 1] are stored in steps of 2 / (2^bits - 2), so rounding moves
// each by at most h = 1 / (2^bits - 2). The point on the octahedron |x|+|y|+|z| = 1
// moves by at most sqrt(h² + h² + (2h)²) = √6 h (z = 1 - |u| - |v|, or its fold, changes
// by |du| + |dv|), and renormalizing divides by its length, at least 1/√3: the unit
// normal moves by at most √18 h. meshopt's filter then stores the decoded normal in the
// same integers again (`requantized`), √3 h more.
float octahedral_bound(int bits, bool requantized) {
  const float h = 1.0f / float((1 << bits) - 2);
  return std::sqrt(18.0f) * h + (requantized ? std::sqrt(3.0f) * h : 0.0f) + 1e-5f;
}

// Each triangle rotated to start at its smallest index, winding kept: meshopt's index
// codec may rotate a triangle's corners (its README, mode 1), which draws the same thing.
std::vector<std::uint32_t> canonical_triangles(const std::vector<std::uint32_t>& in) {
  std::vector<std::uint32_t> out(in.size());
  for (std::size_t t = 0; t + 2 < in.size(); t += 3) {
    const std::size_t k = in[t] <= in[t + 1] && in[t] <= in[t + 2] ? 0 : in[t + 1] <= in[t + 2] ? 1 : 2;
    for (std::size_t c = 0; c < 3; ++c) out[t + c] = in[t + (k + c) % 3];
  }
  return out;
}

// The same vertices bit for bit, and the same triangles up to rotation.
bool same_geometry(const Scene& a, const Scene& b) {
  if (a.meshes.size() != b.meshes.size() || a.meshes.empty()) return false;
  for (std::size_t m = 0; m < a.meshes.size(); ++m)
    if (a.meshes[m].positions != b.meshes[m].positions || a.meshes[m].normals != b.meshes[m].normals ||
        a.meshes[m].uv0 != b.meshes[m].uv0 ||
        canonical_triangles(a.meshes[m].indices) != canonical_triangles(b.meshes[m].indices))
      return false;
  return true;
}

std::string gltf_transform(const std::filesystem::path& in, const std::filesystem::path& out,
                           const std::string& variant) {
  const auto run = sss::testing::run_shell("node '" SSS_SOURCE_DIR "/tools/node/variants.mjs' '" + in.string() +
                                           "' '" + out.string() + "' " + variant + " 2>&1");
  EXPECT_EQ(run.code, 0) << run.out;
  return run.out;
}

}  // namespace

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
    EXPECT_EQ(b.materials[0].sss.enabled, a.materials[0].sss.enabled);  // -ke kept extras.sss
    const Bounds box = a.bounds();
    const glm::vec3 ext = box.max - box.min;
    const float extent = std::max({ext.x, ext.y, ext.z});
    const float tol = half_step(extent, 14, extent);
    const VertexError e = vertex_error(a, b, tol);
    EXPECT_LE(e.position, tol) << "extent " << extent;
    if (e.uv_range > 0.0f) {
      EXPECT_LE(e.uv, half_step(e.uv_range, 12, 1.0f));
    }
    std::printf("[ gltfpack ] %s: worst position error %.3g of tolerance %.3g; worst uv error %.3g\n",
                asset, e.position, tol, e.uv);
  }
}

// gltfpack's meshopt files (issue 21), through the placeholder buffer of a GLB and of a
// .gltf:
// - -c (no filters) is lossless: the same vertices as gltfpack's uncompressed output
//   (-ke alone), bit for bit, and the same triangles up to rotation;
// - -cc (its higher ratio) stores normals with the octahedral filter: the original's
//   vertices are found within half a 14-bit step, normals within octahedral_bound(8, true);
// - another decoder (glTF-Transform with npm's meshoptimizer, written uncompressed) gives
//   the same positions and indices bit for bit, and normals within one step of their 8-bit
//   integers per component, √3/127: meshoptimizer 1.3 rounds the octahedral filter's
//   output differently from Debian's 0.18 for a few vertices.
TEST(CompressedGltf, GltfpackMeshoptDecodesAsTheUncompressedFile) {
  const TempDir dir("gltfpack_meshopt");
  for (const char* asset : {"bunny", "textured_tile"})
    for (const char* ext : {".glb", ".gltf"}) {
      const std::string in = std::string(SSS_SOURCE_DIR) + "/assets/" + asset + ".glb";
      const auto pack = [&](const std::string& flags) {
        const std::filesystem::path out = dir / (std::string(asset) + flags + ext);
        const auto run = sss::testing::run_shell("gltfpack -ke " + flags + " -i '" + in + "' -o '" + out.string() + "' 2>&1");
        EXPECT_EQ(run.code, 0) << run.out;
        return out;
      };
      const Scene original = load_ok(in), plain = load_ok(pack(""));
      const Bounds box = original.bounds();
      const glm::vec3 e3 = box.max - box.min;
      const float extent = std::max({e3.x, e3.y, e3.z});
      for (const std::string flags : {"-c", "-cc"}) {
        SCOPED_TRACE(std::string(asset) + ext + " " + flags);
        const std::filesystem::path file = pack(flags);
        const Scene compressed = load_ok(file);
        ASSERT_EQ(compressed.meshes.size(), 1u);
        if (flags == "-c") {
          EXPECT_TRUE(same_geometry(plain, compressed));
        } else {
          const float tol = half_step(extent, 14, extent);
          const VertexError e = vertex_error(original, compressed, tol);
          EXPECT_LE(e.position, tol);
          EXPECT_LE(e.normal, octahedral_bound(8, true));
          std::printf("[ gltfpack -cc ] %s%s: position %.3g of %.3g, normal %.3g of %.3g\n", asset, ext,
                      e.position, tol, e.normal, octahedral_bound(8, true));
        }
        const std::filesystem::path decoded = dir / (std::string(asset) + flags + "_decoded.glb");
        gltf_transform(file, decoded, "decode");
        const Scene other = load_ok(decoded);
        ASSERT_EQ(other.meshes.size(), 1u);
        EXPECT_EQ(other.meshes[0].positions, compressed.meshes[0].positions);
        EXPECT_EQ(other.meshes[0].uv0, compressed.meshes[0].uv0);
        EXPECT_EQ(other.meshes[0].indices, compressed.meshes[0].indices);  // not even rotated
        ASSERT_EQ(other.meshes[0].normals.size(), compressed.meshes[0].normals.size());
        float gap = 0.0f;
        for (std::size_t i = 0; i < other.meshes[0].normals.size(); ++i)
          gap = std::max(gap, glm::length(other.meshes[0].normals[i] - compressed.meshes[0].normals[i]));
        EXPECT_LE(gap, std::sqrt(3.0f) / 127.0f);
      }
    }
}

// glTF-Transform (npm, tools/node/variants.mjs) writes Draco and meshopt files that load
// as the original bunny:
// - meshopt without filters is lossless: the same vertices, bit for bit;
// - meshopt with its filters: positions exact, normals octahedral in 8 bits, stored
//   again as 8-bit integers (octahedral_bound(8, true) = 0.0235);
// - Draco (edgebreaker reorders vertices): positions within half a 14-bit step of the
//   extent, normals within octahedral_bound(10, false) = 0.0042, as many triangles; and
//   the same file decoded by npm's draco3dgltf (glTF-Transform, written uncompressed)
//   loads to the same vertices and indices as libdraco's decoding here, bit for bit.
TEST(CompressedGltf, GltfTransformVariantsLoadAsTheOriginal) {
  const TempDir dir("gltf_transform");
  const std::filesystem::path in = std::filesystem::path(SSS_SOURCE_DIR) / "assets" / "bunny.glb";
  const Scene a = load_ok(in);
  const Bounds box = a.bounds();
  const glm::vec3 ext = box.max - box.min;
  const float extent = std::max({ext.x, ext.y, ext.z});

  gltf_transform(in, dir / "meshopt.glb", "meshopt");
  EXPECT_TRUE(same_geometry(a, load_ok(dir / "meshopt.glb")));

  gltf_transform(in, dir / "filter.glb", "meshopt-filter");
  const Scene f = load_ok(dir / "filter.glb");
  ASSERT_EQ(f.meshes.size(), 1u);
  EXPECT_EQ(f.meshes[0].positions, a.meshes[0].positions);
  EXPECT_EQ(canonical_triangles(f.meshes[0].indices), canonical_triangles(a.meshes[0].indices));
  float worst_normal = 0.0f;
  for (std::size_t i = 0; i < a.meshes[0].normals.size(); ++i)
    worst_normal = std::max(worst_normal, glm::length(f.meshes[0].normals[i] - a.meshes[0].normals[i]));
  EXPECT_LE(worst_normal, octahedral_bound(8, true));

  gltf_transform(in, dir / "draco.glb", "draco");
  const Scene d = load_ok(dir / "draco.glb");
  const float tol = half_step(extent, 14, extent);
  const VertexError e = vertex_error(a, d, tol);
  EXPECT_LE(e.position, tol);
  EXPECT_LE(e.normal, octahedral_bound(10, false));
  gltf_transform(dir / "draco.glb", dir / "draco_decoded.glb", "decode");
  const Scene other = load_ok(dir / "draco_decoded.glb");
  ASSERT_EQ(other.meshes.size(), 1u);
  ASSERT_EQ(d.meshes.size(), 1u);
  EXPECT_EQ(other.meshes[0].positions, d.meshes[0].positions);
  EXPECT_EQ(other.meshes[0].indices, d.meshes[0].indices);
  float normal_gap = 0.0f;  // libdraco's normals are renormalized here, the file's are not
  for (std::size_t i = 0; i < d.meshes[0].normals.size() && i < other.meshes[0].normals.size(); ++i)
    normal_gap = std::max(normal_gap, glm::length(d.meshes[0].normals[i] - other.meshes[0].normals[i]));
  EXPECT_LE(normal_gap, 1e-6f);
  std::printf("[ glTF-Transform ] meshopt filter: worst normal error %.3g of %.3g; Draco: position %.3g of %.3g, "
              "normal %.3g of %.3g; libdraco vs draco3dgltf normals %.3g\n",
              worst_normal, octahedral_bound(8, true), e.position, tol, e.normal, octahedral_bound(10, false),
              normal_gap);
}

namespace {

// A compressed .gltf (from `make`, writing base.gltf and base.bin into `dir`) changed by
// `edit` (its JSON, and its .bin's bytes) is refused, the message holding `expected`.
void expect_refused(const TempDir& dir, const std::string& name,
                    const std::function<void(nlohmann::json&, std::vector<char>&)>& edit,
                    const std::string& expected) {
  SCOPED_TRACE(name);
  std::ifstream jf(dir / "base.gltf");
  nlohmann::json doc = nlohmann::json::parse(jf);
  const std::string bin_name = doc["buffers"][0]["uri"].get<std::string>();
  std::ifstream bf(dir / bin_name, std::ios::binary);
  std::vector<char> bin((std::istreambuf_iterator<char>(bf)), std::istreambuf_iterator<char>());
  edit(doc, bin);
  doc["buffers"][0]["uri"] = name + ".bin";
  std::ofstream(dir / (name + ".bin"), std::ios::binary).write(bin.data(), std::streamsize(bin.size()));
  std::ofstream(dir / (name + ".gltf")) << doc.dump();
  const std::string error = load_error(dir / (name + ".gltf"));
  EXPECT_NE(error.find(expected), std::string::npos) << error;
}

}  // namespace

// assimp's glTF2 models (Debian's assimp-testmodels) through glTF-Transform: meshopt
// without filters loads bit for bit as the original (triangles up to rotation), and Draco
// keeps every mesh, each with at most its triangles (Draco drops degenerate ones) and its
// bounds within half a 14-bit step of its own extent (Draco quantizes each primitive over
// its own bounds).
TEST(CompressedGltf, AssimpModelsThroughGltfTransform) {
  const std::filesystem::path models = "/usr/share/assimp/models/glTF2";
  if (!std::filesystem::is_directory(models)) GTEST_SKIP() << "assimp-testmodels not installed";
  const TempDir dir("assimp_variants");
  for (const char* rel : {"BoxTextured-glTF-Binary/BoxTextured.glb", "2CylinderEngine-glTF-Binary/2CylinderEngine.glb"}) {
    const std::filesystem::path in = models / rel;
    SCOPED_TRACE(rel);
    const Scene a = load_ok(in);
    gltf_transform(in, dir / "m.glb", "meshopt");
    EXPECT_TRUE(same_geometry(a, load_ok(dir / "m.glb")));
    gltf_transform(in, dir / "d.glb", "draco");
    const Scene d = load_ok(dir / "d.glb");
    ASSERT_EQ(d.meshes.size(), a.meshes.size());
    float worst = 0.0f;
    for (std::size_t m = 0; m < a.meshes.size(); ++m) {
      EXPECT_LE(d.meshes[m].indices.size(), a.meshes[m].indices.size());
      EXPECT_GT(d.meshes[m].indices.size(), 0u);
      const glm::vec3 e = a.meshes[m].bounds.max - a.meshes[m].bounds.min;
      const float extent = std::max({e.x, e.y, e.z});
      for (int c = 0; c < 3; ++c) {
        const float gap = std::max(std::abs(a.meshes[m].bounds.min[c] - d.meshes[m].bounds.min[c]),
                                   std::abs(a.meshes[m].bounds.max[c] - d.meshes[m].bounds.max[c]));
        EXPECT_LE(gap, half_step(extent, 14, extent)) << "mesh " << m;
        worst = std::max(worst, gap / extent);
      }
    }
    std::printf("[ assimp via glTF-Transform ] %s: Draco bounds within %.3g of each mesh's extent (bound %.3g)\n",
                rel, worst, 0.5 / 16383.0);
  }
}


// Hostile or inconsistent meshopt data is refused with the view and field named, before
// or by the decoder, never read past: each case edits one thing of gltfpack's output.
TEST(CompressedGltf, BadMeshoptDataIsRefusedNamingTheField) {
  const TempDir dir("bad_meshopt");
  const std::string in = SSS_SOURCE_DIR "/assets/bunny.glb";
  const auto run = sss::testing::run_shell("gltfpack -ke -c -i '" + in + "' -o '" + (dir / "base.gltf").string() + "' 2>&1");
  ASSERT_EQ(run.code, 0) << run.out;
  using J = nlohmann::json;
  using B = std::vector<char>;
  const auto ext = [](J& d, int v) -> J& { return d["bufferViews"][v]["extensions"]["EXT_meshopt_compression"]; };
  expect_refused(dir, "truncated", [&](J& d, B&) { ext(d, 0)["byteLength"] = ext(d, 0)["byteLength"].get<int>() - 64; },
                 "bufferViews[0].extensions.EXT_meshopt_compression: the compressed bytes do not decode");
  expect_refused(dir, "header", [&](J& d, B& b) { b[ext(d, 0).value("byteOffset", 0)] = 0; },
                 "not a stream it reads");
  expect_refused(dir, "count", [&](J& d, B&) { ext(d, 1)["count"] = ext(d, 1)["count"].get<int>() + 1; },
                 "bufferViews[1].extensions.EXT_meshopt_compression.count: 1840 elements of 4 bytes do not fill");
  expect_refused(dir, "stride", [&](J& d, B&) {
    ext(d, 2)["byteStride"] = 12;  // 12 * 1837 still fills the view's 22044 bytes
    ext(d, 2)["count"] = 1837;
  }, "EXT_meshopt_compression.byteStride: must be 2 or 4 in mode TRIANGLES, got 12");
  expect_refused(dir, "filter", [&](J& d, B&) { ext(d, 1)["filter"] = "QUATERNION"; },
                 "byteStride: 4 does not suit filter QUATERNION (it needs 8)");
  expect_refused(dir, "mode", [&](J& d, B&) { ext(d, 1)["mode"] = "LINES"; },
                 "EXT_meshopt_compression.mode: must be one of");
  expect_refused(dir, "plain_view_in_placeholder",
                 [&](J& d, B&) { d["bufferViews"][1].erase("extensions"); },
                 "bufferViews[1].buffer: buffers[1] is an EXT_meshopt_compression fallback placeholder");
  expect_refused(dir, "source_is_fallback", [&](J& d, B&) { ext(d, 0)["buffer"] = 1; },
                 "buffers[1] is a fallback buffer; compressed bytes must come from another");
  expect_refused(dir, "past_the_buffer", [&](J& d, B&) { ext(d, 2)["byteOffset"] = 1 << 20; },
                 "run past the");
  expect_refused(dir, "undeclared", [&](J& d, B&) {
    d["extensionsUsed"] = {"KHR_mesh_quantization"};
    d["extensionsRequired"] = {"KHR_mesh_quantization"};
  }, "buffers[1].uri: is required in a .gltf file");
}

// The same for Draco: a corrupt bitstream, an attribute id it does not hold, counts that
// disagree with it, the extension undeclared (glTF-Transform's output, edited).
TEST(CompressedGltf, BadDracoDataIsRefusedNamingTheField) {
  const TempDir dir("bad_draco");
  gltf_transform(SSS_SOURCE_DIR "/assets/bunny.glb", dir / "base.gltf", "draco");
  using J = nlohmann::json;
  using B = std::vector<char>;
  const auto ext = [](J& d) -> J& { return d["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]; };
  const std::string where = "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression";
  expect_refused(dir, "corrupt", [&](J& d, B& b) {
    const J& v = d["bufferViews"][ext(d)["bufferView"].get<int>()];
    for (int i = 0; i < 64; ++i) b[std::size_t(v.value("byteOffset", 0) + i)] = char(0x5a);
  }, where + ".bufferView: the Draco bitstream does not decode");
  expect_refused(dir, "attribute_id", [&](J& d, B&) { ext(d)["attributes"]["NORMAL"] = 99; },
                 where + ".attributes.NORMAL: Draco attribute 99 is not in the bitstream");
  expect_refused(dir, "indices_count", [&](J& d, B&) { d["accessors"][d["meshes"][0]["primitives"][0]["indices"].get<int>()]["count"] = 3; },
                 "meshes[0].primitives[0].indices: accessors[0] has 3 elements but the Draco bitstream decodes 11022");
  expect_refused(dir, "position_count", [&](J& d, B&) {
    d["accessors"][d["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<int>()]["count"] = 5;
  }, "meshes[0].primitives[0].attributes.POSITION: has 5 elements");
  expect_refused(dir, "undeclared", [&](J& d, B&) {
    d.erase("extensionsRequired");
    d["extensionsUsed"] = J::array();
  }, where + ": is used but \"KHR_draco_mesh_compression\" is not in extensionsUsed");
  expect_refused(dir, "mode", [&](J& d, B&) { d["meshes"][0]["primitives"][0]["mode"] = 5; },
                 "meshes[0].primitives[0].mode: must be 4 (triangles) with KHR_draco_mesh_compression");
}

}  // namespace sss::scene
