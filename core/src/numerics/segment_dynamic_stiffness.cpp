#include "modalbench/numerics/segment_dynamic_stiffness.hpp"

#include <unsupported/Eigen/MatrixFunctions>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <stdexcept>

#include "modalbench/numerics/balancing.hpp"
#include "modalbench/numerics/symmetric_factor.hpp"

namespace modalbench {

namespace {

// exp() is accurate relative to the norm of its argument; the state matrices mix entries
// of very different size (w, phi, Q, M), so balance first (diagonal similarity by powers
// of two, Parlett & Reinsch) and undo it afterwards: T = D exp(D^-1 A h D) D^-1.
template <class Mat>
Mat segment_dsm_impl(const Mat& A, double h, double* asymmetry, double* log_abs_det_tdf) {
  const Eigen::Index n2 = A.rows();
  if (A.cols() != n2 || n2 % 2 != 0) throw std::invalid_argument("state matrix must be square of even size");
  const Eigen::Index m = n2 / 2;
  Mat B = A * h;
  const Eigen::VectorXd scale = balance_in_place(B, 20);
  const Mat T = scale.asDiagonal() * Mat(B.exp()) * scale.cwiseInverse().asDiagonal();
  const auto Tdd = T.topLeftCorner(m, m), Tdf = T.topRightCorner(m, m);
  const auto Tfd = T.bottomLeftCorner(m, m), Tff = T.bottomRightCorner(m, m);
  Eigen::PartialPivLU<Mat> lu(Tdf);
  if (log_abs_det_tdf) {
    double l = 0;
    for (Eigen::Index i = 0; i < m; ++i) l += std::log(std::abs(lu.matrixLU()(i, i)));
    *log_abs_det_tdf = l;
  }
  const Mat TdfInvTdd = lu.solve(Mat(Tdd));
  // Tdf is well conditioned for the short pieces this is meant for (|p| h of order one); a
  // singular one (a clamped-piece frequency, or a piece far too long) would give noise.
  if (!(lu.rcond() >= 1e-14))
    throw std::runtime_error("segment dynamic stiffness: the transfer block Tdf is singular to working precision "
                             "(segment too long for one exponential, or at a clamped-segment natural frequency)");
  const Mat TdfInv = lu.inverse();
  Mat K(n2, n2);
  K.topLeftCorner(m, m) = TdfInvTdd;
  K.topRightCorner(m, m) = -TdfInv;
  K.bottomLeftCorner(m, m) = Tfd - Tff * TdfInvTdd;
  K.bottomRightCorner(m, m) = Tff * TdfInv;
  if (asymmetry) *asymmetry = (K - K.transpose()).norm() / K.norm();
  // Symmetric in exact arithmetic; remove the rounding asymmetry so the LDL^T sees one matrix.
  return Mat(0.5 * (K + K.transpose()));
}

/// One doubling step on a symmetric segment matrix [K11 K12; K12^T K22] in place:
/// condense the middle node of two copies. `X` and `rhs` are work space.
template <class Mat, class Solver>
void double_in_place(Mat& K, const Solver& solve, Eigen::Index m, Mat& rhs, Mat& X) {
  rhs.resize(m, 2 * m);
  rhs.leftCols(m) = K.bottomLeftCorner(m, m);  // K21
  rhs.rightCols(m) = K.topRightCorner(m, m);   // K12
  X = solve(rhs);                              // [S^-1 K21, S^-1 K12]
  Mat out(2 * m, 2 * m);
  out.topLeftCorner(m, m) = K.topLeftCorner(m, m);
  out.topLeftCorner(m, m).noalias() -= K.topRightCorner(m, m) * X.leftCols(m);
  out.topRightCorner(m, m).noalias() = -K.topRightCorner(m, m) * X.rightCols(m);
  out.bottomLeftCorner(m, m).noalias() = -K.bottomLeftCorner(m, m) * X.leftCols(m);
  out.bottomRightCorner(m, m) = K.bottomRightCorner(m, m);
  out.bottomRightCorner(m, m).noalias() -= K.bottomLeftCorner(m, m) * X.rightCols(m);
  K = 0.5 * (out + out.transpose());
}

}  // namespace

Eigen::MatrixXd segment_dynamic_stiffness(const Eigen::MatrixXd& A, double h, double* asymmetry,
                                          double* log_abs_det_tdf) {
  return segment_dsm_impl(A, h, asymmetry, log_abs_det_tdf);
}

Eigen::MatrixXcd segment_dynamic_stiffness(const Eigen::MatrixXcd& A, double h, double* asymmetry,
                                           double* log_abs_det_tdf) {
  return segment_dsm_impl(A, h, asymmetry, log_abs_det_tdf);
}

LongSegment long_segment_dynamic_stiffness(const Eigen::MatrixXd& A, double h, int levels) {
  if (levels < 0) throw std::invalid_argument("long_segment_dynamic_stiffness: levels must be >= 0");
  LongSegment out;
  out.K = segment_dynamic_stiffness(A, std::ldexp(h, -levels), &out.asymmetry, &out.log_abs_det_tdf);
  const Eigen::Index m = out.K.rows() / 2;
  Eigen::MatrixXd rhs, X;
  for (int level = 0; level < levels; ++level) {
    const SymFactor f(Eigen::MatrixXd(out.K.bottomRightCorner(m, m) + out.K.topLeftCorner(m, m)));
    // J0 doubles per level: past 2^30 clamped frequencies below omega the count cannot be held
    // (and omega is far beyond anything the model represents).
    if (out.clamped_below > (1 << 29))
      throw std::runtime_error("long segment: more than 2^30 clamped-segment natural frequencies below omega: the "
                               "frequency is beyond the range of the model (count overflow avoided)");
    out.clamped_below = 2 * out.clamped_below + f.negative;
    out.log_abs_det_tdf = 2 * out.log_abs_det_tdf + f.log_abs;
    if (f.max_abs > 0) out.min_pivot_rel = std::min(out.min_pivot_rel, f.min_abs / f.max_abs);
    double_in_place(out.K, [&](const Eigen::MatrixXd& B) { return f.solve(B); }, m, rhs, X);
  }
  return out;
}

LongSegmentC long_segment_dynamic_stiffness(const Eigen::MatrixXcd& A, double h, int levels) {
  if (levels < 0) throw std::invalid_argument("long_segment_dynamic_stiffness: levels must be >= 0");
  LongSegmentC out;
  out.K = segment_dynamic_stiffness(A, std::ldexp(h, -levels), &out.asymmetry);
  const Eigen::Index m = out.K.rows() / 2;
  Eigen::MatrixXcd rhs, X;
  for (int level = 0; level < levels; ++level) {
    const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(Eigen::MatrixXcd(out.K.bottomRightCorner(m, m) + out.K.topLeftCorner(m, m)));
    // Pivot ratio as a cheap near-singularity indicator (rcond would cost extra solves).
    const Eigen::VectorXcd d = lu.matrixLU().diagonal();
    double lo = std::numeric_limits<double>::infinity(), hi = 0;
    for (Eigen::Index i = 0; i < d.size(); ++i) {
      const double a = std::abs(d[i].real()) + std::abs(d[i].imag());
      lo = std::min(lo, a);
      hi = std::max(hi, a);
    }
    if (hi > 0) out.min_pivot_rel = std::min(out.min_pivot_rel, lo / hi);
    double_in_place(out.K, [&](const Eigen::MatrixXcd& B) { return Eigen::MatrixXcd(lu.solve(B)); }, m, rhs, X);
  }
  return out;
}

}  // namespace modalbench
