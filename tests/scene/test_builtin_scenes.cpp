// The built-in scenes have what issue 3 specifies.
#include "scene/BuiltinScenes.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <set>
#include <tuple>

namespace sss::scene {
namespace {

Scene get(std::string_view name) {
  auto r = builtin_scene(name);
  if (auto* e = std::get_if<LoadError>(&r)) ADD_FAILURE() << e->what();
  return r.index() == 0 ? std::get<Scene>(std::move(r)) : Scene{};
}

void expect_valid(const Scene& s) {
  ASSERT_FALSE(s.meshes.empty());
  ASSERT_FALSE(s.instances.empty());
  ASSERT_FALSE(s.cameras.empty());
  ASSERT_FALSE(s.lights.empty());
  for (const Mesh& m : s.meshes) {
    EXPECT_EQ(check_mesh(m), std::nullopt) << m.name;
    EXPECT_LT(m.material, s.materials.size());
    // Every triangle faces away from the mesh centre (closed convex shapes) or, for the
    // bunny, the winding agrees with the normals.
    for (std::size_t t = 0; t < m.indices.size(); t += 3) {
      const glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                      c = m.positions[m.indices[t + 2]];
      const glm::vec3 face = glm::cross(b - a, c - a);
      const glm::vec3 n = m.normals[m.indices[t]] + m.normals[m.indices[t + 1]] + m.normals[m.indices[t + 2]];
      if (glm::length(face) > 1e-12f) {
        EXPECT_GT(glm::dot(face, n), 0.0f) << m.name << " triangle " << t / 3;
      }
    }
  }
  for (const Instance& i : s.instances) EXPECT_LT(i.mesh, s.meshes.size());
  EXPECT_FALSE(s.bounds().empty());
}

TEST(BuiltinScenes, NamesAndUnknown) {
  const auto names = builtin_scene_names();
  EXPECT_EQ(names, (std::vector<std::string>{"builtin:bunny", "builtin:edge", "builtin:materials",
                                             "builtin:slab", "builtin:sphere"}));
  auto r = builtin_scene("builtin:teapot");
  ASSERT_TRUE(std::holds_alternative<LoadError>(r));
  const std::string what = std::get<LoadError>(r).what();
  EXPECT_NE(what.find("builtin:teapot"), std::string::npos) << what;
  for (const auto& n : names) EXPECT_NE(what.find(n), std::string::npos) << what;
  EXPECT_EQ(kDefaultScene, "builtin:bunny");
}

TEST(BuiltinScenes, Edge) {
  const Scene s = get("builtin:edge");
  expect_valid(s);
  EXPECT_DOUBLE_EQ(s.mm_per_unit, 1000.0);
  // Camera: orthographic, straight down, image right = +x, 40 mm across.
  ASSERT_EQ(s.cameras.size(), 1u);
  const Camera& cam = s.cameras[0];
  EXPECT_EQ(cam.projection, Projection::Orthographic);
  EXPECT_NEAR(2.0 * cam.xmag * s.mm_per_unit, 40.0, 1e-5);
  EXPECT_NEAR(glm::distance(cam.forward(), glm::vec3(0, -1, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(glm::vec3(cam.world[0]), glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(cam.position().x, 0.0f, 1e-7f);
  EXPECT_NEAR(cam.position().z, 0.0f, 1e-7f);
  EXPECT_GT(cam.position().y, cam.znear);
  // Same mm per pixel along z: ymag follows the image aspect.
  const glm::vec2 half = cam.ortho_half_extent(16.0f / 9.0f);
  EXPECT_NEAR(half.y, half.x * 9.0f / 16.0f, 1e-9f);
  // Light: normal incidence, E = 1, lit only where x < 0, sharp at x = 0.
  ASSERT_EQ(s.lights.size(), 1u);
  const Light& l = s.lights[0];
  EXPECT_EQ(l.type, LightType::Directional);
  EXPECT_NEAR(glm::distance(l.direction(), glm::vec3(0, -1, 0)), 0.0f, 1e-6f);
  EXPECT_FLOAT_EQ(l.intensity, 1.0f);
  EXPECT_EQ(l.color, glm::vec3(1.0f));
  ASSERT_TRUE(l.mask.has_value());
  EXPECT_EQ(*l.mask, glm::vec4(1, 0, 0, 0));
  EXPECT_TRUE(l.reaches({-1e-4f, 0, 5e-3f}));
  EXPECT_FALSE(l.reaches({1e-4f, 0, -5e-3f}));
  // The slab: top face in y = 0, 200 mm square, one SSS material without specular.
  const Bounds b = s.bounds();
  EXPECT_FLOAT_EQ(b.max.y, 0.0f);
  EXPECT_NEAR(b.extent().x, 0.2f, 1e-6f);
  EXPECT_NEAR(b.extent().z, 0.2f, 1e-6f);
  ASSERT_EQ(s.materials.size(), 1u);
  const Material& m = s.materials[0];
  EXPECT_TRUE(m.sss.enabled);
  EXPECT_EQ(std::get<PresetSource>(m.sss.source).name, "skin1");
  EXPECT_EQ(m.sss.model, profiles::kDefaultModel);  // no "model" given
  EXPECT_EQ(m.sss.albedo_mode, AlbedoMode::PostScatter);
  EXPECT_EQ(m.specular, 0.0f);
  EXPECT_EQ(m.roughness, 1.0f);
  EXPECT_EQ(m.base_color, glm::vec4(1.0f));
  EXPECT_FALSE(m.base_color_texture || m.normal_texture);
  EXPECT_TRUE(s.textures.empty());
}

TEST(BuiltinScenes, EdgeWithMarble) {
  const Scene s = edge_scene({.preset = "marble", .half_width_mm = 10.0});
  EXPECT_EQ(std::get<PresetSource>(s.materials[0].sss.source).name, "marble");
  EXPECT_NEAR(2.0 * s.cameras[0].xmag * s.mm_per_unit, 20.0, 1e-5);
  EXPECT_THROW(edge_scene({.preset = "jade"}), std::invalid_argument);
}

TEST(BuiltinScenes, Sphere) {
  const Scene s = get("builtin:sphere");
  expect_valid(s);
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& m = s.meshes[0];
  EXPECT_EQ(m.uv0.size(), m.positions.size());
  EXPECT_EQ(m.tangents.size(), m.positions.size());
  for (const glm::vec3& p : m.positions) EXPECT_NEAR(glm::length(p), 0.030f, 1e-6f);
  EXPECT_TRUE(s.materials[m.material].sss.enabled);
  // The camera sees the sphere: it looks at the centre from outside.
  const Camera& cam = s.cameras[0];
  EXPECT_GT(glm::length(cam.position()), 0.030f / std::sin(0.5f * cam.yfov));
  EXPECT_NEAR(glm::dot(cam.forward(), glm::normalize(-cam.position())), 1.0f, 1e-5f);
}

TEST(BuiltinScenes, MaterialsHasAtLeastEightDistinctProfiles) {
  const Scene s = get("builtin:materials");
  expect_valid(s);
  std::set<std::tuple<double, double, double, double, double, double>> media;
  for (const Instance& i : s.instances) {
    const Material& m = s.materials[s.meshes[i.mesh].material];
    ASSERT_TRUE(m.sss.enabled) << m.name;
    const auto& md = m.sss.medium;
    media.emplace(md.sigma_a[0], md.sigma_a[1], md.sigma_a[2], md.sigma_s[0], md.sigma_s[1], md.sigma_s[2]);
  }
  EXPECT_GE(media.size(), 8u);
  EXPECT_EQ(media.size(), s.instances.size());
  // Every sphere is in front of the camera and inside its field of view.
  const Camera& cam = s.cameras[0];
  for (const Instance& i : s.instances) {
    const glm::vec3 to = glm::vec3(i.world[3]) - cam.position();
    EXPECT_LT(std::acos(glm::dot(glm::normalize(to), cam.forward())), 0.5f * cam.yfov) << i.node;
  }
}

TEST(BuiltinScenes, Bunny) {
  const Scene s = get("builtin:bunny");
  expect_valid(s);
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& m = s.meshes[0];
  EXPECT_EQ(m.vertex_count(), 1839u);
  EXPECT_EQ(m.triangle_count(), 3674u);
  for (const glm::vec3& n : m.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
  // A 150 mm figurine standing on y = 0, centred in x and z.
  const Bounds b = s.bounds();
  EXPECT_NEAR(b.min.y, 0.0f, 1e-6f);
  EXPECT_NEAR(b.max.y * s.mm_per_unit, 150.0, 1e-3);
  EXPECT_NEAR(b.extent().x * s.mm_per_unit, 154.0, 2.0);
  EXPECT_NEAR(b.center().x, 0.0f, 1e-6f);
  EXPECT_NEAR(b.center().z, 0.0f, 1e-6f);
  const Material& mat = s.materials[m.material];
  ASSERT_TRUE(mat.sss.enabled);
  EXPECT_EQ(std::get<PresetSource>(mat.sss.source).name, "skin1");
  // bunny.glb names no model, so the default scene shows the default model (issue 8).
  EXPECT_EQ(mat.sss.model, profiles::kDefaultModel);
  // At scale 0.25, so that light comes through the scan's 9-17 mm thick ears (bunny_scene()).
  EXPECT_EQ(mat.sss.scale, 0.25);
  // The key light comes from behind the bunny (+x side, it faces -x), a little from above.
  ASSERT_GE(s.lights.size(), 1u);
  EXPECT_LT(s.lights[0].direction().x, -0.5f);
  EXPECT_LT(s.lights[0].direction().y, 0.0f);
  // The camera looks from the front (-x side), toward the light: the ears are back-lit.
  EXPECT_GT(s.cameras[0].forward().x, 0.5f);
  EXPECT_LT(glm::dot(s.cameras[0].forward(), s.lights[0].direction()), 0.0f);
}

TEST(BuiltinScenes, LoadSceneDispatches) {
  EXPECT_TRUE(std::holds_alternative<Scene>(load_scene("builtin:edge")));
  auto r = load_scene("/nonexistent/file.gltf");
  ASSERT_TRUE(std::holds_alternative<LoadError>(r));
  EXPECT_NE(std::get<LoadError>(r).what().find("/nonexistent/file.gltf"), std::string::npos);
}

}  // namespace
}  // namespace sss::scene
