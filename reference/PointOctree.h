// Jensen & Buhler 2002, "A Rapid Hierarchical Rendering Technique for Translucent
// Materials", §3.2–3.3: an octree over the irradiance points of one scattering group.
// Every node carries its points' total area, their area-weighted mean irradiance, their
// irradiance-weighted centroid c and spread M (second moment about c), the summed normal
// and a bounding cone of the normals. The exitant flux at x_o is
//
//   M(x_o) = Σ_i K(x_o, x_i) E_i A_i,
//
// and a node (leaf or not) is used whole when x_o lies outside its bounding box and the
// solid angle it subtends, ΔΩ = A_node / |x_o − c|², is below `max_solid_angle`;
// otherwise its children are visited, or a leaf sums its points one by one. A node used
// whole contributes A_node Ē (K(r) + ½ tr(H M)), r = |x_o − c|, H the Hessian of K at
// the centroid: the second-order term removes the bias of the plain K(r) (K is convex,
// so K(r) alone reads low by ~(ε/12)(σr)²: -0.9% at ε = 0.1 in tests/reference/
// test_octree.cpp, against 2e-4 with it). The centroid is weighted by irradiance, as in
// pbrt-v2's implementation, which zeroes the first-order term.
// With a transmittance profile a node is used whole only if, in addition, all its
// normals lie on one side of the plane normal to n_o (the cone tells), so that one
// far-side decision holds for every point in it (a node straddling both faces of a slab
// is opened instead). Without a transmittance profile, nodes farther than the kernel's
// support radius are skipped (every point in them contributes exactly 0).
//
// K is ScatterKernel::reflect(|x_o − x_i|), except for points on the far side of a slab:
// when the kernel has a transmittance profile and the point (or node) normal faces away
// from n_o (n_i · n_o < 0), K = transmit(ρ), ρ the distance from x_i to the normal line
// through x_o. Without a transmittance profile, light reaches far-side points through
// the straight distance inside, reflect(|x_o − x_i|) (Jensen & Buhler's treatment).
//
// Near field (normalize_near): the points closer to x_o than ρ = ScatterKernel::
// near_radius() (4 spacings, about 50 points) carry most of M, and their sum would
// inherit the random local density of the point set as noise (4.8% RMS on a uniformly
// lit plane at 1 mfp spacing, worse for PBD's 1/r peak). They are summed as a ratio
// estimate instead: (Σ K E A / Σ K A) · ∫_disc(ρ) K dA, the K-weighted mean irradiance
// of the near points times what an even density would give (0.7% RMS on that plane,
// tests/reference/test_octree.cpp). It is exact for uniform irradiance on a plane, on a
// sphere (the area of a sphere within distance ρ of a point on it is πρ², Archimedes)
// and across a fold, and follows light edges through the weighted mean. Points whose
// normal is more than 120° from n_o (the far face of a thin part, transmitted points)
// are never in the near field. Nodes that reach into the near ball are always opened.
//
// gather_brute_force() sums every point (no hierarchy, no cut-off, the same near-field
// estimate): the baseline that the hierarchy is tested and benchmarked against.
#pragma once

#include "reference/ScatterKernel.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <array>
#include <vector>

namespace sss::reference {

struct IrradiancePoint {
  glm::vec3 position_mm{0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  glm::vec3 irradiance{0.0f};  // E, linear RGB (W m^-2 in the scene's light units)
};

struct OctreeOptions {
  double max_solid_angle = 0.3;  // ε of Jensen & Buhler, steradians; 0: always descend
  int leaf_points = 8;           // a node with at most this many points is a leaf
  int max_depth = 24;
  bool normalize_near = true;    // the near-field ratio estimate above
};

struct OctreeStats {
  std::size_t points = 0, nodes = 0, leaves = 0;
  int depth = 0;
};

class PointOctree {
 public:
  // Every point stands for the same area (SampledSurface::point_area_mm2). Throws
  // std::invalid_argument for a negative or non-finite max_solid_angle, leaf_points < 1,
  // max_depth outside [0, 32] (the gather's fixed stack is sized for 32; float positions
  // stop splitting long before), a non-positive or non-finite area, or a point with a
  // coordinate that is not finite.
  PointOctree(std::vector<IrradiancePoint> points, double point_area_mm2,
              const OctreeOptions& options = {});

  // Σ K E A over the hierarchy (thread-safe, const).
  glm::dvec3 gather(const glm::vec3& x_mm, const glm::vec3& normal, const ScatterKernel& k) const;
  // Σ K E A over every point.
  glm::dvec3 gather_brute_force(const glm::vec3& x_mm, const glm::vec3& normal,
                                const ScatterKernel& k) const;

  const OctreeStats& stats() const { return stats_; }
  std::size_t size() const { return points_.size(); }

 private:
  struct Node {
    glm::vec3 lo{0.0f}, hi{0.0f};     // bounding box of the node's points
    glm::vec3 centroid{0.0f};         // irradiance-weighted (see PointOctree.cpp)
    glm::vec3 normal_sum{0.0f};       // Σ n_i
    glm::vec3 mean_irradiance{0.0f};  // area-weighted
    float area = 0.0f;                // Σ A_i
    float normal_cone_cos = -1.0f;    // min_i cos(n_i, normal_sum); -1: no cone
    float spread[6] = {};             // irradiance-weighted M about the centroid: xx yy zz xy xz yz
    std::uint32_t first = 0, count = 0;  // the node's points: points_[first, first + count)
    std::int32_t children[8] = {-1, -1, -1, -1, -1, -1, -1, -1};
    bool leaf = true;
  };
  std::int32_t build(std::uint32_t first, std::uint32_t count, glm::dvec3 centre, double half,
                     int depth, std::vector<IrradiancePoint>& scratch);
  // The node over points_[first, first + count): its box, centroid, spread, normals,
  // irradiance and area (build's first stage).
  void summarize(Node& node, std::uint32_t first, std::uint32_t count) const;
  // Reorders points_[first, first + count) by octant about `centre` (a counting sort
  // through scratch); returns where each octant starts, relative to first, and the end.
  std::array<std::uint32_t, 9> sort_by_octant(std::uint32_t first, std::uint32_t count, const glm::dvec3& centre,
                                              std::vector<IrradiancePoint>& scratch);
  static bool one_side(const Node& node, const glm::dvec3& n_o);
  glm::dvec3 node_contribution(const Node& node, const glm::dvec3& x, const glm::dvec3& n_o,
                               bool through, const ScatterKernel& k) const;

  std::vector<IrradiancePoint> points_;  // reordered so each node's points are contiguous
  std::vector<Node> nodes_;              // nodes_[0] is the root (empty tree: no nodes)
  double point_area_ = 0.0;
  OctreeOptions options_;
  OctreeStats stats_;
};

}  // namespace sss::reference
