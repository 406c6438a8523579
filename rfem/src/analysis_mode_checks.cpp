// rfem natural modes, after the eigensolve (analysis_modes.cpp): near-rigid pairs where the solve
// left them in the rounding of K, family labels, and each pair's residual, backward error and
// forward bound.
#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>

#include "modalbench/rfem/analysis.hpp"
#include "analysis_detail.hpp"

namespace modalbench::rfem::detail {

/// Near-rigid modes (rigid motions held only by soft finite springs): where the solve above left
/// them in the rounding of K (below 1e-8 of the first elastic eigenvalue), their Rayleigh-Ritz
/// pairs in the rigid subspace replace them; those are exact to O(k_springs / k_elastic).
/// Returns which modes were replaced; says so in `rigid_text`.
std::vector<char> take_near_rigid_pairs(const Model& model, const System& sys, long nr, Modes& out, std::string& rigid_text) {
  const long m = sys.m();
  std::vector<char> near_rigid(static_cast<std::size_t>(out.lambda.size()), 0);
  {
    const NearRigid near = near_rigid_modes(model, sys);
    // The near-rigid cluster: the largest q such that the q lowest Rayleigh-Ritz pairs lie below
    // 1e-6 of the solve's eigenvalue after them, and the solve's own q values there are in the
    // rounding of it too. Pairs held by stiff springs (a heave on a 1e19 N/m spring) are elastic
    // modes, not near-rigid ones, and stay with the solve.
    long q = 0;
    for (long c = near.lambda.size(); c > 0 && q == 0; --c) {
      if (nr + c >= out.lambda.size() || !(near.lambda[c - 1] < 1e-6 * out.lambda[nr + c])) continue;
      bool small = true;
      for (long i = 0; small && i < c; ++i) small = std::abs(out.lambda[nr + i]) < 1e-4 * out.lambda[nr + c];
      if (small) q = c;
    }
    const long first_elastic = nr + q;
    // The whole cluster or nothing.
    bool cluster = q > 0;
    // And only when each pair is known to 1e-5 (relative eigenvalue): Kato-Temple, the residual's
    // M^-1 norm squared over the gap to the first elastic eigenvalue. Otherwise the solve's own
    // pairs stay (and its checks, and the dense fall-back, decide).
    //
    // Springs to ground so stiff that they act on these pairs as supports (alone on the mass they
    // carry, an eigenvalue 1e6 times the first elastic one: a 1e19 N/m pin beside a 1 N/m spring)
    // are taken as constraints in the bound: their forces in K z are reactions (K z would carry
    // k times the rounding of z there, a residual of rounding alone), projected out like the
    // multipliers' forces; their compliance then lowers the eigenvalue by at most sum R^2 / k
    // (R: the reaction), added to the bound.
    double worst_bound = 0;
    if (cluster) {
      Eigen::SimplicialLDLT<SpMat> m_solver(sys.M);
      const ConstraintProjector Pc(sys.G);
      std::vector<const NearRigid::GroundSpring*> stiff;
      if (m_solver.info() == Eigen::Success)
        for (const auto& sp : near.springs)
          if (const Eigen::VectorXd row(sp.row); sp.k * row.dot(m_solver.solve(row)) >= 1e6 * out.lambda[first_elastic])
            stiff.push_back(&sp);
      const long ns = static_cast<long>(stiff.size());
      Eigen::MatrixXd D(sys.n(), ns);
      for (long j = 0; j < ns; ++j) D.col(j) = Eigen::VectorXd(stiff[static_cast<std::size_t>(j)]->row);
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> dqr;
      if (ns > 0) dqr.compute(D);
      for (long i = 0; i < q && cluster; ++i) {
        const Eigen::VectorXd zi = near.Z.col(i);
        Eigen::VectorXd res = sys.K * zi - near.lambda[i] * (sys.M * zi);
        for (long j = 0; j < ns; ++j) res -= (stiff[static_cast<std::size_t>(j)]->k * D.col(j).dot(zi)) * D.col(j);
        if (m > 0) res = Pc(res);
        double compliance = 0;
        if (ns > 0) {
          const Eigen::VectorXd reactions = dqr.solve(res);  // least squares
          res -= D * reactions;
          for (long j = 0; j < ns; ++j) compliance += reactions[j] * reactions[j] / stiff[static_cast<std::size_t>(j)]->k;
        }
        const double gap = out.lambda[first_elastic] - near.lambda[i];
        const double bound = m_solver.info() == Eigen::Success
                                 ? std::abs(res.dot(m_solver.solve(res))) / std::max(gap, 1e-300) / near.lambda[i] +
                                       compliance / near.lambda[i]
                                 : std::numeric_limits<double>::infinity();
        worst_bound = std::max(worst_bound, bound);
        cluster = bound <= 1e-5;
      }
    }
    if (cluster) {
      out.near_rigid_bound = worst_bound;
      for (long i = 0; i < q; ++i) {
        out.lambda[nr + i] = near.lambda[i];
        out.Z.col(nr + i) = near.Z.col(i);
        near_rigid[static_cast<std::size_t>(nr + i)] = 1;
      }
      rigid_text += fmt::format("; {} near-rigid mode(s) on the soft support springs by Rayleigh-Ritz in the "
                                "rigid-motion subspace (below the resolution of K)", q);
    }
  }
  return near_rigid;
}

/// Separates mode families inside clusters of equal frequencies (modes from `nr` on), then labels
/// every mode by its family (Rigid below `nr`).
void label_families(const Model& model, const System& sys, long nr, Modes& out) {
  const long total = out.lambda.size();
  const int na = model.dofs_per_element();
  for (long i = nr; i < total;) {
    long j = i + 1;
    while (j < total && std::abs(out.lambda[j] - out.lambda[i]) <= 1e-8 * std::abs(out.lambda[j])) ++j;
    if (j - i >= 2) {
      const Eigen::MatrixXd Q = sys.T * out.Z.middleCols(i, j - i);
      Eigen::MatrixXd W = Eigen::MatrixXd::Zero(j - i, j - i);
      for (long row = 0; row < Q.rows(); ++row) {
        const long e = row / na;
        const int k = static_cast<int>(row % na);
        const int d = model.active[static_cast<std::size_t>(k)];
        const double mass = d < 3 ? model.elements[static_cast<std::size_t>(e)].mass
                                  : model.elements[static_cast<std::size_t>(e)].inertia[d - 3];
        const double wgt = 1.0 + static_cast<double>(static_cast<int>(model.dof_family[static_cast<std::size_t>(k)]));
        W += wgt * mass * Q.row(row).transpose() * Q.row(row);
      }
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(W);
      // A failed rotation leaves the cluster's basis as it was: any orthonormal basis of a
      // repeated eigenvalue is correct, only its family labels may mix.
      if (es.info() == Eigen::Success)
        out.Z.middleCols(i, j - i) = (out.Z.middleCols(i, j - i) * es.eigenvectors()).eval();
      else
        out.warnings.push_back(fmt::format("modes {}-{}: the family rotation of a repeated eigenvalue failed; "
                                           "labels may mix families",
                                           i + 1, j));
    }
    i = j;
  }
  Eigen::VectorXd qbuf(sys.T.rows());
  for (long i = 0; i < total; ++i) {
    if (i < nr) {
      out.family.push_back(ModeFamily::Rigid);
      continue;
    }
    qbuf.noalias() = sys.T * out.Z.col(i);
    const auto share = family_shares(model, qbuf);
    const auto best = std::max_element(share.begin(), share.end());
    const auto fam = static_cast<ModeFamily>(best - share.begin());
    out.family.push_back(*best >= 0.95 && fam != ModeFamily::Unknown ? fam : ModeFamily::Unknown);
  }
}

/// Residuals and backward errors of every pair, and each flexible one's forward bound (near-rigid
/// pairs, marked in `near_rigid`, carry their Kato-Temple bound instead).
void measure_residuals(const System& sys, long nr, const std::vector<char>& near_rigid, Modes& out) {
  const long n = sys.n(), m = sys.m(), total = out.lambda.size();
  const ConstraintProjector P(sys.G);
  const SpMat Ka = sys.K.cwiseAbs(), Ma = sys.M.cwiseAbs();
  const double k_norm = detail::norm1(sys.K), m_norm = detail::norm1(sys.M);
  double kmax = 0;
  for (long i = 0; i < n; ++i) kmax = std::max(kmax, std::abs(sys.K.coeff(i, i)));
  Eigen::VectorXd Kz(n), Mz(n), za(n), scale_v(n), res_vec(n);
  for (long i = 0; i < total; ++i) {
    const auto z = out.Z.col(i);
    Kz.noalias() = sys.K * z;
    Mz.noalias() = sys.M * z;
    const double viol = m > 0 ? (sys.G * z).norm() / z.norm() : 0.0;
    res_vec = Kz - out.lambda[i] * Mz;
    if (m > 0) res_vec = P(res_vec);
    za = z.cwiseAbs();
    scale_v.noalias() = Ka * za;
    scale_v.noalias() += std::abs(out.lambda[i]) * (Ma * za);
    const double scale = scale_v.norm();
    double res = i < nr ? (m > 0 ? P(Kz).norm() : Kz.norm()) / (std::max(kmax, 1e-300) * z.norm())
                        : res_vec.norm() / std::max({Kz.norm(), out.lambda[i] * Mz.norm(), 1e-300});
    res = std::max(res, viol);
    double back = std::max(res_vec.norm() / std::max(scale, 1e-300), viol);
    if (near_rigid[static_cast<std::size_t>(i)]) {
      // A Rayleigh-Ritz pair of the rigid subspace leaves the spring forces unbalanced by the small
      // elastic deformation it omits: componentwise that is a residual of the springs' own size.
      // Its eigenvalue was checked by the Kato-Temple bound when it was taken; its backward error
      // is the contract's normwise one.
      back = std::max(res_vec.norm() / std::max((k_norm + out.lambda[i] * m_norm) * z.norm(), 1e-300), viol);
    }
    // Forward error of lambda, first order: (backward error + the rounding of K and M themselves)
    // times the componentwise condition |z|' (|K| + lambda |M|) |z| / lambda (z M-normalized). A
    // slender Timoshenko beam (L/h = 1e4, kGA/d far above EI/d^3) has condition 5e13 for its first
    // mode: known to 1e-2 at 512 segments and worse on finer meshes, which the backward error alone
    // (1e-16) does not say. Rigid modes are exact; near-rigid pairs carry their Kato-Temple bound.
    double forward = 0;
    if (i >= nr && !near_rigid[static_cast<std::size_t>(i)] && out.lambda[i] > 0)
      forward = (back + std::numeric_limits<double>::epsilon()) * za.dot(scale_v) / (out.lambda[i] * z.dot(Mz));
    out.forward_bounds.push_back(forward);
    out.max_forward_bound = std::max(out.max_forward_bound, forward);
    out.residuals.push_back(res);
    out.backward_errors.push_back(back);
    out.max_residual = std::max(out.max_residual, res);
    out.max_backward_error = std::max(out.max_backward_error, back);
  }
  // No warning for a backward error above backward_error_warning alone: it enters each mode's
  // forward bound above, which is the check (in the estimate, and past the tolerance a numerical
  // issue); above 1e-8 the solver warns (the shapes). The level only triggers refinement.
}

}  // namespace modalbench::rfem::detail
