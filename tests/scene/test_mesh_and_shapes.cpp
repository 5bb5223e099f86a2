// Mesh helpers (normals, bounds, checks) and the shapes of the built-in scenes.
#include "scene/Mesh.h"
#include "scene/Shapes.h"
#include "scene/Camera.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace sss::scene {
namespace {

TEST(Mesh, AreaWeightedNormals) {
  // Vertex 0 is shared by a large triangle facing +z and a small one facing +x: the
  // normal leans toward +z in proportion to the areas (4 : 1).
  const std::vector<glm::vec3> p = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, -1}, {0, 1, 0}};
  const std::vector<std::uint32_t> idx = {0, 1, 2, 0, 3, 4};
  const auto n = area_weighted_normals(p, idx);
  const glm::vec3 expected = glm::normalize(glm::vec3(1, 0, 4));
  EXPECT_NEAR(glm::distance(n[0], expected), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(n[1], glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(n[3], glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
}

TEST(Mesh, RepairNormals) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.indices = {0, 1, 2};
  m.normals = {{0, 0, 3}, {0, 0, 0}, {0, 0, 1}};
  EXPECT_EQ(repair_normals(m), 1u);
  for (const glm::vec3& n : m.normals) EXPECT_NEAR(glm::distance(n, glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
  m.normals.clear();
  EXPECT_EQ(repair_normals(m), 0u);
  EXPECT_EQ(m.normals.size(), 3u);
  compute_bounds(m);
  EXPECT_EQ(check_mesh(m), std::nullopt);
  m.indices = {0, 1, 3};
  EXPECT_NE(check_mesh(m), std::nullopt);
}

TEST(Bounds, TransformAndRadius) {
  Bounds b;
  EXPECT_TRUE(b.empty());
  b.extend({-1, -2, -3});
  b.extend({1, 2, 3});
  EXPECT_FLOAT_EQ(b.radius(), std::sqrt(14.0f));
  glm::mat4 t(1.0f);
  t[3] = glm::vec4(10, 0, 0, 1);
  const Bounds moved = b.transformed(t);
  EXPECT_EQ(moved.min, glm::vec3(9, -2, -3));
  EXPECT_EQ(moved.max, glm::vec3(11, 2, 3));
}

TEST(Shapes, SphereIsClosedOutwardAndMapped) {
  const Mesh s = make_uv_sphere(2.0f, 16, 8);
  EXPECT_EQ(check_mesh(s), std::nullopt);
  EXPECT_EQ(s.triangle_count(), 2u * 16 * 8 - 2 * 16);  // no degenerate pole triangles
  double area = 0.0;
  for (std::size_t t = 0; t < s.indices.size(); t += 3) {
    const glm::vec3 a = s.positions[s.indices[t]], b = s.positions[s.indices[t + 1]],
                    c = s.positions[s.indices[t + 2]];
    const glm::vec3 f = glm::cross(b - a, c - a);
    EXPECT_GT(glm::dot(f, a + b + c), 0.0f);  // outward
    area += 0.5 * glm::length(f);
  }
  EXPECT_NEAR(area, 4 * M_PI * 4.0, 0.1 * 4 * M_PI * 4.0);
  for (std::size_t i = 0; i < s.positions.size(); ++i) {
    EXPECT_NEAR(glm::dot(glm::vec3(s.tangents[i]), s.normals[i]), 0.0f, 1e-6f);
    EXPECT_GE(s.uv0[i].x, 0.0f);
    EXPECT_LE(s.uv0[i].y, 1.0f);
  }
}

TEST(Shapes, BoxFacesOutward) {
  const Mesh b = make_box({-1, -2, -3}, {1, 0, 3});
  EXPECT_EQ(check_mesh(b), std::nullopt);
  EXPECT_EQ(b.triangle_count(), 12u);
  EXPECT_EQ(b.bounds.min, glm::vec3(-1, -2, -3));
  EXPECT_EQ(b.bounds.max, glm::vec3(1, 0, 3));
  for (std::size_t t = 0; t < b.indices.size(); t += 3) {
    const glm::vec3 p0 = b.positions[b.indices[t]], p1 = b.positions[b.indices[t + 1]],
                    p2 = b.positions[b.indices[t + 2]];
    const glm::vec3 f = glm::normalize(glm::cross(p1 - p0, p2 - p0));
    EXPECT_NEAR(glm::distance(f, b.normals[b.indices[t]]), 0.0f, 1e-6f);
  }
}

TEST(Camera, FrameBoundsSeesTheSphere) {
  Bounds b;
  b.extend({-1, -1, -1});
  b.extend({3, 1, 1});
  const Camera c = frame_bounds(b, {0, 0, -1}, 0.5f);
  const glm::vec3 to_center = b.center() - c.position();
  EXPECT_NEAR(glm::dot(glm::normalize(to_center), c.forward()), 1.0f, 1e-6f);
  EXPECT_GE(std::asin(b.radius() / glm::length(to_center)), 0.0f);
  EXPECT_LE(std::asin(b.radius() / glm::length(to_center)), 0.5f * c.yfov);
  EXPECT_LT(c.znear, glm::length(to_center) - b.radius());
  EXPECT_GT(c.zfar, glm::length(to_center) + b.radius());
  // view() is the inverse of world.
  const glm::mat4 id = c.view() * c.world;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(id[i][j], i == j ? 1.0f : 0.0f, 1e-5f);
}

}  // namespace
}  // namespace sss::scene
