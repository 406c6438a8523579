#pragma once
// Dynamic stiffness of a one-dimensional Hamiltonian field, with a Wittrick-Williams count.
//
// A field on xi in [0, 1] with state y = [d; f] (m displacements d, m conjugate forces f)
// obeys y' = A(lambda) y, lambda = omega^2, where A is Hamiltonian in the sense
//   A = [[A11, A12], [A21, -A11^T]],  A12 = A12^T,  A21 = A21^T,
// and the strain-energy boundary terms are [f . delta d] from 0 to 1. A segment of length h
// has transfer matrix T = exp(A h); with T = [[Tdd, Tdf], [Tfd, Tff]] its dynamic stiffness
//   [-f(0); f(h)] = K_seg [d(0); d(h)],
//   K_seg = [[Tdf^-1 Tdd, -Tdf^-1], [Tfd - Tff Tdf^-1 Tdd, Tff Tdf^-1]]
// is symmetric. The line is cut into segments short enough that |p| h <= 1 for every
// wavenumber p of A (so exp(A h) is well conditioned and no segment has a clamped-clamped
// natural frequency below omega: the Wittrick-Williams J0 term vanishes); the segment
// matrices are assembled into a block-tridiagonal K(lambda). End springs (per DOF, [0, inf],
// inf = the DOF is held) are added at xi = 0 and xi = 1. Then
//   J(lambda) = number of negative eigenvalues of K(lambda)
// is exactly the number of natural frequencies below sqrt(lambda) (Wittrick & Williams 1971).
//
// Usage:
//   LineSystem sys;  sys.m = 2;  sys.state_matrix = [](double lam) { ... };
//   sys.max_wavenumber = [](double lam) { ... };  sys.left_spring = {inf, 0}; ...
//   std::vector<double> lambdas = lowest_eigenvalues(sys, 6, /*lambda_hint=*/1.0);

#include <Eigen/Dense>
#include <complex>
#include <functional>
#include <memory>
#include <vector>

