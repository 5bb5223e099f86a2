// sample_surface: area-uniform blue-noise irradiance points (weighted sample
// elimination, Yuksel 2015).
#include "reference/SurfaceSampling.h"

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

using namespace sss::reference;

namespace {

void add_triangle(TriangleSoup& s, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  s.positions_mm.insert(s.positions_mm.end(), {a, b, c});
  const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
  s.normals.insert(s.normals.end(), {n, n, n});
}

// The square [0, L]² in z = 0 cut into a fan of triangles of very different areas: the
// left column is split into thin slivers, the rest into two big triangles.
TriangleSoup uneven_square(float L, int slivers) {
  TriangleSoup s;
  const float w = 0.1f * L;  // the sliver column [0, w] x [0, L]
  for (int i = 0; i < slivers; ++i) {
    const float y0 = L * float(i) / float(slivers), y1 = L * float(i + 1) / float(slivers);
    add_triangle(s, {0, y0, 0}, {w, y0, 0}, {w, y1, 0});
    add_triangle(s, {0, y0, 0}, {w, y1, 0}, {0, y1, 0});
  }
  add_triangle(s, {w, 0, 0}, {L, 0, 0}, {L, L, 0});
  add_triangle(s, {w, 0, 0}, {L, L, 0}, {w, L, 0});
  return s;
}

// A UV sphere of radius r with smooth (radial) corner normals.
TriangleSoup sphere(float r, int rings, int segments) {
  TriangleSoup s;
  const auto at = [&](int i, int j) {
    const double th = std::numbers::pi * i / rings, ph = 2.0 * std::numbers::pi * j / segments;
    return glm::vec3(glm::dvec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph),
                                std::cos(th)));
  };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const glm::vec3 a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if (i + 1 < rings) {
        s.positions_mm.insert(s.positions_mm.end(), {r * a, r * b, r * c});
        s.normals.insert(s.normals.end(), {a, b, c});
      }
      if (i > 0) {
        s.positions_mm.insert(s.positions_mm.end(), {r * a, r * c, r * d});
        s.normals.insert(s.normals.end(), {a, c, d});
      }
    }
  return s;
}

double soup_area(const TriangleSoup& s) {
  double a = 0.0;
  for (std::size_t t = 0; t < s.triangle_count(); ++t) {
    const glm::dvec3 p0(s.positions_mm[3 * t]), p1(s.positions_mm[3 * t + 1]),
        p2(s.positions_mm[3 * t + 2]);
    a += 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
  }
  return a;
}

// Nearest-neighbour distance of every point (a hash grid of cubes of side `cell`,
// searching 5³ cubes: exact whenever the nearest neighbour is within 2 cells, which
// blue noise of spacing ≈ cell guarantees; reported as +inf otherwise).
std::vector<double> nearest_neighbour(const std::vector<SampledPoint>& pts, double cell) {
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> grid;
  const auto key = [&](int x, int y, int z) {
    return (std::int64_t(x) * 1000003 + y) * 1000033 + z;
  };
  const auto cube = [&](const glm::vec3& p) {
    return glm::ivec3(glm::floor(glm::dvec3(p) / cell));
  };
  for (std::uint32_t i = 0; i < pts.size(); ++i) {
    const glm::ivec3 c = cube(pts[i].position_mm);
    grid[key(c.x, c.y, c.z)].push_back(i);
  }
  std::vector<double> nn(pts.size(), std::numeric_limits<double>::infinity());
  for (std::uint32_t i = 0; i < pts.size(); ++i) {
    const glm::ivec3 c = cube(pts[i].position_mm);
    for (int dx = -2; dx <= 2; ++dx)
      for (int dy = -2; dy <= 2; ++dy)
        for (int dz = -2; dz <= 2; ++dz) {
          const auto it = grid.find(key(c.x + dx, c.y + dy, c.z + dz));
          if (it == grid.end()) continue;
          for (const std::uint32_t j : it->second)
            if (j != i)
              nn[i] = std::min(nn[i], double(glm::distance(glm::dvec3(pts[i].position_mm),
                                                           glm::dvec3(pts[j].position_mm))));
        }
    if (nn[i] > 2.0 * cell) nn[i] = std::numeric_limits<double>::infinity();
  }
  return nn;
}

}  // namespace

SampledSurface sample(const TriangleSoup& s, double spacing, std::uint64_t seed = 1) {
  SamplingOptions o;
  o.spacing_mm = spacing;
  o.seed = seed;
  return sample_surface(s, o);
}

