#pragma once
// A one-dimensional Hamiltonian field on [0, 1] cut into segments, assembled into a
// block-tridiagonal dynamic stiffness K(lambda), and its spectrum by the Wittrick-Williams count.
//
// The line is cut into segments short enough that |p| h <= 1 for every wavenumber p of the
// state matrix A(lambda) (so exp(A h) is well conditioned and no segment has a clamped-clamped
// natural frequency below omega: the Wittrick-Williams J0 term vanishes); the segment matrices
// (segment_dynamic_stiffness.hpp) are assembled into K(lambda). End springs (per DOF, [0, inf],
// inf = the DOF is held) are added at xi = 0 and xi = 1; the strain-energy boundary terms are
// [f . delta d] from 0 to 1. Then
//   J(lambda) = number of negative eigenvalues of K(lambda)
// is exactly the number of natural frequencies below sqrt(lambda) (Wittrick & Williams 1971).
//
// Usage:
//   LineSystem sys;  sys.m = 2;  sys.state_matrix = [](double lam) { ... };
//   sys.max_wavenumber = [](double lam) { ... };  sys.left_spring = {inf, 0}; ...
//   LineSpectrum s = lowest_eigenvalues(sys, 6, /*lambda_hint=*/1.0);

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <vector>

#include "modalbench/numerics/block_tridiagonal.hpp"
#include "modalbench/numerics/spectrum_slicing.hpp"

