// End conditions of the prism model: admissible end motions and end springs (make_end).
#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "prism_model_detail.hpp"

namespace modalbench::dtfm::detail {

/// End condition from motions T (m x r) with springs k (inf = held). `hold_rest`: everything
/// outside span(T) is held (rigid end plate); otherwise T must be unit vectors (per field).
EndCondition make_end(const Eigen::MatrixXd& T, const std::vector<double>& k, bool hold_rest, int m,
                      std::string text) {
  EndCondition e;
  e.text = std::move(text);
  if (!hold_rest) {
    // Per-field conditions: admissible = every field not held.
    std::vector<int> free_fields;
    std::vector<double> springs;
    std::vector<char> held(m, 0);
    std::vector<double> spring(m, 0.0);
    for (Eigen::Index c = 0; c < T.cols(); ++c) {
      Eigen::Index f = 0;
      T.col(c).cwiseAbs().maxCoeff(&f);
      if (std::isinf(k[c])) held[f] = 1;
      else spring[f] += k[c];
    }
    for (int f = 0; f < m; ++f)
      if (!held[f]) {
        free_fields.push_back(f);
        springs.push_back(spring[f]);
      }
    e.N = Eigen::MatrixXd::Zero(m, static_cast<Eigen::Index>(free_fields.size()));
    e.K = Eigen::MatrixXd::Zero(e.N.cols(), e.N.cols());
    for (std::size_t i = 0; i < free_fields.size(); ++i) {
      e.N(free_fields[i], static_cast<Eigen::Index>(i)) = 1.0;
      e.K(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)) = springs[i];
    }
    return e;
  }
  std::vector<int> cols;
  for (Eigen::Index c = 0; c < T.cols(); ++c)
    if (!std::isinf(k[c]) && T.col(c).norm() > 0) cols.push_back(static_cast<int>(c));
  Eigen::MatrixXd Tf(m, static_cast<Eigen::Index>(cols.size()));
  Eigen::VectorXd kf(static_cast<Eigen::Index>(cols.size()));
  for (std::size_t i = 0; i < cols.size(); ++i) {
    Tf.col(static_cast<Eigen::Index>(i)) = T.col(cols[i]);
    kf[static_cast<Eigen::Index>(i)] = k[cols[i]];
  }
  if (Tf.cols() == 0) {
    e.N = Eigen::MatrixXd(m, 0);
    e.K = Eigen::MatrixXd(0, 0);
    return e;
  }
  // Tf = N R (thin QR): a = R r, springs 1/2 r^T diag(k) r = 1/2 a^T R^-T diag(k) R^-1 a.
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(Tf);
  e.N = qr.householderQ() * Eigen::MatrixXd::Identity(m, Tf.cols());
  // Entries of R at the rounding of the QR (columns orthogonal in exact arithmetic, e.g. a beam's
  // axial translation and bending rotation) are zero: through R^-1 they would leak the stiff
  // springs into a motion the scene leaves free (1e-50 of them: a mechanism passing for a support).
  Eigen::MatrixXd R = e.N.transpose() * Tf;
  const double r_floor = 64.0 * std::numeric_limits<double>::epsilon() * R.cwiseAbs().maxCoeff();
  R = R.unaryExpr([r_floor](double v) { return std::abs(v) <= r_floor ? 0.0 : v; });
  const Eigen::MatrixXd Rinv = checked_inverse(R, "dtfm: the end-spring coordinates (R of Tf = N R)");
  e.K = Rinv.transpose() * kf.asDiagonal() * Rinv;
  e.K = 0.5 * (e.K + e.K.transpose());
  return e;
}

}  // namespace modalbench::dtfm::detail
