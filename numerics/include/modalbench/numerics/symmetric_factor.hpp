#pragma once
// LDL^T of a small dense symmetric block with its inertia (negative pivots), log |det| and
// pivot range; an eigen-decomposition takes over when diagonal pivoting meets a zero or
// non-finite pivot. The building block of the block-tridiagonal LDL^T and of long segments.

#include <Eigen/Dense>
#include <limits>

namespace modalbench {

struct SymFactor {
  Eigen::LDLT<Eigen::MatrixXd> ldlt;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig;
  bool use_eig = false;
  int negative = 0;  ///< negative pivots (eigenvalues, on the fall-back)
  int zero = 0;      ///< pivots that are zero or not finite (relative to the block's scale)
  double min_abs = std::numeric_limits<double>::infinity();  ///< smallest |pivot| (inf for an empty block)
  double max_abs = 0;                                         ///< largest |pivot|
  double log_abs = 0;               ///< log |det| of the block

  explicit SymFactor(const Eigen::MatrixXd& S);
  /// S^-1 B; a zero pivot is regularised so an elimination can go on (callers see `zero`).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;

 private:
  void tally(double d);
};

/// LDL^T of a small symmetric matrix without pivoting, in the order given. For a matrix graded
/// from its stiffest row down (a line's condensed rigid-body block, springs spanning 25 orders)
/// each pivot keeps its relative accuracy, where a pivoting or eigen-decomposition would not.
/// On return the strict lower triangle of S holds the unit lower factor L; the result holds the
/// pivots, NaN from the first zero or non-finite one on (callers fall back or refuse).
Eigen::VectorXd graded_ldlt(Eigen::MatrixXd& S);

/// x with L D L^T x = b, from graded_ldlt's factor (S) and pivots (d, all finite and nonzero).
Eigen::VectorXd graded_ldlt_solve(const Eigen::MatrixXd& S, const Eigen::VectorXd& d, Eigen::VectorXd b);

}  // namespace modalbench
