#pragma once
// Supernodal LDL' without pivoting, in a given elimination order (internal to rfem's factor.cpp).
//
// A = L D L' with L unit lower triangular and D diagonal, eliminated in the natural order of the
// matrix it is given (the caller permutes: KktLdlt's order places every multiplier after its
// primal unknowns, which is what makes the pivots exist; no pivoting may change that order).
// CHOLMOD's symbolic analysis (its supernodes and their row patterns, the order given and not
// postordered) supplies the structure; the numeric factorization is left-looking over the
// supernodes, as CHOLMOD's own LL' is: every update from a descendant is one dense product
// L_d W' (W = L_d D_d restricted to the target's columns) by Eigen's kernels, the diagonal block an
// unblocked dense LDL' and the rows below it one triangular solve. The inertia of D is then the
// inertia of A (Sylvester), which is what the Sturm count reads; a simplicial LDL' (Eigen's) gets
// the same D at a few times the cost on a plate's grid, where the fill is in dense fronts.
//
// analyze() is false where CHOLMOD's analysis chooses a simplicial factor (few flops per entry of
// L: a beam): the caller keeps its simplicial LDL' there.
//
// The factorization and the solve run on two threads where the elimination tree splits into two
// subtrees of comparable weight (a plate's grid: its first separator): each thread factors and
// solves its subtrees (in the solve, what they add to the separators above them kept apart until
// both are done); the separators then alone.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

namespace modalbench::rfem::detail {

class SupernodalLdlt {
 public:
  SupernodalLdlt();
  ~SupernodalLdlt();
  SupernodalLdlt(const SupernodalLdlt&) = delete;
  SupernodalLdlt& operator=(const SupernodalLdlt&) = delete;

  /// Symbolic analysis of the upper triangle `upper` (CSC, compressed, natural elimination order).
  /// False if CHOLMOD chose a simplicial factor (nothing is kept then).
  bool analyze(const Eigen::SparseMatrix<double>& upper);
  /// Numeric factorization with the values of `upper` (the analysed pattern). False at a pivot
  /// that is exactly zero or not finite (the factor is then incomplete).
  bool factorize(const Eigen::SparseMatrix<double>& upper);
  const Eigen::VectorXd& vectorD() const { return D_; }
  /// x := A^{-1} x (in place, length n).
  void solve_in_place(double* x) const;
  long n() const { return n_; }
  /// Whether solves run on two threads (the tree splits into two comparable subtrees).
  bool two_threads() const { return split_; }
  /// Entries of L stored (the supernodes' dense blocks, explicit zeros included).
  long stored_entries() const { return static_cast<long>(Lx_.size()); }

 private:
  long n_ = 0;
  std::vector<int> super_, pi_, px_, rows_;  // CHOLMOD's supernodal pattern (super, pi, px, s)
  std::vector<int> column_super_;            // supernode of each column
  // The lower triangle of A by columns: per column j, the rows i >= j and where A(i, j) sits in
  // the upper CSC values (A(j, i) there).
  std::vector<int> low_start_, low_row_, low_src_;
  // Eigen's vector kernels peel to the packet alignment: with the factor and the work vectors
  // aligned to it the order of every sum, and so the last bits, are the same from run to run (on
  // malloc's 16 bytes the command line and the Python module differed there).
  using Aligned = std::vector<double, Eigen::aligned_allocator<double>>;
  Aligned Lx_;
  Eigen::VectorXd D_;
  mutable Aligned work_;
  int max_update_ = 0;  // rows of the largest supernode
  // The supernodes of each part in elimination order (parts 1 and 2: disjoint subtrees, each on a
  // thread of its own; part 0: the separators above them, or every supernode where the tree does
  // not split), whether a column is in part 0, and each subtree's share for the separators.
  std::vector<int> part_[3];
  std::vector<char> top_column_;
  mutable Aligned work2_;
  mutable std::vector<double> top_share_[2];
  bool split_ = false;
  void plan_split();
  struct Lists;
  struct Scratch;
  bool factor_part(const std::vector<int>& part, int own, const double* av, Lists& l, Scratch& ws);
  void forward(const std::vector<int>& part, double* x, double* t, double* top) const;
  void backward(const std::vector<int>& part, double* x, double* t) const;
};

}  // namespace modalbench::rfem::detail
