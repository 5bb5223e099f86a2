#include "profiles/SeparableKernel.h"

#include "profiles/EdgeResponse.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

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

}  // namespace

SeparableKernel make_separable_kernel(const RgbProfile& profile, int taps, double range_mm) {
  if (taps < 3 || taps % 2 == 0) {
    std::string msg = "make_separable_kernel: taps must be odd and >= 3, got ";
    msg += std::to_string(taps);
    throw std::invalid_argument(msg);
  }
  if (!std::isfinite(range_mm))
    throw std::invalid_argument("make_separable_kernel: range_mm must be finite");
  SeparableKernel k;
  k.total_reflectance = profile.total_reflectance();
  if (range_mm <= 0.0) {
    range_mm = 0.0;
    for (int c = 0; c < 3; ++c)
      range_mm = std::max(range_mm, tail_radius(profile.channel(c), kTailFraction));
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
  // Cell i >= 1 spans [b_{i-1}, b_i] with b_i the midpoint to the next tap and b_half = ∞;
  // the centre cell is [-b_0, b_0]. A cell's weight is the marginal's integral over it,
  // a difference of the edge response M; the telescoping sum is exactly the total.
  std::vector<Rgb> boundary_m(half + 1);  // M(b_i), with M(∞) = 0 last
  for (int i = 0; i < half; ++i)
    boundary_m[i] = edge_response(profile, 0.5 * (positive[i] + positive[i + 1]));
  boundary_m[half] = Rgb{};
  std::vector<Rgb> weight(half + 1);
  for (int c = 0; c < 3; ++c) {
    const double T = k.total_reflectance[c];
    const double inv = T > 0.0 ? 1.0 / T : 0.0;
    weight[0][c] = (T - 2.0 * boundary_m[0][c]) * inv;
    for (int i = 1; i <= half; ++i) weight[i][c] = (boundary_m[i - 1][c] - boundary_m[i][c]) * inv;
  }
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
