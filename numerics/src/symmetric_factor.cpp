#include "modalbench/numerics/symmetric_factor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace modalbench {

SymFactor::SymFactor(const Eigen::MatrixXd& S) {
  if (S.rows() == 0) return;
  ldlt.compute(S);
  bool good = ldlt.info() == Eigen::Success;
  if (good) {
    const Eigen::VectorXd d = ldlt.vectorD();
    for (Eigen::Index i = 0; i < d.size(); ++i)
      if (!std::isfinite(d[i]) || d[i] == 0.0) good = false;
    if (good) {
      for (Eigen::Index i = 0; i < d.size(); ++i) tally(d[i]);
      return;
    }
  }
  use_eig = true;
  eig.compute(S);
  if (eig.info() != Eigen::Success) {
    // No trustworthy pivots at all: every one counts as zero (callers treat the block as singular).
    zero = static_cast<int>(S.rows());
    min_abs = 0;
    max_abs = 0;
    log_abs = -std::numeric_limits<double>::infinity();
    return;
  }
  const Eigen::VectorXd ev = eig.eigenvalues();
  const double scale = ev.cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < ev.size(); ++i) {
    if (!std::isfinite(ev[i]) || std::abs(ev[i]) <= 1e-300 + 1e-15 * scale) ++zero;
    tally(ev[i]);
  }
}

void SymFactor::tally(double d) {
  if (d < 0) ++negative;
  log_abs += std::log(std::abs(d));
  min_abs = std::min(min_abs, std::abs(d));
  max_abs = std::max(max_abs, std::abs(d));
}

Eigen::MatrixXd SymFactor::solve(const Eigen::MatrixXd& B) const {
  if (B.rows() == 0) return B;
  if (!use_eig) return ldlt.solve(B);
  Eigen::VectorXd inv = eig.eigenvalues();
  const double scale = inv.cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < inv.size(); ++i) {
    const double e = inv[i];
    // A zero pivot: regularise so the elimination can go on; callers see `zero`.
    inv[i] = std::abs(e) <= 1e-15 * scale ? 1.0 / (1e-15 * scale + 1e-300) : 1.0 / e;
  }
  return eig.eigenvectors() * inv.asDiagonal() * (eig.eigenvectors().transpose() * B);
}

Eigen::VectorXd graded_ldlt(Eigen::MatrixXd& S) {
  const Eigen::Index r = S.rows();
  Eigen::VectorXd d = Eigen::VectorXd::Constant(r, std::numeric_limits<double>::quiet_NaN());
  for (Eigen::Index k = 0; k < r; ++k) {
    if (S(k, k) == 0.0 || !std::isfinite(S(k, k))) return d;
    d[k] = S(k, k);
    for (Eigen::Index i = k + 1; i < r; ++i) S(i, k) /= d[k];
    for (Eigen::Index i = k + 1; i < r; ++i)
      for (Eigen::Index j = k + 1; j <= i; ++j) S(i, j) -= S(i, k) * d[k] * S(j, k);
  }
  return d;
}

Eigen::VectorXd graded_ldlt_solve(const Eigen::MatrixXd& S, const Eigen::VectorXd& d, Eigen::VectorXd b) {
  const Eigen::Index r = d.size();
  for (Eigen::Index i = 0; i < r; ++i)
    for (Eigen::Index j = 0; j < i; ++j) b[i] -= S(i, j) * b[j];
  for (Eigen::Index i = 0; i < r; ++i) b[i] /= d[i];
  for (Eigen::Index i = r; i-- > 0;)
    for (Eigen::Index j = i + 1; j < r; ++j) b[i] -= S(j, i) * b[j];
  return b;
}

}  // namespace modalbench
