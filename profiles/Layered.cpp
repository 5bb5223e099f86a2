// LayeredProfile: layered media in the Hankel domain. Layered.h states the model and its
// choices; this file has the numerics.
//
// The transform. For a radially symmetric f(r) the 2-D Fourier transform is the Hankel
// transform of order 0, F(k) = 2π ∫0^∞ f(r) J0(kr) r dr, with inverse
// f(r) = (1/2π) ∫0^∞ F(k) J0(kr) k dk, and F(0) = ∫ 2πr f dr is the total. Convolution in
// the plane is a product of transforms.
//
// Sampling. Both f and F are sampled on one log-spaced grid x_j = 10^(-6 + j/128),
// j = 0..1280 (ten decades, 128 nodes a decade), in units of a length L of the stack
// (r = L x, k = x / L; L below). Between nodes the sampled function is taken to be linear
// in x² (and constant on the disc [0, x_0], zero beyond the last node). Then every piece
// integrates exactly against the Bessel kernel, however fast it oscillates:
//   ∫ x J0(yx) dx = x J1(yx)/y,      ∫ x³ J0(yx) dx = x³ J1(yx)/y - 2x² J2(yx)/y²
// (from d/dx[x^n J_n(x)] = x^n J_(n-1)(x)), so the transform is one fixed matrix M of
// node weights, the same for the forward and the inverse direction, computed once:
//   F(x_i / L) = 2π L² Σ_j M_ij f(L x_j),       f(L x_j) = 1/(2π L²) Σ_i M_ji F(x_i / L).
//
// Accuracy. Measured on the analytic pair pole_flux(r, z) <-> 2π e^{-z √(σ² + k²)}
// (Multipole.cpp; σ = 1/mm): the forward transform is within 2e-4 of F(0) everywhere; the
// inverse, over r in [0.25, 8] mm where the function falls by 10^5-10^7, within 0.02% RMS
// for z = 2 mm and 0.1% RMS (1.2% at worst, at 8 mm) for z = 0.3 mm. 32 nodes a decade
// were 200% off there: the resolution is what the dynamic range needs. Sampling error
// comes from where a function is not smooth on the grid, so the top medium's own profile
// (mc-table's 1/r, the dipoles' steep core) is kept exactly in r and only what the stack
// adds to it goes through the inverse: it has crossed the top layer twice, so its
// transform falls off at least like e^{-k d}, negligible long before the last frequency
// node (x = 10^4 / L with L <= d). T of a stack has crossed every layer. The inverse's
// interpolant in k leaves a weak oscillating tail in r: integrated, the profiles lose
// 0.2% (R) and 0.5% (T) of the diffusion solution's exact totals on a skin-like stack.
//
// L is the smallest length of the stack (the smallest reduced mean free path and the
// thinnest layer), raised if needed so that the largest support radius stays within
// 10^4 L: the grid then reaches from 10^-6 of the finest detail out to the widest support,
// and its lowest frequency, 10^-6 / L, is below 10^-2 / (widest support), where every
// transform is its total to 2.5e-5 relative (1 - J0(kr) <= (kr)²/4).
#include "profiles/Layered.h"

#include "profiles/ClassicalDipole.h"
#include "profiles/Fresnel.h"
#include "profiles/McTableProfile.h"
#include "profiles/Multipole.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace sss::profiles {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr int kPerDecade = 128;
constexpr int kDecades = 10;
constexpr double kLogLo = -6.0;
constexpr int kNodes = kPerDecade * kDecades + 1;

double grid_x(int j) { return std::pow(10.0, kLogLo + static_cast<double>(j) / kPerDecade); }

