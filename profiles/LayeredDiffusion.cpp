// LayerCoupling::Diffusion: the layered diffusion equation solved per frequency.
#include "profiles/LayeredImpl.h"

#include "profiles/Fresnel.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace sss::profiles {

using namespace layered;

namespace {

// The layered diffusion equation in the frequency domain (LayerCoupling::Diffusion).
// Layer i (0-based, top first) spans [t_i, t_{i+1}] with D_i = 1/(3σt'_i) and
// κ_i(k)² = σa_i/D_i + k². The source is the classical dipole's: strength α'_0 at depth
// z_s = 1/σt'_0 in the top layer, so the transformed fluence obeys
// D_i (κ_i² - ∂z²) φ = α'_0 δ(z - z_s). In layer i
//   φ = a_i e^{-κ_i (z - o_i)} + b_i e^{κ_i (z - p_i)}   (+ G(z) in the top layer),
// G(z) = α'_0 e^{-κ_0 |z - z_s|} / (2 D_0 κ_0) the free-space solution, with o_i and p_i
// the layer's upper and lower ends (the top layer's upper end moved to the extrapolated
// boundary -z_b, a finite last layer's lower end to t_N + z_b') so that neither
// exponential exceeds 1 in its layer, whatever k. The conditions: φ = 0 on the
// extrapolated boundaries (z_b = 2 A(η) D of the layer at that face), φ and D ∂φ/∂z
// continuous at every interface (index-matched: no jump), b = 0 in a semi-infinite last
// layer. Then R(k) = D_0 ∂φ/∂z at 0 and T(k) = -D_last ∂φ/∂z at the bottom (Fick's law,
// as the dipole's and the multipole's R and T). With one layer this is the image
// solution, i.e. the classical dipole: R(k) = (α'/2)(e^{-κ z_s} + e^{-κ (z_s + 2 z_b)}).
class DiffusionStack {
 public:
  explicit DiffusionStack(const std::vector<Layer>& layers) : n_(layers.size()) {
    double t = 0.0;
    top_.push_back(0.0);
    for (const Layer& l : layers) {
      D_.push_back(1.0 / (3.0 * l.c.sigma_t_reduced()));
      sa_.push_back(l.c.sigma_a);
      t += l.thickness_mm;
      top_.push_back(t);
    }
    finite_ = std::isfinite(t);
    const double eta = layers[0].c.eta;
    const double fdr = fresnel_diffuse_reflectance_fit(eta);
    const double A = (1.0 + fdr) / (1.0 - fdr);
    zb_ = 2.0 * A * D_[0];
    zb_bottom_ = 2.0 * A * D_[n_ - 1];
    zs_ = 1.0 / layers[0].c.sigma_t_reduced();
    alpha_ = layers[0].c.albedo_reduced();
  }

  // {R(k), T(k)}.
  std::pair<double, double> solve(double k) const {
    const std::size_t m = 2 * n_;
    double a[2 * kMaxLayers][2 * kMaxLayers + 1] = {};
    double kappa[kMaxLayers] = {};
    for (std::size_t i = 0; i < n_; ++i) kappa[i] = std::sqrt(sa_[i] / D_[i] + k * k);
    const auto o = [&](std::size_t i) { return i == 0 ? -zb_ : top_[i]; };
    const auto p = [&](std::size_t i) {
      return i + 1 == n_ && finite_ ? top_[n_] + zb_bottom_ : top_[i + 1];
    };
    const auto u = [&](std::size_t i, double z) { return std::exp(-kappa[i] * (z - o(i))); };
    const auto v = [&](std::size_t i, double z) {
      return std::isfinite(p(i)) ? std::exp(kappa[i] * (z - p(i))) : 0.0;
    };
    const double g0 = alpha_ / (2.0 * D_[0] * kappa[0]);
    // The particular solution G in the top layer (none below) and its z-derivative.
    const auto phi_p = [&](std::size_t i, double z) {
      return i == 0 ? g0 * std::exp(-kappa[0] * std::fabs(z - zs_)) : 0.0;
    };
    const auto dphi_p = [&](std::size_t i, double z) {
      return i == 0 ? (z < zs_ ? kappa[0] : -kappa[0]) * phi_p(0, z) : 0.0;
    };
    std::size_t row = 0;
    // φ(-z_b) = 0.
    a[row][0] = 1.0;
    a[row][1] = v(0, -zb_);
    a[row][m] = -phi_p(0, -zb_);
    ++row;
    for (std::size_t i = 0; i + 1 < n_; ++i) {
      const double z = top_[i + 1];
      const std::size_t ai = 2 * i, bi = ai + 1, aj = ai + 2, bj = ai + 3;
      a[row][ai] = u(i, z);
      a[row][bi] = v(i, z);
      a[row][aj] = -u(i + 1, z);
      a[row][bj] = -v(i + 1, z);
      a[row][m] = phi_p(i + 1, z) - phi_p(i, z);
      ++row;
      a[row][ai] = -D_[i] * kappa[i] * u(i, z);
      a[row][bi] = D_[i] * kappa[i] * v(i, z);
      a[row][aj] = D_[i + 1] * kappa[i + 1] * u(i + 1, z);
      a[row][bj] = -D_[i + 1] * kappa[i + 1] * v(i + 1, z);
      a[row][m] = D_[i + 1] * dphi_p(i + 1, z) - D_[i] * dphi_p(i, z);
      ++row;
    }
    const std::size_t last = n_ - 1;
    if (finite_) {  // φ = 0 on the bottom's extrapolated boundary
      a[row][2 * last] = u(last, p(last));
      a[row][2 * last + 1] = 1.0;
      a[row][m] = -phi_p(last, p(last));
    } else {
      a[row][2 * last + 1] = 1.0;  // b = 0: nothing grows with depth
    }
    // Gaussian elimination with partial pivoting.
    for (std::size_t c = 0; c < m; ++c) {
      std::size_t piv = c;
      for (std::size_t r = c + 1; r < m; ++r)
        if (std::fabs(a[r][c]) > std::fabs(a[piv][c])) piv = r;
      if (piv != c)
        for (std::size_t j = 0; j <= m; ++j) std::swap(a[c][j], a[piv][j]);
      for (std::size_t r = c + 1; r < m; ++r) {
        const double f = a[r][c] / a[c][c];
        if (f == 0.0) continue;
        for (std::size_t j = c; j <= m; ++j) a[r][j] -= f * a[c][j];
      }
    }
    double x[2 * kMaxLayers] = {};
    for (std::size_t c = m; c-- > 0;) {
      double acc = a[c][m];
      for (std::size_t j = c + 1; j < m; ++j) acc -= a[c][j] * x[j];
      x[c] = acc / a[c][c];
    }
    const double dphi0 =
        -kappa[0] * x[0] * u(0, 0.0) + kappa[0] * x[1] * v(0, 0.0) + dphi_p(0, 0.0);
    double t = 0.0;
    if (finite_) {
      const double z = top_[n_];
      t = -D_[last] * (-kappa[last] * x[2 * last] * u(last, z) +
                       kappa[last] * x[2 * last + 1] * v(last, z) + dphi_p(last, z));
    }
    return {D_[0] * dphi0, t};
  }

