#pragma once
// The transfer matrix of a linear field y' = A(x) y whose coefficients vary along x (a tapered
// member), by the sixth-order Magnus integrator (Blanes, Casas & Ros 2000; Blanes, Casas, Oteo &
// Ros, Phys. Rep. 470, 2009: three Gauss-Legendre points per step), on equal steps doubled
// until two successive step counts agree.
//
// Each step's exponent is built from commutators of A at the Gauss points, so it lies in the Lie
// algebra A lies in: a Hamiltonian A gives a symplectic step, and the product stays symplectic to
// rounding (the segment dynamic stiffness built from it is symmetric, as a uniform piece's). For a
// constant A the exponent is A h exactly and the product is exp(A (x1 - x0)).
//
// Error: the local error is O(h^7), so doubling the steps divides the global error by about 64;
// with T_n and T_2n the estimate of T_2n's error is |T_2n - T_n| / 63 (max norm, relative to
// |T_2n|). Steps double from `first_steps` until that estimate is below `tolerance` or the count
// reaches `max_steps`; the caller decides what a larger estimate means.

#include <Eigen/Dense>
#include <functional>

namespace modalbench {

struct VaryingTransfer {
  Eigen::MatrixXd T;        ///< y(x1) = T y(x0)
  double error = 0;         ///< estimated relative error of T (see above)
  int steps = 0;            ///< Magnus steps taken for T
};

/// y(x1) = T y(x0) for y' = A(x) y, A(x) square. Each step's exponential is balanced (a diagonal
/// similarity by powers of two) by its own exponent, or by `scaling` where one is given (d: the
/// exponent as D^-1 Omega D, D = diag(d)). Throws std::invalid_argument for x1 < x0 or a
/// non-square A.
VaryingTransfer varying_transfer(const std::function<Eigen::MatrixXd(double x)>& A, double x0, double x1,
                                 double tolerance = 1e-15, const Eigen::VectorXd& scaling = {}, int first_steps = 2,
                                 int max_steps = 4096);

/// One sixth-order Magnus exponent over [x, x + h] (exposed for the order test).
Eigen::MatrixXd magnus6_exponent(const std::function<Eigen::MatrixXd(double x)>& A, double x, double h);

}  // namespace modalbench
