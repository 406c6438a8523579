#include "modalbench/numerics/balancing.hpp"

#include <cmath>
#include <complex>

namespace modalbench {

namespace {

// A cheap magnitude for balancing (|re| + |im| for complex: no hypot).
inline double magnitude(double v) { return std::abs(v); }
inline double magnitude(const std::complex<double>& v) { return std::abs(v.real()) + std::abs(v.imag()); }

// Diagonal similarity by powers of two (Parlett & Reinsch), in place; returns the scaling d
// with B_balanced = D^-1 B D, D = diag(d).
template <class Mat>
Eigen::VectorXd balance_impl(Mat& B, int max_sweeps) {
  const Eigen::Index n = B.rows();
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(n);
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    bool changed = false;
    for (Eigen::Index i = 0; i < n; ++i) {
      double c = 0, r = 0;
      for (Eigen::Index j = 0; j < n; ++j)
        if (j != i) {
          c += magnitude(B(j, i));
          r += magnitude(B(i, j));
        }
      if (c == 0 || r == 0) continue;
      int e = 0;
      std::frexp(std::sqrt(r / c), &e);
      const double f = std::ldexp(1.0, e - 1);
      if (f != 1.0 && (c * f + r / f) < 0.95 * (c + r)) {
        B.col(i) *= f;
        B.row(i) /= f;
        scale[i] *= f;
        changed = true;
      }
    }
    if (!changed) break;
  }
  return scale;
}

}  // namespace

Eigen::MatrixXd balanced(Eigen::MatrixXd B, int max_sweeps) {
  balance_in_place(B, max_sweeps);
  return B;
}

Eigen::VectorXd balance_in_place(Eigen::MatrixXd& B, int max_sweeps) { return balance_impl(B, max_sweeps); }
Eigen::VectorXd balance_in_place(Eigen::MatrixXcd& B, int max_sweeps) { return balance_impl(B, max_sweeps); }

}  // namespace modalbench
