#include "profiles/VariableProjection.h"

#include <Eigen/Householder>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>

namespace sss::profiles::detail {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Weight of the row Σw = T relative to the data: λ = kPenalty · max_c ‖b_c‖/T_c, where
// ‖b_c‖/T_c is the norm of a column with the profile's own width. Narrower columns have
// larger norms (∝ v^-1/4), so the row outweighs them by less; the row's residual
// (Σw − T)/T stays below 5e-9 on the dipole presets (measured) and the rescale removes
// it. A larger λ raises the QR's condition number in proportion, for little gain.
constexpr double kPenalty = 1e4;

// Gaussian terms with r²/2v above this are exactly 0 in the fit (e^-300 ~ 5e-131).
constexpr double kTailCut = 300.0;

}  // namespace

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

}  // namespace sss::profiles::detail
