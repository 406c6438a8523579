#pragma once
// A mode of a line system (line_system.hpp) at one of its eigenvalues: the null vector of the
// assembled dynamic stiffness K(lambda), and the exact field between the nodes by each
// segment's transfer matrix, y(xi) = exp(A (xi - xi_i)) y_i, with y = [d; f].
//
// The null vector comes from two steps of inverse iteration at lambda (1 + 1e-11) (a relative
// gap of 1e-11 to the mode against O(1) to the others: its contamination drops to ~1e-22; lambda
// itself is known to ~1e-13); the
// forces at a node follow from the segment dynamic stiffness. Requested points are nodes of
// the assembly (LineSystem::nodes_at), so values there are the null vector itself.

#include <Eigen/Dense>
#include <functional>
#include <vector>

#include "modalbench/numerics/line_system.hpp"

namespace modalbench {

class LineMode {
 public:
  /// The mode of `sys` at eigenvalue `lambda` (> 0; rigid modes are the caller's). Throws
  /// std::runtime_error if K(lambda (1 + 1e-11)) cannot be factorized.
  LineMode(const LineSystem& sys, double lambda);
  /// The state [d; f] (2m entries) at xi in [0, 1] (dimensionless, as the system's).
  Eigen::VectorXd state(double xi) const;
  /// The displacements d at xi.
  Eigen::VectorXd displacement(double xi) const { return state(xi).head(m_); }
  /// int_0^1 g(d(xi), xi) dxi, segment by segment (GSL adaptive quadrature, quadrature.hpp), to
  /// 1e-12 relative or 1e-13 absolutely of |g| on each segment; `zero_scale`, where given, is a size
  /// of |g| for the whole mode below which the integral counts as zero (a participation integral of
  /// a mode without that motion, e.g. a Timoshenko beam's thickness-shear mode with w = 0, is
  /// rounding only, and no relative accuracy can be reached on it).
  double integrate(const std::function<double(const Eigen::VectorXd& d, double xi)>& g, double zero_scale = 0) const;

 private:
  int m_ = 0;
  LineSystem sys_;  ///< the line (a varying piece's transfer matrices come from it)
  double lambda_ = 0;
  std::vector<Eigen::MatrixXd> A_;  ///< per segment (a stepped line's pieces differ)
  std::vector<double> xi_;
  std::vector<Eigen::VectorXd> y_;  ///< state at the left end of each segment (and the last node)
  Eigen::MatrixXd transfer(std::size_t segment, double s) const;
};

}  // namespace modalbench
