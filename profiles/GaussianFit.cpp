#include "profiles/GaussianFit.h"

#include "profiles/Nnls.h"

#include <Eigen/Cholesky>
#include <Eigen/Householder>
#include <Eigen/QR>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace sss::profiles {

namespace {

constexpr double kPi = 3.14159265358979323846;

using VecN = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxGaussians, 1>;
using MatN = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxGaussians,
                           kMaxGaussians>;
using MatN3 = Eigen::Matrix<double, Eigen::Dynamic, 3, 0, kMaxGaussians, 3>;

// Weight of the row Σw = T relative to the data: λ = kPenalty · max_c ‖b_c‖/T_c, where
// ‖b_c‖/T_c is the norm of a column with the profile's own width. Narrower columns have
// larger norms (∝ v^-1/4), so the row outweighs them by less; the row's residual
// (Σw − T)/T stays below 5e-9 on the dipole presets (measured) and the rescale removes
// it. A larger λ raises the QR's condition number in proportion, for little gain.
constexpr double kPenalty = 1e4;

// Gaussian terms with r²/2v above this are exactly 0 in the fit (e^-300 ~ 5e-131).
constexpr double kTailCut = 300.0;

// Levenberg–Marquardt stops when an accepted step gains less than this fraction of the cost.
constexpr double kStall = 1e-8;

// One point of the variable-projection functional Φ(θ) = Σ_c s_c² min_{w>=0} ‖A w − b_c‖²
// (θ = log-variances, rows weighted by √dr·r, s_c = 1/‖b_c‖, row 0 the energy row), with
// the Gauss–Newton pieces LM needs: H = JᵀJ and g = Jᵀρ.
struct Point {
  VecN theta;
  double cost = std::numeric_limits<double>::infinity();
  MatN H;
  VecN g;
  MatN3 W;  // weights per channel, before the energy rescale
};

class VarPro {
 public:
  VarPro(const FitTarget& t, int n);
  void evaluate(Point& p);
  int levenberg_marquardt(Point& p, int max_iterations);
  double theta_min() const { return theta_min_; }
  double theta_max() const { return theta_max_; }
  // The weighted column a_j = √dr_j r_j G(v, r_j), v = e^θ.
  void column(double theta, Eigen::Ref<Eigen::VectorXd> out) const;
  // The weighted targets b_c = √dr r R_c (one column per channel, no energy row).
  const Eigen::MatrixXd& targets() const { return B_; }
  double scale(int c) const { return scale_[c]; }
  Eigen::Index samples() const { return M_; }

