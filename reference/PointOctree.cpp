#include "reference/PointOctree.h"

#include "profiles/Medium.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace sss::reference {

namespace {

constexpr int kMaxDepthLimit = 32;
// Depth-first with at most 8 children pushed per level: 7 per level on the way down
// plus the last level's 8.
constexpr std::size_t kStackSize = 7 * kMaxDepthLimit + 8 + 1;

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Sums points one by one: those in the near field (reflected, closer than ρ) into the
// ratio estimate of PointOctree.h, the others straight into `far`.
class NearField {
 public:
  NearField(const glm::dvec3& x, const glm::dvec3& n_o, bool through, const ScatterKernel& k,
            double area, bool normalize)
      : x_(x), n_o_(n_o), through_(through), k_(k), area_(area) {
    const double r = normalize ? k.near_radius() : 0.0;
    radius2 = r * r;
  }
  void add(const IrradiancePoint& p, glm::dvec3& far) {
    const glm::dvec3 v = glm::dvec3(p.position_mm) - x_;
    const glm::dvec3 n(p.normal);
    if (through_ && glm::dot(n, n_o_) < 0.0) {
      far += k_.transmit(glm::length(glm::cross(v, n_o_))) * glm::dvec3(p.irradiance) * area_;
      return;
    }
    const double d2 = glm::dot(v, v);
    const glm::dvec3 K = k_.reflect(std::sqrt(d2));
    // The far face of a part thinner than ρ faces away: it stays out of the ratio
    // (its area is not part of the disc the near integral stands for).
    if (d2 < radius2 && glm::dot(n, n_o_) > -0.5) {
      ke_ += K * glm::dvec3(p.irradiance) * area_;
      ka_ += K * area_;
    } else {
      far += K * glm::dvec3(p.irradiance) * area_;
    }
  }
  // The near field's estimate: Σ K E A scaled to an even density, per channel. When the
  // near points cover less than a quarter of the disc's weight (x_o away from the
  // surface, a sliver of geometry), their plain sum.
  glm::dvec3 total() const {
    glm::dvec3 out = ke_;
    const glm::dvec3& target = k_.near_integral();
    for (int c = 0; c < 3; ++c)
      if (ka_[c] > 0.25 * target[c]) out[c] = ke_[c] * (target[c] / ka_[c]);
    return out;
  }
  double radius2 = 0.0;

 private:
  glm::dvec3 x_, n_o_;
  bool through_;
  const ScatterKernel& k_;
  double area_;
  glm::dvec3 ke_{0.0}, ka_{0.0};
};

}  // namespace

// A node as one point at its representative position c, with the second-order term of
// the Taylor expansion of K about c: Σ_i K(|x_i − x|) w_i / Σ w_i ≈ K(r) + ½ tr(H M),
// H the Hessian of the radial K(|y|) at y = c − x: H = K'' r̂r̂ᵀ + (K'/r)(I − r̂r̂ᵀ), so
// tr(H M) = K'' q + (K'/r)(tr M − q), q = r̂ᵀ M r̂. Far-side nodes use T of the lateral
// offset: the same with M projected onto the plane normal to n_o. The node is far
// (ΔΩ < ε), so |x_i − c| < r √ε; the correction removes the bias of the plain estimate
// (K is convex: the plain estimate is low by ~(ε/12)(σr)² relative, measured -0.9% RMS
// at ε = 0.1 without it; tests/reference/test_octree.cpp).
glm::dvec3 PointOctree::node_contribution(const Node& node, const glm::dvec3& x,
                                          const glm::dvec3& n_o, bool through,
                                          const ScatterKernel& k) const {
  const glm::dvec3 v = glm::dvec3(node.centroid) - x;
  const glm::dvec3 n(node.normal_sum);
  const double mxx = node.spread[0], myy = node.spread[1], mzz = node.spread[2];
  const double mxy = node.spread[3], mxz = node.spread[4], myz = node.spread[5];
  const auto quad = [&](const glm::dvec3& u) {  // uᵀ M u
    return mxx * u.x * u.x + myy * u.y * u.y + mzz * u.z * u.z +
           2.0 * (mxy * u.x * u.y + mxz * u.x * u.z + myz * u.y * u.z);
  };
  double trace = mxx + myy + mzz;
  glm::dvec3 offset = v;
  ScatterKernel::Jet j;
  if (through && glm::dot(n, n_o) < 0.0) {
    offset = v - glm::dot(v, n_o) * n_o;  // lateral
    trace -= quad(n_o);
    j = k.transmit_jet(glm::length(offset));
  } else {
    j = k.reflect_jet(glm::length(offset));
  }
  const double r = glm::length(offset);
  glm::dvec3 K = j.value;
  if (r > 1e-3 * std::sqrt(double(node.area))) {
    const double q = quad(offset / r);
    K += 0.5 * (j.second * q + j.first / r * (trace - q));
  } else {  // on the axis: H = K''(0) I in the plane (K' → 0 as r → 0)
    K += 0.5 * j.second * trace;
  }
  return glm::max(K, glm::dvec3(0.0)) * glm::dvec3(node.mean_irradiance) * double(node.area);
}