// M_ij = ∫ (hat function of node j, linear in x²) J0(x_i x) x dx over the grid. The
// antiderivatives at node j for row i are
//   a1 = x_j J1(x_i x_j) / x_i,    a3 = x_j³ J1(x_i x_j) / x_i - 2 x_j² J2(x_i x_j) / x_i²,
// and x_i x_j = 10^(2 kLogLo + (i + j)/kPerDecade) depends on i + j alone: 2 kNodes - 1
// Bessel values build the whole matrix.
struct HankelMatrix {
  std::vector<double> x;
  std::vector<double> m;  // [i][j]
  HankelMatrix() : x(kNodes), m(static_cast<std::size_t>(kNodes) * kNodes, 0.0) {
    for (int j = 0; j < kNodes; ++j) x[j] = grid_x(j);
    std::vector<double> j1(2 * kNodes - 1), j2(2 * kNodes - 1);
    for (int k = 0; k < 2 * kNodes - 1; ++k) {
      const double u = std::pow(10.0, 2.0 * kLogLo + static_cast<double>(k) / kPerDecade);
      j1[k] = std::cyl_bessel_j(1.0, u);
      j2[k] = std::cyl_bessel_j(2.0, u);
    }
    for (int i = 0; i < kNodes; ++i) {
      const double y = x[i];
      double* row = m.data() + static_cast<std::size_t>(i) * kNodes;
      const auto a1 = [&](int j) { return x[j] * j1[i + j] / y; };
      const auto a3 = [&](int j) {
        return x[j] * x[j] * (x[j] * j1[i + j] / y - 2.0 * j2[i + j] / (y * y));
      };
      // The disc [0, x0] carries the value of node 0 (a1 vanishes at 0).
      double prev1 = a1(0), prev3 = a3(0);
      row[0] += prev1;
      for (int j = 0; j + 1 < kNodes; ++j) {
        const double xa = x[j], xb = x[j + 1];
        const double n1 = a1(j + 1), n3 = a3(j + 1);
        const double A = n1 - prev1, B = n3 - prev3;
        // f = α + β x² through (xa, fa), (xb, fb): fa A + (fb - fa) (B - xa² A) / (xb² - xa²).
        const double C = (B - xa * xa * A) / (xb * xb - xa * xa);
        row[j] += A - C;
        row[j + 1] += C;
        prev1 = n1, prev3 = n3;
      }
    }
  }
};

const HankelMatrix& hankel() {
  static const HankelMatrix h;
  return h;
}

// Σ_j M_ij v_j, times `scale`.
std::vector<double> apply(const std::vector<double>& v, double scale) {
  const auto& h = hankel();
  std::vector<double> out(kNodes, 0.0);
  for (int i = 0; i < kNodes; ++i) {
    const double* row = h.m.data() + static_cast<std::size_t>(i) * kNodes;
    double acc = 0.0;
    for (int j = 0; j < kNodes; ++j) acc += row[j] * v[j];
    out[i] = scale * acc;
  }
  return out;
}

// Samples f(L x_j) -> F(x_i / L).
std::vector<double> forward(const std::vector<double>& f, double L) {
  return apply(f, 2.0 * std::numbers::pi * L * L);
}
// F(x_i / L) -> f(L x_j).
std::vector<double> inverse(const std::vector<double>& F, double L) {
  return apply(F, 1.0 / (2.0 * std::numbers::pi * L * L));
}

// One finite layer's profiles (one channel): reflectance from above and from below, and
// transmittance. Reflectance is the base model's semi-infinite profile times the
// multipole's finite-thickness factor R_multipole / R_dipole (the multipole's i = 0 pair
// is the classical dipole with the same lit face): near the axis, where a layer thicker
// than a mean free path does not yet feel its far face, that is the semi-infinite model
// (mc-table: within 1-2% of Monte Carlo, where the classical dipole is off by 20-70%);
// far out, the light the far face lets through is missing as the multipole says. With
// base = dipole it is the multipole itself. Transmittance is the multipole's.
struct FiniteLayer {
  Multipole down, up;  // lit from above (faces top, bottom) and from below (swapped)
  ClassicalDipole dipole_down, dipole_up;
  std::unique_ptr<RadialProfile> semi_down, semi_up;
  bool pure = false;  // base = dipole: the multipole alone

  double corrected(const RadialProfile& semi, const ClassicalDipole& dip, const Multipole& mp,
                   double r) const {
    const double m = mp.reflectance(r);
    if (pure) return m;
    const double d = dip.reflectance(r);
    if (!(d > 0.0)) return 0.0;
    return semi.reflectance(r) * std::clamp(m / d, 0.0, 1.0);
  }
  double reflectance_down(double r) const { return corrected(*semi_down, dipole_down, down, r); }
  double reflectance_up(double r) const { return corrected(*semi_up, dipole_up, up, r); }
  // The layer's totals: closed forms for the pure multipole; otherwise ∫ 2πr R dr of the
  // corrected profile (its transform at the lowest frequency, set by LayeredProfile).
  double tot_down = 0.0, tot_up = 0.0;
  double total_down() const { return pure ? down.total_reflectance() : tot_down; }
  double total_up() const { return pure ? up.total_reflectance() : tot_up; }
};