 private:
  Eigen::Index M_, M1_, N_;
  Eigen::ArrayXd rs_, r2_;
  Eigen::MatrixXd B_;
  // [A | B | D], (M+1) × (2N+3): the design matrix, the targets and ∂A/∂θ, with the
  // energy row first. The QR of A is done in place and its reflectors rotate B and D.
  Eigen::MatrixXd C_;
  Eigen::MatrixXd Rsq_;
  Eigen::VectorXd w_;
  NnlsSolver nnls_;
  Rgb scale_{};
  Rgb total_{};
  double lambda_ = 0.0;
  double theta_min_, theta_max_;
  Point trial_;
};

VarPro::VarPro(const FitTarget& t, int n)
    : M_(static_cast<Eigen::Index>(t.r_mm.size())), M1_(M_ + 1), N_(n), rs_(M_), r2_(M_),
      B_(M_, 3), C_(M1_, 2 * N_ + 3), Rsq_(N_, N_), w_(N_), nnls_(N_, N_) {
  for (Eigen::Index j = 0; j < M_; ++j) {
    rs_[j] = std::sqrt(t.dr[j]) * t.r_mm[j];
    r2_[j] = t.r_mm[j] * t.r_mm[j];
  }
  double lambda = 0.0;
  for (int c = 0; c < 3; ++c) {
    for (Eigen::Index j = 0; j < M_; ++j) B_(j, c) = rs_[j] * t.R[j][c];
    const double norm = B_.col(c).norm();
    total_[c] = t.total_reflectance[c];
    scale_[c] = (norm > 0.0 && total_[c] > 0.0) ? 1.0 / norm : 0.0;
    if (scale_[c] > 0.0) lambda = std::max(lambda, norm / total_[c]);
  }
  lambda_ = kPenalty * lambda;
  // A Gaussian narrower than twice the first radius, or wider than the last, is not
  // resolved by the samples.
  theta_min_ = 2.0 * std::log(2.0 * t.r_mm.front());
  theta_max_ = 2.0 * std::log(t.r_mm.back());
}

void VarPro::column(double theta, Eigen::Ref<Eigen::VectorXd> out) const {
  const double v = std::exp(theta);
  // Terms below e^-kTailCut of the peak are set to 0: they cannot matter in double, and
  // left alone their products in the QR would underflow into subnormals, which are
  // slower by orders of magnitude. The radii ascend, so the cut is a tail of the samples.
  const Eigen::Index m = M_;
  const double r2_cut = 2.0 * v * kTailCut;
  Eigen::Index head = m;
  while (head > 0 && r2_[head - 1] >= r2_cut) --head;
  out.head(head).array() =
      (r2_.head(head) * (-0.5 / v)).exp() * rs_.head(head) * (1.0 / (2.0 * kPi * v));
  out.tail(m - head).setZero();
}

void VarPro::evaluate(Point& p) {
  const Eigen::Index N = N_, M1 = M1_, cols = C_.cols();
  for (Eigen::Index i = 0; i < N; ++i) {
    const double v = std::exp(p.theta[i]);
    C_(0, i) = lambda_;
    C_(0, N + 3 + i) = 0.0;
    auto a = C_.col(i).tail(M_).array();
    column(p.theta[i], C_.col(i).tail(M_));
    // ∂G/∂ln v = G·(r²/2v − 1).
    C_.col(N + 3 + i).tail(M_).array() = a * (r2_ * (0.5 / v) - 1.0);
  }
  for (int c = 0; c < 3; ++c) {
    C_(0, N + c) = lambda_ * total_[c];
    C_.col(N + c).tail(M_) = B_.col(c);
  }
  // Householder QR of the first N columns (H = I − τ u uᵀ, u = [1; essential]), each
  // reflector applied to every later column of C.
  for (Eigen::Index j = 0; j < N; ++j) {
    const Eigen::Index len = M1 - j;
    auto u = C_.col(j).segment(j + 1, len - 1);  // the essential part, in place
    const double x0 = C_(j, j);
    const double tail2 = u.squaredNorm();
    if (tail2 == 0.0) continue;  // already triangular in this column: H = I
    const double beta = -std::copysign(std::sqrt(x0 * x0 + tail2), x0);
    const double tau = (beta - x0) / beta;
    u *= 1.0 / (x0 - beta);
    C_(j, j) = beta;
    for (Eigen::Index k = j + 1; k < cols; ++k) {
      auto y = C_.col(k).segment(j + 1, len - 1);
      const double dot = tau * (C_(j, k) + u.dot(y));
      C_(j, k) -= dot;
      y -= dot * u;
    }
  }
  Rsq_.setZero();
  Rsq_.triangularView<Eigen::Upper>() = C_.topLeftCorner(N, N);
  // Complement block [tails | DP]: its Gram matrix gives ‖t_c‖², DPᵀt_c and DPᵀDP.
  const auto X = C_.bottomRightCorner(M1 - N, N + 3);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxGaussians + 3,
                kMaxGaussians + 3>
      XtX(N + 3, N + 3);
  XtX.noalias() = X.transpose() * X;
  const auto DPtDP = XtX.bottomRightCorner(N, N);
  const auto DQ = C_.block(0, N + 3, N, N);

  p.cost = 0.0;
  p.H.setZero(N, N);
  p.g.setZero(N);
  p.W.setZero(N, 3);
  for (int c = 0; c < 3; ++c) {
    if (scale_[c] == 0.0) continue;
    const auto y = C_.col(N + c).head(N);
    nnls_.solve(Rsq_, y, w_);
    const VecN top = Rsq_ * w_ - y;
    const double s2 = scale_[c] * scale_[c];
    p.cost += s2 * (top.squaredNorm() + XtX(c, c));
    p.W.col(c) = w_;

    // Exact variable-projection Jacobian (Golub & Pereyra 1973) for the passive set P,
    // in the rotated coordinates [Qᵀ; Q⊥ᵀ]: column k of J is
    //   P⊥_{A_P} D_k w_k − (A_P⁺)ᵀ e_k (D_kᵀ ρ),
    // whose top block is (I − UUᵀ)(QᵀD)_k w_k − U T⁻ᵀ e_k s_k (R_P = U T) and whose
    // bottom block is (Q⊥ᵀD)_k w_k. Columns outside P are zero.
    const Eigen::Index k = nnls_.passive_count();
    if (k == 0) continue;
    MatN Rp(N, k);
    for (Eigen::Index q = 0; q < k; ++q) Rp.col(q) = Rsq_.col(nnls_.passive()[q]);
    const Eigen::HouseholderQR<MatN> qr(Rp);
    const MatN Qfull = qr.householderQ();
    const auto U = Qfull.leftCols(k);
    MatN Tinv_t = MatN::Identity(k, k);
    qr.matrixQR().topLeftCorner(k, k).transpose().triangularView<Eigen::Lower>().solveInPlace(
        Tinv_t);
    const auto DPt_tail = XtX.col(c).segment(3, N);
    MatN Z = MatN::Zero(N, N);
    for (Eigen::Index q = 0; q < k; ++q) {
      const Eigen::Index col = nnls_.passive()[q];
      const VecN dq = DQ.col(col);
      const double s = dq.dot(top) - DPt_tail(col);
      Z.col(col) = (dq - U * (U.transpose() * dq)) * w_[col] - U * Tinv_t.col(q) * s;
    }
    MatN Hc = Z.transpose() * Z;
    Hc += (w_ * w_.transpose()).cwiseProduct(DPtDP);
    p.H += s2 * Hc;
    p.g += s2 * (Z.transpose() * top - w_.cwiseProduct(DPt_tail));
  }
}

int VarPro::levenberg_marquardt(Point& p, int max_iterations) {
  evaluate(p);
  double max_diag = p.H.diagonal().maxCoeff();
  if (!(max_diag > 0.0)) return 0;
  double mu = 1e-3 * max_diag, nu = 2.0;
  int it = 0;
  while (it < max_iterations) {
    ++it;
    max_diag = p.H.diagonal().maxCoeff();
    if (!(max_diag > 0.0) || p.cost < 1e-28) break;
    // Marquardt's scaling by diag(H), floored so that a Gaussian with no weight (a zero
    // column of J) stays put instead of making the system singular. A variance held at
    // a bound that the gradient pushes against is frozen for this step (projected LM).
    VecN d = p.H.diagonal().cwiseMax(1e-12 * max_diag);
    MatN S = p.H;
    VecN rhs = -p.g;
    for (Eigen::Index k = 0; k < N_; ++k) {
      const bool pinned = (p.theta[k] <= theta_min_ && p.g[k] > 0.0) ||
                          (p.theta[k] >= theta_max_ && p.g[k] < 0.0);
      if (pinned) {
        S.row(k).setZero();
        S.col(k).setZero();
        S(k, k) = 1.0;
        rhs[k] = 0.0;
        d[k] = 0.0;
      }
    }
    S.diagonal() += mu * d;
    VecN step = S.ldlt().solve(rhs);
    const double longest = step.cwiseAbs().maxCoeff();
    if (longest > 3.0) step *= 3.0 / longest;  // at most a factor e³ per iteration
    trial_.theta = (p.theta + step).cwiseMax(theta_min_).cwiseMin(theta_max_);
    step = trial_.theta - p.theta;
    evaluate(trial_);
    const double actual = p.cost - trial_.cost;
    if (actual > 0.0) {
      // Gain ratio against the Gauss–Newton model ‖ρ + Jδ‖².
      const double predicted = -2.0 * step.dot(p.g) - step.dot(p.H * step);
      const double rho = predicted > 0.0 ? actual / predicted : 0.5;
      const double before = p.cost;
      std::swap(p, trial_);
      mu *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));
      nu = 2.0;
      // Converged when a step gains less than kStall of the cost (e_c changes by less
      // than kStall/2 relative) or moves no variance by more than 1e-9 relative.
      if (actual < kStall * before || step.cwiseAbs().maxCoeff() < 1e-9) break;
    } else {
      mu *= nu;
      nu *= 2.0;
      if (mu > 1e16 * max_diag) break;
    }
  }
  return it;
}

