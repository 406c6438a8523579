// rfem statics: K z = f by the saddle-point LDL', or the mechanism that makes it undefined.
#include "modalbench/rfem/analysis.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <string>
#include <vector>

#include "modalbench/rfem/factor.hpp"
#include "analysis_detail.hpp"

namespace modalbench::rfem {

namespace {
using detail::Clock;
using detail::ConstraintProjector;
using detail::seconds_since;
}  // namespace

namespace {

/// Below this smallest pivot ratio of K, statics with rigid motions held only by finite springs
/// go through near_mechanism_solve (the plain solve keeps about eps / ratio of the rigid part).
constexpr double kNearMechanismPivot = 1e-8;

/// K z = f where the rigid motions Phi (near.Z, M-orthonormal, G Phi = 0) are held only by the
/// springs to ground: K Phi = Kg Phi, tiny beside the elastic stiffness (a beam on springs of
/// 1e-12 EI / L^3: smallest pivot 3e-15 of the largest, "singular"). Anchors E (r coordinates the
/// rigid motions move most, by a pivoted QR of Phi') get springs c = |K_ii|: K_a = K + E C E' is
/// as well conditioned as the anchored structure. Woodbury on K = K_a - E C E', with
/// K_a^-1 E C E' Phi = Phi - X, X = K_a^-1 Kg Phi, reduces exactly to
///   z = y + (Phi - X) (E' X)^-1 E' y,   y = K_a^-1 f,
/// whatever C is, with Kg Phi from the springs themselves (sum k d d' Phi, never K Phi, whose
/// rounding is eps of the elastic stiffness): nothing in it cancels.
bool near_mechanism_solve(const System& sys, const NearRigid& near, const Eigen::VectorXd& f, KktLdlt& ldlt,
                          Eigen::VectorXd& z, std::string& why) {
  const Eigen::MatrixXd& Phi = near.Z;
  const long n = sys.n(), r = Phi.cols();
  Eigen::MatrixXd KgPhi = Eigen::MatrixXd::Zero(n, r);
  for (const auto& sp : near.springs) {
    const Eigen::RowVectorXd dPhi = Eigen::VectorXd(sp.row).transpose() * Phi;
    for (Eigen::SparseVector<double>::InnerIterator it(sp.row); it; ++it)
      KgPhi.row(it.index()) += sp.k * it.value() * dPhi;
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Phi.transpose());
  std::vector<long> anchor(static_cast<std::size_t>(r));
  SpMat Ka = sys.K;
  for (long j = 0; j < r; ++j) {
    const long i = qr.colsPermutation().indices()[j];
    anchor[static_cast<std::size_t>(j)] = i;
    const double kii = std::abs(sys.K.coeff(i, i));
    Ka.coeffRef(i, i) += kii > 0 ? kii : 1.0;
  }
  long where = -1;
  ldlt.analyze(Ka, sys.G, sys.groups);  // an anchor's diagonal may be new to the pattern
  if (!ldlt.factorize(Ka) || ldlt.negative_count() != 0 || ldlt.smallest_primal_pivot_ratio(&where) < 1e-14) {
    why = "the anchored stiffness matrix is singular or indefinite";
    return false;
  }
  const Eigen::VectorXd y = ldlt.solve(f);
  Eigen::MatrixXd X(n, r);
  for (long j = 0; j < r; ++j) X.col(j) = ldlt.solve(KgPhi.col(j));
  Eigen::MatrixXd EX(r, r);
  Eigen::VectorXd Ey(r);
  for (long j = 0; j < r; ++j) {
    EX.row(j) = X.row(anchor[static_cast<std::size_t>(j)]);
    Ey[j] = y[anchor[static_cast<std::size_t>(j)]];
  }
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(EX);
  if (!lu.isInvertible()) {
    why = "the springs do not hold the rigid motions at the anchors";
    return false;
  }
  z = y + (Phi - X) * lu.solve(Ey);
  if (!z.allFinite()) {
    why = "non-finite deflections";
    return false;
  }
  return true;
}

}  // namespace

StaticSolution solve_static(const Model& model, const System& sys, const Eigen::VectorXd& f) {
  StaticSolution s;
  const auto t0 = Clock::now();
  const RigidModes rigid = free_rigid_modes(model, sys);
  if (rigid.Z.cols() > 0) {
    s.mechanism = true;
    // Name the coordinates each free motion moves most.
    std::vector<std::string> moved;
    for (long c = 0; c < rigid.Z.cols(); ++c) {
      const Eigen::VectorXd z = rigid.Z.col(c);
      const double zmax = z.cwiseAbs().maxCoeff();
      long listed = 0, more = 0;
      for (long i = 0; i < z.size(); ++i)
        if (std::abs(z[i]) >= 0.5 * zmax) {
          if (listed < 4) moved.push_back(coordinate_name(model, sys, i)), ++listed;
          else ++more;
        }
      if (more > 0) moved.push_back(fmt::format("... {} more", more));
    }
    s.message = fmt::format(
        "mechanism: the supports leave {} rigid-body motion(s) free ({}); free coordinates include {}. Static "
        "deflection is undefined: add supports or springs",
        rigid.Z.cols(), fmt::join(rigid.motions, "; "), fmt::join(moved, ", "));
    s.factor_seconds = seconds_since(t0);
    return s;
  }
  KktLdlt ldlt;
  ldlt.analyze(sys.K, sys.G, sys.groups);
  const bool fact = ldlt.factorize(sys.K);
  long where = -1;
  const double ratio = ldlt.smallest_primal_pivot_ratio(&where);
  s.factor_seconds = seconds_since(t0);
  if (!fact || ldlt.negative_count() != 0 || ratio < kNearMechanismPivot) {
    // A near-mechanism (rigid motions held only by soft springs): solved with those motions split
    // off (near_mechanism_solve); where there are none, K is singular for another reason.
    const NearRigid near = near_rigid_modes(model, sys);
    if (near.Z.cols() > 0) {
      const auto t1 = Clock::now();
      std::string why;
      if (near_mechanism_solve(sys, near, f, ldlt, s.z, why)) {
        const ConstraintProjector P(sys.G);
        const double fn = f.norm();
        s.residual = fn > 0 ? P(sys.K * s.z - f).norm() / fn : 0.0;
        s.near_mechanism = static_cast<int>(near.Z.cols());
        s.factor_seconds = seconds_since(t0);
        s.solve_seconds = seconds_since(t1);
        s.ok = true;
        return s;
      }
      s.message = "near-mechanism solve failed: " + why;
      return s;
    }
  }
  if (!fact || ldlt.negative_count() != 0 || ratio < 1e-14) {
    s.message = fmt::format(
        "stiffness matrix singular or indefinite: {} negative pivot(s), smallest pivot ratio {:.3g} at {}",
        fact ? ldlt.negative_count() : -1, ratio,
        where >= 0 ? coordinate_name(model, sys, where) : std::string("?"));
    return s;
  }
  const auto t1 = Clock::now();
  s.z = ldlt.solve(f);
  const ConstraintProjector P(sys.G);
  const double fn = f.norm();
  s.residual = fn > 0 ? P(sys.K * s.z - f).norm() / fn : 0.0;
  s.solve_seconds = seconds_since(t1);
  s.ok = true;
  return s;
}

}  // namespace modalbench::rfem
