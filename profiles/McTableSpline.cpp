#include "profiles/McTableSpline.h"

#include "profiles/Integrate.h"
#include "profiles/McTableProfile.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace sss::profiles {

namespace {

constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

// Histopolation in x = ln r (optical units). q(x) = 2π r² R(r), so the flux through
// an annulus [r_k, r_k+1) is ∫ q dx over [x_k, x_k+1]: the log-uniform annuli are equal
// intervals of width Δ in x. Node k sits at the centre c_k = x_1 + (k - ½)Δ of bin k;
// node 0, at x_1 - Δ/2, belongs to the disc [0, r_1). φ = ln q is a uniform Catmull-Rom
// spline through the nodes 0..K (K: the last enforced annulus), and outside them:
//  - below c_0, with every order: φ is linear with slope s: q ∝ r^s, R ∝ r^{s-2}. Near
//    the source a pencil beam's single scattering gives R ~ 1/r (s = 1) and multiple
//    scattering an R that grows only like ln(1/r) (s -> 2); s is the slope between the
//    first two enforced annuli, clamped to [1, 2] (outside that range it can only be
//    noise). The disc's flux sets node 0's value.
//  - below c_0, single scattering apart: no 1/r term is left. Twice-scattered light
//    makes R grow like ln(1/r) at the source: the first event on the beam at depth z1,
//    the second at x2, two 1/d² propagators whose product integrated over x2 is ~1/|z1 -
//    r| (a convolution of two 1/d² kernels in 3D), and ∫ dz1/|z1 - r| ~ ln(1/r); higher
//    orders are finite there (PBD's ms term has the same ln r, PhotonBeamDiffusion.h).
//    A power law would overshoot that by orders of magnitude over the 6 decades from
//    the first node to min_radius, so R = R_0 (1 + (2 - s)(x_0 - x)) below x_0 = c_0:
//    R ∝ ln(r_c/r) with r_c = r_0 e^{1/(2-s)}, whose slope d ln q/dx is s at c_0 (C1
//    with the spline), s a clamped estimate as above but fitted over the first decade
//    of enforced annuli (see inner_fit; s = 2: R constant). Its integral
//    below c_0 is q_0 (1/2 + (2 - s)/4). Annuli before the first enforced one follow
//    the same law from that annulus down (so the law below c_0 is its continuation,
//    with R ∝ 1 + (2 - s)(c_first - x)).
//  - above c_K, R(r) = R(r_K) exp(-κ (r - r_K)), an exponential tail in r continuous
//    with node K (and C1 with the spline, whose tangent at c_K is the tail's). κ is the
//    asymptotic transport decay rate κ0 (transport_decay_rate: the slowest mode of
//    isotropic transport decays like e^{-κ0 r}), or the rate between the last two
//    enforced nodes if that is steeper (the power-law factor in front of e^{-κ0 r}
//    steepens the profile at finite r).
// An unreliable annulus between enforced ones gets the value linear in x between its
// enforced neighbours; one before the first enforced annulus the law below c_0 (power
// or log), continued from the first enforced annulus.
// The node values are adjusted by the fixed point φ_k += ω ln(F_k / I_k), I_k being the
// spline's integral over bin k (6-point Gauss-Legendre per half bin: the integrand
// exp(cubic) is smooth on a half bin; the tail's half bin in closed form), until every
// enforced bin's integral matches its flux to 1e-12, at most 60 steps. Convergence:
// linearised, ln I_k responds to the node values through the integral of the
// Catmull-Rom cardinal function over a bin, 0.839 for its own node, 0.094 for each
// neighbour, -0.013 for the next; the step's error factor 1 - ωλ then ranges over
// λ ∈ [0.625, 1] (alternating to smooth modes), 0.375 at worst for ω = 1 and 0.23 for
// ω = 1.2 (measured: ~0.19 per step, 20 steps from a flat start). s and κ are
// re-estimated during the first 4 steps only: fed back every step they slow the
// iteration (measured 0.6 per step), and 4 steps leave them within ~1% of their limit.

// The fit's state: the spline, and what its stages share.
class SplineFit {
 public:
  SplineFit(const std::vector<double>& r_edges, std::size_t bins_used, const std::vector<double>& target,
            const std::vector<char>& enforced, double alpha, bool apart, const std::string& too_few,
            const std::string& medium);
  McTableSpline solve();

