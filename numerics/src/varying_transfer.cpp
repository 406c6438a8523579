#include "modalbench/numerics/varying_transfer.hpp"

#include <unsupported/Eigen/MatrixFunctions>

#include <cmath>
#include <stdexcept>

#include "modalbench/numerics/balancing.hpp"

namespace modalbench {

namespace {

Eigen::MatrixXd commutator(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y) { return X * Y - Y * X; }

/// exp(B), balanced first (the fields' scales differ, as in segment_dynamic_stiffness): by B's own
/// balancing, or by the scaling d given.
Eigen::MatrixXd balanced_exp(Eigen::MatrixXd B, const Eigen::VectorXd& d) {
  Eigen::VectorXd s = d;
  if (s.size() == 0) s = balance_in_place(B, 20);
  else B = s.cwiseInverse().asDiagonal() * B * s.asDiagonal();
  return s.asDiagonal() * Eigen::MatrixXd(B.exp()) * s.cwiseInverse().asDiagonal();
}

Eigen::MatrixXd product_of_steps(const std::function<Eigen::MatrixXd(double)>& A, double x0, double x1, int n,
                                 const Eigen::VectorXd& d) {
  const double h = (x1 - x0) / n;
  Eigen::MatrixXd T = balanced_exp(magnus6_exponent(A, x0, h), d);
  for (int i = 1; i < n; ++i) T = (balanced_exp(magnus6_exponent(A, x0 + (x1 - x0) * i / n, h), d) * T).eval();
  return T;
}

}  // namespace

Eigen::MatrixXd magnus6_exponent(const std::function<Eigen::MatrixXd(double)>& A, double x, double h) {
  // Gauss-Legendre points c = 1/2 -+ sqrt(15)/10 and 1/2; alpha_1..3 the Legendre moments of A h.
  const double r = std::sqrt(15.0) / 10.0;
  const Eigen::MatrixXd A1 = A(x + (0.5 - r) * h), A2 = A(x + 0.5 * h), A3 = A(x + (0.5 + r) * h);
  const Eigen::MatrixXd a1 = h * A2;
  const Eigen::MatrixXd a2 = (std::sqrt(15.0) * h / 3.0) * (A3 - A1);
  const Eigen::MatrixXd a3 = (10.0 * h / 3.0) * (A3 - 2.0 * A2 + A1);
  const Eigen::MatrixXd C1 = commutator(a1, a2);
  const Eigen::MatrixXd C2 = (-1.0 / 60.0) * commutator(a1, Eigen::MatrixXd(2.0 * a3 + C1));
  return a1 + a3 / 12.0 + (1.0 / 240.0) * commutator(Eigen::MatrixXd(-20.0 * a1 - a3 + C1), Eigen::MatrixXd(a2 + C2));
}

VaryingTransfer varying_transfer(const std::function<Eigen::MatrixXd(double)>& A, double x0, double x1,
                                 double tolerance, const Eigen::VectorXd& scaling, int first_steps, int max_steps) {
  if (!(x1 >= x0)) throw std::invalid_argument("varying_transfer: x1 must not lie before x0");
  VaryingTransfer out;
  const Eigen::MatrixXd A0 = A(x0);
  if (A0.rows() != A0.cols()) throw std::invalid_argument("varying_transfer: A(x) must be square");
  if (x1 == x0) {
    out.T = Eigen::MatrixXd::Identity(A0.rows(), A0.cols());
    return out;
  }
  int n = std::max(1, first_steps);
  Eigen::MatrixXd coarse = product_of_steps(A, x0, x1, n, scaling);
  for (;;) {
    out.T = product_of_steps(A, x0, x1, 2 * n, scaling);
    out.steps = 2 * n;
    const double size = out.T.cwiseAbs().maxCoeff();
    out.error = (out.T - coarse).cwiseAbs().maxCoeff() / (63.0 * size);
    if (!(out.error > tolerance) || 2 * n >= max_steps) return out;
    n *= 2;
    coarse = std::move(out.T);
  }
}

}  // namespace modalbench