Coefficients with_eta(Coefficients c, double eta) {
  c.eta = eta;
  return c;
}

std::string layer_field(std::size_t k, const std::string& field) {
  return "layers[" + std::to_string(k) + "]." + field;
}

// Linear interpolation of samples on the grid at r = L x, in log x; 0 beyond the last
// node, the first node's value on the disc.
double at_grid(const std::vector<double>& v, double L, double r) {
  const auto& x = hankel().x;
  const double t = r / L;
  if (!(t > x.front())) return v.front();
  if (t >= x.back()) return 0.0;
  const double u = (std::log10(t) - kLogLo) * kPerDecade;
  const int j = std::min(static_cast<int>(u), kNodes - 2);
  const double w = u - j;
  return v[j] + w * (v[j + 1] - v[j]);
}

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

// The sampled inverse transform's floor (LayeredTransform test: 1e-3 of the value plus
// 1e-7 of the peak): beyond where a decaying profile first falls under 1e-6 of its peak,
// what is left is the interpolant's weak oscillating tail, not light. Cut it there.
void cut_tail(std::vector<double>& v) {
  std::size_t peak = 0;
  for (std::size_t j = 1; j < v.size(); ++j)
    if (std::fabs(v[j]) > std::fabs(v[peak])) peak = j;
  const double floor = 1e-6 * std::fabs(v[peak]);
  for (std::size_t j = peak; j < v.size(); ++j)
    if (std::fabs(v[j]) < floor) {
      std::fill(v.begin() + static_cast<std::ptrdiff_t>(j), v.end(), 0.0);
      break;
    }
}

// ∫ 2πr f dr from 0 to `outer`: f(lo) on the disc [0, lo), lo = 10^-6 L, then the
// midpoint rule on 256 log steps a decade (relative step 0.9%: the rule's error is
// ~ (0.009)²/24 = 3e-6 of the integral where f is smooth).
template <class F>
double integrate_profile(F&& f, double L, double outer) {
  const double lo = 1e-6 * L;
  double sum = std::numbers::pi * lo * lo * f(0.0);
  const double q = std::pow(10.0, 1.0 / 256.0);
  for (double a = lo, b = lo * q; a < outer; a = b, b *= q) {
    const double m = 0.5 * (a + b);
    sum += 2.0 * std::numbers::pi * m * f(m) * (b - a);
  }
  return sum;
}

}  // namespace

namespace detail {
const std::vector<double>& hankel_grid() { return hankel().x; }
std::vector<double> hankel_forward(const std::vector<double>& f, double L) { return forward(f, L); }
std::vector<double> hankel_inverse(const std::vector<double>& F, double L) { return inverse(F, L); }
}  // namespace detail

std::optional<FieldError> validate_layers(const LayerStack& stack) {
  if (stack.empty()) return FieldError{"layers", "needs at least one layer"};
  if (stack.size() > static_cast<std::size_t>(kMaxLayers))
    return FieldError{"layers", "at most " + std::to_string(kMaxLayers) + " layers, got " +
                                    std::to_string(stack.size())};
  for (std::size_t k = 0; k < stack.size(); ++k) {
    const Medium& m = stack[k];
    const bool last = k + 1 == stack.size();
    if (std::isnan(m.thickness_mm) || !(m.thickness_mm > 0.0))
      return FieldError{layer_field(k, "thickness_mm"),
                        "must be a number > 0 (mm), got " + message_number(m.thickness_mm)};
    if (!last && !m.is_slab())
      return FieldError{layer_field(k, "thickness_mm"),
                        "only the last layer may be semi-infinite; this one needs a thickness"};
    if (auto e = m.validate()) return FieldError{layer_field(k, e->field), e->message};
    // Both couplings put the source (or a layer's own source) one reduced mean free path
    // deep: a finite layer must be thicker than that (Multipole.h).
    if (m.is_slab())
      for (int c = 0; c < 3; ++c) {
        const double mfp = m.channel(c).mfp_reduced();
        if (!(m.thickness_mm > mfp))
          return FieldError{layer_field(k, std::string("thickness_mm[") + kChannelNames[c] + "]"),
                            "a layer must be thicker than one reduced mean free path (1/sigma_t' = " +
                                message_number(mfp) + " mm here), got " +
                                message_number(m.thickness_mm) + " mm"};
      }
    for (int c = 0; c < 3; ++c)
      if (m.eta[c] != stack[0].eta[c])
        return FieldError{layer_field(k, std::string("eta[") + kChannelNames[c] + "]"),
                          "must equal layers[0]'s (" + message_number(stack[0].eta[c]) +
                              "): the interfaces between layers are index-matched"};
  }
  return std::nullopt;
}

