#pragma once
// A complex symmetric block-tridiagonal matrix (no conjugation): the damped dynamic
// stiffness of a line, solved by block LU for harmonic responses.

#include <Eigen/Dense>
#include <complex>
#include <vector>

namespace modalbench {

/// A complex symmetric block-tridiagonal matrix (no conjugation), for damped harmonic solves.
/// Factorized by block LU with partial pivoting inside each pivot block; a nearly singular
/// pivot block is merged with the next node's, as in BlockTridiagonal.
class ComplexBlockTridiagonal {
 public:
  ComplexBlockTridiagonal(int nodes, int m);
  int nodes() const { return static_cast<int>(diag_.size()); }
  int block_size() const { return m_; }
  void add_segment(int i, const Eigen::MatrixXcd& k_seg);
  void add_diagonal(int node, int dof, std::complex<double> value) { diag_[node](dof, dof) += value; }
  void hold(int node, int dof) { held_[node][dof] = 1; }
  bool held(int node, int dof) const { return held_[node][dof] != 0; }
  int free_dofs() const;
  /// Solves K d = f; held DOFs get d = 0. Throws std::runtime_error if K is singular.
  Eigen::VectorXcd solve(const Eigen::VectorXcd& f) const;
  Eigen::MatrixXcd dense_free() const;

 private:
  int m_;
  std::vector<Eigen::MatrixXcd> diag_, lower_;
  std::vector<std::vector<char>> held_;
  std::vector<int> free_index(int node) const;
};

}  // namespace modalbench
