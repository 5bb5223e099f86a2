// Non-negative least squares: min ‖A x − b‖₂ subject to x ≥ 0, by the active-set
// algorithm of Lawson & Hanson ("Solving Least Squares Problems", 1974, ch. 23, NNLS).
//
// Each passive-set subproblem is solved by a fresh Householder QR of the passive columns
// (no normal equations, so the conditioning is that of A, not of AᵀA). The solver keeps
// its workspace between calls, so repeated solves of the same size do not allocate.
#pragma once

#include <Eigen/Core>

namespace sss::profiles {

struct NnlsOptions {
  // Stop when every zero variable's dual (the gradient Aᵀ(b − Ax) component) is at most
  // tolerance · ‖A_j‖ · ‖b‖, i.e. moving x_j cannot reduce the residual noticeably.
  double tolerance = 1e-13;
  // A column joins the passive set only if each passive column stays farther than
  // rank_tolerance times its norm from the span of the columns that joined before it
  // (Lawson & Hanson's independence test).
  double rank_tolerance = 1e-12;
  // Cap on the number of subproblem solves; 0 means 3·(cols + 1)² (LH suggest 3n outer
  // loops; each outer loop has at most n inner ones).
  int max_iterations = 0;
};

struct NnlsResult {
  int iterations = 0;       // subproblem solves
  bool converged = false;   // false: the cap was hit; x is feasible, maybe not optimal
  double residual_norm = 0.0;
};

class NnlsSolver {
 public:
  // Reserves workspace for problems of up to rows × cols; larger problems grow it.
  explicit NnlsSolver(Eigen::Index rows = 0, Eigen::Index cols = 0);

  // Solves into x, which must have A.cols() entries. Throws std::invalid_argument when
  // the sizes of b or x do not match A.
  NnlsResult solve(const Eigen::Ref<const Eigen::MatrixXd>& A,
                   const Eigen::Ref<const Eigen::VectorXd>& b, Eigen::Ref<Eigen::VectorXd> x,
                   const NnlsOptions& opt = {});

  // The passive set of the last solve (the columns with x_j > 0), in the order they
  // joined; passive_count() of them are valid.
  const Eigen::VectorXi& passive() const { return passive_; }
  Eigen::Index passive_count() const { return n_passive_; }

 private:
  void reserve(Eigen::Index rows, Eigen::Index cols);
  // Least squares on the passive columns; writes z (zeros outside the passive set).
  // Returns min_i |R_ii| / ‖A_i‖ of their QR (0: numerically dependent).
  double solve_passive(const Eigen::Ref<const Eigen::MatrixXd>& A,
                       const Eigen::Ref<const Eigen::VectorXd>& b);
  // The zero variable whose dual (the negative gradient, from the residual) per unit column
  // norm is largest and above tolerance x ‖b‖; -1 when none is (the solution is optimal).
  Eigen::Index entering_variable(const Eigen::Ref<const Eigen::MatrixXd>& A, double b_norm, double tolerance);
  void remove_passive(Eigen::Index j);
  // The inner loop: steps x back towards z while some passive z_j <= 0, dropping the
  // variables that reach zero and solving again. False when the iteration cap stopped it.
  bool step_to_feasibility(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::VectorXd>& b,
                           Eigen::Ref<Eigen::VectorXd> x, int cap, NnlsResult& result);

  Eigen::MatrixXd qr_;        // rows × cols: the passive columns, factorised in place
  Eigen::VectorXd rhs_, z_, dual_, residual_, work_;
  Eigen::VectorXi passive_;   // indices of passive columns
  Eigen::Matrix<bool, Eigen::Dynamic, 1> is_passive_, excluded_;
  Eigen::Index n_passive_ = 0;
};

// One-shot convenience wrapper.
Eigen::VectorXd nnls(const Eigen::MatrixXd& A, const Eigen::VectorXd& b,
                     NnlsResult* result = nullptr, const NnlsOptions& opt = {});

}  // namespace sss::profiles