void validate(const FitTarget& t, int n) {
  if (n < 1 || n > kMaxGaussians) {
    std::string msg = "fit_gaussians: gaussians must be in [1, ";
    msg += std::to_string(kMaxGaussians);
    msg += "], got ";
    msg += std::to_string(n);
    throw std::invalid_argument(msg);
  }
  const std::size_t m = t.r_mm.size();
  if (m < static_cast<std::size_t>(n) + 1)
    throw std::invalid_argument("fit_gaussians: the target needs more samples than gaussians");
  if (t.R.size() != m || t.dr.size() != m)
    throw std::invalid_argument("fit_gaussians: r_mm, R and dr must have the same size");
  for (std::size_t j = 0; j < m; ++j) {
    if (!(t.r_mm[j] > 0.0) || !std::isfinite(t.r_mm[j]) || (j > 0 && !(t.r_mm[j] > t.r_mm[j - 1])))
      throw std::invalid_argument("fit_gaussians: radii must be positive, finite, ascending");
    if (!(t.dr[j] >= 0.0) || !std::isfinite(t.dr[j]))
      throw std::invalid_argument("fit_gaussians: dr must be finite and >= 0");
    for (double v : t.R[j])
      if (!std::isfinite(v)) throw std::invalid_argument("fit_gaussians: R must be finite");
  }
  for (int c = 0; c < 3; ++c) {
    const double T = t.total_reflectance[c];
    if (!(T >= 0.0) || !std::isfinite(T))
      throw std::invalid_argument("fit_gaussians: total reflectance must be finite and >= 0");
    bool all_zero = true;
    for (std::size_t j = 0; j < m; ++j) all_zero = all_zero && t.R[j][c] == 0.0;
    if (all_zero && T > 0.0) {
      std::string msg = "fit_gaussians: R is zero on every sample of channel ";
      msg += kChannelNames[c];
      msg += " but its total is not";
      throw std::invalid_argument(msg);
    }
  }
}

