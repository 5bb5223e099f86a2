// Internal to the Gaussian fit (GaussianFit.cpp): the variable-projection functional of
// Golub & Pereyra 1973 for a sum of 2D Gaussians with shared variances. For fixed
// log-variances θ the per-channel weights are eliminated by non-negative least squares
// (Lawson–Hanson, with the energy equality as a heavily weighted extra row), leaving a
// function of θ alone whose exact Jacobian the outer Levenberg–Marquardt uses
// (VariableProjectionSearch.h).
#pragma once

#include "profiles/GaussianFit.h"
#include "profiles/Nnls.h"

#include <Eigen/Core>

#include <limits>

namespace sss::profiles::detail {

using VecN = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxGaussians, 1>;
using MatN = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxGaussians,
                           kMaxGaussians>;
using MatN3 = Eigen::Matrix<double, Eigen::Dynamic, 3, 0, kMaxGaussians, 3>;

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
  // Fills p.cost, p.H, p.g and p.W at p.theta.
  void evaluate(Point& p);
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
};

}  // namespace sss::profiles::detail
