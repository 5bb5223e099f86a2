#include "reference/ScatterKernel.h"

#include "reference/ProfileTable.h"

#include "profiles/Integrate.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace sss::reference {

namespace {

// Table cells: 2^kCellBits per octave of y = |d/a − 1|, the distance from the kink at
// d = a, on either side. A positive double y = 2^e (1 + m 2^-52) has bits
// (e + 1023) << 52 | m, so bits >> kShift counts cells monotonically across octaves,
// and the low kShift bits over 2^kShift are the position t in [0, 1) within the cell,
// exactly linear in y (the cell is uniform in y inside its octave).
constexpr int kCellBits = 4;
constexpr int kShift = 52 - kCellBits;
constexpr std::uint64_t kMask = (std::uint64_t(1) << kShift) - 1;
constexpr double kInvCell = 1.0 / double(std::uint64_t(1) << kShift);

constexpr int kOrder = 16;             // Gauss–Legendre points per panel
constexpr double kPerDecade = 6.0;     // geometric break points per factor of 10
constexpr double kGridFloor = 1e-7;    // the geometric grid starts at 1e-7 min(ℓ, a)

// Closer than 2^-20 a to the kink, K is K(a): K(a(1 ± y)) − K(a) ~ y log(1/y) K ~ 1e-5 K.
constexpr double kKinkGap = 0x1.0p-20;

double edge(std::uint64_t key) { return std::bit_cast<double>(key << kShift); }
std::uint64_t key_of(double y) { return std::bit_cast<std::uint64_t>(y) >> kShift; }

// K(d) = 1/(πa²) ∫_0^S f(s) 2s θ(s) ds for one channel's R or T (DESIGN.md §3 units).
class DiscAverage {
 public:
  DiscAverage(const profiles::RadialProfile& p, bool transmit, bool interpolate, double a,
              double support, double inner)
      : f_(p, transmit, interpolate, kGridFloor * std::min(inner, a), support), a_(a),
        support_(support), rule_(profiles::gauss_legendre(kOrder)) {
    // Geometric break points resolve R on every scale from far below its inner radius
    // (the 1/r peak of PBD and Burley) to its support; cum_[k] = ∫_0^grid_[k] 2πs f ds.
    const double g0 = kGridFloor * std::min(inner, a);
    const double ratio = std::pow(10.0, 1.0 / kPerDecade);
    for (double g = g0; g < support_; g *= ratio) grid_.push_back(g);
    grid_.push_back(support_);
    double sum = 0.0, from = 0.0;
    for (const double g : grid_) {
      sum += panel_radial(from, g);
      cum_.push_back(sum);
      from = g;
    }
  }

  double operator()(double d) const {
    double sum = band(d);
    if (d < a_) sum += radial(std::min(a_ - d, support_));
    return sum / (std::numbers::pi * a_ * a_);
  }

 private:
  double f(double s) const { return f_(s); }

  // ∫_x0^x1 2πs f(s) ds on one Gauss–Legendre panel.
  double panel_radial(double x0, double x1) const {
    const double mid = 0.5 * (x0 + x1), half = 0.5 * (x1 - x0);
    double s = 0.0;
    for (int k = 0; k < kOrder; ++k) {
      const double x = mid + half * rule_.nodes[k];
      s += rule_.weights[k] * x * f(x);
    }
    return 2.0 * std::numbers::pi * half * s;
  }

  // ∫_0^x 2πs f(s) ds (θ = π), x <= S: the cumulative sum to the last break point below
  // x, then one panel.
  double radial(double x) const {
    if (!(x > 0.0)) return 0.0;
    const auto it = std::upper_bound(grid_.begin(), grid_.end(), x);
    if (it == grid_.begin()) return panel_radial(0.0, x);
    const std::size_t j = std::size_t(it - grid_.begin()) - 1;
    return cum_[j] + panel_radial(grid_[j], x);
  }

