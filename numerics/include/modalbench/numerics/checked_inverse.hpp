#pragma once
// The inverse of a small dense matrix, refused when it is singular to working precision (its
// reciprocal condition estimate below 1e-14), with the reason: an explicit inverse of a
// near-singular matrix is noise that looks like numbers.

#include <Eigen/Dense>
#include <string>

namespace modalbench {

/// A^-1 by LU with partial pivoting; throws std::runtime_error naming `what` and the reciprocal
/// condition estimate when rcond(A) < 1e-14 or A has a non-finite entry.
Eigen::MatrixXd checked_inverse(const Eigen::MatrixXd& A, const std::string& what);

/// Solves the symmetric system A x = b by LDL^T; throws std::runtime_error naming `what` if the
/// factorization fails or the solution is not finite.
Eigen::MatrixXd checked_symmetric_solve(const Eigen::MatrixXd& A, const Eigen::MatrixXd& b, const std::string& what);

}  // namespace modalbench
