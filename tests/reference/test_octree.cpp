// PointOctree: the Jensen–Buhler hierarchy against the brute-force sum it approximates.
#include "reference/PointOctree.h"

#include "profiles/Presets.h"
#include "profiles/Integrate.h"
#include "profiles/Random.h"
#include "reference/SurfaceSampling.h"

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

using namespace sss;
using namespace sss::reference;
using profiles::Model;
using profiles::RgbProfile;

namespace {

constexpr double kPi = std::numbers::pi;

profiles::Medium preset(const char* name) {
  return profiles::preset_medium(*profiles::find_preset(name));
}

// Irradiance with structure on every scale: a smooth gradient, a shadow edge (a step)
// and a small bright spot; positive in every channel.
glm::vec3 irradiance_at(const glm::vec3& p) {
  const float smooth = 1.0f + 0.5f * std::sin(0.2f * p.x) * std::cos(0.15f * p.y);
  const float shadow = p.x + 0.3f * p.z > 2.0f ? 0.1f : 1.0f;
  const float spot = 4.0f * std::exp(-glm::dot(p - glm::vec3(-3, 4, 0), p - glm::vec3(-3, 4, 0)));
  return glm::vec3(1.0f, 0.7f, 0.4f) * (smooth * shadow + spot);
}

// n uniform random points on a sphere of radius r (normals outwards).
std::vector<IrradiancePoint> sphere_points(std::size_t n, float r, std::uint64_t seed) {
  profiles::Xoshiro256ss rng(seed);
  std::vector<IrradiancePoint> pts(n);
  for (IrradiancePoint& p : pts) {
    const double z = 2.0 * rng.uniform() - 1.0, phi = 2.0 * kPi * rng.uniform();
    const double s = std::sqrt(1.0 - z * z);
    p.normal = glm::vec3(glm::dvec3(s * std::cos(phi), s * std::sin(phi), z));
    p.position_mm = r * p.normal;
    p.irradiance = irradiance_at(p.position_mm);
  }
  return pts;
}

// n uniform random points on the square [-L/2, L/2]² of the plane z = 0 (normal +z).
std::vector<IrradiancePoint> plane_points(std::size_t n, float L, std::uint64_t seed) {
  profiles::Xoshiro256ss rng(seed);
  std::vector<IrradiancePoint> pts(n);
  for (IrradiancePoint& p : pts) {
    p.position_mm = glm::vec3(float((rng.uniform() - 0.5) * L), float((rng.uniform() - 0.5) * L), 0.0f);
    p.normal = glm::vec3(0, 0, 1);
    p.irradiance = irradiance_at(p.position_mm);
  }
  return pts;
}

double rel(const glm::dvec3& got, const glm::dvec3& want) {
  return glm::length(got - want) / glm::length(want);
}

struct ErrorStats {
  double rms = 0.0, max = 0.0;
  double bias = 0.0;                     // mean signed relative error, red channel
  double ns_tree = 0.0, ns_brute = 0.0;  // per gather
};

// The brute-force sums at the first `queries` points of `pts` (they are random), and
// the time per gather.
std::vector<glm::dvec3> brute_force(const PointOctree& tree, const std::vector<IrradiancePoint>& pts,
                                    const ScatterKernel& k, std::size_t queries, double& ns) {
  std::vector<glm::dvec3> out(queries);
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t q = 0; q < queries; ++q)
    out[q] = tree.gather_brute_force(pts[q].position_mm, pts[q].normal, k);
  ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count() /
       double(queries);
  return out;
}

// RMS and max relative error (vector norm over RGB) of gather at ε against `brute`.
ErrorStats compare(const std::vector<IrradiancePoint>& pts, double area, double eps,
                   const ScatterKernel& k, const std::vector<glm::dvec3>& brute) {
  OctreeOptions o;
  o.max_solid_angle = eps;
  const PointOctree tree(pts, area, o);
  ErrorStats s;
  const std::size_t queries = brute.size();
  std::vector<glm::dvec3> fast(queries);
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t q = 0; q < queries; ++q)
    fast[q] = tree.gather(pts[q].position_mm, pts[q].normal, k);
  s.ns_tree = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count() /
              double(queries);
  for (std::size_t q = 0; q < queries; ++q) {
    s.bias += (fast[q].x - brute[q].x) / brute[q].x / double(queries);
    const double e = rel(fast[q], brute[q]);
    s.rms += e * e;
    s.max = std::max(s.max, e);
  }
  s.rms = std::sqrt(s.rms / double(queries));
  return s;
}

}  // namespace