  // ∫ 2s θ(s) f(s) ds over the band |a − d| < s < min(a + d, S), where the circle of
  // radius s about x_o crosses the disc's rim. With lo = |a − d|, hi = a + d, h = min(a, d)
  // (half the width), s = lo + 2h sin²(u/2), u in [0, π]: ds = h sin u du and
  // hi − s = 2h cos²(u/2). θ from the half-angle formula of the triangle (s, d, a),
  // tan²(θ/2) = (a + s − d)(a − s + d) / ((s + d − a)(s + d + a)), whose factors are
  // written as products of sin(u/2), cos(u/2) and sums (no cancellation near either
  // end, where θ behaves like a square root in s but is smooth in u):
  //   d >= a: tan(θ/2) = h sin u / √((s + lo)(s + hi)),
  //   d <  a: tan(θ/2) = cos(u/2) √(s + lo) / (sin(u/2) √(s + hi)).
  double band(double d) const {
    const double lo = std::fabs(a_ - d), hi = a_ + d, h = std::min(a_, d);
    const double top = std::min(hi, support_);
    if (!(h > 0.0) || !(top > lo)) return 0.0;
    // Break points in s: R's grid, and a geometric grid in s − lo at the scale of lo
    // (θ changes on that scale when d is near a, lo ≪ h).
    std::vector<double> cuts;
    cuts.reserve(64);
    cuts.push_back(lo);
    for (auto it = std::upper_bound(grid_.begin(), grid_.end(), lo);
         it != grid_.end() && *it < top; ++it)
      cuts.push_back(*it);
    if (lo > 0.0 && lo < h) {
      for (int j = -2; j <= 6; ++j) {
        const double s = lo + lo * std::pow(10.0, j / 2.0);
        if (s < top) cuts.push_back(s);
      }
    }
    cuts.push_back(top);
    std::sort(cuts.begin(), cuts.end());
    const bool outside = d >= a_;
    const auto u_of = [&](double s) {
      return 2.0 * std::asin(std::sqrt(std::clamp((s - lo) / (2.0 * h), 0.0, 1.0)));
    };
    double sum = 0.0;
    double u0 = 0.0;
    for (std::size_t i = 1; i < cuts.size(); ++i) {
      const double u1 = (i + 1 == cuts.size() && top == hi) ? std::numbers::pi : u_of(cuts[i]);
      if (!(u1 > u0)) continue;
      const double mid = 0.5 * (u0 + u1), half = 0.5 * (u1 - u0);
      double panel = 0.0;
      for (int k = 0; k < kOrder; ++k) {
        const double u = mid + half * rule_.nodes[k];
        const double sh = std::sin(0.5 * u), ch = std::cos(0.5 * u);
        const double s = lo + 2.0 * h * sh * sh;
        const double sin_u = 2.0 * sh * ch;
        const double theta =
            outside ? 2.0 * std::atan2(h * sin_u, std::sqrt((s + lo) * (s + hi)))
                    : 2.0 * std::atan2(ch * std::sqrt(s + lo), sh * std::sqrt(s + hi));
        panel += rule_.weights[k] * 2.0 * s * theta * f(s) * h * sin_u;
      }
      sum += half * panel;
      u0 = u1;
    }
    return sum;
  }

  ProfileTable f_;
  double a_, support_;
  const profiles::GaussLegendreRule& rule_;
  std::vector<double> grid_, cum_;
};

}  // namespace

