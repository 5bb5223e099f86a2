// reference::sky_occlusion (the GPU's environment occlusion bakes it per vertex), checked
// against closed forms of what a vertex's sky is blocked by:
//   - a long, tall wall beside a floor point blocks the quarter {w.x > 0} of its
//     hemisphere: B_k = that quarter's integral of Y_k (n.w), by a midpoint rule fine
//     enough (1000 x 1000 cells, error < 1e-6) to be exact here;
//   - a polygon parallel to a floor point above it: the blocked irradiance of a uniform
//     sky is pi L F, F the polygon's view factor by Lambert's contour formula (exact for
//     any polygon: F = (1 / 2 pi) sum over edges of the edge's subtended angle times the
//     cosine between n and the normal of the plane through the point and the edge).
// Each bake is a Monte Carlo estimate, seeded by the vertex's position and normal, so each
// test bakes M vertices at positions apart by far less than the closed form changes over
// (but not equal: each has its own seed) and Z-tests their mean against the closed form
// with their own standard error: |Z| < 4.5 fails a correct bake about once in 150,000
// per coefficient.
#include "reference/SkyOcclusion.h"

#include "reference/RayScene.h"
#include "reference/Shading.h"
#include "scene/BuiltinScenes.h"

#include "scene/Environment.h"
#include "scene/Shapes.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>

namespace sss::reference {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kZ = 4.5;
constexpr std::uint32_t kVertices = 300;

// A floor "mesh" of kVertices points from p along `step` (normal +z), with one small
// triangle below.
scene::Mesh floor_points(const glm::vec3& p, const glm::vec3& step) {
  scene::Mesh m;
  m.name = "floor points";
  for (std::uint32_t k = 0; k < kVertices; ++k) m.positions.push_back(p + float(k) * step);
  m.normals.assign(kVertices, {0.0f, 0.0f, 1.0f});
  const std::uint32_t base = kVertices;
  m.positions.insert(m.positions.end(), {{-3.0f, -3.0f, -1.0f}, {-2.0f, -3.0f, -1.0f}, {-3.0f, -2.0f, -1.0f}});
  m.normals.insert(m.normals.end(), 3, {0.0f, 0.0f, 1.0f});
  m.indices = {base, base + 1, base + 2};
  return m;
}

scene::Scene scene_of(std::vector<scene::Mesh> meshes) {
  scene::Scene s;
  s.mm_per_unit = 1.0;
  s.meshes = std::move(meshes);
  for (std::uint32_t i = 0; i < s.meshes.size(); ++i) s.instances.push_back({i, glm::mat4(1.0f), "n"});
  return s;
}

struct Stats {
  double mean = 0.0, se = 0.0;
};
template <class F>
Stats stats_of(const std::vector<SkyTransfer>& t, F value) {
  double sum = 0.0, sum2 = 0.0;
  for (std::uint32_t v = 0; v < kVertices; ++v) {
    const double x = value(t[v]);
    sum += x;
    sum2 += x * x;
  }
  const double mean = sum / kVertices;
  const double var = std::max(0.0, (sum2 - kVertices * mean * mean) / (kVertices - 1));
  return {mean, std::sqrt(var / kVertices)};
}

TEST(SkyOcclusion, AWallBlocksTheQuarterOfTheSkyBesideIt) {
  // The wall: the plane x = 0, 2e4 long and 1e4 tall, facing -x; the floor points 1e-3
  // from it, 0.01 apart along it (0..3). What it leaves open on the blocked side is under
  // 1e-6 sr.
  scene::Mesh wall;
  wall.name = "wall";
  wall.positions = {{0, -1e4f, 0}, {0, 1e4f, 0}, {0, 1e4f, 1e4f}, {0, -1e4f, 1e4f}};
  wall.normals.assign(4, {-1.0f, 0.0f, 0.0f});
  wall.indices = {0, 1, 2, 0, 2, 3};
  const scene::Scene s = scene_of({floor_points({-1e-3f, 0.0f, 0.0f}, {0.0f, 0.01f, 0.0f}), wall});
  const auto transfer = sky_occlusion(s);
  ASSERT_EQ(transfer.size(), 2u);
  ASSERT_EQ(transfer[0].size(), kVertices + 3);
  // B_k over theta in (0, pi/2), phi in (-pi/2, pi/2), with dw = sin(theta).
  std::array<double, 9> exact{};
  const int n = 1000;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double th = (i + 0.5) * (kPi / 2) / n, ph = -kPi / 2 + (j + 0.5) * kPi / n;
      const glm::vec3 w(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
      const std::array<float, 9> y = scene::sh_basis(w);
      const double dw = std::cos(th) * std::sin(th) * ((kPi / 2) / n) * (kPi / n);
      for (int k = 0; k < 9; ++k) exact[k] += y[k] * dw;
    }
  const std::array<double, 9> a = {kPi, 2 * kPi / 3, 2 * kPi / 3, 2 * kPi / 3, kPi / 4,
                                   kPi / 4, kPi / 4, kPi / 4, kPi / 4};
  for (int k = 0; k < 9; ++k) {
    const Stats st = stats_of(transfer[0], [k](const SkyTransfer& t) { return double(t[k]); });
    const double want = exact[k] / a[k];
    std::printf("T_%d: %.5f +- %.5f, exact %.5f\n", k, st.mean, st.se, want);
    EXPECT_LT(std::fabs(st.mean - want), kZ * st.se + 1e-6) << "coefficient " << k;  // + the rule's error
  }
}

// Lambert's formula for the view factor from a point at the origin with normal +z to a
// polygon (corners in order).
double polygon_view_factor(const std::vector<glm::dvec3>& corners) {
  double sum = 0.0;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const glm::dvec3 a = glm::normalize(corners[i]);
    const glm::dvec3 b = glm::normalize(corners[(i + 1) % corners.size()]);
    const double gamma = std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
    sum += gamma * glm::normalize(glm::cross(a, b)).z;
  }
  return std::fabs(sum) / (2.0 * kPi);
}