// Log-variances of n Gaussians spread evenly in log between sd_lo² and sd_hi².
VecN spread(int n, double sd_lo, double sd_hi) {
  VecN theta(n);
  const double lo = 2.0 * std::log(sd_lo), hi = 2.0 * std::log(sd_hi);
  for (int i = 0; i < n; ++i)
    theta[i] = n == 1 ? 0.5 * (lo + hi) : lo + (hi - lo) * i / (n - 1);
  return theta;
}

// The smallest (lowest = true) or largest radius over channels at which the running
// trapezoid sum of r R dr reaches the fraction q of its total.
double energy_radius(const FitTarget& t, double q, bool lowest) {
  double out = lowest ? t.r_mm.back() : t.r_mm.front();
  for (int c = 0; c < 3; ++c) {
    double total = 0.0;
    for (std::size_t j = 0; j < t.r_mm.size(); ++j) total += t.r_mm[j] * t.R[j][c] * t.dr[j];
    if (!(total > 0.0)) continue;
    double sum = 0.0;
    std::size_t j = 0;
    for (; j + 1 < t.r_mm.size(); ++j) {
      sum += t.r_mm[j] * t.R[j][c] * t.dr[j];
      if (sum >= q * total) break;
    }
    out = lowest ? std::min(out, t.r_mm[j]) : std::max(out, t.r_mm[j]);
  }
  return out;
}

}  // namespace

double gaussian_2d(double variance_mm2, double r_mm) {
  return std::exp(-r_mm * r_mm / (2.0 * variance_mm2)) / (2.0 * kPi * variance_mm2);
}

Rgb GaussianFit::evaluate(double r_mm) const {
  Rgb out{};
  for (std::size_t i = 0; i < variances_mm2.size(); ++i) {
    const double g = gaussian_2d(variances_mm2[i], r_mm);
    for (int c = 0; c < 3; ++c) out[c] += weights[i][c] * g;
  }
  return out;
}

FitTarget make_fit_target(const RgbProfile& profile, int samples) {
  if (samples < 2) {
    std::string msg = "make_fit_target: samples must be >= 2, got ";
    msg += std::to_string(samples);
    throw std::invalid_argument(msg);
  }
  FitTarget t;
  const double r0 = 1e-3 * profile.inner_radius();
  const double r1 = profile.support_radius();
  if (!(r0 > 0.0) || !(r1 > r0) || !std::isfinite(r1))
    throw std::invalid_argument("make_fit_target: the profile's radii are not usable");
  const double h = std::log(r1 / r0) / (samples - 1);
  t.r_mm.resize(samples);
  t.R.resize(samples);
  t.dr.resize(samples);
  for (int j = 0; j < samples; ++j) {
    const double r = j == samples - 1 ? r1 : r0 * std::exp(h * j);
    t.r_mm[j] = r;
    t.R[j] = profile.reflectance(r);
    // Trapezoid rule in u = ln r: ∫ f dr = ∫ f(e^u) e^u du.
    t.dr[j] = (j == 0 || j == samples - 1 ? 0.5 : 1.0) * h * r;
  }
  t.total_reflectance = profile.total_reflectance();
  return t;
}