PointOctree::PointOctree(std::vector<IrradiancePoint> points, double point_area_mm2,
                         const OctreeOptions& options)
    : points_(std::move(points)), point_area_(point_area_mm2), options_(options) {
  if (!std::isfinite(options.max_solid_angle) || options.max_solid_angle < 0.0)
    throw std::invalid_argument("max_solid_angle: must be finite and >= 0, got " +
                                message_number(options.max_solid_angle));
  if (options.leaf_points < 1)
    throw std::invalid_argument("leaf_points: must be >= 1, got " +
                                std::to_string(options.leaf_points));
  if (options.max_depth < 0 || options.max_depth > kMaxDepthLimit)
    throw std::invalid_argument("max_depth: must be in [0, " + std::to_string(kMaxDepthLimit) +
                                "], got " + std::to_string(options.max_depth));
  if (!std::isfinite(point_area_mm2) || !(point_area_mm2 > 0.0))
    throw std::invalid_argument("point_area_mm2: must be finite and > 0, got " +
                                message_number(point_area_mm2));
  if (points_.size() >= std::size_t(0xFFFFFFFFu))
    throw std::invalid_argument("points: more than 2^32 - 2 points");
  for (std::size_t i = 0; i < points_.size(); ++i)
    if (!finite(points_[i].position_mm) || !finite(points_[i].normal) ||
        !finite(points_[i].irradiance))
      throw std::invalid_argument("points: point " + std::to_string(i) +
                                  " has a coordinate that is not finite");
  stats_.points = points_.size();
  if (points_.empty()) return;

  // The root cube: the bounding box's centre, its largest extent.
  glm::vec3 lo = points_[0].position_mm, hi = lo;
  for (const IrradiancePoint& p : points_) {
    lo = glm::min(lo, p.position_mm);
    hi = glm::max(hi, p.position_mm);
  }
  const glm::dvec3 centre = 0.5 * (glm::dvec3(lo) + glm::dvec3(hi));
  const double half = 0.5 * std::max({double(hi.x) - lo.x, double(hi.y) - lo.y,
                                      double(hi.z) - lo.z, 1e-30});
  std::vector<IrradiancePoint> scratch(points_.size());
  build(0, std::uint32_t(points_.size()), centre, half, 0, scratch);
  stats_.nodes = nodes_.size();
}

