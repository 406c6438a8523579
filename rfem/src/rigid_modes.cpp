// rfem rigid-body motions: the free ones no spring, support or coupling resists (a structural
// test over the elements' six rigid motions), and the near-rigid ones held only by finite springs
// to ground, solved in their own subspace (system.hpp).
#include "modalbench/rfem/system.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "system_detail.hpp"

namespace modalbench::rfem {

namespace {
using detail::body_vector;
using detail::deformation;
}  // namespace

namespace {
/// The six rigid motions of the elements about their mean centre (active DOFs), over q.
void rigid_candidates(const Model& m, std::vector<Eigen::VectorXd>& cand, std::vector<std::string>& cand_names) {
  const double L = m.length_scale;
  const int na = m.dofs_per_element();
  const long nq = m.body_dofs();
  Eigen::Vector3d c0 = Eigen::Vector3d::Zero();
  for (const auto& e : m.elements) c0 += e.centre;
  c0 /= static_cast<double>(m.elements.size());
  static const char* kNames[6] = {"translation x", "translation y", "translation z",
                                  "rotation about x", "rotation about y", "rotation about z"};
  for (int c = 0; c < 6; ++c) {
    const Vector6d e6 = Vector6d::Unit(c) * (c < 3 ? 1.0 : 1.0 / L);
    Eigen::VectorXd q(nq);
    for (std::size_t e = 0; e < m.elements.size(); ++e) {
      const Vector6d v = attached_motion(m.elements[e].centre - c0, e6);
      for (int k = 0; k < na; ++k) q[static_cast<long>(e) * na + k] = v[m.active[static_cast<std::size_t>(k)]];
    }
    if (q.norm() > 1e-12 * std::sqrt(static_cast<double>(m.elements.size()))) {
      cand.push_back(q);
      cand_names.push_back(kNames[c]);
    }
  }
}
}  // namespace

namespace {
/// Adds each coupling block's deformation under the candidate motions to A'A (normalized by the
/// block's norm and the length scale, like the SDE rows).
template <class Mat>
void add_coupling_deformation(const Model& m, const std::vector<Eigen::VectorXd>& cand, Mat& AtA) {
  const double L = m.length_scale;
  const long nc = static_cast<long>(cand.size());
  const Eigen::MatrixXd* last = nullptr;  // couplings of a regular grid share their block
  double nk = 0;
  Eigen::MatrixXd V, F;
  for (const Coupling& cp : m.couplings) {
    if (cp.stiffness.get() != last) last = cp.stiffness.get(), nk = last->norm();
    if (nk == 0) continue;
    V.resize(6 * static_cast<long>(cp.elements.size()), nc);
    for (long j = 0; j < nc; ++j)
      for (std::size_t i = 0; i < cp.elements.size(); ++i)
        V.block<6, 1>(6 * static_cast<long>(i), j) = body_vector(m, cand[static_cast<std::size_t>(j)], cp.elements[i]);
    F.noalias() = *last * V;
    AtA.noalias() += (L / nk) * (L / nk) * (F.transpose() * F);
  }
}
}  // namespace

namespace {
/// Below this an eigenvalue of a deformation Gram matrix (AtA over candidate rigid motions) is
/// null to rounding. The measure is geometric (every component's rows count alike, normalized to
/// a unit motion), so a motion that deforms anything scores of order one, and one that deforms
/// nothing scores the eigensolver's rounding: eps times the largest eigenvalue, or one. An
/// absolute 1e-9 on the square root (1e-18 on the eigenvalue) was below that rounding: a beam on
/// one soft spring lost its rigid rotation at 5.2e-18 once the products were compiled with FMA.
double deformation_null_floor(const Eigen::VectorXd& eigenvalues) {
  return 64.0 * static_cast<double>(eigenvalues.size()) * std::numeric_limits<double>::epsilon() *
         std::max(eigenvalues.cwiseAbs().maxCoeff(), 1.0);
}
}  // namespace

RigidModes free_rigid_modes(const Model& m, const System& sys) {
  const double L = m.length_scale;
  const long nq = m.body_dofs();
  std::vector<Eigen::VectorXd> cand;
  std::vector<std::string> cand_names;
  rigid_candidates(m, cand, cand_names);
  RigidModes out;
  out.Z.resize(sys.n(), 0);
  if (cand.empty()) return out;
  const long nc = static_cast<long>(cand.size());

  // Deformation of every stiff component under each candidate: A' A accumulated directly.
  // At most six candidates: fixed-capacity storage keeps the loop over the SDEs off the heap.
  using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
  Small AtA = Small::Zero(nc, nc);
  Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6> def(6, nc);
  for (const Sde& sd : m.sdes) {
    for (long j = 0; j < nc; ++j) def.col(j) = deformation(m, sd, cand[static_cast<std::size_t>(j)]);
    for (int c = 0; c < 6; ++c) {
      if (sd.stiffness[c] == 0) continue;
      const Eigen::Matrix<double, 1, Eigen::Dynamic, Eigen::RowMajor, 1, 6> r = def.row(c) * (c < 3 ? 1.0 : L);
      AtA.noalias() += r.transpose() * r;
    }
  }
  add_coupling_deformation(m, cand, AtA);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es{Eigen::MatrixXd(AtA)};
  if (es.info() != Eigen::Success)
    throw std::runtime_error("rfem: the eigensolver of the rigid-motion test failed (no convergence)");
  std::vector<long> null_cols;
  const double floor = deformation_null_floor(es.eigenvalues());
  for (long i = 0; i < nc; ++i)
    if (es.eigenvalues()[i] <= floor) null_cols.push_back(i);
  if (null_cols.empty()) return out;

  Eigen::MatrixXd Cq(nq, nc);
  for (long j = 0; j < nc; ++j) Cq.col(j) = cand[static_cast<std::size_t>(j)];
  // Least-squares map to z (T has full column rank): (T'T) z = T' q.
  SpMat TtT = sys.T.transpose() * sys.T;
  Eigen::SimplicialLDLT<SpMat> ldlt(TtT);
  if (ldlt.info() != Eigen::Success) throw std::runtime_error("rfem: T'T factorization failed");
  std::vector<Eigen::VectorXd> zs;
  for (long i : null_cols) {
    const Eigen::VectorXd nv = es.eigenvectors().col(i);
    const Eigen::VectorXd q = Cq * nv;
    const Eigen::VectorXd z = ldlt.solve(sys.T.transpose() * q);
    if ((sys.T * z - q).norm() > 1e-8 * q.norm()) continue;  // not representable (held)
    zs.push_back(z);
    std::string desc;
    for (long j = 0; j < nc; ++j)
      if (std::abs(nv[j]) > 1e-6) desc += (desc.empty() ? "" : " + ") + cand_names[static_cast<std::size_t>(j)];
    out.motions.push_back(desc);
  }
  if (zs.empty()) return out;
  Eigen::MatrixXd Z(sys.n(), static_cast<long>(zs.size()));
  for (std::size_t i = 0; i < zs.size(); ++i) Z.col(static_cast<long>(i)) = zs[i];
  const Eigen::MatrixXd S = Z.transpose() * (sys.M * Z);
  Eigen::LLT<Eigen::MatrixXd> llt(S);
  if (llt.info() != Eigen::Success) throw std::runtime_error("rfem: rigid-mode Gram matrix not positive definite");
  out.Z = llt.matrixU().solve<Eigen::OnTheRight>(Z);  // Z U^{-1}: M-orthonormal
  return out;
}

namespace {

/// The candidates' deformation: A'A of the components between elements, the springs to ground as rows.
void split_deformation(const Model& m, const std::vector<Eigen::VectorXd>& cand, Eigen::MatrixXd& internal,
                       std::vector<Eigen::RowVectorXd>& ground_rows, std::vector<Eigen::RowVectorXd>& ground_shape) {
  const double L = m.length_scale;
  const long nc = static_cast<long>(cand.size());
  // Internal deformation (SDEs between elements, couplings), as in free_rigid_modes, and the
  // energy of the finite springs to ground; a spring to ground that is rigid is a held support.
  // The ground springs are kept as rows sqrt(k) d' (d: the spring's deformation under each
  // candidate), not summed into d k d': springs of 1e19 and 1 N/m on one beam (pinned at one end
  // by the stiff one, rocking on the soft one) leave the soft pair in the rounding of the sum.
  Eigen::MatrixXd def(6, nc);
  for (const Sde& sd : m.sdes) {
    for (long j = 0; j < nc; ++j) def.col(j) = deformation(m, sd, cand[static_cast<std::size_t>(j)]);
    for (int c = 0; c < 6; ++c) {
      const double k = sd.stiffness[c];
      if (k == 0) continue;
      if (sd.b == kGround && std::isfinite(k)) {
        if (def.row(c).squaredNorm() > 0) {
          ground_rows.push_back(std::sqrt(k) * def.row(c));
          ground_shape.push_back(def.row(c) * (c < 3 ? 1.0 : L));
        }
      } else if (sd.b != kGround) {
        const Eigen::RowVectorXd r = def.row(c) * (c < 3 ? 1.0 : L);
        internal.noalias() += r.transpose() * r;
      }
    }
  }
}

/// The combinations deforming nothing inside, representable over z (Z, coefficients C); false if none.
bool internal_null_space(const System& sys, const std::vector<Eigen::VectorXd>& cand, const Eigen::MatrixXd& internal,
                         Eigen::MatrixXd& Z, Eigen::MatrixXd& C) {
  const long nc = static_cast<long>(cand.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(internal);
  if (es.info() != Eigen::Success) return false;
  // Combinations that deform nothing inside, representable over z (not held by a rigid support).
  SpMat TtT = sys.T.transpose() * sys.T;
  Eigen::SimplicialLDLT<SpMat> ldlt(TtT);
  if (ldlt.info() != Eigen::Success) return false;
  std::vector<Eigen::VectorXd> zs, coef;
  const double floor = deformation_null_floor(es.eigenvalues());
  for (long i = 0; i < nc; ++i) {
    if (!(es.eigenvalues()[i] <= floor)) continue;
    const Eigen::VectorXd nv = es.eigenvectors().col(i);
    Eigen::VectorXd q = Eigen::VectorXd::Zero(cand[0].size());
    for (long j = 0; j < nc; ++j) q += nv[j] * cand[static_cast<std::size_t>(j)];
    const Eigen::VectorXd z = ldlt.solve(sys.T.transpose() * q);
    if ((sys.T * z - q).norm() > 1e-8 * q.norm()) continue;
    zs.push_back(z);
    coef.push_back(nv);
  }
  const long r = static_cast<long>(zs.size());
  if (r == 0) return false;
  Z.resize(sys.n(), r);
  C.resize(nc, r);
  for (long i = 0; i < r; ++i) {
    Z.col(i) = zs[static_cast<std::size_t>(i)];
    C.col(i) = coef[static_cast<std::size_t>(i)];
  }
  return true;
}

/// Keeps in Z and C only the combinations that a spring to ground holds; false where none is.
bool leave_out_free_motions(const System& sys, const std::vector<Eigen::RowVectorXd>& ground_shape, Eigen::MatrixXd& Z,
                            Eigen::MatrixXd& C) {
  const long r = Z.cols();
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(r, r);
  for (const Eigen::RowVectorXd& g : ground_shape) {
    const Eigen::RowVectorXd gc = g * C;
    W.noalias() += gc.transpose() * gc;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ws(W);
  if (ws.info() != Eigen::Success) return false;
  std::vector<long> held, free;
  const double held_floor = deformation_null_floor(ws.eigenvalues());
  for (long i = 0; i < r; ++i) (ws.eigenvalues()[i] > held_floor ? held : free).push_back(i);
  if (held.empty()) return false;
  Eigen::MatrixXd E(r, static_cast<long>(held.size())), F(r, static_cast<long>(free.size()));
  for (std::size_t i = 0; i < held.size(); ++i) E.col(static_cast<long>(i)) = ws.eigenvectors().col(held[i]);
  for (std::size_t i = 0; i < free.size(); ++i) F.col(static_cast<long>(i)) = ws.eigenvectors().col(free[i]);
  // Near-rigid modes are M-orthogonal to the free rigid ones (K is zero on those): the held
  // combinations less their M-projection on the free ones, which deforms no spring either. The
  // Euclidean complement alone gave a bar rocking on one end spring sqrt(1.5 k / m) for 2 sqrt(k / m).
  if (!free.empty()) {
    const Eigen::MatrixXd Mz = Z.transpose() * (sys.M * Z);
    const Eigen::MatrixXd Mff = F.transpose() * Mz * F, Mfh = F.transpose() * Mz * E;
    E -= F * Mff.ldlt().solve(Mfh);
  }
  C = C * E;
  Z = Z * E;
  return true;
}

/// The near-rigid pairs (out.lambda, out.Z), ascending; false, and out untouched, where one fails.
bool near_rigid_pairs(const System& sys, const std::vector<Eigen::RowVectorXd>& ground_rows, const Eigen::MatrixXd& Z,
                      const Eigen::MatrixXd& C, NearRigid& out) {
  const long r = Z.cols();
  const Eigen::MatrixXd Mr = Z.transpose() * (sys.M * Z);
  const Eigen::LLT<Eigen::MatrixXd> llt(0.5 * (Mr + Mr.transpose()));
  if (llt.info() != Eigen::Success) return false;
  const Eigen::MatrixXd Uinv = llt.matrixU().solve(Eigen::MatrixXd::Identity(r, r));
  std::vector<Eigen::RowVectorXd> rows;
  rows.reserve(ground_rows.size());
  for (const Eigen::RowVectorXd& g : ground_rows) rows.push_back(g * C * Uinv);
  std::sort(rows.begin(), rows.end(), [](const Eigen::RowVectorXd& a, const Eigen::RowVectorXd& b) {
    return a.squaredNorm() > b.squaredNorm();
  });
  Eigen::MatrixXd B(static_cast<long>(std::max<std::size_t>(rows.size(), static_cast<std::size_t>(r))), r);
  B.setZero();
  for (std::size_t i = 0; i < rows.size(); ++i) B.row(static_cast<long>(i)) = rows[i];
  const Eigen::JacobiSVD<Eigen::MatrixXd, Eigen::FullPivHouseholderQRPreconditioner> svd(B, Eigen::ComputeFullV);
  if (svd.info() != Eigen::Success) return false;
  // Ascending (the SVD's order is descending).
  const Eigen::VectorXd& sv = svd.singularValues();
  std::vector<long> keep;
  for (long i = r - 1; i >= 0; --i)
    if (sv[i] > 0) keep.push_back(i);
  out.lambda.resize(static_cast<long>(keep.size()));
  out.Z.resize(sys.n(), static_cast<long>(keep.size()));
  for (std::size_t k = 0; k < keep.size(); ++k) {
    out.lambda[static_cast<long>(k)] = sv[keep[k]] * sv[keep[k]];
    out.Z.col(static_cast<long>(k)) = Z * (Uinv * svd.matrixV().col(keep[k]));  // M-orthonormal
  }
  return true;
}

/// Every finite spring component to ground as a functional over z, with its stiffness (out.springs).
void add_ground_springs(const Model& m, const System& sys, NearRigid& out) {
  // The ground springs' deformation functionals over z (body DOFs of element a, then T').
  const int na = m.dofs_per_element();
  Eigen::VectorXd q = Eigen::VectorXd::Zero(m.body_dofs());
  for (const Sde& sd : m.sdes) {
    if (sd.b != kGround) continue;
    Eigen::Matrix<double, 6, Eigen::Dynamic> D(6, na);
    for (int j = 0; j < na; ++j) {
      const long idx = static_cast<long>(sd.a) * na + j;
      q[idx] = 1.0;
      D.col(j) = deformation(m, sd, q);
      q[idx] = 0.0;
    }
    for (int c = 0; c < 6; ++c) {
      const double k = sd.stiffness[c];
      if (!(k > 0) || !std::isfinite(k) || D.row(c).squaredNorm() == 0) continue;
      Eigen::SparseVector<double> rq(m.body_dofs());
      for (int j = 0; j < na; ++j)
        if (D(c, j) != 0) rq.insert(static_cast<long>(sd.a) * na + j) = D(c, j);
      out.springs.push_back({k, Eigen::SparseVector<double>(sys.T.transpose() * rq)});
    }
  }
}

}  // namespace

NearRigid near_rigid_modes(const Model& m, const System& sys) {
  NearRigid out;
  out.Z.resize(sys.n(), 0);
  std::vector<Eigen::VectorXd> cand;
  std::vector<std::string> names;
  rigid_candidates(m, cand, names);
  const long nc = static_cast<long>(cand.size());
  if (nc == 0) return out;
  Eigen::MatrixXd internal = Eigen::MatrixXd::Zero(nc, nc);
  std::vector<Eigen::RowVectorXd> ground_rows, ground_shape;
  split_deformation(m, cand, internal, ground_rows, ground_shape);
  if (ground_rows.empty()) return out;
  add_coupling_deformation(m, cand, internal);
  Eigen::MatrixXd Z, C;
  if (!internal_null_space(sys, cand, internal, Z, C)) return out;
  // Rayleigh-Ritz: K_r = B' B with B = [sqrt(k) d'] C, M_r = U' U. The eigenvalues of K_r c =
  // lambda M_r c are the squared singular values of B U^-1, taken by a QR with full pivoting on
  // the rows sorted by decreasing norm, then Jacobi: a row-graded matrix keeps its small singular
  // values to relative accuracy that way (Demmel and Veselic; Cox and Higham), where forming
  // B' B would lose every one below eps times the largest.
  // The free rigid motions (no spring deformed at all: free_rigid_modes' structural test, without
  // the stiffnesses) are left out first, so every singular value below is a near-rigid pair's,
  // however small the soft springs are against the stiff ones.
  if (!leave_out_free_motions(sys, ground_shape, Z, C)) return out;
  if (!near_rigid_pairs(sys, ground_rows, Z, C, out)) return out;
  if (out.lambda.size() > 0) add_ground_springs(m, sys, out);
  return out;
}

}  // namespace modalbench::rfem