TEST(SkyOcclusion, APolygonAboveAPointBlocksItsViewFactorOfAUniformSky) {
  // A 24-gon of radius 1.5 at height 1, facing down, off the point's axis by 0.4 in x.
  const int sides = 24;
  const double r = 1.5, h = 1.0, off = 0.4;
  scene::Mesh roof;
  roof.name = "roof";
  std::vector<glm::dvec3> corners;
  roof.positions.push_back({float(off), 0.0f, float(h)});
  roof.normals.push_back({0.0f, 0.0f, -1.0f});
  for (int i = 0; i < sides; ++i) {
    const double phi = 2.0 * kPi * i / sides;
    corners.push_back({off + r * std::cos(phi), r * std::sin(phi), h});
    roof.positions.push_back(glm::vec3(corners.back()));
    roof.normals.push_back({0.0f, 0.0f, -1.0f});
    roof.indices.insert(roof.indices.end(), {0u, std::uint32_t(1 + (i + 1) % sides), std::uint32_t(1 + i)});
  }
  // The points 1e-7 apart along x (3e-5 in all): F changes by less than 1e-4 of its SE.
  const scene::Scene s = scene_of({floor_points({0.0f, 0.0f, 0.0f}, {1e-7f, 0.0f, 0.0f}), roof});
  const auto transfer = sky_occlusion(s);
  const scene::Environment sky = scene::uniform_environment({0.5f, 1.0f, 2.0f});
  // The point's ray origin is raised 1e-4 x the scene's diagonal (from the triangle
  // below to the roof), which brings it nearer the roof: the exact value is taken there.
  const double lift = 1e-4 * glm::length(glm::dvec3(off + r + 3.0, r + 3.0, h + 1.0));
  std::vector<glm::dvec3> seen = corners;
  for (glm::dvec3& c : seen) c.z -= lift;
  const double f = polygon_view_factor(seen);
  for (int c = 0; c < 3; ++c) {
    const Stats st = stats_of(transfer[0], [&](const SkyTransfer& t) {
      return double(blocked_irradiance(sky.irradiance_sh, t)[c]);
    });
    const double want = kPi * sky.colour[c] * f;
    std::printf("channel %d: E_blocked %.5f +- %.5f, pi L F %.5f (F %.5f)\n", c, st.mean, st.se, want, f);
    EXPECT_LT(std::fabs(st.mean - want), kZ * st.se) << "channel " << c;
  }
}

// A convex object alone blocks nothing: every vertex of a sphere and of a box gets exactly
// zero, so an unoccluded surface is lit exactly as without the bake.
TEST(SkyOcclusion, AConvexObjectBlocksNothing) {
  for (const scene::Mesh& m : {scene::make_uv_sphere(3.0f, 32, 16), scene::make_box({-1, -2, -3}, {1, 2, 3})}) {
    const auto transfer = sky_occlusion(scene_of({m}));
    ASSERT_EQ(transfer[0].size(), m.positions.size());
    for (std::size_t v = 0; v < m.positions.size(); ++v)
      for (int k = 0; k < 9; ++k) ASSERT_EQ(transfer[0][v][k], 0.0f) << "vertex " << v << " k " << k;
  }
}