// Σ (n − e)²/e over bins, and its number of degrees of freedom.
struct ChiSquare {
  double value = 0.0;
  int dof = -1;
  void add(double observed, double expected) {
    value += (observed - expected) * (observed - expected) / expected;
    ++dof;
  }
  // Under the null hypothesis of independent (multinomial) counts χ² has mean dof and
  // variance 2 dof; blue noise is under-dispersed (fewer fluctuations than independent
  // points), so the same bound is conservative for it.
  double sigmas() const { return (value - dof) / std::sqrt(2.0 * dof); }
};

TEST(SurfaceSampling, CountAreaAndEveryPointOnItsTriangle) {
  for (const TriangleSoup& soup : {uneven_square(10.0f, 50), sphere(6.0f, 24, 48)}) {
    const double spacing = 0.1;
    const SampledSurface out = sample(soup, spacing);
    const double area = soup_area(soup);
    // The area is summed in double over the same triangles: equal to rounding (1e-14
    // relative over a few thousand terms).
    EXPECT_NEAR(out.area_mm2, area, 1e-12 * area);
    EXPECT_EQ(out.points.size(), std::size_t(std::ceil(area / (spacing * spacing))));
    EXPECT_DOUBLE_EQ(out.point_area_mm2, out.area_mm2 / double(out.points.size()));
    for (const SampledPoint& p : out.points) {
      ASSERT_LT(p.triangle, soup.triangle_count());
      const glm::dvec3 p0(soup.positions_mm[3 * p.triangle]), p1(soup.positions_mm[3 * p.triangle + 1]),
          p2(soup.positions_mm[3 * p.triangle + 2]);
      const double b1 = p.barycentric.x, b2 = p.barycentric.y;
      // Barycentrics are stored in float: inside the triangle to float rounding (6e-8).
      EXPECT_GE(b1, 0.0);
      EXPECT_GE(b2, 0.0);
      EXPECT_LE(b1 + b2, 1.0 + 1e-6);
      // The position is that point, to float rounding of coordinates up to 10 mm
      // (1e-6 mm) plus the barycentrics' (6e-8 of the triangle's size).
      const glm::dvec3 at = p0 + b1 * (p1 - p0) + b2 * (p2 - p0);
      EXPECT_LT(glm::length(glm::dvec3(p.position_mm) - at), 1e-5);
      // The normal is the interpolated corner normal, normalised.
      const glm::dvec3 n = (1.0 - b1 - b2) * glm::dvec3(soup.normals[3 * p.triangle]) +
                           b1 * glm::dvec3(soup.normals[3 * p.triangle + 1]) +
                           b2 * glm::dvec3(soup.normals[3 * p.triangle + 2]);
      EXPECT_LT(glm::length(glm::dvec3(p.normal) - glm::normalize(n)), 1e-6);
    }
  }
}

TEST(SurfaceSampling, AreaUniformOverTrianglesOfVeryDifferentAreas) {
  // The square [0, 10]² as 100 slivers of 0.1 mm² (the column x < 1) and two big
  // triangles of 45 mm²: counts per triangle against N·A_t/A (χ²), and the sliver
  // column's share against its area share (binomial, in sigmas). Limit: 4 sigmas. The
  // rim's small excess (RimDensity) moves the column's share by ~0.4% of its count, a
  // quarter of one sigma.
  const TriangleSoup soup = uneven_square(10.0f, 50);
  const SampledSurface out = sample(soup, 0.05);
  const double N = double(out.points.size());
  std::vector<double> count(soup.triangle_count(), 0.0);
  for (const SampledPoint& p : out.points) count[p.triangle] += 1.0;
  ChiSquare chi;
  double column = 0.0;
  for (std::size_t t = 0; t < soup.triangle_count(); ++t) {
    const glm::vec3* q = &soup.positions_mm[3 * t];
    const double at = 0.5 * glm::length(glm::cross(glm::dvec3(q[1] - q[0]), glm::dvec3(q[2] - q[0])));
    chi.add(count[t], N * at / out.area_mm2);
    if (t < 100) column += count[t];
  }
  EXPECT_LT(chi.sigmas(), 4.0) << "chi2 " << chi.value << " dof " << chi.dof;
  const double share = 0.1, sd = std::sqrt(N * share * (1.0 - share));
  EXPECT_NEAR(column, N * share, 4.0 * sd);
  std::printf("[ info ] %0.f points: chi2/dof over triangles %.2f (independent points: 1); "
              "sliver column %+.2f sigma\n", N, chi.value / chi.dof, (column - N * share) / sd);
}

