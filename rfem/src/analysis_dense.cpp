// rfem dense modes: shift-invert symmetric eigenproblem on an orthonormal basis of the flexible space.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <stdexcept>
#include <string>

#include "analysis_detail.hpp"

namespace modalbench::rfem::detail {

Flexible dense_flexible(const System& sys, const Eigen::MatrixXd& R, long want, double sigma, std::string& method) {
  const long n = sys.n(), m = sys.m(), r = R.cols();
  Eigen::MatrixXd N;
  if (m + r > 0) {
    Eigen::MatrixXd Cd(m + r, n);
    if (m > 0) Cd.topRows(m) = Eigen::MatrixXd(sys.G);
    if (r > 0) Cd.bottomRows(r) = (sys.M * R).transpose();
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Cd.transpose());
    const long rank = qr.rank();
    const Eigen::MatrixXd Q = qr.householderQ();
    N = Q.rightCols(n - rank);
  } else {
    N = Eigen::MatrixXd::Identity(n, n);
  }
  Eigen::MatrixXd Kr = N.transpose() * (sys.K * N), Mr = N.transpose() * (sys.M * N);
  Kr = 0.5 * (Kr + Kr.transpose()).eval();
  Mr = 0.5 * (Mr + Mr.transpose()).eval();
  const long k = std::min<long>(want, N.cols());
  const std::string basis =
      m + r > 0 ? fmt::format(" (orthonormal basis of G z = 0{})", r > 0 ? ", rigid modes deflated" : "") : "";
  Flexible f;
  // Shift-invert form, as the Lanczos path: (Kr - sigma Mr) = L L', eigenvalues mu of
  // L^-1 Mr L^-T, lambda = sigma + 1/mu. Its absolute error is eps / (lambda_1 - sigma), so the
  // low modes keep their relative accuracy when the stiffness spans many decades (stiff
  // supports); the forward form (Cholesky of Mr) errs by eps * lambda_max and lost the
  // fundamental of a beam on 1e12 EI/L^3 springs.
  Eigen::LLT<Eigen::MatrixXd> llt(Kr - sigma * Mr);
  if (llt.info() == Eigen::Success) {
    Eigen::MatrixXd B = llt.matrixL().solve(llt.matrixL().solve(Mr).transpose());
    B = 0.5 * (B + B.transpose()).eval();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(B);
    if (es.info() != Eigen::Success) throw std::runtime_error("dense symmetric eigensolver failed");
    const long nb = B.rows();
    f.lambda.resize(k);
    Eigen::MatrixXd Y(nb, k);
    for (long i = 0; i < k; ++i) {
      const double mu = es.eigenvalues()[nb - 1 - i];  // largest mu = lowest lambda
      f.lambda[i] = sigma + 1.0 / mu;
      Y.col(i) = es.eigenvectors().col(nb - 1 - i);
    }
    f.Z = N * llt.matrixU().solve(Y);
    method = fmt::format(
        "dense shift-invert symmetric eigensolver (Eigen: Cholesky of K - sigma M, sigma = {:.6g} rad^2/s^2, tridiagonal "
        "QR) on {} unknowns{}",
        sigma, N.cols(), basis);
    return f;
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ges(Kr, Mr);
  if (ges.info() != Eigen::Success) throw std::runtime_error("dense generalized eigensolver failed");
  f.lambda = ges.eigenvalues().head(k);
  f.Z = N * ges.eigenvectors().leftCols(k);
  method = fmt::format(
      "dense generalized symmetric eigensolver (Eigen, Cholesky of M + tridiagonal QR; K - sigma M was not positive "
      "definite at sigma = {:.6g}) on {} unknowns{}",
      sigma, N.cols(), basis);
  return f;
}

}  // namespace modalbench::rfem::detail
