#include "modalbench/numerics/segment_dynamic_stiffness.hpp"

#include <Eigen/Eigenvalues>
#include <unsupported/Eigen/MatrixFunctions>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <optional>
#include <utility>
#include <vector>
#include <stdexcept>

#include "modalbench/numerics/balancing.hpp"
#include "modalbench/numerics/symmetric_factor.hpp"

namespace modalbench {

namespace {

/// The fields of R's +1 and -1 halves (r_i = +-1), each in order.
std::pair<std::vector<Eigen::Index>, std::vector<Eigen::Index>> halves_of(const Eigen::VectorXd& r) {
  std::pair<std::vector<Eigen::Index>, std::vector<Eigen::Index>> h;
  for (Eigen::Index i = 0; i < r.size(); ++i) (r[i] > 0 ? h.first : h.second).push_back(i);
  return h;
}

/// diag(p, -p): R of a state with field parities p.
Eigen::VectorXd state_signs(const Eigen::VectorXd& p) {
  Eigen::VectorXd r(2 * p.size());
  r << p, -p;
  return r;
}

/// exp(B) for a B that anticommutes with R = diag(r), r_i = +-1 (R B R = -B: B maps R's +1
/// fields to its -1 fields and back, its blocks within either are zero). Eigen's algorithm
/// (Higham 2005: the [d/d] Pade approximant, d = 3, 5, 7, 9 by the 1-norm, else 13 after s
/// halvings and followed by s squarings), with the structure used: the even powers of B are
/// block diagonal in R's two halves, so the Pade polynomials in B^2 cost products of half the
/// size (a quarter of the work), and U = B u(B^2) is block off-diagonal. The Pade quotient
/// (V - U)^-1 (V + U) and the squarings are done on the whole matrix.
template <class Mat>
Mat exp_anticommuting(const Mat& B, const Eigen::VectorXd& r) {
  const Eigen::Index n = B.rows();
  const auto [plus, minus] = halves_of(r);
  const Eigen::Index a = static_cast<Eigen::Index>(plus.size()), b = static_cast<Eigen::Index>(minus.size());
  const double l1 = B.cwiseAbs().colwise().sum().maxCoeff();
  // Degree by the 1-norm (Higham's theta_d for double, as Eigen's MatrixExponential).
  static constexpr double kTheta[] = {1.495585217958292e-2, 2.539398330063230e-1, 9.504178996162932e-1,
                                      2.097847961257068, 5.371920351148152};
  static constexpr double c3[] = {120., 60., 12., 1.};
  static constexpr double c5[] = {30240., 15120., 3360., 420., 30., 1.};
  static constexpr double c7[] = {17297280., 8648640., 1995840., 277200., 25200., 1512., 56., 1.};
  static constexpr double c9[] = {17643225600., 8821612800., 2075673600., 302702400., 30270240.,
                                  2162160.,     110880.,      3960.,        90.,        1.};
  static constexpr double c13[] = {64764752532480000., 32382376266240000., 7771770303897600., 1187353796428800.,
                                   129060195264000.,   10559470521600.,    670442572800.,     33522128640.,
                                   1323241920.,        40840800.,          960960.,           16380.,
                                   182.,               1.};
  int degree = 13, squarings = 0;
  const double* c = c13;
  if (l1 < kTheta[0]) {
    degree = 3;
    c = c3;
  } else if (l1 < kTheta[1]) {
    degree = 5;
    c = c5;
  } else if (l1 < kTheta[2]) {
    degree = 7;
    c = c7;
  } else if (l1 < kTheta[3]) {
    degree = 9;
    c = c9;
  } else if (l1 > kTheta[4]) {
    std::frexp(l1 / kTheta[4], &squarings);
  }
  const double down = std::ldexp(1.0, -squarings);
  const Mat Bpm = B(plus, minus) * down, Bmp = B(minus, plus) * down;  // +1 <- -1 and -1 <- +1
  // u(X) and v(X), X = B^2 restricted to one half: U = B u(B^2), V = v(B^2).
  auto polys = [&](const Mat& X2, Mat& u, Mat& v) {
    const Eigen::Index k = X2.rows();
    const Mat I = Mat::Identity(k, k);
    if (degree == 13) {  // Eigen's pade13 scheme: X^2, X^3 and two products
      const Mat X4 = X2 * X2, X6 = X4 * X2;
      u.noalias() = X6 * Mat(c[13] * X6 + c[11] * X4 + c[9] * X2);
      u += c[7] * X6 + c[5] * X4 + c[3] * X2 + c[1] * I;
      v.noalias() = X6 * Mat(c[12] * X6 + c[10] * X4 + c[8] * X2);
      v += c[6] * X6 + c[4] * X4 + c[2] * X2 + c[0] * I;
      return;
    }
    u = c[1] * I;
    v = c[0] * I;
    Mat P = I;
    for (int j = 1; 2 * j < degree + 1; ++j) {
      P = (P * X2).eval();
      u += c[2 * j + 1] * P;
      v += c[2 * j] * P;
    }
  };
  Mat up, vp, um, vm;
  polys(Mat(Bpm * Bmp), up, vp);
  polys(Mat(Bmp * Bpm), um, vm);
  Mat num(n, n);  // V + U in the order [plus; minus]; V - U flips U's (off-diagonal) blocks
  num.topLeftCorner(a, a) = vp;
  num.bottomRightCorner(b, b) = vm;
  num.topRightCorner(a, b).noalias() = Bpm * um;
  num.bottomLeftCorner(b, a).noalias() = Bmp * up;
  Mat den = num;
  den.topRightCorner(a, b) *= -1.0;
  den.bottomLeftCorner(b, a) *= -1.0;
  Mat E = den.partialPivLu().solve(num);
  for (int i = 0; i < squarings; ++i) E = (E * E).eval();
  std::vector<Eigen::Index> order(plus);
  order.insert(order.end(), minus.begin(), minus.end());
  Mat T(n, n);
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = 0; i < n; ++i) T(order[static_cast<std::size_t>(i)], order[static_cast<std::size_t>(j)]) = E(i, j);
  return T;
}

template <class Mat>
Mat stiffness_of_transfer(const Mat& T, double* asymmetry, double* log_abs_det_tdf);

// exp() is accurate relative to the norm of its argument; the state matrices mix entries
// of very different size (w, phi, Q, M), so balance first (diagonal similarity by powers
// of two, Parlett & Reinsch) and undo it afterwards: T = D exp(D^-1 A h D) D^-1. With the
// segment's reflection signs p (reflection_signs), B anticommutes with diag(p, -p) and the
// exponential takes the structured way (exp_anticommuting).
template <class Mat>
Mat segment_dsm_impl(const Mat& A, double h, double* asymmetry, double* log_abs_det_tdf,
                     const Eigen::VectorXd* p = nullptr) {
  const Eigen::Index n2 = A.rows();
  if (A.cols() != n2 || n2 % 2 != 0) throw std::invalid_argument("state matrix must be square of even size");
  Mat B = A * h;
  const Eigen::VectorXd scale = balance_in_place(B, 20);
  Mat E;
  if (p) {
    E = exp_anticommuting(B, state_signs(*p));
  } else {
    E = B.exp();
  }
  const Mat T = scale.asDiagonal() * E * scale.cwiseInverse().asDiagonal();
  return stiffness_of_transfer(T, asymmetry, log_abs_det_tdf);
}

/// K_seg from the segment's transfer matrix T (the header's formula), symmetrised.
template <class Mat>
Mat stiffness_of_transfer(const Mat& T, double* asymmetry, double* log_abs_det_tdf) {
  const Eigen::Index n2 = T.rows(), m = n2 / 2;
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

/// K from its near-end blocks K11, K12 as the reflection requires them (PP = p p^T): K11
/// symmetric, K12 = P K12^T P, K22 = P K11 P, K21 = K12^T; each from the mean of its two copies.
template <class Mat>
void set_reflected(Mat& K, const Mat& K11, const Mat& K12, const Mat& PP) {
  const Eigen::Index m = PP.rows();
  K.topLeftCorner(m, m) = 0.5 * (K11 + K11.transpose());
  K.topRightCorner(m, m) = 0.5 * (K12 + (PP.array() * K12.transpose().array()).matrix());
  K.bottomRightCorner(m, m) = (PP.array() * K.topLeftCorner(m, m).array()).matrix();
  K.bottomLeftCorner(m, m) = K.topRightCorner(m, m).transpose();
}

/// K's blocks made exactly what the reflection requires (set_reflected), each from the mean of
/// the copies it has.
template <class Mat>
void impose_reflection(Mat& K, const Eigen::VectorXd& p) {
  using Scalar = typename Mat::Scalar;
  const Eigen::Index m = p.size();
  const Mat PP = (p * p.transpose()).template cast<Scalar>();
  const Mat K11 = (0.5 * (K.topLeftCorner(m, m).array() + PP.array() * K.bottomRightCorner(m, m).array())).matrix();
  const Mat K12 = (0.5 * (K.topRightCorner(m, m).array() + PP.array() * K.bottomLeftCorner(m, m).array())).matrix();
  set_reflected(K, K11, K12, PP);
}

/// One doubling step of a segment symmetric under reflection (impose_reflection's form): the two
/// copies' middle block S = K11 + P K11 P commutes with P, so S^-1 K12 = P (S^-1 K21) P and the
/// joined segment's far-end blocks follow from its near-end ones. Half the solves and half the
/// products of double_in_place.
template <class Mat, class Solver>
void double_reflected(Mat& K, const Solver& solve, const Eigen::VectorXd& p) {
  using Scalar = typename Mat::Scalar;
  const Eigen::Index m = p.size();
  const Mat PP = (p * p.transpose()).template cast<Scalar>();
  const Mat Y = solve(Mat(K.bottomLeftCorner(m, m)));  // S^-1 K21
  Mat n11 = K.topLeftCorner(m, m);
  n11.noalias() -= K.topRightCorner(m, m) * Y;
  const Mat PYP = (PP.array() * Y.array()).matrix();
  Mat n12;
  n12.noalias() = -K.topRightCorner(m, m) * PYP;
  set_reflected(K, n11, n12, PP);
}

/// reflection_signs (segment_dynamic_stiffness.hpp), real or complex.
template <class Mat>
std::optional<Eigen::VectorXd> reflection_signs_impl(const Mat& A) {
  const Eigen::Index n2 = A.rows();
  if (A.cols() != n2 || n2 % 2 != 0 || n2 == 0) return std::nullopt;
  const Eigen::Index m = n2 / 2;
  // Fields i, j whose coupling requires p_i p_j = s: a graph with signed edges, two-coloured by
  // a search; a coupling that contradicts the colouring (or a diagonal entry of A11) rules the
  // reflection out.
  std::vector<std::vector<std::pair<Eigen::Index, int>>> adj(static_cast<std::size_t>(m));
  auto relate = [&](Eigen::Index i, Eigen::Index j, int sign) {
    adj[static_cast<std::size_t>(i)].emplace_back(j, sign);
    adj[static_cast<std::size_t>(j)].emplace_back(i, sign);
  };
  for (Eigen::Index j = 0; j < m; ++j)
    for (Eigen::Index i = 0; i < m; ++i) {
      if (A(i, j) != 0.0 || A(m + j, m + i) != 0.0) relate(i, j, -1);
      if (A(i, m + j) != 0.0 || A(m + i, j) != 0.0) relate(i, j, +1);
    }
  std::vector<int> sign(static_cast<std::size_t>(m), 0);
  std::vector<Eigen::Index> stack;
  for (Eigen::Index r = 0; r < m; ++r) {
    if (sign[static_cast<std::size_t>(r)] != 0) continue;
    sign[static_cast<std::size_t>(r)] = 1;
    stack.push_back(r);
    while (!stack.empty()) {
      const Eigen::Index i = stack.back();
      stack.pop_back();
      for (const auto& [j, s] : adj[static_cast<std::size_t>(i)]) {
        const int want = s * sign[static_cast<std::size_t>(i)];
        int& sj = sign[static_cast<std::size_t>(j)];
        if (sj == 0) {
          sj = want;
          stack.push_back(j);
        } else if (sj != want) {
          return std::nullopt;
        }
      }
    }
  }
  Eigen::VectorXd p(m);
  for (Eigen::Index i = 0; i < m; ++i) p[i] = sign[static_cast<std::size_t>(i)];
  return p;
}

/// Below 8 fields the structured way's bookkeeping costs more than it saves (measured: m = 3,
/// 4 levels, 10.2 us against 8.3; m = 12, 39 against 45; m = 24, 147 against 226).
constexpr Eigen::Index kReflectionFromFields = 8;
template <class Mat>
bool use_reflection(const Mat& A, EndReflection reflection) {
  return reflection == EndReflection::Use && A.rows() >= 2 * kReflectionFromFields;
}

}  // namespace

std::optional<Eigen::VectorXd> reflection_signs(const Eigen::MatrixXd& A) { return reflection_signs_impl(A); }

Eigen::VectorXcd state_wavenumbers(const Eigen::MatrixXd& A) {
  const Eigen::MatrixXd B = balanced(A);
  const std::optional<Eigen::VectorXd> p = reflection_signs(B);
  if (!p) {
    Eigen::EigenSolver<Eigen::MatrixXd> es(B, false);
    if (es.info() != Eigen::Success) throw std::runtime_error("state_wavenumbers: the eigenvalue iteration did not converge");
    return es.eigenvalues();
  }
  // B^2 = diag(Bpm Bmp, Bmp Bpm): its eigenvalues p^2 from the first block, each pair +-p once.
  const auto [plus, minus] = halves_of(state_signs(*p));
  const Eigen::MatrixXd X = B(plus, minus) * B(minus, plus);
  Eigen::EigenSolver<Eigen::MatrixXd> es(X, false);
  if (es.info() != Eigen::Success) throw std::runtime_error("state_wavenumbers: the eigenvalue iteration did not converge");
  const Eigen::Index k = X.rows();
  Eigen::VectorXcd out(2 * k);
  for (Eigen::Index i = 0; i < k; ++i) {
    out[i] = std::sqrt(es.eigenvalues()[i]);
    out[k + i] = -out[i];
  }
  return out;
}
std::optional<Eigen::VectorXd> reflection_signs(const Eigen::MatrixXcd& A) { return reflection_signs_impl(A); }

Eigen::MatrixXd segment_stiffness_of_transfer(const Eigen::MatrixXd& T, double* asymmetry) {
  if (T.rows() != T.cols() || T.rows() % 2 != 0) throw std::invalid_argument("transfer matrix must be square of even size");
  return stiffness_of_transfer(T, asymmetry, nullptr);
}

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
  return segment_divided_from_transfers(E.topLeftCorner(n2, n2), E.bottomRightCorner(n2, n2), E.topRightCorner(n2, n2));
}