 private:
  double inner_fit() const;
  void fill(bool rates);
  void build_segments();
  double seg_integral(std::size_t k, double t0) const;
  double tail_integral() const;
  double inner_integral() const;
  double bin_integral(std::size_t k) const;

  const std::vector<double>& target;
  const std::vector<char>& enforced;
  const bool apart;
  const std::string& medium;
  McTableSpline out;
  // Aliases into `out`, the names the method's comments use.
  std::size_t& K = out.K;
  double& dx = out.dx;
  std::vector<double>& centre = out.centre;
  std::vector<double>& phi = out.phi;
  std::vector<double>& seg = out.seg;
  double& s0 = out.s0;
  double& kappa = out.kappa;
  double& rK = out.rK;
  int& iterations = out.iterations;
  double& residual = out.residual;
  std::size_t first = 0, second = 0;
  double s = 1.5;
  double kappa0 = 0.0;
  double d_tail = 0.0;  // the tail's half bin past r_K
  const GaussLegendreRule& gl = gauss_legendre(6);
};

SplineFit::SplineFit(const std::vector<double>& r_edges, std::size_t bins_used, const std::vector<double>& target_,
                     const std::vector<char>& enforced_, double alpha, bool apart_, const std::string& too_few,
                     const std::string& medium_)
    : target(target_), enforced(enforced_), apart(apart_), medium(medium_) {
  const double x1 = std::log(r_edges[1]);
  dx = std::log(r_edges[2] / r_edges[1]);
  std::size_t enforced_annuli = 0;
  for (std::size_t b = 1; b < bins_used; ++b)
    if (enforced[b]) {
      K = b;
      if (enforced_annuli == 0) first = b;
      if (enforced_annuli == 1) second = b;
      ++enforced_annuli;
    }
  if (enforced_annuli < 2)
    throw std::invalid_argument(too_few + " with a reliable flux at " + medium +
                                " (the table's photon budget is too small)");
  phi.assign(K + 1, 0.0);
  centre.assign(K + 1, 0.0);
  for (std::size_t k = 0; k <= K; ++k) {
    centre[k] = x1 + (static_cast<double>(k) - 0.5) * dx;
    if (enforced[k]) phi[k] = std::log(target[k] / dx);
  }
  // s0: the slope of φ at c_0, which the law below c_0 continues (= s, or for the log
  // law anchored at c_first (see fill), 2 - k0 with k0 = (2 - s)/(1 + (2 - s)(c_first - c_0))).
  kappa0 = transport_decay_rate(alpha);
  rK = std::exp(centre[K]);
  // Segment k (c_k..c_k+1) in t ∈ [0, 1]: φ = a0 + a1 t + a2 t² + a3 t³.
  seg.assign(4 * K, 0.0);
  const double r_edge = std::exp(centre[K] + 0.5 * dx);
  d_tail = r_edge - rK;
}

  // Apart: the least-squares slope of φ over the enforced annuli within a decade of the
  // first one (16 on the shipped grid). The first two alone are the noisiest annuli of
  // the multiply-scattered part (relative errors 10-40% near the source, where the once-
  // scattered light dominates the walks' exits): at η = 1.4 their slope sat at the clamp
  // 2 for 5 of 6 albedos from 0.01 to 0.9999. Over the decade it is 1.53-2 on the shipped
  // table (at the clamp for 10% of 3131 media swept over η and α'), as ln(r_c/r) gives
  // there (2 - 1/ln(r_c/r), 1.6-1.8 for r_c ~ 0.03-1 mfp at r ~ 0.005 mfp).
double SplineFit::inner_fit() const {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = first; k <= K && centre[k] <= centre[first] + std::log(10.0); ++k) {
    if (!enforced[k]) continue;
    const double x = centre[k] - centre[first];
    n += 1, sx += x, sy += phi[k], sxx += x * x, sxy += x * phi[k];
  }
  const double det = n * sxx - sx * sx;
  return det > 0.0 ? (n * sxy - sx * sy) / det
                   : (phi[second] - phi[first]) / (centre[second] - centre[first]);
}

