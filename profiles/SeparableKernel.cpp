#include "profiles/SeparableKernel.h"

#include "profiles/EdgeResponse.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace sss::profiles {

namespace {

// The marginal's tails beyond ±range hold at most this fraction of its energy per side:
// 2·5e-4 = 0.1%, i.e. the range holds 99.9%.
constexpr double kTailFraction = 5e-4;

// The x > 0 where M(x) = fraction·total (M decreases from total/2 at 0 to 0 at the
// support), by bisection to a relative width of 1e-9.
double tail_radius(const RadialProfile& p, double fraction) {
  const double target = fraction * p.total_reflectance();
  double lo = 0.0, hi = p.support_radius();
  while (hi - lo > 1e-9 * hi) {
    const double mid = 0.5 * (lo + hi);
    (edge_response(p, mid) > target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// One channel's R(r) sampled once on a log grid and interpolated log-log with a cubic
// (Catmull-Rom; power laws, such as PBD's 1/r near the origin, are exact); the exact
// profile outside the grid.
// total, support and inner radius are the exact profile's, so edge_response integrates
// over the same panels as for the exact profile.
class LogGridProfile final : public RadialProfile {
 public:
  explicit LogGridProfile(const RadialProfile& exact) : exact_(exact) {
    const double lo = 1e-4 * exact.inner_radius(), hi = exact.support_radius();
    log_lo_ = std::log(lo);
    const double decades = std::log10(hi / lo);
    const int n = std::max(2, static_cast<int>(std::ceil(decades * kTabulatedNodesPerDecade)) + 1);
    step_ = (std::log(hi) - log_lo_) / (n - 1);
    log_hi_ = log_lo_ + step_ * (n - 1);
    log_v_.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      // R underflows to 0 (or rounds below it) far out: a tiny floor keeps the log finite
      // and interpolates to ~0 there.
      const double v = exact.reflectance(std::exp(log_lo_ + step_ * i));
      log_v_[static_cast<std::size_t>(i)] = std::log(std::max(v, 1e-300));
    }
  }
  double reflectance(double r_mm) const override {
    if (!(r_mm > 0.0)) return exact_.reflectance(r_mm);
    const double lr = std::log(r_mm);
    if (lr < log_lo_ || lr > log_hi_) return exact_.reflectance(r_mm);
    const double u = (lr - log_lo_) / step_;
    const std::size_t n = log_v_.size();
    const std::size_t i = std::min(static_cast<std::size_t>(u), n - 2);
    const double t = u - static_cast<double>(i);
    const double y1 = log_v_[i], y2 = log_v_[i + 1];
    double y = y1 + t * (y2 - y1);
    if (i > 0 && i + 2 < n) {
      // Catmull-Rom (cubic, centred slopes) between the two middle nodes: O(h^4).
      const double y0 = log_v_[i - 1], y3 = log_v_[i + 2];
      y = y1 + 0.5 * t * (y2 - y0 + t * (2.0 * y0 - 5.0 * y1 + 4.0 * y2 - y3 +
                                         t * (3.0 * (y1 - y2) + y3 - y0)));
    }
    const double v = std::exp(y);
    return v <= 1e-299 ? 0.0 : v;
  }
  double total_reflectance() const override { return exact_.total_reflectance(); }
  double support_radius() const override { return exact_.support_radius(); }
  double inner_radius() const override { return exact_.inner_radius(); }

 private:
  const RadialProfile& exact_;
  double log_lo_ = 0.0, log_hi_ = 0.0, step_ = 1.0;
  std::vector<double> log_v_;
};

bool tabulate(Model model, KernelQuadrature q) {
  if (q == KernelQuadrature::Auto) return model_is_costly(model);
  return q == KernelQuadrature::Tabulated;
}

}  // namespace

namespace {

// Each half-cell's weight: the marginal's integral over the cell around positive[i], a
// difference of the edge response M at the midpoints to the neighbouring taps, over the
// total. Cell i >= 1 spans [b_{i-1}, b_i] with b_i the midpoint to the next tap and
// b_half = ∞; the centre cell is [-b_0, b_0]; the telescoping sum is exactly the total.
template <typename Edge>
std::vector<Rgb> cell_weights(const std::vector<double>& positive, const Rgb& total, Edge&& edge) {
  const int half = static_cast<int>(positive.size()) - 1;
  std::vector<Rgb> boundary_m(half + 1);  // M(b_i), with M(∞) = 0 last
  for (int i = 0; i < half; ++i) boundary_m[i] = edge(0.5 * (positive[i] + positive[i + 1]));
  boundary_m[half] = Rgb{};
  std::vector<Rgb> weight(half + 1);
  for (int c = 0; c < 3; ++c) {
    const double T = total[c];
    const double inv = T > 0.0 ? 1.0 / T : 0.0;
    weight[0][c] = (T - 2.0 * boundary_m[0][c]) * inv;
    for (int i = 1; i <= half; ++i) weight[i][c] = (boundary_m[i - 1][c] - boundary_m[i][c]) * inv;
  }
  return weight;
}

}  // namespace

SeparableKernel make_separable_kernel(const RgbProfile& profile, int taps, double range_mm,
                                      KernelQuadrature quadrature) {
  if (taps < 3 || taps % 2 == 0) {
    std::string msg = "make_separable_kernel: taps must be odd and >= 3, got ";
    msg += std::to_string(taps);
    throw std::invalid_argument(msg);
  }
  if (!std::isfinite(range_mm))
    throw std::invalid_argument("make_separable_kernel: range_mm must be finite");
  // The channels M is integrated over: the exact ones or their tables.
  std::array<std::unique_ptr<LogGridProfile>, 3> tables;
  std::array<const RadialProfile*, 3> channel{};
  for (int c = 0; c < 3; ++c) {
    if (tabulate(profile.model(), quadrature))
      tables[c] = std::make_unique<LogGridProfile>(profile.channel(c));
    channel[c] = tables[c] ? tables[c].get() : &profile.channel(c);
  }
  SeparableKernel k;
  k.total_reflectance = profile.total_reflectance();
  if (range_mm <= 0.0) {
    range_mm = 0.0;
    for (int c = 0; c < 3; ++c)
      range_mm = std::max(range_mm, tail_radius(*channel[c], kTailFraction));
  }
  k.range_mm = range_mm;

  // Offsets x = range·sign(t)·t², t = -1 + 2i/(taps-1) (Jimenez et al. 2015); the positive
  // half is computed and mirrored so the kernel is exactly symmetric with a tap at 0.
  const int half = (taps - 1) / 2;
  std::vector<double> positive(half + 1);
  for (int i = 0; i <= half; ++i) {
    const double t = static_cast<double>(i) / half;
    positive[i] = range_mm * t * t;
  }
  const std::vector<Rgb> weight = cell_weights(positive, k.total_reflectance, [&](double x) {
    Rgb m{};
    for (int c = 0; c < 3; ++c) m[c] = edge_response(*channel[c], x);
    return m;
  });
  k.offsets_mm.resize(taps);
  k.weights.resize(taps);
  for (int i = 0; i <= half; ++i) {
    // The mirror first: at i = 0 both write the centre tap, which must end +0.0, not
    // -positive[0] = -0.0 (printed "-0.00000", serialised "-0").
    k.offsets_mm[half - i] = -positive[i];
    k.offsets_mm[half + i] = positive[i];
    k.weights[half + i] = weight[i];
    k.weights[half - i] = weight[i];
  }
  return k;
}

}  // namespace sss::profiles