TEST(PointOctree, RejectsBadOptionsNamingThem) {
  const std::vector<IrradiancePoint> pts = plane_points(100, 10.0f, 1);
  const auto expect_throw = [&](const OctreeOptions& o, double area, const char* field) {
    try {
      PointOctree t(pts, area, o);
      ADD_FAILURE() << "accepted bad " << field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  OctreeOptions o;
  o.max_solid_angle = -0.1;
  expect_throw(o, 1.0, "max_solid_angle");
  o.max_solid_angle = std::numeric_limits<double>::quiet_NaN();
  expect_throw(o, 1.0, "max_solid_angle");
  o.max_solid_angle = std::numeric_limits<double>::infinity();
  expect_throw(o, 1.0, "max_solid_angle");
  o = {};
  o.leaf_points = 0;
  expect_throw(o, 1.0, "leaf_points");
  o = {};
  o.max_depth = -1;
  expect_throw(o, 1.0, "max_depth");
  o.max_depth = 33;
  expect_throw(o, 1.0, "max_depth");
  o = {};
  expect_throw(o, 0.0, "point_area");
  expect_throw(o, -1.0, "point_area");
  expect_throw(o, std::numeric_limits<double>::quiet_NaN(), "point_area");
  std::vector<IrradiancePoint> bad = pts;
  bad[7].position_mm.y = std::numeric_limits<float>::infinity();
  try {
    PointOctree t(bad, 1.0);
    ADD_FAILURE() << "accepted a point at infinity";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("point 7"), std::string::npos) << e.what();
  }
}

TEST(PointOctree, StructureHoldsEveryPointOnce) {
  const std::vector<IrradiancePoint> pts = sphere_points(20000, 10.0f, 3);
  OctreeOptions o;
  o.leaf_points = 8;
  const PointOctree tree(pts, 0.1, o);
  const OctreeStats& st = tree.stats();
  EXPECT_EQ(st.points, pts.size());
  EXPECT_EQ(tree.size(), pts.size());
  EXPECT_GT(st.nodes, st.leaves);
  // A leaf holds at most leaf_points unless max_depth stopped it; 20000 random points
  // need about log8(20000/8) ≈ 4 levels, far below 24, so leaves ≥ 20000/8.
  EXPECT_GE(st.leaves, pts.size() / 8);
  EXPECT_GE(st.depth, 4);
  EXPECT_LE(st.depth, 12);
  // Every point is gathered exactly once: with K ≡ const the brute force and the exact
  // hierarchy (ε = 0) both sum E over all points. Here: a kernel far wider than the
  // sphere is nearly constant; compare ε = 0 with brute force to 1e-12.
  const ScatterKernel k(RgbProfile(Model::BetterDipole, preset("marble")), 0.1);
  OctreeOptions exact;
  exact.max_solid_angle = 0.0;
  const PointOctree t0(pts, 0.1, exact);
  const glm::dvec3 a = t0.gather(pts[0].position_mm, pts[0].normal, k);
  const glm::dvec3 b = t0.gather_brute_force(pts[0].position_mm, pts[0].normal, k);
  EXPECT_LT(rel(a, b), 1e-12);

  // Empty and degenerate trees.
  const PointOctree empty({}, 1.0);
  EXPECT_EQ(empty.stats().nodes, 0u);
  EXPECT_EQ(empty.gather(glm::vec3(0), glm::vec3(0, 0, 1), k), glm::dvec3(0.0));
  EXPECT_EQ(empty.gather_brute_force(glm::vec3(0), glm::vec3(0, 0, 1), k), glm::dvec3(0.0));
  std::vector<IrradiancePoint> same(100, pts[0]);  // 100 coincident points: max_depth stops
  const PointOctree stacked(same, 0.1);
  EXPECT_EQ(stacked.stats().points, 100u);
  EXPECT_LE(stacked.stats().depth, 24);
  EXPECT_LT(rel(stacked.gather(pts[1].position_mm, pts[1].normal, k),
                stacked.gather_brute_force(pts[1].position_mm, pts[1].normal, k)),
            1e-6);
}

TEST(PointOctree, ZeroSolidAngleIsTheBruteForce) {
  // ε = 0 never uses a node whole, so the hierarchy sums exactly the same terms as the
  // brute force, in another order: rounding only, ~1e-16 per term over 50k terms (sums
  // of positive terms in double): 1e-9 leaves a wide margin.
  const std::vector<IrradiancePoint> pts = sphere_points(50000, 15.0f, 7);
  const double area = 4.0 * kPi * 15.0 * 15.0 / double(pts.size());
  const ScatterKernel k(RgbProfile(Model::BetterDipole, preset("skin1")), area);
  OctreeOptions o;
  o.max_solid_angle = 0.0;
  const PointOctree tree(pts, area, o);
  for (std::size_t q = 0; q < 50; ++q) {
    const glm::dvec3 a = tree.gather(pts[q].position_mm, pts[q].normal, k);
    const glm::dvec3 b = tree.gather_brute_force(pts[q].position_mm, pts[q].normal, k);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 1e-9 * b[c]) << q;
  }
}