namespace modalbench {

/// A point attachment inside the line (a support or a mass between the ends): at its node the
/// dynamic stiffness gains spring[j] - lambda mass[j] on DOF j (dimensionless, as the end springs),
/// and a DOF with an infinite spring is held. It has no internal modes, so the count stays exact.
struct LineAttachment {
  double xi = 0;              ///< in (0, 1); an end (0 or 1) is allowed too and adds to its spring
  std::vector<double> spring; ///< per DOF, [0, inf]
  std::vector<double> mass;   ///< per DOF (multiplies lambda = omega^2); a spinning disc's whirl may make it < 0
  /// Per DOF (empty: none): the dynamic stiffness also gains + sqrt(lambda) gyro[j] (a spinning
  /// disc's gyroscopic moment in one whirl direction, s J_p Omega omega). The count stays exact: at
  /// every zero crossing the term's quadratic form still decreases with lambda (one positive root).
  std::vector<double> gyro = {};
  /// spring[j] - lambda mass[j] + sqrt(lambda) gyro[j] (spring finite).
  double term(std::size_t j, double lambda) const {
    return spring[j] - lambda * mass[j] + (gyro.empty() || lambda <= 0 ? 0.0 : std::sqrt(lambda) * gyro[j]);
  }
};

/// A piece whose coefficients vary along it (a tapered member); empty: a uniform piece.
///
/// `state` gives A(lambda, xi) at each xi of the piece; the piece's segments take their transfer
/// matrices from it by the sixth-order Magnus integrator (varying_transfer.hpp), steps doubled
/// until two agree to 1e-15 (an estimate above 1e-12 throws std::runtime_error). `wavenumber_over`
/// bounds the wavenumbers, over [xi0, xi1], of a uniform comparison piece nowhere stiffer and
/// nowhere heavier than this one there (each stiffness at its lowest, each inertia at its highest):
/// by the min-max principle its clamped-clamped frequencies are no higher than the varying
/// segment's, so a segment with |p| h <= 1 by this bound has none below omega, as a uniform one,
/// and the Wittrick-Williams count stays exact. The piece's state_matrix (below) must give A at its
/// start, and its kinematic block A_dd(0) (with A_fd(0) = 0) must hold along it (a beam's does).
struct LineVariation {
  std::function<Eigen::MatrixXd(double lambda, double xi)> state;
  std::function<double(double lambda, double xi0, double xi1)> wavenumber_over;
  explicit operator bool() const { return static_cast<bool>(state); }
};

/// A piece of a stepped line from xi_from on (to the next piece or 1): its own state matrix and
/// wavenumber bound (LineSystem's meaning), and its variation if its coefficients vary. Its start
/// is a node.
struct LinePiece {
  double xi_from = 0;
  std::function<Eigen::MatrixXd(double lambda)> state_matrix;
  std::function<double(double lambda)> max_wavenumber;
  LineVariation variation = {};
};

/// A line field problem in dimensionless form on [0, 1].
struct LineSystem {
  int m = 0;
  std::function<Eigen::MatrixXd(double lambda)> state_matrix;  ///< A(lambda), 2m x 2m (the first piece's)
  /// An upper bound on |p| over the eigenvalues p of A(lambda) (sets the segment length).
  std::function<double(double lambda)> max_wavenumber;
  /// A stepped line: the pieces after the first, by ascending xi_from in (0, 1) (empty: uniform).
  /// The pieces must share A's kinematic block A_dd(0) (a beam's, whatever its section) for the
  /// rigid-motion split; lines whose pieces do not are factored as they stand.
  std::vector<LinePiece> steps;
  /// The piece holding xi (-1: the first; else an index into steps); a piece's start belongs to it.
  int piece_at(double xi) const;
  /// A(lambda) of the piece holding xi (pass a segment's midpoint).
  Eigen::MatrixXd state_matrix_at(double lambda, double xi) const;
  /// The wavenumber bound of the piece holding xi.
  double max_wavenumber_at(double lambda, double xi) const;
  /// The first piece's variation (empty: uniform).
  LineVariation variation = {};
  /// The variation of the piece holding xi (empty: a uniform piece).
  const LineVariation& variation_at(double xi) const;
  std::vector<double> left_spring, right_spring;  ///< per DOF, dimensionless, [0, inf]
  std::vector<double> nodes_at;  ///< interior positions in (0, 1) that must be nodes (loads, probes)
  /// Supports and masses between (or at) the ends; each is a node. A line with attachments is
  /// factored as it stands (the rigid-motion split of LineRigidity is for end-supported lines).
  std::vector<LineAttachment> attachments;
  /// Whether A(lambda) and the attachments are polynomials in lambda (false: a whirl line's
  /// sqrt(lambda) terms). The rigid-motion split divides A(lambda) - A(0) by lambda, which only a
  /// polynomial allows down to 1e-250 of the scale; without it, the count runs on K(lambda) itself.
  bool polynomial_in_lambda = true;
};

/// The transfer matrix y(x1) = T y(x0) over [x0, x1] inside one piece (a segment or part of one):
/// exp(A (x1 - x0)) in a uniform piece, the Magnus product in a varying one (LineVariation).
Eigen::MatrixXd line_transfer(const LineSystem& sys, double lambda, double x0, double x1);
/// The dynamic stiffness of the segment [x0, x1] inside one piece (segment_dynamic_stiffness.hpp).
Eigen::MatrixXd line_segment_stiffness(const LineSystem& sys, double lambda, double x0, double x1);

/// The assembled K(lambda) with its node positions.
struct AssembledLine {
  BlockTridiagonal K;
  std::vector<double> xi;  ///< position of every node
  int node_at(double x) const;  ///< index of the node at x (exact match required)
};
AssembledLine assemble(const LineSystem& sys, double lambda);

/// Number of natural frequencies with omega^2 < lambda (Wittrick-Williams), with nodes only at the
/// line's features (ends, steps, attachments): each gap between them is one long segment built by
/// doubling (long_segment_dynamic_stiffness) with its own J0, so a count costs O(log(gap length x
/// wavenumber)) per gap instead of assemble's O(gap length x wavenumber) segments.
int count_below(const LineSystem& sys, double lambda);

/// The rigid-body motions of the unsupported line and how its supports act on them.
///
/// When A(0) has no displacement-to-force block (A_fd(0) = 0: nothing ties the line to the
/// ground), every d(xi) = Phi(xi) c with Phi = exp(A_dd(0) xi) and f = 0 solves the static field
/// equations: m rigid motions. The supported DOFs (the ends' and the attachments' springs and
/// holds, then the ends' free DOFs) are taken in order of decreasing spring stiffness (held ones
/// first) and the first m whose rows of Phi are independent become the anchors; the
/// rigid basis has unit value at one anchor and zero at the others. Then the line is written as
/// d_i = Psi_i a + e_i with e = 0 at the anchors: the elastic part e sees a line held at its
/// anchors (positive definite below its first natural frequency), the rigid amplitudes a see the
/// springs and the inertia of the rigid motions, both formed without the cancellation of
/// K(0) Psi = 0 (segment_dynamic_stiffness_divided). In anchor order the condensed r x r matrix is
/// graded from the stiffest spring down, so an LDL^T without pivoting keeps the relative accuracy
/// of its smallest pivot: near-rigid modes (springs of 1e-12 of the beam's stiffness) and
/// near-mechanism statics (springs spanning 25 orders) keep their digits.
struct LineRigidity {
  bool available = false;  ///< A_fd(0) = 0: the line has m rigid motions
  int held_rank = 0;       ///< how many of them the held (infinite) springs stop
  int free_rigid = 0;      ///< how many no spring (finite or infinite) restrains: true rigid modes
};

/// A point action anywhere on the line (a node or not): its load in the nodal convention of
/// K(lambda) d = f (m entries, the line's dimensionless units).
struct LinePoint {
  double xi = 0;
  Eigen::VectorXd f;
};

/// Adds the equivalent nodal loads of `p` to F (nodes * m entries): at a node, p.f itself; inside a
/// segment, the exact fixed-end reactions of that segment, from its transfer matrices exp(A h) and
/// exp(A (h - s)). Loads and probes need not be nodes, so two close points never make a short,
/// stiff segment whose elimination cancels every digit (a load 3e-7 L from a probe did).
void add_point_load(const LineSystem& sys, const AssembledLine& asmb, double lambda, const LinePoint& p,
                    Eigen::VectorXd& F);

/// The m displacements at xi of the solution d of K(lambda) d = F, F built from `loads` by
/// add_point_load: at a node, d there; inside a segment, the state of its left end (displacement
/// and the end force of the segment, fixed-end reactions included) carried to xi by exp(A t), with
/// the jumps of the loads in between.
Eigen::VectorXd displacement_at(const LineSystem& sys, const AssembledLine& asmb, double lambda, const Eigen::VectorXd& d,
                                const std::vector<LinePoint>& loads, double xi);
/// The whole state [d; f] (2m entries) at xi of the same solution: f the state's force part just
/// beyond xi (x + 0: past a point action or support there; at xi = 1, the value at 1 - 0).
Eigen::VectorXd state_at(const LineSystem& sys, const AssembledLine& asmb, double lambda, const Eigen::VectorXd& d,
                         const std::vector<LinePoint>& loads, double xi);

/// Solves K(lambda) d = f on `asmb` (built by assemble(sys, lambda) or with the same nodes).
/// Uses the rigid-body split above where the line has rigid motions and its anchored elastic
/// part is positive definite at lambda, otherwise the block LDL^T of asmb.K. Throws
/// std::runtime_error naming a mechanism (a rigid motion no spring restrains) or a singular K.
Eigen::VectorXd solve_line(const LineSystem& sys, const AssembledLine& asmb, double lambda, const Eigen::VectorXd& f);

/// What one support of the line exerts on it (m entries, the line's force units): at a held DOF
/// the row of K(lambda) d - f there, at a spring -k d. One per end with a support and per
/// attachment with a spring, in that order (left end, right end, attachments).
struct LineReaction {
  double xi = 0;
  Eigen::VectorXd r;
};
std::vector<LineReaction> line_reactions(const LineSystem& sys, const AssembledLine& asmb, const Eigen::VectorXd& d,
                                         const Eigen::VectorXd& f);

/// Eigenvalues below kRigidThreshold * lambda_hint count as rigid-body modes (exactly 0) only on
/// lines without rigid motions of their own (line_rigidity().available false); lines with them
/// report exactly their free_rigid modes as rigid and resolve every other one, however small.
inline constexpr double kRigidThreshold = 1e-10;

struct LineSpectrum {
  std::vector<double> lambdas;  ///< lowest k values of omega^2, ascending; rigid ones are 0
  int rigid = 0;                ///< how many of them are rigid-body modes
  /// Eigenvalues below 1e-250 lambda_hint (beyond double precision: reported as 0 and counted
  /// in `rigid`, but not rigid-body modes of the model); callers should flag them.
  int unresolved = 0;
};
/// The lowest k eigenvalues lambda = omega^2 of a line system. `lambda_hint` sets the
/// scale (e.g. the lambda at which the dimensionless frequency is 1).
LineSpectrum lowest_eigenvalues(const LineSystem& sys, int k, double lambda_hint, SliceStats* stats = nullptr);

}  // namespace modalbench