namespace modalbench {

/// B balanced by a diagonal similarity of powers of two (Parlett & Reinsch): same eigenvalues,
/// rows and columns of comparable size. State matrices span many orders of magnitude; exp()
/// and eigensolvers lose digits (and a Hamiltonian's (p, -p) pairing) on them unbalanced.
Eigen::MatrixXd balanced(Eigen::MatrixXd B, int max_sweeps = 50);

/// Dynamic stiffness of one segment from the Hamiltonian state matrix A and length h.
/// Returned symmetrised; `asymmetry`, if given, receives |K - K^T| / |K| before that
/// (rounding-small exactly when A is Hamiltonian: a check on the operator's derivation).
/// `log_abs_det_tdf`, if given, receives log |det Tdf|: K_seg's poles are the zeros of det Tdf
/// (the clamped segment's natural frequencies), so det K_global * prod det Tdf over the
/// segments has no poles, only the natural frequencies as zeros (a smooth function to polish on).
Eigen::MatrixXd segment_dynamic_stiffness(const Eigen::MatrixXd& A, double h, double* asymmetry = nullptr,
                                          double* log_abs_det_tdf = nullptr);

/// A long segment's dynamic stiffness by repeated doubling: a base piece of length
/// h / 2^levels from exp(A h / 2^levels), then `levels` times two equal pieces joined by
/// condensing their middle node (S = K22 + K11; K_2h = [[K11 - K12 S^-1 K21, -K12 S^-1 K12],
/// [-K21 S^-1 K21, K22 - K21 S^-1 K12]]). Exact and stable where exp(A h) is not. The middle
/// nodes' negative pivots give the Wittrick-Williams J0 of the long segment (its clamped-clamped
/// natural frequencies below lambda; the base piece must have none: |p| h_base small), and
/// log |det Tdf| follows from |det Tdf(2h)| = |det Tdf(h)|^2 |det S|.
struct LongSegment {
  Eigen::MatrixXd K;
  int clamped_below = 0;       ///< J0 of the segment
  double log_abs_det_tdf = 0;  ///< log |det Tdf| of the whole segment
  double asymmetry = 0;        ///< of the base piece (see segment_dynamic_stiffness)
  double min_pivot_rel = 1;    ///< smallest |eigenvalue| / norm of the condensed middle blocks
};
LongSegment long_segment_dynamic_stiffness(const Eigen::MatrixXd& A, double h, int levels);

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
  /// Throws std::runtime_error if K is singular to working precision.
  Eigen::VectorXd solve(const Eigen::VectorXd& f) const;
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

/// A line field problem in dimensionless form on [0, 1].
struct LineSystem {
  int m = 0;
  std::function<Eigen::MatrixXd(double lambda)> state_matrix;  ///< A(lambda), 2m x 2m
  /// An upper bound on |p| over the eigenvalues p of A(lambda) (sets the segment length).
  std::function<double(double lambda)> max_wavenumber;
  std::vector<double> left_spring, right_spring;  ///< per DOF, dimensionless, [0, inf]
  std::vector<double> nodes_at;  ///< interior positions in (0, 1) that must be nodes (loads, probes)
};

/// The assembled K(lambda) with its node positions.
struct AssembledLine {
  BlockTridiagonal K;
  std::vector<double> xi;  ///< position of every node
  int node_at(double x) const;  ///< index of the node at x (exact match required)
};
AssembledLine assemble(const LineSystem& sys, double lambda);

/// Number of natural frequencies with omega^2 < lambda (Wittrick-Williams).
int count_below(const LineSystem& sys, double lambda);

/// Count-driven spectrum slicing: the k eigenvalues just above `lambda_lo` of a problem
/// whose counting function is `count(lambda)` = number of eigenvalues < lambda;
/// `lambda_hint` is a scale (the bracket grows from it until it holds k more). Repeated
/// eigenvalues are returned repeatedly. Bisection to `rel_tol` relative (1e-8 of that
/// relative to `lambda_hint` near zero). Throws std::runtime_error if the count is not
/// monotonic (numerical breakdown) or cannot be bracketed.
struct SliceStats {
  long count_evaluations = 0;
};
std::vector<double> slice_spectrum(const std::function<int(double)>& count, int k, double lambda_lo,
                                   double lambda_hint, double rel_tol = 1e-13, SliceStats* stats = nullptr);

/// What a polished slicer needs at one lambda: the count and the log of |det K(lambda)| times
/// any positive factor that is smooth in lambda (best: prod |det Tdf| over the segments, which
/// removes det K's poles).
struct CountDet {
  int count = 0;
  double log_abs_det = 0;
};
/// Every eigenvalue in [lambda_lo, lambda_hi) of a problem whose `eval(lambda)` gives the
/// count below lambda and log |det K(lambda)|, with multiplicity, ascending. Bisection on the
/// count until an interval holds exactly one eigenvalue; that one is then polished by Brent's
/// method on the signed determinant (-1)^count |det K| (continuous there: `eval` must use one
/// discretization for every lambda in the range, so that det has no pole and no jump).
/// Intervals narrower than rel_tol (relative; abs_tol near zero) with several eigenvalues give
/// them as a repeated value. Throws std::runtime_error if the count is not monotonic.
std::vector<double> slice_interval_polished(const std::function<CountDet(double)>& eval, double lambda_lo,
                                            double lambda_hi, double rel_tol, double abs_tol,
                                            SliceStats* stats = nullptr);

/// Eigenvalues below kRigidThreshold * lambda_hint are rigid-body modes (exactly 0).
inline constexpr double kRigidThreshold = 1e-10;

struct LineSpectrum {
  std::vector<double> lambdas;  ///< lowest k values of omega^2, ascending; rigid ones are 0
  int rigid = 0;                ///< how many of them are rigid-body modes
};
/// The lowest k eigenvalues lambda = omega^2 of a line system. `lambda_hint` sets the
/// scale (e.g. the lambda at which the dimensionless frequency is 1).
LineSpectrum lowest_eigenvalues(const LineSystem& sys, int k, double lambda_hint, SliceStats* stats = nullptr);

// ---- Complex path: damped harmonic response (structural damping, lambda = omega^2 / (1 + i eta)).

/// Segment dynamic stiffness of a complex (damped) Hamiltonian state matrix: complex symmetric.
Eigen::MatrixXcd segment_dynamic_stiffness(const Eigen::MatrixXcd& A, double h, double* asymmetry = nullptr,
                                           double* log_abs_det_tdf = nullptr);

/// Complex (damped) version of long_segment_dynamic_stiffness (no count).
struct LongSegmentC {
  Eigen::MatrixXcd K;
  double asymmetry = 0;
  double min_pivot_rel = 1;  ///< smallest reciprocal condition estimate of the middle blocks
};
LongSegmentC long_segment_dynamic_stiffness(const Eigen::MatrixXcd& A, double h, int levels);

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