// The inside of a closed box, turned 30 degrees about a skew axis, scaled, in a scene of
// other units: every direction from every vertex meets the box, so each vertex blocks the
// whole sky, T_0 = Y_00 = 1 / (2 sqrt(pi)) exactly (each sample adds Y_00). The box's
// vertices sit on creases between faces with split normals, where a ray into the next
// face starts in its plane: the bake starts it off that plane (toward the vertex's own
// triangles), or rounding loses some of those rays.
TEST(SkyOcclusion, EveryVertexInsideAClosedBoxSeesNoSky) {
  scene::Mesh box = scene::make_box({-1.0f, -2.0f, -0.5f}, {3.0f, 1.0f, 2.5f});
  for (glm::vec3& n : box.normals) n = -n;
  for (std::size_t t = 0; t + 2 < box.indices.size(); t += 3) std::swap(box.indices[t + 1], box.indices[t + 2]);
  scene::Scene s = scene_of({box});
  s.mm_per_unit = 25.4;
  s.instances[0].world = glm::rotate(glm::scale(glm::mat4(1.0f), glm::vec3(1.7f)), 0.5236f,
                                     glm::normalize(glm::vec3(1.0f, 2.0f, 3.0f)));
  const auto transfer = sky_occlusion(s);
  const double y00 = 0.5 / std::sqrt(kPi);
  for (std::size_t v = 0; v < box.positions.size(); ++v)
    EXPECT_NEAR(transfer[0][v][0], y00, 1e-6) << "vertex " << v;
}

// A cancelled bake stops before it casts a ray (the points beside a wall, which a bake
// gives T_0 = 0.14, keep 0); an empty scene bakes nothing.
TEST(SkyOcclusion, EmptyAndCancelled) {
  EXPECT_TRUE(sky_occlusion(scene::Scene{}).empty());
  scene::Mesh wall = scene::make_box({0.0f, -10.0f, 0.0f}, {1.0f, 10.0f, 10.0f});
  const scene::Scene s = scene_of({floor_points({-1e-3f, 0.0f, 0.0f}, {0.0f, 0.01f, 0.0f}), wall});
  EXPECT_GT(sky_occlusion(s)[0][0][0], 0.1f);
  std::atomic<bool> cancel{true};
  const auto transfer = sky_occlusion(s, &cancel);
  ASSERT_EQ(transfer.size(), 2u);
  for (std::uint32_t v = 0; v < kVertices; ++v) EXPECT_EQ(transfer[0][v][0], 0.0f);
}

// The bake against the references' own sky sampler (reference::environment_irradiance,
// shadow rays from the point, independent code and seeds) at the bunny's vertices, under
// a uniform sky: the irradiance the GPU keeps, E_open - E_blocked, against the sampled E.
// Both estimate the visible sky's irradiance; their ray origins differ by less than the
// sampling resolves (the bake lifts by 1e-4 of the scene's diagonal along n, the sampler
// by 1e-4 of |p| along the geometric normal), so their per-vertex differences have mean
// 0: Z-tested over every vertex.
TEST(SkyOcclusion, AgreesWithTheReferencesSamplerOnTheBunny) {
  auto loaded = scene::load_scene("builtin:bunny");
  ASSERT_TRUE(std::holds_alternative<scene::Scene>(loaded));
  scene::Scene s = std::get<scene::Scene>(std::move(loaded));
  const scene::Environment sky = scene::uniform_environment({1.0f, 1.0f, 1.0f});
  const auto transfer = sky_occlusion(s);
  const RayScene rays(s);
  double sum = 0.0, sum2 = 0.0, blocked = 0.0;
  std::size_t n = 0;
  for (std::uint32_t i = 0; i < s.instances.size(); ++i) {
    const scene::Mesh& mesh = s.meshes[s.instances[i].mesh];
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      SurfacePoint p;
      p.position_mm = rays.world_positions(i)[v];
      p.normal = glm::normalize(rays.normal_matrix(i) * mesh.normals[v]);
      p.geometric_normal = p.normal;
      const double ref = environment_irradiance(sky, rays, p, p.normal, false, nullptr).x;
      const double gpu = kPi - blocked_irradiance(sky.irradiance_sh, transfer[i][v]).x;
      sum += gpu - ref;
      sum2 += (gpu - ref) * (gpu - ref);
      blocked += kPi - gpu;
      ++n;
    }
  }
  const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / (n - 1));
  std::printf("%zu vertices: mean blocked %.4f of pi; GPU - reference %.5f +- %.5f\n", n,
              blocked / n / kPi, mean, se);
  EXPECT_LT(std::fabs(mean), kZ * se);
}

}  // namespace
}  // namespace sss::reference