void SplineFit::fill(bool rates) {
  if (rates)
    s = std::clamp(apart
                       ? inner_fit()
                       : (phi[second] - phi[first]) / (centre[second] - centre[first]),
                   1.0, 2.0);
  // Before the first enforced annulus, the law that holds below c_0 (above), anchored
  // at the first enforced node: the power law φ = φ_f - s (c_f - x), or the log law
  // φ = φ_f - 2 (c_f - x) + ln(1 + (2 - s)(c_f - x)).
  const double k_log = 2.0 - s;
  const std::size_t anchor = enforced[0] ? 0 : first;
  s0 = apart
           ? 2.0 - k_log / (1.0 + k_log * (centre[anchor] - centre[0]))
           : s;
  std::size_t prev = kNone;  // none yet
  for (std::size_t k = 0; k <= K; ++k) {
    if (enforced[k]) {
      prev = k;
      continue;
    }
    if (prev == kNone) {
      const double d = centre[first] - centre[k];
      phi[k] = apart ? phi[first] - 2.0 * d + std::log1p(k_log * d)
                                        : phi[first] - s * d;
    } else {
      std::size_t next = k + 1;
      while (!enforced[next]) ++next;  // K is enforced
      const double t = (centre[k] - centre[prev]) / (centre[next] - centre[prev]);
      phi[k] = phi[prev] + t * (phi[next] - phi[prev]);
    }
  }
  std::size_t p = K - 1;
  while (!enforced[p]) --p;  // `first` < K is enforced
  const double rp = std::exp(centre[p]);
  const double k2 = ((phi[p] - 2.0 * centre[p]) - (phi[K] - 2.0 * centre[K])) / (rK - rp);
  if (rates) kappa = std::max(kappa0, k2);
}

void SplineFit::build_segments() {
  auto tangent = [&](std::size_t k) {  // dφ/dt, t in units of Δ
    if (k == 0) return s0 * dx;
    if (k == K) return (2.0 - kappa * rK) * dx;
    return 0.5 * (phi[k + 1] - phi[k - 1]);
  };
  for (std::size_t k = 0; k < K; ++k) {
    const double p0 = phi[k], p1 = phi[k + 1], m0 = tangent(k), m1 = tangent(k + 1);
    seg[4 * k] = p0;
    seg[4 * k + 1] = m0;
    seg[4 * k + 2] = 3.0 * (p1 - p0) - 2.0 * m0 - m1;
    seg[4 * k + 3] = 2.0 * (p0 - p1) + m0 + m1;
  }
}

// ∫ exp(segment k) over t ∈ [t0, t0 + ½], in x units.
double SplineFit::seg_integral(std::size_t k, double t0) const {
  const double* a = &seg[4 * k];
  double sum = 0.0;
  for (std::size_t i = 0; i < gl.nodes.size(); ++i) {
    const double t = t0 + 0.25 * (gl.nodes[i] + 1.0);
    sum += gl.weights[i] * std::exp(a[0] + t * (a[1] + t * (a[2] + t * a[3])));
  }
  return 0.25 * dx * sum;
}

// ∫ exp(tail) over x ∈ [c_K, c_K + Δ/2], in closed form (the tail can fall by many
// orders of magnitude across a half bin, which no fixed quadrature follows):
// q_K/r_K² ∫ r e^{-κ(r - r_K)} dr over [r_K, r_K + d] = q_K/r_K² [(1 - E)(r_K/κ + 1/κ²) - d E/κ],
// E = e^{-κ d}.
double SplineFit::tail_integral() const {
  const double E = std::exp(-kappa * d_tail), one_minus_E = -std::expm1(-kappa * d_tail);
  return std::exp(phi[K]) / (rK * rK) *
         (one_minus_E * (rK / kappa + 1.0 / (kappa * kappa)) - d_tail * E / kappa);
}

