#pragma once
// A symmetric block-tridiagonal matrix (the assembled dynamic stiffness of a line) and its
// block LDL^T: the Sylvester inertia (the Wittrick-Williams count), log |det| and solves.

#include <Eigen/Dense>
#include <vector>

namespace modalbench {

/// A symmetric block-tridiagonal matrix: `nodes` diagonal blocks of size m x m.
/// DOFs may be marked held (removed); the factorization works on the rest.
class BlockTridiagonal {
 public:
  BlockTridiagonal(int nodes, int m);
  int nodes() const { return static_cast<int>(diag_.size()); }
  int block_size() const { return m_; }
  /// Adds a 2m x 2m segment matrix between node i and node i + 1.
  void add_segment(int i, const Eigen::MatrixXd& k_seg);
  void add_diagonal(int node, int dof, double value) { diag_[node](dof, dof) += value; }
  void hold(int node, int dof) { held_[node][dof] = 1; }
  bool held(int node, int dof) const { return held_[node][dof] != 0; }
  int free_dofs() const;

  struct Inertia {
    int negative = 0;        ///< number of negative eigenvalues
    int zero = 0;            ///< pivots that were exactly zero or not finite
    double min_abs_pivot_rel = 0;  ///< smallest |pivot| / max |pivot| (a conditioning hint)
    /// log |det K| over the free DOFs (sign: (-1)^negative). Continuous in lambda on a fixed
    /// mesh, so it can polish a root once the count has isolated it.
    double log_abs_det = 0;
  };
  /// Sylvester inertia by block LDL^T (congruence, so the count is exact up to rounding).
  Inertia inertia() const;
  /// Solves K d = f (f, d: nodes*m vectors; held DOFs get d = 0 and their f is ignored).
  /// Throws std::runtime_error if a pivot is zero or smaller than min_pivot_rel times the
  /// largest (singular to working precision; inverse iteration passes 0: near-singular is
  /// what it wants).
  Eigen::VectorXd solve(const Eigen::VectorXd& f, double min_pivot_rel = 1e-14) const;
  /// K d over every DOF, held ones included (their rows are what holds them: the reactions).
  Eigen::VectorXd multiply(const Eigen::VectorXd& d) const;
  /// Dense copy of the free part (for tests).
  Eigen::MatrixXd dense_free() const;

 private:
  int m_;
  std::vector<Eigen::MatrixXd> diag_, lower_;  // lower_[i] = block (i+1, i)
  std::vector<std::vector<char>> held_;
  std::vector<int> free_index(int node) const;
  struct Factorization;
  Factorization factor() const;
};

}  // namespace modalbench