// Builds the node for points_[first, first + count) in the cube (centre, half side);
// returns its index. Children split the cube at its centre (octant bit 0: x, 1: y, 2: z).
void PointOctree::summarize(Node& node, std::uint32_t first, std::uint32_t count) const {
  glm::dvec3 sum_p(0.0), sum_n(0.0), sum_e(0.0), sum_ep(0.0);
  double sum_w = 0.0;
  glm::vec3 lo = points_[first].position_mm, hi = lo;
  for (std::uint32_t i = first; i < first + count; ++i) {
    const IrradiancePoint& p = points_[i];
    sum_p += glm::dvec3(p.position_mm);
    const double w = double(p.irradiance.x) + p.irradiance.y + p.irradiance.z;
    sum_ep += w * glm::dvec3(p.position_mm);
    sum_w += w;
    sum_n += glm::dvec3(p.normal);
    sum_e += glm::dvec3(p.irradiance);
    lo = glm::min(lo, p.position_mm);
    hi = glm::max(hi, p.position_mm);
  }
  // Every point has the same area, so the area-weighted means are plain means.
  const glm::dvec3 axis = glm::length(sum_n) > 0.0 ? glm::normalize(sum_n) : glm::dvec3(0.0);
  // The representative position is weighted by irradiance, as in pbrt-v2's octree for
  // Jensen & Buhler's method (which weights by luminance; here the channel sum, so no
  // colour space is assumed): then the first-order term of
  // Σ_i K(|x − x_i|) E_i about it, ∇K · Σ (x_i − c) E_i, vanishes (for each channel
  // when the irradiance has one spectral shape across the node). The second-order term
  // uses the spread M = Σ w_i (x_i − c)(x_i − c)ᵀ / Σ w_i with the same weights.
  // Unlit nodes fall back to equal weights.
  const bool lit = sum_w > 0.0;
  const glm::dvec3 c = lit ? sum_ep / sum_w : sum_p / double(count);
  double cone = 1.0;
  std::array<double, 6> m{};  // xx, yy, zz, xy, xz, yz
  for (std::uint32_t i = first; i < first + count; ++i) {
    const IrradiancePoint& p = points_[i];
    const glm::dvec3 n(p.normal);
    const double len = glm::length(n);
    cone = std::min(cone, len > 0.0 ? glm::dot(n, axis) / len : -1.0);
    const double w = lit ? double(p.irradiance.x) + p.irradiance.y + p.irradiance.z : 1.0;
    const glm::dvec3 v = glm::dvec3(p.position_mm) - c;
    m[0] += w * v.x * v.x;
    m[1] += w * v.y * v.y;
    m[2] += w * v.z * v.z;
    m[3] += w * v.x * v.y;
    m[4] += w * v.x * v.z;
    m[5] += w * v.y * v.z;
  }
  const double norm = lit ? sum_w : double(count);
  node.lo = lo;
  node.hi = hi;
  node.centroid = glm::vec3(c);
  for (int k = 0; k < 6; ++k) node.spread[k] = float(m[std::size_t(k)] / norm);
  node.normal_sum = glm::vec3(sum_n);
  node.mean_irradiance = glm::vec3(sum_e / double(count));
  node.area = float(point_area_ * count);
  node.first = first;
  node.count = count;
  node.normal_cone_cos = glm::length(sum_n) > 0.0 ? float(std::max(-1.0, cone)) : -1.0f;
}

std::array<std::uint32_t, 9> PointOctree::sort_by_octant(std::uint32_t first, std::uint32_t count,
                                                         const glm::dvec3& centre,
                                                         std::vector<IrradiancePoint>& scratch) {
  std::array<std::uint32_t, 9> start{};
  const auto octant = [&](const glm::vec3& p) {
    return (double(p.x) >= centre.x ? 1 : 0) | (double(p.y) >= centre.y ? 2 : 0) |
           (double(p.z) >= centre.z ? 4 : 0);
  };
  for (std::uint32_t i = first; i < first + count; ++i) ++start[octant(points_[i].position_mm) + 1];
  for (int o = 0; o < 8; ++o) start[o + 1] += start[o];
  std::array<std::uint32_t, 8> fill{};
  for (std::uint32_t i = first; i < first + count; ++i) {
    const int o = octant(points_[i].position_mm);
    scratch[first + start[o] + fill[o]++] = points_[i];
  }
  std::copy(scratch.begin() + first, scratch.begin() + first + count, points_.begin() + first);
  return start;
}

std::int32_t PointOctree::build(std::uint32_t first, std::uint32_t count, glm::dvec3 centre,
                                double half, int depth, std::vector<IrradiancePoint>& scratch) {
  const std::int32_t index = std::int32_t(nodes_.size());
  nodes_.emplace_back();
  stats_.depth = std::max(stats_.depth, depth);
  summarize(nodes_[std::size_t(index)], first, count);
  if (count <= std::uint32_t(options_.leaf_points) || depth >= options_.max_depth) {
    ++stats_.leaves;
    return index;
  }
  const std::array<std::uint32_t, 9> start = sort_by_octant(first, count, centre, scratch);
  nodes_[std::size_t(index)].leaf = false;
  for (int o = 0; o < 8; ++o) {
    const std::uint32_t n = start[o + 1] - start[o];
    if (n == 0) continue;
    const glm::dvec3 c(centre.x + ((o & 1) ? 0.5 : -0.5) * half,
                       centre.y + ((o & 2) ? 0.5 : -0.5) * half,
                       centre.z + ((o & 4) ? 0.5 : -0.5) * half);
    const std::int32_t child = build(first + start[o], n, c, 0.5 * half, depth + 1, scratch);
    nodes_[std::size_t(index)].children[o] = child;
  }
  return index;
}

