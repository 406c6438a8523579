#pragma once
// Sparse factorizations of A = K - sigma M, alone or with constraints G z = 0.
//
// KktLdlt: LDL' of the saddle-point matrix [[A + s G'G, s G'], [s G, 0]] without pivoting (the
// augmentation s G'G changes nothing on G x = 0 but makes A definite there on its own). The
// ordering is AMD on the pattern of A + G'G for the primal unknowns (grouped by rigid element:
// amd_order), with each multiplier placed
// right after the last primal unknown of its row: every leading block is then
// [[A11, G1'], [G1, 0]] with A11 a principal block of A and G1 of full row rank, so the
// factorization exists whenever A is definite on the null space of G. By Sylvester's law the
// number of negative pivots minus m is the number of eigenvalues of the constrained pencil
// below sigma (the Sturm count used to prove that no mode was missed). Without constraints it
// is a plain sparse LDL' (statics, counts).
// PdFactor: Cholesky of a positive definite A via SuiteSparse CHOLMOD, which chooses a
// supernodal or simplicial factor from the fill it predicts (supernodal pays on plates and 3D),
// in the grouped AMD order when groups are given.

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <memory>
#include <string>
#include <vector>

#include "modalbench/rfem/model.hpp"

namespace modalbench::rfem {

namespace detail {
class SupernodalLdlt;
}

/// Fill-reducing elimination order of a symmetric pattern (SuiteSparse AMD): order[k] is the
/// unknown eliminated k-th. With `groups` (groups[i]: the group of unknown i, e.g. the rigid
/// element it moves), AMD orders the quotient graph of the groups and each group's unknowns are
/// eliminated together: on a plate's grid as little fill as nested dissection (1.31e6 entries in
/// L against 1.69e6 ungrouped and 1.33e6 for METIS, Mindlin 100 x 60), at AMD's cost.
Eigen::VectorXi amd_order(const SpMat& pattern, const std::vector<int>& groups = {});

/// Indices of rows of G (unit 2-norm rows) that depend linearly on earlier rows in an AMD
/// elimination order of G G' (pivot of the regularized Gram matrix below 1e-10, i.e. the row
/// lies within 1e-5 of the span of the others).
std::vector<long> dependent_rows(const SpMat& G);

class KktLdlt {
 public:
  KktLdlt();
  ~KktLdlt();
  KktLdlt(const KktLdlt&) = delete;
  KktLdlt& operator=(const KktLdlt&) = delete;
  /// Orders (amd_order with `groups`) and analyses for A's pattern (union of every A to be
  /// factored) and G.
  void analyze(const SpMat& pattern, const SpMat& G, const std::vector<int>& groups = {});
  /// Factors with the values of A (same pattern as analysed). False if a pivot was exactly zero.
  bool factorize(const SpMat& A);
  /// Primal part x of the KKT solve with right-hand side [b; 0] (x satisfies G x = 0).
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  /// The same into preallocated memory (no allocation: the Lanczos inner loop).
  void solve_into(const double* b, double* x) const;
  /// Negative pivots minus the number of constraints (eigenvalues of the pencil below the shift).
  long negative_count() const;
  /// Smallest |pivot| / |diagonal| over the primal pivots, and the primal unknown where it occurs.
  double smallest_primal_pivot_ratio(long* where) const;
  long n() const { return n_; }
  long m() const { return m_; }
  /// True where the factor is supernodal (plates: CHOLMOD's analysis found dense fronts), false
  /// where it is Eigen's simplicial LDL' (beams).
  bool supernodal() const { return use_super_; }
  /// True where the supernodal solves run on two threads (the elimination tree splits into two
  /// subtrees of comparable weight: Mindlin plates from 84 x 60 fragments on).
  bool two_thread_solves() const;

 private:
  Eigen::VectorXd pivots() const;  ///< D
  long n_ = 0, m_ = 0;
  double s_ = 1;                       // constraint scaling
  Eigen::VectorXi pos_;                // new position of old unknown (primal 0..n-1, multipliers n..)
  SpMat G_, GtG_;
  // The permuted saddle-point matrix, upper triangle (pattern fixed at analysis; upper column-major
  // storage is factored in place, without the copy a lower one costs on every factorization).
  // Per nonzero: where its value comes from -- A's values, G'G's, G's (index, or -1).
  SpMat K_;
  std::vector<int> from_a_, from_gtg_, from_g_;
  long a_nnz_ = 0;
  Eigen::SimplicialLDLT<SpMat, Eigen::Upper, Eigen::NaturalOrdering<int>> ldlt_;
  std::unique_ptr<detail::SupernodalLdlt> super_;  // the same factor, supernodal, where it pays
  bool use_super_ = false;
  Eigen::VectorXd diag_;               // permuted diagonal of the last factored matrix
  mutable Eigen::VectorXd work_;       // permuted right-hand side / solution
  bool analysed_ = false;
};

/// Cholesky of a symmetric positive definite matrix through CHOLMOD (automatic supernodal choice).
class PdFactor {
 public:
  PdFactor();
  ~PdFactor();
  PdFactor(const PdFactor&) = delete;
  PdFactor& operator=(const PdFactor&) = delete;
  /// Symbolic analysis; with `groups`, in amd_order's grouped order (else CHOLMOD chooses).
  void analyze(const SpMat& pattern, const std::vector<int>& groups = {});
  bool factorize(const SpMat& A);  ///< false if A is not (numerically) positive definite
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  /// x = A^{-1} b with CHOLMOD's reusable workspace (no allocation after the first call).
  void solve_into(const double* b, double* x) const;
  bool supernodal() const;
  std::string name() const;  ///< "CHOLMOD supernodal LL'" or "CHOLMOD simplicial LL'"

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace modalbench::rfem