SegmentDivided segment_divided_from_transfers(const Eigen::MatrixXd& T1, const Eigen::MatrixXd& T0, const Eigen::MatrixXd& dT) {
  const Eigen::Index n2 = T1.rows(), m = n2 / 2;
  SegmentDivided out;
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

LongSegment long_segment_dynamic_stiffness(const Eigen::MatrixXd& A, double h, int levels, EndReflection reflection) {
  if (levels < 0) throw std::invalid_argument("long_segment_dynamic_stiffness: levels must be >= 0");
  LongSegment out;
  const std::optional<Eigen::VectorXd> p = use_reflection(A, reflection) ? reflection_signs(A) : std::nullopt;
  out.K = segment_dsm_impl(A, std::ldexp(h, -levels), &out.asymmetry, &out.log_abs_det_tdf, p ? &*p : nullptr);
  const Eigen::Index m = out.K.rows() / 2;
  if (p) impose_reflection(out.K, *p);
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
    if (const double scale = out.K.norm(); scale > 0)
      out.min_pivot_scale = std::min(out.min_pivot_scale, f.min_abs / scale);
    auto solve = [&](const Eigen::MatrixXd& B) { return f.solve(B); };
    if (p) double_reflected(out.K, solve, *p);
    else double_in_place(out.K, solve, m, rhs, X);
  }
  return out;
}

LongSegmentC long_segment_dynamic_stiffness(const Eigen::MatrixXcd& A, double h, int levels, EndReflection reflection) {
  if (levels < 0) throw std::invalid_argument("long_segment_dynamic_stiffness: levels must be >= 0");
  LongSegmentC out;
  const std::optional<Eigen::VectorXd> p = use_reflection(A, reflection) ? reflection_signs(A) : std::nullopt;
  out.K = segment_dsm_impl(A, std::ldexp(h, -levels), &out.asymmetry, nullptr, p ? &*p : nullptr);
  const Eigen::Index m = out.K.rows() / 2;
  if (p) impose_reflection(out.K, *p);
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
    auto solve = [&](const Eigen::MatrixXcd& B) { return Eigen::MatrixXcd(lu.solve(B)); };
    if (p) double_reflected(out.K, solve, *p);
    else double_in_place(out.K, solve, m, rhs, X);
  }
  return out;
}

}  // namespace modalbench