glm::dvec3 PointOctree::gather(const glm::vec3& x_mm, const glm::vec3& normal,
                               const ScatterKernel& k) const {
  glm::dvec3 sum(0.0);
  if (nodes_.empty()) return sum;
  const glm::dvec3 x(x_mm);
  const double nlen = glm::length(glm::dvec3(normal));
  const glm::dvec3 n_o = nlen > 0.0 ? glm::dvec3(normal) / nlen : glm::dvec3(0.0, 0.0, 1.0);
  const bool through = k.has_transmittance();
  const double eps = options_.max_solid_angle;
  // Without transmission every contribution is reflect(distance), 0 beyond the support.
  const double cull2 = through && !k.far_side_dark() ? std::numeric_limits<double>::infinity()
                                                     : k.support_radius() * k.support_radius();

  NearField near(x, n_o, through, k, point_area_, options_.normalize_near);
  std::array<std::int32_t, kStackSize> stack;
  std::size_t top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[std::size_t(stack[--top])];
    // Distance from x to the node's box (0 inside).
    const glm::dvec3 lo(node.lo), hi(node.hi);
    const glm::dvec3 gap = glm::max(glm::max(lo - x, x - hi), glm::dvec3(0.0));
    const double box2 = glm::dot(gap, gap);
    if (box2 >= cull2) continue;
    if (box2 > 0.0) {  // x outside the box
      const glm::dvec3 c(node.centroid);
      const double dist2 = glm::dot(c - x, c - x);
      if (box2 >= near.radius2 && double(node.area) < eps * dist2 && (!through || one_side(node, n_o))) {
        sum += node_contribution(node, x, n_o, through, k);
        continue;
      }
    }
    if (node.leaf) {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i) near.add(points_[i], sum);
    } else {
      for (int o = 7; o >= 0; --o)
        if (node.children[o] >= 0) stack[top++] = node.children[o];
    }
  }
  return sum + near.total();
}

// True when every point of the node faces the same way relative to n_o, so that one far-
// side decision serves them all: the cone of normals (axis = normal_sum, half-angle α,
// cos α = normal_cone_cos) lies within one hemisphere about n_o: β + α < π/2 (all in
// front) or β − α > π/2 (all behind), β the angle between the axis and n_o.
bool PointOctree::one_side(const Node& node, const glm::dvec3& n_o) {
  if (!(node.normal_cone_cos > 0.0f)) return false;  // α >= π/2: both sides possible
  const glm::dvec3 axis = glm::normalize(glm::dvec3(node.normal_sum));
  const double beta = std::acos(std::clamp(glm::dot(axis, n_o), -1.0, 1.0));
  const double alpha = std::acos(double(node.normal_cone_cos));
  constexpr double kHalfPi = 0.5 * std::numbers::pi;
  return beta + alpha < kHalfPi || beta - alpha > kHalfPi;
}

glm::dvec3 PointOctree::gather_brute_force(const glm::vec3& x_mm, const glm::vec3& normal,
                                           const ScatterKernel& k) const {
  const glm::dvec3 x(x_mm);
  const double nlen = glm::length(glm::dvec3(normal));
  const glm::dvec3 n_o = nlen > 0.0 ? glm::dvec3(normal) / nlen : glm::dvec3(0.0, 0.0, 1.0);
  const bool through = k.has_transmittance();
  glm::dvec3 sum(0.0);
  NearField near(x, n_o, through, k, point_area_, options_.normalize_near);
  for (const IrradiancePoint& p : points_) near.add(p, sum);
  return sum + near.total();
}

}  // namespace sss::reference