TEST(PointOctree, HierarchyErrorAgainstSolidAngle) {
  // 80k random points on a sphere of radius 15 mm and on a 60 mm square, skin1
  // (better dipole), varying irradiance (gradient, shadow edge, spot). Acceptance: at the
  // default ε = 0.1 the RMS relative error over 300 random query points is below 1%
  // (DESIGN.md §6 asks the hierarchy to agree with the brute force; 1% is the budget
  // the reference renderer's tests allot to it). The other ε are reported, and the error
  // must grow with ε (monotone within noise: 20% slack).
  const RgbProfile profile(Model::BetterDipole, preset("skin1"));
  struct Scene {
    const char* name;
    std::vector<IrradiancePoint> pts;
    double area;
  };
  std::vector<Scene> scenes;
  scenes.push_back({"sphere", sphere_points(80000, 15.0f, 11), 4.0 * kPi * 225.0 / 80000.0});
  scenes.push_back({"plane", plane_points(80000, 60.0f, 12), 3600.0 / 80000.0});
  for (const Scene& sc : scenes) {
    const ScatterKernel k(profile, sc.area);
    double ns_brute = 0.0;
    const std::vector<glm::dvec3> brute = brute_force(PointOctree(sc.pts, sc.area), sc.pts, k, 300, ns_brute);
    double previous = 0.0;
    for (const double eps : {0.01, 0.05, 0.1, 0.3}) {
      ErrorStats s = compare(sc.pts, sc.area, eps, k, brute);
      s.ns_brute = ns_brute;
      std::printf("[ info ] %s, %zu points, eps %.2f: RMS %.1e, max %.1e, bias %+.1e; gather "
                  "%.1f us, brute force %.0f us (x%.0f)\n",
                  sc.name, sc.pts.size(), eps, s.rms, s.max, s.bias, s.ns_tree * 1e-3,
                  s.ns_brute * 1e-3, s.ns_brute / s.ns_tree);
      if (eps == 0.1) {
        EXPECT_LT(s.rms, 0.01) << sc.name;  // the budget
        // Regression guard for the second-order node estimate (PointOctree.cpp):
        // measured 1.4e-4 (sphere) and 2.1e-4 (plane); the plain centroid estimate gave
        // 7e-3 to 9e-3 here, biased low by the kernel's convexity.
        EXPECT_LT(s.rms, 1e-3) << sc.name;
      }
      EXPECT_GE(s.rms, 0.8 * previous) << sc.name << " eps " << eps;
      previous = s.rms;
    }
  }
}

