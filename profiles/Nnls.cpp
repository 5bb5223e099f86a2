#include "profiles/Nnls.h"

#include <Eigen/Householder>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sss::profiles {

NnlsSolver::NnlsSolver(Eigen::Index rows, Eigen::Index cols) { reserve(rows, cols); }

void NnlsSolver::reserve(Eigen::Index rows, Eigen::Index cols) {
  if (qr_.rows() != rows || qr_.cols() != cols) qr_.resize(rows, cols);
  if (rhs_.size() != rows) {
    rhs_.resize(rows);
    residual_.resize(rows);
  }
  if (z_.size() != cols) {
    z_.resize(cols);
    dual_.resize(cols);
    work_.resize(cols);
    passive_.resize(cols);
    is_passive_.resize(cols);
    excluded_.resize(cols);
  }
}

double NnlsSolver::solve_passive(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                 const Eigen::Ref<const Eigen::VectorXd>& b) {
  const Eigen::Index m = A.rows();
  const Eigen::Index k = n_passive_;
  z_.setZero();
  if (k > m) return 0.0;  // more passive columns than rows: the last one is dependent
  for (Eigen::Index i = 0; i < k; ++i) qr_.col(i) = A.col(passive_[i]);
  rhs_ = b;
  // Householder QR of the passive columns, applied to the right-hand side as it goes.
  for (Eigen::Index j = 0; j < k; ++j) {
    double tau = 0.0, beta = 0.0;
    qr_.col(j).segment(j, m - j).makeHouseholderInPlace(tau, beta);
    qr_(j, j) = beta;
    const auto essential = qr_.col(j).segment(j + 1, m - j - 1);
    if (j + 1 < k)
      qr_.block(j, j + 1, m - j, k - j - 1).applyHouseholderOnTheLeft(essential, tau, work_.data());
    rhs_.segment(j, m - j).applyHouseholderOnTheLeft(essential, tau, work_.data());
  }
  // Each |R_ii| is column i's distance from the span of the columns before it.
  double independence = k > 0 ? 1.0 : 0.0;
  for (Eigen::Index i = 0; i < k; ++i) {
    const double norm = A.col(passive_[i]).norm();
    independence = std::min(independence, norm > 0.0 ? std::fabs(qr_(i, i)) / norm : 0.0);
  }
  if (independence == 0.0) return 0.0;
  // Back substitution R y = (Qᵀb)[0:k].
  for (Eigen::Index i = k - 1; i >= 0; --i) {
    double s = rhs_(i);
    for (Eigen::Index j = i + 1; j < k; ++j) s -= qr_(i, j) * work_(j);
    work_(i) = s / qr_(i, i);
  }
  for (Eigen::Index i = 0; i < k; ++i) z_(passive_[i]) = work_(i);
  return independence;
}

Eigen::Index NnlsSolver::entering_variable(const Eigen::Ref<const Eigen::MatrixXd>& A, double b_norm,
                                           double tolerance) {
  dual_.noalias() = A.transpose() * residual_;
  Eigen::Index t = -1;
  double best = 0.0;
  for (Eigen::Index j = 0; j < A.cols(); ++j) {
    if (is_passive_[j] || excluded_[j]) continue;
    const double col_norm = A.col(j).norm();
    if (col_norm == 0.0) continue;
    const double score = dual_(j) / col_norm;
    if (score > tolerance * b_norm && score > best) {
      best = score;
      t = j;
    }
  }
  return t;
}

void NnlsSolver::remove_passive(Eigen::Index j) {
  Eigen::Index out = 0;
  for (Eigen::Index i = 0; i < n_passive_; ++i)
    if (passive_[i] != j) passive_[out++] = passive_[i];
  n_passive_ = out;
  is_passive_[j] = false;
}

bool NnlsSolver::step_to_feasibility(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                     const Eigen::Ref<const Eigen::VectorXd>& b, Eigen::Ref<Eigen::VectorXd> x,
                                     int cap, NnlsResult& result) {
  while (true) {
    Eigen::Index blocking = -1;
    double alpha = 1.0;
    for (Eigen::Index i = 0; i < n_passive_; ++i) {
      const Eigen::Index j = passive_[i];
      if (z_(j) <= 0.0) {
        const double a = x(j) / (x(j) - z_(j));
        if (blocking < 0 || a < alpha) {
          alpha = a;
          blocking = j;
        }
      }
    }
    if (blocking < 0) break;
    for (Eigen::Index i = 0; i < n_passive_; ++i) {
      const Eigen::Index j = passive_[i];
      x(j) += alpha * (z_(j) - x(j));
    }
    x(blocking) = 0.0;
    for (Eigen::Index i = n_passive_ - 1; i >= 0; --i) {
      const Eigen::Index j = passive_[i];
      if (x(j) <= 0.0) {
        x(j) = 0.0;
        remove_passive(j);
      }
    }
    if (result.iterations >= cap) return false;
    ++result.iterations;
    solve_passive(A, b);
  }
  return true;
}

NnlsResult NnlsSolver::solve(const Eigen::Ref<const Eigen::MatrixXd>& A,
                             const Eigen::Ref<const Eigen::VectorXd>& b,
                             Eigen::Ref<Eigen::VectorXd> x, const NnlsOptions& opt) {
  const Eigen::Index m = A.rows();
  const Eigen::Index n = A.cols();
  if (b.size() != m || x.size() != n)
    throw std::invalid_argument("nnls: b must have A.rows() and x A.cols() entries");
  reserve(m, n);
  x.setZero();
  is_passive_.setConstant(false);
  excluded_.setConstant(false);
  n_passive_ = 0;
  NnlsResult result;
  const double b_norm = b.norm();
  const int cap = opt.max_iterations > 0 ? opt.max_iterations
                                         : 3 * static_cast<int>((n + 1) * (n + 1));
  residual_ = b;

  while (true) {
    const Eigen::Index t = entering_variable(A, b_norm, opt.tolerance);
    if (t < 0) {
      result.converged = true;
      break;
    }
    if (result.iterations >= cap) break;
    passive_[n_passive_++] = t;
    is_passive_[t] = true;
    ++result.iterations;
    if (solve_passive(A, b) <= opt.rank_tolerance || !(z_(t) > 0.0)) {
      // Numerically dependent, or rounding made the gradient lie: leave t at zero until
      // x changes (Lawson & Hanson, step 6 safeguard).
      remove_passive(t);
      excluded_[t] = true;
      continue;
    }
    const bool capped = !step_to_feasibility(A, b, x, cap, result);
    if (!capped)
      for (Eigen::Index i = 0; i < n_passive_; ++i) x(passive_[i]) = z_(passive_[i]);
    excluded_.setConstant(false);
    residual_ = b;
    residual_.noalias() -= A * x;
    if (capped) break;
  }
  result.residual_norm = residual_.norm();
  return result;
}

Eigen::VectorXd nnls(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, NnlsResult* result,
                     const NnlsOptions& opt) {
  NnlsSolver solver(A.rows(), A.cols());
  Eigen::VectorXd x(A.cols());
  const NnlsResult r = solver.solve(A, b, x, opt);
  if (result) *result = r;
  return x;
}

}  // namespace sss::profiles
