// Symmetry classes of the prism model: the section reflections' classes and their commutation check.
#include <Eigen/Dense>
#include <vector>

#include "prism_model_detail.hpp"

namespace modalbench::dtfm::detail {

/// Symmetry classes from commuting reflections: orbit sums of unit vectors with signs.
void build_classes(PrismModel& mdl, const std::vector<ModeFamily>& families_by_class,
                   const std::vector<std::vector<int>>& family_rigid_columns) {
  const int m = mdl.m;
  const int nr = static_cast<int>(mdl.reflections.size());
  const int nclass = 1 << nr;
  // Group elements: products of subsets of reflections, applied as (Pi q)_k = s_k q_{perm_k}.
  auto apply = [&](int r, const Eigen::VectorXd& v) {
    Eigen::VectorXd out(m);
    const auto& R = mdl.reflections[r];
    for (int k = 0; k < m; ++k) out[k] = R.sign[k] * v[R.perm[k]];
    return out;
  };
  std::vector<std::vector<Eigen::VectorXd>> basis(nclass);
  std::vector<char> seen(m, 0);
  for (int k = 0; k < m; ++k) {
    if (seen[k]) continue;
    Eigen::VectorXd e = Eigen::VectorXd::Zero(m);
    e[k] = 1.0;
    // Images under every group element g (subset mask), for each character c.
    std::vector<Eigen::VectorXd> images(nclass);
    for (int g = 0; g < nclass; ++g) {
      Eigen::VectorXd v = e;
      for (int r = 0; r < nr; ++r)
        if (g & (1 << r)) v = apply(r, v);
      images[g] = v;
      for (int j = 0; j < m; ++j)
        if (v[j] != 0.0) seen[j] = 1;
    }
    for (int c = 0; c < nclass; ++c) {
      Eigen::VectorXd sum = Eigen::VectorXd::Zero(m);
      for (int g = 0; g < nclass; ++g) {
        int chi = 1;
        for (int r = 0; r < nr; ++r)
          if ((g & (1 << r)) && (c & (1 << r))) chi = -chi;
        sum += chi * images[g];
      }
      if (sum.norm() > 1e-12) basis[c].push_back(sum.normalized());
    }
  }
  mdl.classes.clear();
  for (int c = 0; c < nclass; ++c) {
    if (basis[c].empty()) continue;
    FieldClass fc;
    for (int r = 0; r < nr; ++r) fc.parity.push_back((c & (1 << r)) ? -1 : +1);
    fc.V = Eigen::MatrixXd(m, static_cast<Eigen::Index>(basis[c].size()));
    for (std::size_t i = 0; i < basis[c].size(); ++i) fc.V.col(static_cast<Eigen::Index>(i)) = basis[c][i];
    fc.family = families_by_class.empty() ? ModeFamily::Unknown : families_by_class[c];
    if (!family_rigid_columns.empty() && mdl.rigid_motions.cols() == 6) {
      const auto& cols = family_rigid_columns[c];
      fc.family_motions = Eigen::MatrixXd(m, static_cast<Eigen::Index>(cols.size()));
      for (std::size_t i = 0; i < cols.size(); ++i)
        fc.family_motions.col(static_cast<Eigen::Index>(i)) = mdl.rigid_motions.col(cols[i]);
    }
    mdl.classes.push_back(std::move(fc));
  }
}

/// Checks that each reflection commutes with every operator and end condition; drops them all
/// otherwise (then a single class holds everything).
bool reflections_commute(const PrismModel& mdl) {
  for (const auto& R : mdl.reflections) {
    Eigen::MatrixXd P = Eigen::MatrixXd::Zero(mdl.m, mdl.m);
    for (int k = 0; k < mdl.m; ++k) P(k, R.perm[k]) = R.sign[k];
    for (const Eigen::MatrixXd* A : {&mdl.M, &mdl.C, &mdl.S, &mdl.X, &mdl.Q1}) {
      const double scale = A->norm() + 1e-300;
      if ((P * *A - *A * P).norm() > 1e-10 * scale) return false;
    }
    for (const auto& e : mdl.ends) {
      // span(N) invariant and springs commuting: compare the projected spring operators.
      const Eigen::MatrixXd Ks = e.N * e.K * e.N.transpose(), Pn = e.N * e.N.transpose();
      if ((P * Pn - Pn * P).norm() > 1e-10 * (Pn.norm() + 1)) return false;
      if ((P * Ks - Ks * P).norm() > 1e-10 * (Ks.norm() + 1e-300)) return false;
    }
  }
  return true;
}

}  // namespace modalbench::dtfm::detail