TEST(PointOctree, FarSideOfASlabUsesTheTransmittance) {
  // A 2 mm slab of skin1 (multipole): points on the lit face z = 0 (normal +z) and on
  // the far face z = -2 (normal -z). Seen from a point on the far face, the lit face's
  // points face away (n_i · n_o < 0): they contribute transmit(ρ), ρ the lateral
  // distance; the far face's own points contribute reflect(distance).
  profiles::Medium m = preset("skin1");
  m.thickness_mm = 2.0;
  const RgbProfile slab(Model::Multipole, m);
  const float L = 30.0f, t = 2.0f;
  std::vector<IrradiancePoint> lit = plane_points(20000, L, 21), far = plane_points(20000, L, 22);
  for (IrradiancePoint& p : far) {
    p.position_mm.z = -t;
    p.normal = glm::vec3(0, 0, -1);
    p.irradiance = glm::vec3(0.0f);  // only the lit face is lit
  }
  std::vector<IrradiancePoint> both = lit;
  both.insert(both.end(), far.begin(), far.end());
  const double area = double(L) * L / 20000.0;
  const ScatterKernel k(slab, area);
  ASSERT_TRUE(k.has_transmittance());
  // Plain sums (no near-field ratio estimate), so they can be checked against sums by hand.
  OctreeOptions exact, plain;
  exact.max_solid_angle = 0.0;
  exact.normalize_near = plain.normalize_near = false;
  const PointOctree tree(both, area, exact), fast(both, area, plain);

  const glm::vec3 x(0.3f, -0.2f, -t), n(0, 0, -1);
  // The expected sum by hand: transmit(ρ) for the lit points, nothing from the dark ones.
  glm::dvec3 want(0.0);
  for (const IrradiancePoint& p : lit) {
    const double rho = std::hypot(double(p.position_mm.x) - x.x, double(p.position_mm.y) - x.y);
    want += k.transmit(rho) * glm::dvec3(p.irradiance) * area;
  }
  const glm::dvec3 brute = tree.gather_brute_force(x, n, k);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(brute[c], want[c], 1e-9 * want[c]);
  // Rounding only (ε = 0), and the hierarchy within its budget at the default ε: the
  // slab is thinner than the nodes that would mix its faces, which the normal-cone
  // rule opens.
  EXPECT_LT(rel(tree.gather(x, n, k), brute), 1e-9);
  EXPECT_LT(rel(fast.gather(x, n, k), brute), 0.01);
  // And the lit face seen from the lit face: reflection only (the far face is dark).
  const glm::vec3 y(0.3f, -0.2f, 0.0f), ny(0, 0, 1);
  glm::dvec3 want_r(0.0);
  for (const IrradiancePoint& p : lit)
    want_r += k.reflect(glm::length(glm::dvec3(p.position_mm) - glm::dvec3(y))) *
              glm::dvec3(p.irradiance) * area;
  const glm::dvec3 brute_r = tree.gather_brute_force(y, ny, k);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(brute_r[c], want_r[c], 1e-9 * want_r[c]);
  EXPECT_LT(rel(fast.gather(y, ny, k), brute_r), 0.01);

  // Without a transmittance profile (a semi-infinite model), far-side points are reached
  // through the straight distance: reflect(|x_o − x_i|).
  const ScatterKernel bd(RgbProfile(Model::BetterDipole, preset("skin1")), area);
  glm::dvec3 want_bd(0.0);
  for (const IrradiancePoint& p : lit)
    want_bd += bd.reflect(glm::length(glm::dvec3(p.position_mm) - glm::dvec3(x))) *
               glm::dvec3(p.irradiance) * area;
  const glm::dvec3 brute_bd = tree.gather_brute_force(x, n, bd);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(brute_bd[c], want_bd[c], 1e-9 * want_bd[c]);
}

TEST(PointOctree, GatherIsThreadSafe) {
  // const gathers from several threads at once give the single-threaded answers bit for
  // bit (no shared mutable state).
  const std::vector<IrradiancePoint> pts = sphere_points(20000, 10.0f, 5);
  const double area = 4.0 * kPi * 100.0 / 20000.0;
  const ScatterKernel k(RgbProfile(Model::BetterDipole, preset("skin1")), area);
  const PointOctree tree(pts, area);
  std::vector<glm::dvec3> serial(64), parallel(64);
  for (std::size_t q = 0; q < 64; ++q) serial[q] = tree.gather(pts[q].position_mm, pts[q].normal, k);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (std::size_t q = std::size_t(t); q < 64; q += 4)
        parallel[q] = tree.gather(pts[q].position_mm, pts[q].normal, k);
    });
  for (std::thread& th : threads) th.join();
  for (std::size_t q = 0; q < 64; ++q) EXPECT_EQ(serial[q], parallel[q]) << q;
}