std::vector<Layer> channel_layers(const LayerStack& stack, int channel) {
  std::vector<Layer> out;
  for (const Medium& m : stack) out.push_back({m.channel(channel), m.thickness_mm});
  return out;
}

struct LayeredProfile::Impl {
  std::vector<Layer> layers;
  std::unique_ptr<RadialProfile> top_semi;    // a one-layer semi-infinite stack
  std::unique_ptr<FiniteLayer> top_finite;    // the top layer when finite
  double L = 1.0;
  std::vector<double> added;     // R12 - R1 on the grid
  std::vector<double> trans;     // T of the stack on the grid (finite bottom only)
  bool has_added = false, has_trans = false, one_finite = false;
  double total_r = 0.0, total_t = 0.0;  // scalar adding of the layers' totals
  double grid_total_r = 0.0, grid_total_t = 0.0;
  double exact_total_r = 0.0, exact_total_t = 0.0;  // Diffusion: the k = 0 solve
  double support = 0.0, inner = 0.0;

  // LayerCoupling::Diffusion: the top medium's classical dipole, to scale what the stack
  // removes (reflectance()).
  std::unique_ptr<ClassicalDipole> top_dipole;

  double top_reflectance(double r) const {
    return top_semi ? top_semi->reflectance(r) : top_finite->reflectance_down(r);
  }
  // The stack's reflectance from the top profile and the added part at r.
  double combined(double r) const {
    const double top = top_reflectance(r);
    if (!has_added) return top;
    const double d = at_grid(added, L, r);
    if (d >= 0.0 || !top_dipole) return std::max(0.0, top + d);
    // Light the stack takes away (an absorbing base): the same fraction of the top
    // profile as of the top medium's diffusion profile, so that it stays >= 0.
    const double dip = top_dipole->reflectance(r);
    return dip > 0.0 ? top * std::max(0.0, 1.0 + d / dip) : 0.0;
  }
};