// ∫ q dx below c_0: q_0/s0 for the power law, q_0 (1/2 + (2 - s0)/4) for the log law
// (∫_0^∞ e^{-2t} (1 + k t) dt = 1/2 + k/4).
double SplineFit::inner_integral() const {
  return apart ? std::exp(phi[0]) * (0.5 + 0.25 * (2.0 - s0))
                                  : std::exp(phi[0]) / s0;
}

double SplineFit::bin_integral(std::size_t k) const {
  if (k == 0) return inner_integral() + seg_integral(0, 0.0);
  return seg_integral(k - 1, 0.5) + (k < K ? seg_integral(k, 0.0) : tail_integral());
}

McTableSpline SplineFit::solve() {
  constexpr int kRateIterations = 4;
  constexpr double kRelax = 1.2;
  for (iterations = 0; iterations < 60; ++iterations) {
    fill(iterations < kRateIterations);
    build_segments();
    residual = 0.0;
    std::vector<double> step(K + 1, 0.0);
    for (std::size_t k = 0; k <= K; ++k) {
      if (!enforced[k]) continue;
      step[k] = std::log(target[k] / bin_integral(k));
      // Written so that a NaN step raises the residual (std::max would drop it).
      if (!(std::fabs(step[k]) <= residual)) residual = std::fabs(step[k]);
    }
    if (!std::isfinite(residual))
      throw std::runtime_error("mc-table: the R(r) reconstruction diverged at " + medium);
    if (residual < 1e-12) break;
    for (std::size_t k = 0; k <= K; ++k) phi[k] += kRelax * step[k];
  }
  // Not converged in 60 iterations (never seen): the segments must still describe the
  // φ the evaluation constants below are taken from.
  if (!(residual < 1e-12)) {
    fill(false);
    build_segments();
  }
  return out;
}

}  // namespace

McTableSpline fit_mc_table_spline(const std::vector<double>& r_edges, std::size_t bins_used,
                                  const std::vector<double>& target, const std::vector<char>& enforced,
                                  double alpha, bool apart, const std::string& too_few,
                                  const std::string& medium) {
  return SplineFit(r_edges, bins_used, target, enforced, alpha, apart, too_few, medium).solve();
}

double mc_table_support_mfp(const McTableSpline& spline) {
  const std::size_t K = spline.K;
  const double kappa = spline.kappa, rK = spline.rK;
  const std::vector<double>& phi = spline.phi;
  const std::vector<double>& centre = spline.centre;
  // Support: r R = q / (2π r) = e^{φ - x}/2π. Its peak is at a node, or in the tail at
  // r = 1/κ if that lies past r_K (r e^{-κ r} peaks there).
  double peak = -std::numeric_limits<double>::infinity();
  std::size_t peak_k = 0;
  for (std::size_t k = 0; k <= K; ++k)
    if (phi[k] - centre[k] > peak) peak = phi[k] - centre[k], peak_k = k;
  // ln(r R 2π) in the tail: φ_K - 2c_K + ln r - κ (r - r_K).
  auto tail_log = [&](double r) { return phi[K] - 2.0 * centre[K] + std::log(r) - kappa * (r - rK); };
  const double r_turn = std::max(rK, 1.0 / kappa);
  peak = std::max(peak, tail_log(r_turn));
  const double floor_log = peak + std::log(1e-8);
  double support_mfp = 0.0;
  for (std::size_t k = peak_k + 1; k <= K && support_mfp == 0.0; ++k)
    if (phi[k] - centre[k] < floor_log) support_mfp = std::exp(centre[k]);
  if (support_mfp == 0.0) {
    // tail_log decreases past r_turn: bracket the crossing by doubling, then bisect.
    double lo = r_turn, hi = 2.0 * r_turn;
    while (tail_log(hi) > floor_log) lo = hi, hi *= 2.0;
    for (int i = 0; i < 100 && hi - lo > 1e-12 * hi; ++i) {
      const double mid = 0.5 * (lo + hi);
      (tail_log(mid) > floor_log ? lo : hi) = mid;
    }
    support_mfp = hi;
  }
  return support_mfp;
}

}  // namespace sss::profiles