TEST(SurfaceSampling, AreaUniformOverGridCellsAndOnASphere) {
  // 20 x 20 cells of the square (400 points each) and the 24 rings of a UV sphere (the
  // rings' areas, from the mesh, differ by 15x from equator to pole): χ² within 4 sigmas.
  {
    const SampledSurface out = sample(uneven_square(10.0f, 50), 0.05);
    std::vector<double> count(400, 0.0);
    for (const SampledPoint& p : out.points) {
      const int i = std::min(19, int(p.position_mm.x / 0.5f)), j = std::min(19, int(p.position_mm.y / 0.5f));
      count[std::size_t(20 * i + j)] += 1.0;
    }
    ChiSquare chi;
    for (const double c : count) chi.add(c, double(out.points.size()) / 400.0);
    EXPECT_LT(chi.sigmas(), 4.0) << "chi2 " << chi.value << " dof " << chi.dof;
    std::printf("[ info ] grid cells: chi2/dof %.2f\n", chi.value / chi.dof);
  }
  {
    const int rings = 24, segments = 48;
    const TriangleSoup soup = sphere(6.0f, rings, segments);
    const SampledSurface out = sample(soup, 0.08);
    // Triangles are laid out ring by ring: the first ring has `segments` triangles, the
    // middle ones 2 segments, the last `segments`.
    const auto ring_of = [&](std::uint32_t t) {
      if (t < std::uint32_t(segments)) return 0;
      return std::min(rings - 1, 1 + int((t - segments) / (2 * segments)));
    };
    std::vector<double> count(rings, 0.0), area(rings, 0.0);
    for (std::uint32_t t = 0; t < soup.triangle_count(); ++t) {
      const glm::vec3* q = &soup.positions_mm[3 * t];
      area[std::size_t(ring_of(t))] +=
          0.5 * glm::length(glm::cross(glm::dvec3(q[1] - q[0]), glm::dvec3(q[2] - q[0])));
    }
    for (const SampledPoint& p : out.points) count[std::size_t(ring_of(p.triangle))] += 1.0;
    ChiSquare chi;
    for (int r = 0; r < rings; ++r)
      chi.add(count[std::size_t(r)], double(out.points.size()) * area[std::size_t(r)] / out.area_mm2);
    EXPECT_LT(chi.sigmas(), 4.0) << "chi2 " << chi.value << " dof " << chi.dof;
    std::printf("[ info ] sphere rings: chi2/dof %.2f\n", chi.value / chi.dof);
  }
}

TEST(SurfaceSampling, BlueNoiseSpacing) {
  // Nearest-neighbour distances in units of the spacing s (N = A/s²). Independent
  // uniform points would have a mean of 0.5 s (Poisson process: 1/(2√density)) and a
  // minimum near 0; the hexagonal packing, the densest, has 2 r_max = 1.0746 s for
  // every point. Weighted elimination (Yuksel 2015) reaches a minimum of ~0.7 s
  // (measured 0.744 s here; Yuksel reports similar relative radii). Limits: minimum
  // >= 0.5 s (typical of elimination, far from random), mean within [0.8 s, 1.0746 s]
  // (measured 0.849 s).
  const double s = 0.05;
  const SampledSurface out = sample(uneven_square(10.0f, 50), s);
  const std::vector<double> nn = nearest_neighbour(out.points, s);
  double lo = 1e9, mean = 0.0;
  for (const double d : nn) {
    lo = std::min(lo, d);
    mean += d;
  }
  mean /= double(nn.size());
  EXPECT_GE(lo, 0.5 * s);
  EXPECT_GE(mean, 0.8 * s);
  EXPECT_LE(mean, 2.0 * std::sqrt(1.0 / (2.0 * std::sqrt(3.0))) * s);
  std::printf("[ info ] nearest neighbour: min %.3f s, mean %.3f s\n", lo / s, mean / s);
}