// The disc-averaged kernel K(d) of reflection (or, transmit, of transmission) as cubics
// over the cells described below, for irradiance points of radius a.
ScatterKernel::Table ScatterKernel::build_table(const profiles::RgbProfile& profile, bool transmit,
                                                double a, double support_mm) {
  const double S = profile.support_radius();
  const double inner = profile.inner_radius();
  // Two tables in y = |d/a − 1|: inside the disc's rim (y = 1 − d/a, from 2^-20 to 1,
  // d = 0) and outside it (y = d/a − 1, from 2^-20 to S/a): log-spaced towards the kink
  // at d = a on both sides, where K' has a logarithmic singularity for profiles with a
  // 1/r peak (the rim crossing the peak), and log-spaced in d far from it.
  const double inv_a = 1.0 / a;
  const std::uint64_t base = key_of(kKinkGap);
  const std::size_t inner_cells = std::size_t(key_of(1.0) - base) + 1;
  const std::size_t cells =
      inner_cells + std::size_t(key_of(std::max(S * inv_a, kKinkGap)) - base) + 1;
  // The two models whose profile is costly (PBD: 64 beam samples; the multipole: up to
  // hundreds of dipole pairs) are read through a log-log interpolant (ProfileTable.h).
  const bool interpolate = profiles::model_is_costly(profile.model());

  Table t;
  t.inv_a = inv_a;
  t.end = support_mm * inv_a;
  t.base = base;
  t.inner_cells = std::uint32_t(inner_cells);
  t.coef.assign(16 * cells, 0.0f);
  for (int c = 0; c < 3; ++c) {
    const DiscAverage K(profile.channel(c), transmit, interpolate, a, S, inner);
    t.at_kink[c] = K(a);
    // K at t = 0, 1/3, 2/3 and 1 of every cell (the far edge computed again: cells on
    // the two sides do not share edges).
    std::vector<double> v(4 * cells);
    tbb::parallel_for(std::size_t(0), 4 * cells, [&](std::size_t i) {
      const std::size_t cell = i / 4;
      const bool outside = cell >= inner_cells;
      const std::uint64_t key = base + (outside ? cell - inner_cells : cell);
      const double y0 = edge(key), y1 = edge(key + 1);
      const double y = y0 + double(i % 4) / 3.0 * (y1 - y0);
      v[i] = K(a * std::fabs(outside ? 1.0 + y : 1.0 - y));
    });
    // The cubic through (0, K0), (1/3, K1), (2/3, K2), (1, K3) in monomial form.
    for (std::size_t cell = 0; cell < cells; ++cell) {
      const double* k = &v[4 * cell];
      float* out = &t.coef[16 * cell];
      out[0 + c] = float(k[0]);
      out[4 + c] = float(0.5 * (-11.0 * k[0] + 18.0 * k[1] - 9.0 * k[2] + 2.0 * k[3]));
      out[8 + c] = float(4.5 * (2.0 * k[0] - 5.0 * k[1] + 4.0 * k[2] - k[3]));
      out[12 + c] = float(4.5 * (-k[0] + 3.0 * k[1] - 3.0 * k[2] + k[3]));
    }
  }
  return t;
}

// ∫_0^near_radius_ 2πd K(d) dd of the reflectance through the table, with a break at the
// kink d = a.
glm::dvec3 ScatterKernel::near_disc_integral(double a) const {
  const auto ring = [&](double lo, double hi) {
    const profiles::GaussLegendreRule& gl = profiles::gauss_legendre(16);
    glm::dvec3 sum(0.0);
    const int panels = 32;
    for (int p = 0; p < panels; ++p) {
      const double p0 = lo + (hi - lo) * p / panels, p1 = lo + (hi - lo) * (p + 1) / panels;
      for (std::size_t i = 0; i < gl.nodes.size(); ++i) {
        const double d = 0.5 * (p0 + p1) + 0.5 * (p1 - p0) * gl.nodes[i];
        sum += 0.5 * (p1 - p0) * gl.weights[i] * 2.0 * std::numbers::pi * d * reflect(d);
      }
    }
    return sum;
  };
  return ring(0.0, std::min(a, near_radius_)) + ring(std::min(a, near_radius_), near_radius_);
}

