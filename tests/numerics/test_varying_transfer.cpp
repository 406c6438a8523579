// The Magnus transfer matrix of a field with varying coefficients (varying_transfer.hpp), against
// its defining properties: exp(A h) for a constant A, symplectic for a Hamiltonian A(x), observed
// order 6 against a fine reference, and an error estimate no smaller than the error it estimates.
#define BOOST_TEST_MODULE varying_transfer
#include <boost/test/unit_test.hpp>

#include <unsupported/Eigen/MatrixFunctions>

#include <cmath>

#include "modalbench/numerics/varying_transfer.hpp"

using namespace modalbench;

namespace {

/// An Euler-Bernoulli beam's state matrix, y = [w, phi, Q, M], with EI(x) = (1 - 0.6 x)^4 and
/// rho A(x) = (1 - 0.6 x)^2 (a cone) at O2 = lambda rho A0 L^4 / EI0: Hamiltonian,
/// [[A11, A12], [A21, -A11^T]] with A12, A21 symmetric.
Eigen::MatrixXd cone_state(double x, double O2) {
  const double d = 1.0 - 0.6 * x;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(4, 4);
  A(0, 1) = 1.0;
  A(1, 3) = 1.0 / (d * d * d * d);
  A(2, 0) = -O2 * d * d;
  A(3, 2) = -1.0;
  return A;
}

double max_rel(const Eigen::MatrixXd& X, const Eigen::MatrixXd& ref) {
  return (X - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_constant_field_gives_its_exponential) {
  Eigen::MatrixXd A = cone_state(0.0, 30.0);
  const auto t = varying_transfer([&](double) { return A; }, 0.1, 0.6);
  const Eigen::MatrixXd ref = Eigen::MatrixXd(A * 0.5).exp();
  BOOST_TEST(max_rel(t.T, ref) < 1e-14);
  BOOST_TEST(t.error < 1e-15);
}

BOOST_AUTO_TEST_CASE(a_hamiltonian_field_gives_a_symplectic_transfer) {
  const auto t = varying_transfer([](double x) { return cone_state(x, 200.0); }, 0.0, 1.0);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(4, 4);
  J.topRightCorner(2, 2) = Eigen::MatrixXd::Identity(2, 2);
  J.bottomLeftCorner(2, 2) = -Eigen::MatrixXd::Identity(2, 2);
  const double size = t.T.cwiseAbs().maxCoeff();
  BOOST_TEST_INFO("T^T J T - J: " << (t.T.transpose() * J * t.T - J).cwiseAbs().maxCoeff() << ", |T| " << size);
  BOOST_TEST((t.T.transpose() * J * t.T - J).cwiseAbs().maxCoeff() < 1e-13 * size * size);
}

BOOST_AUTO_TEST_CASE(sixth_order_and_an_honest_estimate) {
  const auto A = [](double x) { return cone_state(x, 200.0); };
  const Eigen::MatrixXd ref = varying_transfer(A, 0.0, 1.0, 0.0, {}, 1024, 2048).T;  // 2048 steps
  // Fixed step counts (no refinement: tolerance 1e30), their errors against the reference.
  std::vector<double> err;
  for (int n : {2, 4, 8}) err.push_back(max_rel(varying_transfer(A, 0.0, 1.0, 1e30, {}, n, 2 * n).T, ref));
  for (std::size_t i = 0; i + 1 < err.size(); ++i) {
    const double order = std::log2(err[i] / err[i + 1]);
    BOOST_TEST_INFO("errors " << err[i] << " and " << err[i + 1] << ": observed order " << order);
    BOOST_TEST(std::abs(order - 6.0) < 0.5);
  }
  // A refinement stopped at 1e-10: its estimate bounds its error (within a factor 2 of the
  // asymptotic ratio 1/63 it assumes).
  const auto t = varying_transfer(A, 0.0, 1.0, 1e-10);
  BOOST_TEST_INFO("estimate " << t.error << ", error " << max_rel(t.T, ref) << " at " << t.steps << " steps");
  BOOST_TEST(t.error <= 1e-10);
  BOOST_TEST(max_rel(t.T, ref) <= 2.0 * t.error + 1e-15);
}