LayeredProfile::LayeredProfile(const std::vector<Layer>& layers, const ModelOptions& opt,
                               Model base, LayerCoupling coupling)
    : impl_(std::make_unique<Impl>()) {
  if (base == Model::Multipole || base == Model::MonteCarlo || base == Model::Layered)
    throw std::invalid_argument("model: the base of a stack must be a semi-infinite model "
                                "(dipole, better-dipole, pbd, burley, mc-table, qd), got " +
                                std::string(model_name(base)));
  if (layers.empty()) throw std::invalid_argument("layers: needs at least one layer");
  Impl& s = *impl_;
  s.layers = layers;
  const std::size_t n = layers.size();
  const double eta = layers[0].c.eta;
  // Per-layer checks (validate_layers does the RGB stack; this is the one-channel form).
  for (std::size_t k = 0; k < n; ++k) {
    const Layer& l = layers[k];
    if (auto e = l.c.validate()) throw std::invalid_argument(layer_field(k, e->what()));
    if (l.c.eta != eta)
      throw std::invalid_argument(layer_field(k, "eta") +
                                  ": must equal layers[0]'s: the interfaces between layers are "
                                  "index-matched");
    const bool last = k + 1 == n;
    if (std::isnan(l.thickness_mm) || !(l.thickness_mm > 0.0) ||
        (!last && !std::isfinite(l.thickness_mm)))
      throw std::invalid_argument(layer_field(k, "thickness_mm") +
                                  ": must be a finite number > 0 (only the last layer may be "
                                  "semi-infinite), got " + message_number(l.thickness_mm));
    // Donner & Jensen put the source one reduced mean free path deep: a thinner layer has
    // its source below it (negative transmittance; Multipole.h).
    if (std::isfinite(l.thickness_mm) && !(l.thickness_mm > l.c.mfp_reduced()))
      throw std::invalid_argument(
          layer_field(k, "thickness_mm") + ": the multipole describes a layer thicker than one "
          "reduced mean free path (1/sigma_t' = " + message_number(l.c.mfp_reduced()) +
          " mm here), got " + message_number(l.thickness_mm) + " mm");
  }
  ModelOptions semi_opt = opt;
  const bool pure = base == Model::Dipole;
  if (coupling == LayerCoupling::Diffusion) {
    build_diffusion(layers, opt, base);
    return;
  }
  // Index: the lit face of layer k sees the outside (eta) for k = 0, another layer (1)
  // below; its far face sees the outside when it is the last layer.
  auto make_finite = [&](std::size_t k) {
    const Layer& l = layers[k];
    const double top = k == 0 ? eta : 1.0;
    const double bottom = k + 1 == n ? eta : 1.0;
    auto f = std::unique_ptr<FiniteLayer>(new FiniteLayer{
        Multipole(l.c, l.thickness_mm, opt.multipole_pairs, top, bottom),
        Multipole(l.c, l.thickness_mm, opt.multipole_pairs, bottom, top),
        ClassicalDipole(with_eta(l.c, top)), ClassicalDipole(with_eta(l.c, bottom)),
        make_profile(base, with_eta(l.c, top), kInfinity, semi_opt),
        make_profile(base, with_eta(l.c, bottom), kInfinity, semi_opt), pure});
    return f;
  };
  auto make_semi = [&](std::size_t k) {
    return make_profile(base, with_eta(layers[k].c, k == 0 ? eta : 1.0), kInfinity, semi_opt);
  };

  std::vector<std::unique_ptr<FiniteLayer>> finite(n);
  std::unique_ptr<RadialProfile> base_profile;
  double smallest = kInfinity, widest = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    if (std::isfinite(layers[k].thickness_mm)) {
      finite[k] = make_finite(k);
      smallest = std::min({smallest, layers[k].thickness_mm, finite[k]->down.inner_radius()});
      widest = std::max(widest, finite[k]->down.support_radius());
      if (!pure) widest = std::max(widest, finite[k]->semi_down->support_radius());
    } else {
      base_profile = make_semi(k);
      smallest = std::min(smallest, base_profile->inner_radius());
      widest = std::max(widest, base_profile->support_radius());
    }
  }
  s.support = widest;
  s.inner = smallest;
  s.L = std::max(smallest, widest * 1e-4);

  const auto& x = hankel().x;
  auto sample = [&](auto&& f) {
    std::vector<double> v(kNodes);
    for (int j = 0; j < kNodes; ++j) v[j] = f(s.L * x[j]);
    return forward(v, s.L);
  };
  // Transforms of the corrected layer reflectances (both directions), kept for the adding.
  std::vector<std::vector<double>> hat_down(n), hat_up(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (!finite[k]) continue;
    FiniteLayer& f = *finite[k];
    if (pure && n == 1) break;  // the multipole alone: nothing to transform
    hat_down[k] = sample([&](double r) { return f.reflectance_down(r); });
    if (k + 1 < n) hat_up[k] = sample([&](double r) { return f.reflectance_up(r); });
    // At the lowest frequency, 10^-2 / (widest support) or below, J0 is 1 to 2.5e-5.
    f.tot_down = hat_down[k].front();
    if (k + 1 < n) f.tot_up = hat_up[k].front();
  }

  // Scalar adding of the totals, bottom up.
  double tot_r = base_profile ? base_profile->total_reflectance() : finite[n - 1]->total_down();
  double tot_t = base_profile ? 0.0 : finite[n - 1]->down.total_transmittance();
  for (std::size_t k = n - 1; k-- > 0;) {
    const FiniteLayer& f = *finite[k];
    const double t = f.down.total_transmittance();
    const double denom = 1.0 - tot_r * f.total_up();
    tot_t = t * tot_t / denom;
    tot_r = f.total_down() + t * t * tot_r / denom;
  }
  s.total_r = tot_r;
  s.total_t = tot_t;

  if (n == 1) {
    if (base_profile) s.top_semi = std::move(base_profile);
    else s.top_finite = std::move(finite[0]), s.one_finite = true;
    s.grid_total_r = s.total_r, s.grid_total_t = s.total_t;
    return;
  }

  // The stack in the frequency domain, bottom up.
  std::vector<double> R, T;
  if (base_profile) {
    R = sample([&](double r) { return base_profile->reflectance(r); });
    T.assign(kNodes, 0.0);
  } else {
    const FiniteLayer& f = *finite[n - 1];
    R = hat_down[n - 1];
    T = sample([&](double r) { return f.down.transmittance(r); });
  }
  for (std::size_t k = n - 1; k-- > 0;) {
    const FiniteLayer& f = *finite[k];
    const auto Tk = sample([&](double r) { return f.down.transmittance(r); });
    const std::vector<double>& Rup = hat_up[k];
    const std::vector<double>& Rdown = hat_down[k];
    std::vector<double> added(kNodes), Rn(kNodes), Tn(kNodes);
    const bool top = k == 0;
    for (int i = 0; i < kNodes; ++i) {
      const double denom = 1.0 - R[i] * Rup[i];
      added[i] = Tk[i] * Tk[i] * R[i] / denom;
      Tn[i] = Tk[i] * T[i] / denom;
      if (!top) Rn[i] = Rdown[i] + added[i];
    }
    T = std::move(Tn);
    if (top) {
      s.added = inverse(added, s.L);
      cut_tail(s.added);
      s.has_added = true;
      s.grid_total_r = f.total_down() + added.front();
    } else {
      R = std::move(Rn);
    }
  }
  s.top_finite = std::move(finite[0]);
  if (!base_profile) {
    s.trans = inverse(T, s.L);
    cut_tail(s.trans);
    s.has_trans = true;
    s.grid_total_t = T.front();
  }
}

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

