// load_gltf on valid files written by the test: node hierarchy, indexed and non-indexed
// primitives, strips, textures, cameras, lights, extras.sss; .gltf (embedded and
// external buffer) and .glb give the same scene.
#include "scene/GltfLoader.h"

#include "GltfTestWriter.h"
#include "LoadExpect.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace sss::scene {
namespace {

using testing::GltfTestWriter;
using testing::TempDir;
using testing::load_error;
using testing::load_ok;


void expect_near(const glm::vec3& a, const glm::vec3& b, float tol = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

// Two nodes in a chain, both transformed, over an indexed triangle (u16) and a
// non-indexed quad (two triangles, no normals), plus a camera and a spot light.
GltfTestWriter hierarchy_file() {
  GltfTestWriter w;
  const int pos = w.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  const int nrm = w.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
  const int idx = w.indices(std::vector<std::uint16_t>{0, 1, 2});
  const int quad = w.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3", 3);
  w.push("meshes", {{"name", "tri"},
                    {"primitives", {{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}},
                                     {"indices", idx}, {"material", 0}}}}});
  w.push("meshes", {{"name", "quad"}, {"primitives", {{{"attributes", {{"POSITION", quad}}}}}}});
  w.push("materials", {{"name", "skin"},
                       {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.25, 1, 1}},
                                                 {"metallicFactor", 0}, {"roughnessFactor", 0.3}}},
                       {"extras", {{"sss", {{"preset", "marble"}, {"gaussians", 4},
                                            {"scale", 2}, {"albedo_mode", "pre-post"}}}}}});
  // parent: translate (1, 2, 3); child: rotate 90 degrees about +y, scale 2.
  const double s = std::sqrt(0.5);
  w.push("nodes", {{"name", "parent"}, {"translation", {1, 2, 3}}, {"children", {1, 2}}});
  w.push("nodes", {{"name", "child"}, {"rotation", {0, s, 0, s}}, {"scale", {2, 2, 2}}, {"mesh", 0}});
  w.push("nodes", {{"name", "quad"}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -5, 1}},
                   {"mesh", 1}});
  w.push("nodes", {{"name", "eye"}, {"translation", {0, 0, 10}}, {"camera", 0}});
  w.push("nodes", {{"name", "lamp"}, {"translation", {0, 4, 0}}, {"rotation", {-s, 0, 0, s}},
                   {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  w.push("cameras", {{"type", "perspective"},
                     {"perspective", {{"yfov", 0.7}, {"znear", 0.05}, {"zfar", 50}}}});
  w.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  w.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "spot"}, {"color", {1, 0.5, 0.25}}, {"intensity", 20},
       {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}}};
  w.doc["scenes"] = {{{"nodes", {0, 3, 4}}}};
  w.doc["scene"] = 0;
  return w;
}

void check_hierarchy_scene(const Scene& s) {
  ASSERT_EQ(s.meshes.size(), 2u);
  ASSERT_EQ(s.instances.size(), 2u);
  const Mesh& tri = s.meshes[s.instances[0].mesh];
  EXPECT_EQ(tri.name, "tri");
  EXPECT_EQ(tri.indices, (std::vector<std::uint32_t>{0, 1, 2}));
  // Vertex (1, 0, 0): scaled to (2, 0, 0), rotated about +y to (0, 0, -2), moved by (1, 2, 3).
  const glm::vec4 p = s.instances[0].world * glm::vec4(tri.positions[1], 1.0f);
  expect_near(glm::vec3(p), {1.0f, 2.0f, 1.0f});
  const Mesh& quad = s.meshes[s.instances[1].mesh];
  EXPECT_EQ(quad.indices, (std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5}));  // generated
  for (const glm::vec3& n : quad.normals) expect_near(n, {0, 0, 1});        // generated
  expect_near(glm::vec3(s.instances[1].world * glm::vec4(quad.positions[2], 1.0f)), {2, 3, -2});
  // The quad has no material: the glTF default one is appended.
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[quad.material].name, "default");
  const Material& m = s.materials[tri.material];
  EXPECT_FLOAT_EQ(m.base_color.g, 0.25f);
  EXPECT_FLOAT_EQ(m.roughness, 0.3f);
  EXPECT_FLOAT_EQ(m.metallic, 0.0f);
  ASSERT_TRUE(m.sss.enabled);
  EXPECT_EQ(std::get<PresetSource>(m.sss.source).name, "marble");
  EXPECT_EQ(m.sss.gaussians, 4);
  EXPECT_EQ(m.sss.scale, 2.0);
  EXPECT_EQ(m.sss.albedo_mode, AlbedoMode::PrePost);
  EXPECT_EQ(m.sss.model, profiles::kDefaultModel);  // no "model" given
  EXPECT_NEAR(m.sss.effective_medium().sigma_a[0], 2 * m.sss.medium.sigma_a[0], 1e-15);
  EXPECT_DOUBLE_EQ(s.mm_per_unit, 1000.0);
  // The camera (child of the root scene list) sits at (0, 0, 10) looking down -z.
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.cameras[0].projection, Projection::Perspective);
  EXPECT_FLOAT_EQ(s.cameras[0].yfov, 0.7f);
  expect_near(s.cameras[0].position(), {0, 0, 10});
  expect_near(s.cameras[0].forward(), {0, 0, -1});
  // The spot light, rotated -90 degrees about x, points down.
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, LightType::Spot);
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 20.0f);
  EXPECT_FLOAT_EQ(s.lights[0].outer_cone, 0.5f);
  expect_near(s.lights[0].direction(), {0, -1, 0});
  expect_near(s.lights[0].position(), {0, 4, 0});
  EXPECT_TRUE(s.warnings.empty());
}

