// reference::inward_thickness (the environment's transmission on the GPU bakes it per
// vertex): checked against the closed forms of shapes whose chords are known exactly.
// Tolerance: the ray's float arithmetic, a few ulps of the shape's size (1e-5 relative),
// and on curved shapes what the start's nudge toward the triangles around it costs (the
// sphere's test derives it); the 1e-4 start offset only skips the vertex's own triangles
// and does not shorten t.
#include "reference/Thickness.h"

#include "scene/Shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sss::reference {
namespace {

// A box's vertices carry their face's normal: the ray crosses the box along that axis,
// so the thickness is the box's side along it. The corners' rays run along the side
// faces' planes and must still find the opposite face.
TEST(InwardThickness, ABoxsVertexGetsTheBoxsSideAlongItsNormal) {
  const scene::Mesh box = scene::make_box({-1.0f, -2.0f, -3.0f}, {1.0f, 2.0f, 3.0f});
  const std::vector<float> d = inward_thickness(box);
  ASSERT_EQ(d.size(), box.positions.size());
  for (std::size_t i = 0; i < d.size(); ++i) {
    const glm::vec3 n = box.normals[i];
    const double side = std::fabs(n.x) * 2.0 + std::fabs(n.y) * 4.0 + std::fabs(n.z) * 6.0;
    EXPECT_NEAR(d[i], side, 1e-5 * side) << "vertex " << i;
  }
}

// A UV sphere's vertices carry radial normals and its antipodes are vertices (an even
// number of segments): the chord is the diameter, less what the start's nudge costs. The
// ray starts at most 1e-3 h from the vertex (h the longest edge, 2 pi r / segments), so
// it meets the facets around the antipode that far from their vertex, where they lie
// inside the sphere by at most 1e-3 h tan(pi / rings) (adjacent normals differ by at
// most pi / rings); and its own end likewise: 2e-3 h tan(pi / rings) = 0.0010 here
// (measured 3.7e-4), plus float rounding.
TEST(InwardThickness, ASpheresVertexGetsItsDiameter) {
  const float r = 12.5f;
  const std::uint32_t segments = 32, rings = 16;
  const scene::Mesh sphere = scene::make_uv_sphere(r, segments, rings);
  const std::vector<float> d = inward_thickness(sphere);
  ASSERT_EQ(d.size(), sphere.positions.size());
  const double pi = 3.14159265358979323846;
  const double h = 2.0 * pi * r / segments;
  const double tol = 2e-3 * h * std::tan(pi / rings) + 1e-5 * 2.0 * r;
  double worst = 0.0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    EXPECT_NEAR(d[i], 2.0f * r, tol) << "vertex " << i;
    worst = std::max(worst, std::fabs(d[i] - 2.0 * r));
  }
  std::printf("sphere r %.1f: worst |d - 2r| %.2e (bound %.2e)\n", r, worst, tol);
}

// An open mesh (one quad): nothing behind it, so no thickness (-1), and the GPU
// transmits none of the sky through it.
TEST(InwardThickness, AnOpenQuadHasNone) {
  scene::Mesh quad;
  quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  quad.normals.assign(4, {0, 0, 1});
  quad.indices = {0, 1, 2, 0, 2, 3};
  for (const float d : inward_thickness(quad)) EXPECT_EQ(d, -1.0f);
  quad.indices.clear();
  EXPECT_TRUE(inward_thickness(quad).empty());
}

// Two boxes side by side: the ray leaves the first box through its far face and stops
// there, the gap and the second box do not count.
TEST(InwardThickness, TheFirstExitCountsNotTheNextObject) {
  scene::Mesh a = scene::make_box({0, 0, 0}, {1, 1, 1});
  const scene::Mesh b = scene::make_box({2, 0, 0}, {5, 1, 1});
  const std::uint32_t base = std::uint32_t(a.positions.size());
  a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
  a.normals.insert(a.normals.end(), b.normals.begin(), b.normals.end());
  for (const std::uint32_t i : b.indices) a.indices.push_back(base + i);
  const std::vector<float> d = inward_thickness(a);
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (a.normals[i].x > 0.5f) {
      EXPECT_NEAR(d[i], i < base ? 1.0f : 3.0f, 1e-5f) << "vertex " << i;
    }
  }
}

}  // namespace
}  // namespace sss::reference