LayeredProfile::~LayeredProfile() = default;

double LayeredProfile::reflectance(double r) const { return impl_->combined(r); }

double LayeredProfile::transmittance(double r) const {
  const Impl& s = *impl_;
  if (s.one_finite) return s.top_finite->down.transmittance(r);
  if (!s.has_trans) return 0.0;
  return std::max(0.0, at_grid(s.trans, s.L, r));
}

double LayeredProfile::total_reflectance() const { return impl_->total_r; }
double LayeredProfile::total_transmittance() const { return impl_->total_t; }
double LayeredProfile::lowest_frequency_reflectance() const { return impl_->grid_total_r; }
double LayeredProfile::lowest_frequency_transmittance() const { return impl_->grid_total_t; }
double LayeredProfile::diffusion_total_reflectance() const { return impl_->exact_total_r; }
double LayeredProfile::diffusion_total_transmittance() const { return impl_->exact_total_t; }
double LayeredProfile::support_radius() const { return impl_->support; }
double LayeredProfile::inner_radius() const { return impl_->inner; }
std::size_t LayeredProfile::layer_count() const { return impl_->layers.size(); }

std::vector<std::string> layered_g_warnings(const LayerStack& stack, Model base) {
  if (stack.empty() || base != Model::McTable) return {};
  std::vector<std::string> out = mc_table_g_warnings(stack.front());
  for (std::string& w : out) w = "top layer " + w;
  return out;
}

RgbProfile make_layered_rgb_profile(const LayerStack& stack, const ModelOptions& opt,
                                    Model base, LayerCoupling coupling) {
  if (auto e = validate_layers(stack)) throw std::invalid_argument(e->what());
  std::array<std::unique_ptr<RadialProfile>, 3> ch;
  for (int c = 0; c < 3; ++c) {
    try {
      ch[c] = std::make_unique<LayeredProfile>(channel_layers(stack, c), opt, base, coupling);
    } catch (const std::invalid_argument& e) {
      // Name the channel: "layers[0].thickness_mm[G]: ..."
      const std::string what = e.what();
      const auto colon = what.find(": ");
      if (what.rfind("layers[", 0) != 0 || colon == std::string::npos ||
          what.find('[', what.find('.')) < colon)
        throw;
      throw std::invalid_argument(what.substr(0, colon) + "[" + kChannelNames[c] + "]" +
                                  what.substr(colon));
    }
  }
  return RgbProfile(Model::Layered, std::move(ch));
}

}  // namespace sss::profiles