TEST(GltfLoader, HierarchyEmbeddedBuffer) {
  const TempDir dir("hierarchy_embedded");
  hierarchy_file().write_gltf(dir / "h.gltf");
  check_hierarchy_scene(load_ok(dir / "h.gltf"));
}

TEST(GltfLoader, HierarchyExternalBuffer) {
  const TempDir dir("hierarchy_external");
  std::filesystem::create_directories(dir / "data");
  hierarchy_file().write_gltf_external(dir / "h.gltf", "data/h%20buffer.bin");
  std::filesystem::rename(dir / "data/h%20buffer.bin", dir / "data/h buffer.bin");
  check_hierarchy_scene(load_ok(dir / "h.gltf"));
}

TEST(GltfLoader, HierarchyGlb) {
  const TempDir dir("hierarchy_glb");
  hierarchy_file().write_glb(dir / "h.glb");
  check_hierarchy_scene(load_ok(dir / "h.glb"));
}

TEST(GltfLoader, GlbWithNulPaddingAndAnUnknownChunk) {
  const TempDir dir("hierarchy_glb_odd");
  hierarchy_file().write_glb(dir / "h.glb", '\0', true);
  check_hierarchy_scene(load_ok(dir / "h.glb"));
}

TEST(GltfLoader, MissingExternalBufferIsAnError) {
  const TempDir dir("missing_bin");
  hierarchy_file().write_gltf_external(dir / "h.gltf", "h.bin");
  std::filesystem::remove(dir / "h.bin");
  const std::string e = load_error(dir / "h.gltf");
  EXPECT_NE(e.find("h.gltf"), std::string::npos) << e;
  EXPECT_NE(e.find("h.bin"), std::string::npos) << e;
}

TEST(GltfLoader, StripsFansPointsAndU8Indices) {
  const TempDir dir("modes");
  GltfTestWriter w;
  const int pos = w.floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, "VEC3", 3);
  const int idx = w.indices(std::vector<std::uint8_t>{0, 1, 2, 3});
  const auto prim = [&](int mode) {
    return nlohmann::json{{"attributes", {{"POSITION", pos}}}, {"indices", idx}, {"mode", mode}};
  };
  w.push("meshes", {{"primitives", {prim(5), prim(6), prim(0)}}});
  w.push("nodes", {{"mesh", 0}});
  w.write_gltf(dir / "m.gltf");
  const Scene s = load_ok(dir / "m.gltf");
  ASSERT_EQ(s.meshes.size(), 2u);  // the points primitive is skipped
  EXPECT_EQ(s.meshes[0].indices, (std::vector<std::uint32_t>{0, 1, 2, 1, 3, 2}));  // strip
  EXPECT_EQ(s.meshes[1].indices, (std::vector<std::uint32_t>{1, 2, 0, 2, 3, 0}));  // fan
  ASSERT_EQ(s.warnings.size(), 2u);  // points skipped; no scenes
  EXPECT_NE(s.warnings[0].find("primitives[2]"), std::string::npos) << s.warnings[0];
  // No camera or light in the file: one of each is added.
  EXPECT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.lights.size(), 1u);
}