TEST(PointOctree, NearFieldRatioEstimateRemovesTheDensityNoise) {
  // A 40 x 40 mm plane of blue-noise points (SurfaceSampling at 1 reduced mfp of skin1's
  // blue channel), lit uniformly with E = 1: the exact exitant flux is the total
  // reflectance everywhere. With the near-field ratio estimate the near points (d < ρ =
  // 2 s) are exact for uniform E; what is left is the far points' quadrature, whose
  // per-cell error has SD |K'(r)| s/√3 A, so σ² = A (s²/3) ∫_{r>ρ} K'(r)² dA, plus the
  // cells straddling r = ρ (below). Tolerance per query: 4σ + 1e-3 (kernel table). The plain sum must be the noisier of the two
  // (its near points carry the point set's local density).
  const profiles::Medium medium = preset("skin1");
  const RgbProfile profile(Model::BetterDipole, medium);
  const double s = medium.channel(2).mfp_reduced();
  TriangleSoup soup;
  const float L = 20.0f;
  const glm::vec3 c[4] = {{-L, -L, 0}, {L, -L, 0}, {L, L, 0}, {-L, L, 0}};
  for (int v : {0, 1, 2, 0, 2, 3}) {
    soup.positions_mm.push_back(c[v]);
    soup.normals.push_back({0, 0, 1});
  }
  SamplingOptions so;
  so.spacing_mm = s;
  const SampledSurface surf = sample_surface(soup, so);
  std::vector<IrradiancePoint> pts;
  for (const SampledPoint& p : surf.points) pts.push_back({p.position_mm, p.normal, glm::vec3(1.0f)});
  const ScatterKernel k(profile, surf.point_area_mm2);
  OctreeOptions plain_options;
  plain_options.normalize_near = false;
  const PointOctree normalized(pts, surf.point_area_mm2), plain(pts, surf.point_area_mm2, plain_options);
  const Rgb total = profile.total_reflectance();
  profiles::Xoshiro256ss rng(7);
  double worst = 0.0, sd_norm = 0.0, sd_plain = 0.0;
  const int queries = 200;
  for (int ch = 0; ch < 3; ++ch) {
    const double A = surf.point_area_mm2;
    const auto dK = [&](double r) {
      const double e = 1e-3 * r;
      return (k.reflect(r + e)[ch] - k.reflect(r - e)[ch]) / (2.0 * e);
    };
    const double var = A * A / 3.0 *
                       profiles::integrate_log([&](double r) {
                         return r < k.near_radius() ? 0.0 : 2.0 * kPi * r * dK(r) * dK(r);
                       }, k.near_radius(), 15.0);
    // Cells straddling the circle r = ρ fall wholly in the near or the far sum, and only
    // the near sum is normalized: ± K(ρ) A/2 each, over the ring of width s.
    const double rho = k.near_radius(), Kr = k.reflect(rho)[ch];
    const double var_ring = A / 4.0 * 2.0 * kPi * rho * std::sqrt(A) * Kr * Kr;
    const double tol = 4.0 * std::sqrt(var + var_ring) + 1e-3 * total[ch];
    for (int q = 0; q < queries; ++q) {
      const glm::vec3 x(float((rng.uniform() - 0.5) * 10.0), float((rng.uniform() - 0.5) * 10.0), 0.0f);
      const double got = normalized.gather(x, {0, 0, 1}, k)[ch];
      const double raw = plain.gather(x, {0, 0, 1}, k)[ch];
      EXPECT_NEAR(got, total[ch], tol) << "channel " << ch << " at " << x.x << ", " << x.y;
      worst = std::max(worst, std::abs(got - total[ch]) / tol);
      sd_norm += (got - total[ch]) * (got - total[ch]) / (total[ch] * total[ch]);
      sd_plain += (raw - total[ch]) * (raw - total[ch]) / (total[ch] * total[ch]);
    }
  }
  sd_norm = std::sqrt(sd_norm / (3 * queries));
  sd_plain = std::sqrt(sd_plain / (3 * queries));
  std::printf("[ info ] uniform plane, %zu points at %.3f mm: relative RMS error %.2e with the near-field "
              "ratio estimate, %.2e without; worst/tolerance %.2f\n",
              pts.size(), s, sd_norm, sd_plain, worst);
  EXPECT_LT(sd_norm, sd_plain);
}
