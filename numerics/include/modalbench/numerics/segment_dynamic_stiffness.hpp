#pragma once
// Dynamic stiffness of one segment of a one-dimensional Hamiltonian field.
//
// A field on xi with state y = [d; f] (m displacements d, m conjugate forces f) obeys
// y' = A(lambda) y, lambda = omega^2, where A is Hamiltonian in the sense
//   A = [[A11, A12], [A21, -A11^T]],  A12 = A12^T,  A21 = A21^T.
// A segment of length h has transfer matrix T = exp(A h); with T = [[Tdd, Tdf], [Tfd, Tff]]
// its dynamic stiffness
//   [-f(0); f(h)] = K_seg [d(0); d(h)],
//   K_seg = [[Tdf^-1 Tdd, -Tdf^-1], [Tfd - Tff Tdf^-1 Tdd, Tff Tdf^-1]]
// is symmetric (complex symmetric for a damped, complex A). exp(A h) is only well
// conditioned for |p| h of order one (p the wavenumbers of A): longer segments are built by
// doubling (long_segment_dynamic_stiffness).

#include <Eigen/Dense>
#include <optional>

namespace modalbench {

/// Dynamic stiffness of one segment from the Hamiltonian state matrix A and length h.
/// Returned symmetrised; `asymmetry`, if given, receives |K - K^T| / |K| before that
/// (rounding-small exactly when A is Hamiltonian: a check on the operator's derivation).
/// `log_abs_det_tdf`, if given, receives log |det Tdf|: K_seg's poles are the zeros of det Tdf
/// (the clamped segment's natural frequencies), so det K_global * prod det Tdf over the
/// segments has no poles, only the natural frequencies as zeros (a smooth function to polish on).
Eigen::MatrixXd segment_dynamic_stiffness(const Eigen::MatrixXd& A, double h, double* asymmetry = nullptr,
                                          double* log_abs_det_tdf = nullptr);

/// K_seg from the segment's transfer matrix T = [[Tdd, Tdf], [Tfd, Tff]] (any segment, uniform or
/// not: a varying one's from varying_transfer.hpp), symmetrised; `asymmetry` as above.
Eigen::MatrixXd segment_stiffness_of_transfer(const Eigen::MatrixXd& T, double* asymmetry = nullptr);

/// K_seg(lambda) together with its divided difference dK = (K_seg(lambda) - K_seg(0)) / lambda,
/// both to working precision relative to their own size: dK is not the difference of two
/// computed K (which loses every digit of lambda dK below the rounding of K(0)) but follows from
/// one exponential of the block matrix [[A(lambda) h, dA h], [0, A(0) h]], dA = (A(lambda) -
/// A(0)) / lambda, whose upper right block is (T(lambda) - T(0)) / lambda exactly (Van Loan
/// 1978), by the product rules d(XY) = dX Y(0) + X(lambda) dY, d(X^-1) = -X(lambda)^-1 dX X(0)^-1.
/// K(0) times a rigid motion is zero analytically, so K(lambda) times it is lambda dK times it,
/// with no cancellation: what the near-rigid modes and near-mechanism statics of a line need.
/// lambda = 0 gives dK = 0 (and K = K(0)).
struct SegmentDivided {
  Eigen::MatrixXd K, dK;
};
SegmentDivided segment_dynamic_stiffness_divided(const Eigen::MatrixXd& A_lambda, const Eigen::MatrixXd& A_0,
                                                 double lambda, double h);
/// The same from the transfer matrices T(lambda), T(0) and their divided difference
/// dT = (T(lambda) - T(0)) / lambda (for a varying segment: the upper right block of the transfer
/// of the block field [[A(lambda, x), dA(x)], [0, A(0, x)]], Van Loan's construction along x).
SegmentDivided segment_divided_from_transfers(const Eigen::MatrixXd& T1, const Eigen::MatrixXd& T0, const Eigen::MatrixXd& dT);

/// The reflection of a uniform segment end for end (x -> h - x): signs p_i = +-1, one per field,
/// with R A R = -A for R = diag(P, -P), P = diag(p), i.e. P A11 P = -A11, P A12 P = A12,
/// P A21 P = A21 exactly (a pattern of zeros: which fields are even and which odd in x). Then
/// K22 = P K11 P and K21 = K12^T = P K12 P, and a doubling needs half the work. nullopt when the
/// couplings allow no such signs (a field coupled to its own derivative, an odd cycle).
std::optional<Eigen::VectorXd> reflection_signs(const Eigen::MatrixXd& A);
std::optional<Eigen::VectorXd> reflection_signs(const Eigen::MatrixXcd& A);

/// The wavenumbers of a real state matrix (its eigenvalues, +-p pairs), after balancing. With
/// reflection signs, from the half-size block of A^2 (A^2 is block diagonal in R's halves): an
/// eigenvalue problem of m instead of 2m. Throws std::runtime_error if the iteration fails.
Eigen::VectorXcd state_wavenumbers(const Eigen::MatrixXd& A);

/// Whether long_segment_dynamic_stiffness may use the reflection (Use: where reflection_signs
/// finds one and the state has 8 fields or more, below which the general way is faster;
/// Ignore: the general way always, a second way to the same matrix).
enum class EndReflection { Use, Ignore };

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
  /// Smallest |pivot| of a condensed middle block relative to the norm of the two halves' matrix
  /// it condenses (how near a halving's clamped frequency lambda lies, as the condensation sees
  /// it; min_pivot_rel is 1 for a single field, whatever the pivot).
  double min_pivot_scale = 1;
};
LongSegment long_segment_dynamic_stiffness(const Eigen::MatrixXd& A, double h, int levels,
                                           EndReflection reflection = EndReflection::Use);

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
LongSegmentC long_segment_dynamic_stiffness(const Eigen::MatrixXcd& A, double h, int levels,
                                            EndReflection reflection = EndReflection::Use);

}  // namespace modalbench