 private:
  std::size_t n_;
  std::vector<double> D_, sa_, top_;
  bool finite_ = false;
  double zb_ = 0.0, zb_bottom_ = 0.0, zs_ = 0.0, alpha_ = 0.0;
};

}  // namespace

void LayeredProfile::build_diffusion(const std::vector<Layer>& layers, const ModelOptions& opt,
                                     Model base) {
  Impl& s = *impl_;
  const std::size_t n = layers.size();
  const double eta = layers[0].c.eta;
  s.top_semi = make_profile(base, layers[0].c, kInfinity, opt);
  if (n == 1 && !std::isfinite(layers[0].thickness_mm)) {
    s.total_r = s.grid_total_r = s.top_semi->total_reflectance();
    s.support = s.top_semi->support_radius();
    s.inner = s.top_semi->inner_radius();
    return;
  }
  s.top_dipole = std::make_unique<ClassicalDipole>(layers[0].c);
  double smallest = s.top_semi->inner_radius(), widest = s.top_semi->support_radius();
  for (const Layer& l : layers) {
    const ClassicalDipole d(with_eta(l.c, eta));
    smallest = std::min(smallest, d.inner_radius());
    if (std::isfinite(l.thickness_mm)) smallest = std::min(smallest, l.thickness_mm);
    widest = std::max(widest, d.support_radius());
  }
  s.support = widest;
  s.inner = smallest;
  s.L = std::max(smallest, widest * 1e-4);

  const DiffusionStack stack(layers);
  // The top medium alone, semi-infinite, in the same diffusion model: what the stack changes.
  const DiffusionStack alone({{layers[0].c, kInfinity}});
  const auto& x = hankel().x;
  std::vector<double> delta(kNodes), trans(kNodes);
  for (int i = 0; i < kNodes; ++i) {
    const double k = x[i] / s.L;
    const auto [r, t] = stack.solve(k);
    delta[i] = r - alone.solve(k).first;
    trans[i] = t;
  }
  s.added = inverse(delta, s.L);
  cut_tail(s.added);
  s.has_added = true;
  const auto [r0, t0] = stack.solve(0.0);
  s.exact_total_r = r0, s.exact_total_t = t0;
  s.grid_total_r = alone.solve(x[0] / s.L).first + delta.front();
  const bool transmits = std::isfinite(layers[n - 1].thickness_mm);
  if (transmits) {
    s.trans = inverse(trans, s.L);
    cut_tail(s.trans);
    s.has_trans = true;
    s.grid_total_t = trans.front();
  }
  // The totals are the integrals of the profiles as reflectance() and transmittance()
  // give them, so that a user's ∫ 2πr R dr is the total. The diffusion solve's own totals
  // at k = 0 (exact_total_*) differ from them by what the sampled inverse transform
  // misses: its interpolant in k leaves a weak oscillating tail in r beyond the support
  // (0.2% of the total on a skin-like stack; tests/profiles/test_layered.cpp).
  s.total_r = integrate_profile([&](double r) { return s.combined(r); }, s.L, s.support);
  if (transmits)
    s.total_t = integrate_profile([&](double r) { return std::max(0.0, at_grid(s.trans, s.L, r)); },
                                  s.L, s.support);
}

}  // namespace sss::profiles