GaussianFit fit_gaussians(const FitTarget& target, const FitOptions& opt) {
  const int n = opt.gaussians;
  validate(target, n);
  VarPro vp(target, n);

  // Three starting spreads, log-spaced standard deviations from the radius that holds
  // q_lo of the energy ∫ 2πr R dr (smallest over channels) to half the radius that
  // holds q_hi (largest over channels). Each start gets kProbe iterations; the best one
  // is then run to convergence. The profile's support radius is a poor scale for this:
  // it is set by a 1e-8 tail and lies 100-300 inner radii out for the presets, and
  // starts placed from it stick at the upper bound. Measured on the dipole and better
  // dipole over all presets and N = 2..8 (scratch study, not a test): the first start
  // alone comes within 1.3% of the best cost of 100 random starts, and probing then
  // continuing the best gives the same cost as running all three starts to the end,
  // with 37 instead of 90 iterations on average.
  constexpr double kStarts[3][2] = {{0.05, 0.95}, {0.02, 0.99}, {0.1, 0.8}};
  constexpr int kProbe = 5;
  Point best;
  GaussianFit fit;
  for (const auto& q : kStarts) {
    Point p;
    p.theta = spread(n, energy_radius(target, q[0], true), 0.5 * energy_radius(target, q[1], false))
                  .cwiseMax(vp.theta_min())
                  .cwiseMin(vp.theta_max());
    fit.iterations += vp.levenberg_marquardt(p, std::min(kProbe, opt.max_iterations));
    if (p.cost < best.cost) best = p;
  }
  fit.iterations += vp.levenberg_marquardt(best, opt.max_iterations);

  // Re-seed Gaussians that carry no weight in any channel, or that duplicate another:
  // move each to the variance whose column best matches the remaining residual (the
  // largest NNLS dual), then run LM again; keep the result if it is better.
  const Eigen::Index m = vp.samples();
  Eigen::MatrixXd Adata(m, n);
  Eigen::VectorXd a(m);
  constexpr int kCandidates = 32;
  for (int round = 0; round < 2; ++round) {
    std::array<bool, kMaxGaussians> is_dead{};
    for (int i = 0; i < n; ++i) is_dead[i] = best.W.row(i).isZero(0.0);
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j)
        if (!is_dead[i] && !is_dead[j] && std::fabs(best.theta[i] - best.theta[j]) < 1e-3)
          is_dead[best.W.row(i).sum() < best.W.row(j).sum() ? i : j] = true;
    std::vector<int> dead;
    for (int i = 0; i < n; ++i)
      if (is_dead[i]) dead.push_back(i);
    if (dead.empty()) break;
    for (int i = 0; i < n; ++i) vp.column(best.theta[i], Adata.col(i));
    Eigen::MatrixXd residual = vp.targets() - Adata * best.W;
    std::array<double, kCandidates> score{};
    std::array<double, kCandidates> cand{};
    for (int q = 0; q < kCandidates; ++q) {
      cand[q] = vp.theta_min() + (vp.theta_max() - vp.theta_min()) * q / (kCandidates - 1);
      vp.column(cand[q], a);
      const double a2 = a.squaredNorm();
      for (int c = 0; c < 3; ++c) {
        const double dual = std::max(0.0, a.dot(residual.col(c)));
        score[q] += vp.scale(c) * vp.scale(c) * dual * dual / a2;
      }
    }
    Point p = best;
    for (int i : dead) {
      const int q = static_cast<int>(std::max_element(score.begin(), score.end()) - score.begin());
      p.theta[i] = cand[q];
      for (int d = std::max(0, q - 2); d <= std::min(kCandidates - 1, q + 2); ++d) score[d] = -1.0;
    }
    fit.iterations += vp.levenberg_marquardt(p, opt.max_iterations);
    if (!(p.cost < best.cost)) break;
    best = p;
  }

  // Sort by variance, rescale each channel to the exact total, measure the error.
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int x, int y) { return best.theta[x] < best.theta[y]; });
  fit.variances_mm2.resize(n);
  fit.weights.assign(n, Rgb{});
  for (int c = 0; c < 3; ++c) {
    const double sum = best.W.col(c).sum();
    const double T = target.total_reflectance[c];
    for (int i = 0; i < n; ++i) {
      const double w = best.W(order[i], c);
      fit.weights[i][c] = (sum > 0.0 ? w * (T / sum) : 0.0);
    }
  }
  Eigen::MatrixXd Wfinal(n, 3);
  for (int i = 0; i < n; ++i) {
    fit.variances_mm2[i] = std::exp(best.theta[order[i]]);
    vp.column(best.theta[order[i]], Adata.col(i));
    for (int c = 0; c < 3; ++c) Wfinal(i, c) = fit.weights[i][c];
  }
  const Eigen::MatrixXd residual = vp.targets() - Adata * Wfinal;
  for (int c = 0; c < 3; ++c) {
    for (int i = 0; i < n; ++i) fit.total_reflectance[c] += fit.weights[i][c];
    const double norm = vp.targets().col(c).norm();
    fit.relative_error[c] = norm > 0.0 ? residual.col(c).norm() / norm : 0.0;
  }
  return fit;
}

}  // namespace sss::profiles