TEST(GltfLoader, TextureSamplerAndTexcoords) {
  const TempDir dir("texture");
  const std::vector<unsigned char> png = testing::tiny_png();
  GltfTestWriter w;
  const int pos = w.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  const std::vector<std::uint16_t> uv = {0, 0, 65535, 0, 0, 65535};
  const int tex = w.accessor(w.view(uv.data(), uv.size() * 2), 5123, 3, "VEC2", true);
  const int view = w.view(png.data(), png.size());
  w.push("images", {{"bufferView", view}, {"mimeType", "image/png"}});
  w.push("images", {{"uri", "data:image/png;base64," + testing::base64(png)}});
  w.push("samplers", {{"magFilter", 9728}, {"minFilter", 9729}, {"wrapS", 33071}, {"wrapT", 33648}});
  w.push("textures", {{"source", 0}, {"sampler", 0}});
  w.push("textures", {{"source", 1}});
  w.push("materials", {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
                       {"normalTexture", {{"index", 1}, {"scale", 0.5}}}});
  w.push("meshes", {{"primitives", {{{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", tex}}},
                                     {"material", 0}}}}});
  w.push("nodes", {{"mesh", 0}});
  w.doc["scenes"] = {{{"nodes", {0}}}};
  w.write_gltf(dir / "t.gltf");
  const Scene s = load_ok(dir / "t.gltf");
  ASSERT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(s.meshes[0].uv0.size(), 3u);
  EXPECT_FLOAT_EQ(s.meshes[0].uv0[1].x, 1.0f);
  ASSERT_EQ(s.textures.size(), 2u);
  const Material& m = s.materials[0];
  ASSERT_TRUE(m.base_color_texture && m.normal_texture);
  EXPECT_FLOAT_EQ(m.normal_scale, 0.5f);
  const Texture& base = s.textures[*m.base_color_texture];
  EXPECT_EQ(base.sampler.mag, Filter::Nearest);
  EXPECT_FALSE(base.sampler.mipmaps);
  EXPECT_EQ(base.sampler.wrap_s, Wrap::ClampToEdge);
  EXPECT_EQ(base.sampler.wrap_t, Wrap::MirroredRepeat);
  ASSERT_EQ(base.image->width, 2u);
  EXPECT_EQ(base.image->pixels[4 + 1], 255);  // second pixel green, alpha added
  EXPECT_EQ(base.image->pixels[3], 255);
  EXPECT_EQ(s.textures[*m.normal_texture].sampler.wrap_s, Wrap::Repeat);
  EXPECT_EQ(s.textures[*m.normal_texture].image->pixels, base.image->pixels);
}

TEST(GltfLoader, SssCoefficientsAndArtistModes) {
  const TempDir dir("sss_modes");
  GltfTestWriter w;
  const int pos = w.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  w.push("materials", {{"extras", {{"sss", {{"sigma_a", {0.01, 0.02, 0.03}}, {"sigma_s", 2.0},
                                           {"g", 0.5}, {"eta", 1.4}, {"model", "dipole"}}}}}});
  w.push("materials", {{"extras", {{"sss", {{"color", {0.8, 0.5, 0.3}}, {"mfp", {2, 1, 0.5}},
                                           {"model", "burley"}, {"gaussians", 3}}}}}});
  w.push("materials", {{"extras", {{"sss", {{"preset", "skin2"}, {"enabled", false}}}}}});
  w.push("meshes", {{"primitives", {{{"attributes", {{"POSITION", pos}}}, {"material", 1}}}}});
  w.push("nodes", {{"mesh", 0}});
  w.doc["scenes"] = {{{"nodes", {0}}}};
  w.write_gltf(dir / "s.gltf");
  const Scene s = load_ok(dir / "s.gltf");
  ASSERT_EQ(s.materials.size(), 3u);
  const SssMaterial& c = s.materials[0].sss;
  EXPECT_TRUE(c.enabled);
  EXPECT_EQ(c.model, profiles::Model::Dipole);
  EXPECT_DOUBLE_EQ(c.medium.sigma_a[2], 0.03);
  EXPECT_DOUBLE_EQ(c.medium.sigma_s[1], 2.0);
  EXPECT_DOUBLE_EQ(c.medium.g[0], 0.5);
  EXPECT_DOUBLE_EQ(c.medium.eta[0], 1.4);
  const SssMaterial& a = s.materials[1].sss;
  EXPECT_EQ(a.model, profiles::Model::Burley);
  EXPECT_EQ(a.gaussians, 3);
  ASSERT_TRUE(std::holds_alternative<ArtistSource>(a.source));
  // mfp is the reduced mean free path: 1 / sigma_t'.
  EXPECT_NEAR(1.0 / (a.medium.sigma_a[1] + a.medium.sigma_s[1] * (1 - a.medium.g[1])), 1.0, 1e-9);
  EXPECT_FALSE(s.materials[2].sss.enabled);
}

}  // namespace
}  // namespace sss::scene
