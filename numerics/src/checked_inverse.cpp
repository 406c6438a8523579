#include "modalbench/numerics/checked_inverse.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace modalbench {

Eigen::MatrixXd checked_inverse(const Eigen::MatrixXd& A, const std::string& what) {
  if (!A.allFinite()) throw std::runtime_error(what + ": matrix has a non-finite entry");
  if (A.rows() == 0) return A;
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(A);
  const double rc = lu.rcond();
  if (!(rc >= 1e-14))
    throw std::runtime_error(fmt::format("{}: matrix singular to working precision (reciprocal condition {:.2g})", what, rc));
  return lu.inverse();
}

Eigen::MatrixXd checked_symmetric_solve(const Eigen::MatrixXd& A, const Eigen::MatrixXd& b, const std::string& what) {
  const Eigen::LDLT<Eigen::MatrixXd> f(A);
  if (f.info() != Eigen::Success) throw std::runtime_error(what + ": LDL' factorization failed");
  Eigen::MatrixXd x = f.solve(b);
  if (!x.allFinite()) throw std::runtime_error(what + ": matrix singular (non-finite solution)");
  return x;
}

}  // namespace modalbench