ScatterKernel::ScatterKernel(const profiles::RgbProfile& profile, double point_area_mm2, bool far_side_dark) {
  if (!std::isfinite(point_area_mm2) || !(point_area_mm2 > 0.0))
    throw std::invalid_argument("point_area_mm2: must be finite and > 0, got " +
                                message_number(point_area_mm2));
  point_area_mm2_ = point_area_mm2;
  const double a = std::sqrt(point_area_mm2 / std::numbers::pi);
  support_mm_ = profile.support_radius() + a;
  const Rgb total_t = profile.total_transmittance();
  has_transmittance_ = total_t[0] > 0.0 || total_t[1] > 0.0 || total_t[2] > 0.0;

  reflect_ = build_table(profile, false, a, support_mm_);
  if (far_side_dark) {  // the reflectance table's cells, all zero
    far_side_dark_ = has_transmittance_ = true;
    transmit_ = reflect_;
    std::fill(transmit_.coef.begin(), transmit_.coef.end(), 0.0f);
    transmit_.at_kink = glm::dvec3(0.0);
  } else if (has_transmittance_) {
    transmit_ = build_table(profile, true, a, support_mm_);
  }
  near_radius_ = kNearSpacings * std::sqrt(point_area_mm2);
  near_integral_ = near_disc_integral(a);
}

glm::dvec3 ScatterKernel::Table::eval(double d) const {
  const double x = std::fabs(d) * inv_a;
  if (!(x < end)) return glm::dvec3(0.0);  // also NaN, and no table (end = 0)
  const bool outside = x >= 1.0;
  const double y = outside ? x - 1.0 : 1.0 - x;
  if (y < kKinkGap) return at_kink;
  const std::uint64_t bits = std::bit_cast<std::uint64_t>(y);
  const std::size_t cell = std::size_t((bits >> kShift) - base) + (outside ? inner_cells : 0);
  const float* c = coef.data() + 16 * cell;
  const double t = double(bits & kMask) * kInvCell;
  return {c[0] + t * (c[4] + t * (c[8] + t * double(c[12]))),
          c[1] + t * (c[5] + t * (c[9] + t * double(c[13]))),
          c[2] + t * (c[6] + t * (c[10] + t * double(c[14])))};
}

ScatterKernel::Jet ScatterKernel::Table::jet(double d) const {
  Jet j;
  const double x = std::fabs(d) * inv_a;
  if (!(x < end)) return j;
  const bool outside = x >= 1.0;
  const double y = outside ? x - 1.0 : 1.0 - x;
  if (y < kKinkGap) {
    j.value = at_kink;
    return j;
  }
  const std::uint64_t bits = std::bit_cast<std::uint64_t>(y);
  const std::uint64_t key = bits >> kShift;
  const float* c = coef.data() + 16 * (std::size_t(key - base) + (outside ? inner_cells : 0));
  const double t = double(bits & kMask) * kInvCell;
  // dK/dd = dK/dt · dt/dy · dy/dd, with dt/dy = 1/(cell width in y), dy/dd = ±1/a.
  const double dt_dd = (outside ? inv_a : -inv_a) / (edge(key + 1) - edge(key));
  for (int ch = 0; ch < 3; ++ch) {
    const double c0 = c[ch], c1 = c[4 + ch], c2 = c[8 + ch], c3 = c[12 + ch];
    j.value[ch] = c0 + t * (c1 + t * (c2 + t * c3));
    j.first[ch] = (c1 + t * (2.0 * c2 + 3.0 * t * c3)) * dt_dd;
    j.second[ch] = (2.0 * c2 + 6.0 * t * c3) * dt_dd * dt_dd;
  }
  return j;
}

glm::dvec3 ScatterKernel::reflect(double d_mm) const { return reflect_.eval(d_mm); }
ScatterKernel::Jet ScatterKernel::reflect_jet(double d_mm) const { return reflect_.jet(d_mm); }
ScatterKernel::Jet ScatterKernel::transmit_jet(double rho_mm) const { return transmit_.jet(rho_mm); }
glm::dvec3 ScatterKernel::transmit(double rho_mm) const { return transmit_.eval(rho_mm); }

}  // namespace sss::reference