TEST(SurfaceSampling, RimDensity) {
  // Near the open rim of a surface, elimination keeps too many points (their
  // neighbourhoods are half empty, so their weights read low); SurfaceSampling.cpp
  // divides the weight by the kernel's mass on the surface side. Measured density within
  // one spacing of the rim: 1.18x uncorrected (1.5x in the first half spacing), 1.07x to
  // 1.10x corrected. Limit 1.2x, and the next spacing within [0.85, 1.15] (the band holds
  // ~800 points: 1 sigma = 3.5%).
  const double s = 0.05, L = 10.0;
  const SampledSurface out = sample(uneven_square(float(L), 50), s);
  std::array<double, 2> count{};
  for (const SampledPoint& p : out.points) {
    const double rim = std::min({double(p.position_mm.x), L - p.position_mm.x,
                                 double(p.position_mm.y), L - p.position_mm.y});
    if (rim < 2.0 * s) count[rim < s ? 0 : 1] += 1.0;
  }
  const auto band_area = [&](double d0, double d1) {
    return (L - 2.0 * d0) * (L - 2.0 * d0) - (L - 2.0 * d1) * (L - 2.0 * d1);
  };
  const double first = count[0] / (band_area(0.0, s) / (s * s));
  const double second = count[1] / (band_area(s, 2.0 * s) / (s * s));
  EXPECT_LT(first, 1.2);
  EXPECT_GT(first, 0.85);
  EXPECT_NEAR(second, 1.0, 0.15);
  std::printf("[ info ] density within one spacing of the rim %.3f, the next %.3f\n", first, second);
}

TEST(SurfaceSampling, DeterministicForASeed) {
  const TriangleSoup soup = sphere(3.0f, 12, 24);
  const SampledSurface a = sample(soup, 0.1, 7), b = sample(soup, 0.1, 7), c = sample(soup, 0.1, 8);
  ASSERT_EQ(a.points.size(), b.points.size());
  bool differs = false;
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].position_mm, b.points[i].position_mm);
    EXPECT_EQ(a.points[i].triangle, b.points[i].triangle);
    EXPECT_EQ(a.points[i].barycentric, b.points[i].barycentric);
    differs = differs || a.points[i].position_mm != c.points[i].position_mm;
  }
  EXPECT_TRUE(differs);
}

TEST(SurfaceSampling, EmptyAndDegenerateSoupsGiveNoPoints) {
  EXPECT_TRUE(sample(TriangleSoup{}, 0.1).points.empty());
  TriangleSoup flat;
  add_triangle(flat, {0, 0, 0}, {1, 0, 0}, {2, 0, 0});  // zero area
  flat.normals.assign(3, glm::vec3(0, 0, 1));
  const SampledSurface out = sample(flat, 0.1);
  EXPECT_TRUE(out.points.empty());
  EXPECT_EQ(out.area_mm2, 0.0);
  // A soup without normals uses the geometric normal.
  TriangleSoup bare;
  bare.positions_mm = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}};  // clockwise seen from +z: -z
  const SampledSurface g = sample(bare, 0.1);
  ASSERT_FALSE(g.points.empty());
  for (const SampledPoint& p : g.points) EXPECT_EQ(p.normal, glm::vec3(0, 0, -1));
}

TEST(SurfaceSampling, RejectsBadInputNamingIt) {
  const TriangleSoup soup = uneven_square(10.0f, 2);
  const auto expect_throw = [&](const TriangleSoup& s, const SamplingOptions& o,
                                std::vector<std::string> words) {
    try {
      sample_surface(s, o);
      ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& e) {
      for (const std::string& w : words)
        EXPECT_NE(std::string(e.what()).find(w), std::string::npos) << e.what() << " lacks " << w;
    }
  };
  for (const double bad : {0.0, -0.5, std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity()}) {
    SamplingOptions o;
    o.spacing_mm = bad;
    expect_throw(soup, o, {"spacing"});
  }
  // 100 mm² at 0.01 mm: 1e6 points, over a limit of 1000. The message gives N, the
  // area and the spacing, and says what to do.
  SamplingOptions o;
  o.spacing_mm = 0.01;
  o.max_points = 1000;
  expect_throw(soup, o, {"spacing", "1e+06", "100", "0.01", "raise the spacing"});
  TriangleSoup odd = soup;
  odd.positions_mm.pop_back();
  expect_throw(odd, {}, {"positions_mm"});
  TriangleSoup short_normals = soup;
  short_normals.normals.pop_back();
  expect_throw(short_normals, {}, {"normals"});
  TriangleSoup nan = soup;
  nan.positions_mm[4].x = std::numeric_limits<float>::quiet_NaN();
  expect_throw(nan, {}, {"positions_mm", "triangle 1"});
}

TEST(SurfaceSampling, Speed) {
  // Informational: time for 100k points (500k candidates) on one core (1M points took
  // ~9 s on the development VM, 70% of it in the elimination's random memory accesses).
  const auto t0 = std::chrono::steady_clock::now();
  const SampledSurface out = sample(uneven_square(10.0f, 50), 0.0316);
  EXPECT_EQ(out.points.size(), std::size_t(std::ceil(100.0 / (0.0316 * 0.0316))));
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::printf("[ info ] %zu points in %.0f ms\n", out.points.size(), ms);
}
