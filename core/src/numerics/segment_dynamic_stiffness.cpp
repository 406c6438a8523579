#include "modalbench/numerics/segment_dynamic_stiffness.hpp"

#include <unsupported/Eigen/MatrixFunctions>

#include <algorithm>
#include <array>
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

SegmentDivided segment_dynamic_stiffness_divided(const Eigen::MatrixXd& A_lambda, const Eigen::MatrixXd& A_0,
                                                 double lambda, double h) {
  const Eigen::Index n2 = A_lambda.rows();
  if (A_lambda.cols() != n2 || A_0.rows() != n2 || A_0.cols() != n2 || n2 % 2 != 0)
    throw std::invalid_argument("segment_dynamic_stiffness_divided: state matrices must be square, even, equal");
  SegmentDivided out;
  if (lambda == 0.0) {
    out.K = segment_dynamic_stiffness(A_0, h);
    out.dK = Eigen::MatrixXd::Zero(n2, n2);
    return out;
  }
  const Eigen::Index m = n2 / 2;
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(2 * n2, 2 * n2);
  X.topLeftCorner(n2, n2) = A_lambda * h;
  X.topRightCorner(n2, n2) = (A_lambda - A_0) * (h / lambda);
  X.bottomRightCorner(n2, n2) = A_0 * h;
  // One diagonal scaling for both copies of the state, from A(0) h: balancing the block matrix
  // itself would chase entries of size lambda (1e-250 near a rigid mode) to extreme scales.
  Eigen::MatrixXd B0 = A_0 * h;
  const Eigen::VectorXd s0 = balance_in_place(B0, 20);
  Eigen::VectorXd scale(2 * n2);
  scale << s0, s0;
  X = scale.cwiseInverse().asDiagonal() * X * scale.asDiagonal();
  const Eigen::MatrixXd E = scale.asDiagonal() * Eigen::MatrixXd(X.exp()) * scale.cwiseInverse().asDiagonal();
  const Eigen::MatrixXd T1 = E.topLeftCorner(n2, n2), dT = E.topRightCorner(n2, n2), T0 = E.bottomRightCorner(n2, n2);
  auto blocks = [m](const Eigen::MatrixXd& T) {
    return std::array<Eigen::MatrixXd, 4>{T.topLeftCorner(m, m), T.topRightCorner(m, m), T.bottomLeftCorner(m, m),
                                          T.bottomRightCorner(m, m)};
  };
  const auto [dd1, df1, fd1, ff1] = blocks(T1);
  const auto [dd0, df0, fd0, ff0] = blocks(T0);
  const auto [ddd, ddf, dfd, dff] = blocks(dT);
  Eigen::PartialPivLU<Eigen::MatrixXd> lu1(df1), lu0(df0);
  if (!(lu1.rcond() >= 1e-14) || !(lu0.rcond() >= 1e-14))
    throw std::runtime_error("segment dynamic stiffness: the transfer block Tdf is singular to working precision");
  const Eigen::MatrixXd U1 = lu1.inverse(), U0 = lu0.inverse();
  const Eigen::MatrixXd K11_1 = U1 * dd1, K11_0 = U0 * dd0;
  const Eigen::MatrixXd dU = -U1 * ddf * U0;
  const Eigen::MatrixXd dK11 = dU * dd0 + U1 * ddd;
  Eigen::MatrixXd K(n2, n2), dK(n2, n2);
  K.topLeftCorner(m, m) = K11_1;
  K.topRightCorner(m, m) = -U1;
  K.bottomLeftCorner(m, m) = fd1 - ff1 * K11_1;
  K.bottomRightCorner(m, m) = ff1 * U1;
  dK.topLeftCorner(m, m) = dK11;
  dK.topRightCorner(m, m) = -dU;
  dK.bottomLeftCorner(m, m) = dfd - (dff * K11_0 + ff1 * dK11);
  dK.bottomRightCorner(m, m) = dff * U0 + ff1 * dU;
  out.K = 0.5 * (K + K.transpose());
  out.dK = 0.5 * (dK + dK.transpose());
  return out;
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
