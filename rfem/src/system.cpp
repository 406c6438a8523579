#include "modalbench/rfem/system.hpp"

#include "modalbench/rfem/factor.hpp"
#include "system_detail.hpp"

#include <fmt/format.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

namespace modalbench::rfem {

namespace {

using detail::body_vector;
using detail::deformation;
using detail::SparseRow;
using detail::Triplet;

Matrix6d block_rotation(const Eigen::Matrix3d& R) {
  Matrix6d Rb = Matrix6d::Zero();
  Rb.topLeftCorner<3, 3>() = R;
  Rb.bottomRightCorner<3, 3>() = R;
  return Rb;
}

/// Master-slave elimination of held components: z0 = S z.
class Eliminator {
 public:
  explicit Eliminator(long n0) : expr_(static_cast<std::size_t>(n0)), slave_(static_cast<std::size_t>(n0), 0) {}

  /// Adds the constraint row . z0 = 0. Returns false if it was redundant.
  bool add(const SparseRow& row) {
    std::map<long, double> acc;
    double scale = 0;
    for (auto [j, c] : row) {
      scale = std::max(scale, std::abs(c));
      expand(j, c, acc);
    }
    long s = -1;
    double best = 0;
    for (auto [j, c] : acc)
      if (std::abs(c) > best) best = std::abs(c), s = j;
    if (s < 0 || best <= 1e-12 * scale) return false;
    SparseRow e;
    for (auto [j, c] : acc)
      if (j != s && std::abs(c) > 1e-14 * best) e.emplace_back(j, -c / acc[s]);
    expr_[static_cast<std::size_t>(s)] = std::move(e);
    slave_[static_cast<std::size_t>(s)] = 1;
    return true;
  }

  bool is_slave(long j) const { return slave_[static_cast<std::size_t>(j)] != 0; }

  /// S with z0 = S z over the free coordinates (in their original order).
  SpMat substitution(std::vector<long>& free_index) const {
    const long n0 = static_cast<long>(slave_.size());
    free_index.assign(static_cast<std::size_t>(n0), -1);
    long nf = 0;
    for (long j = 0; j < n0; ++j)
      if (!is_slave(j)) free_index[static_cast<std::size_t>(j)] = nf++;
    std::vector<Triplet> t;
    for (long j = 0; j < n0; ++j) {
      if (!is_slave(j)) {
        t.emplace_back(j, free_index[static_cast<std::size_t>(j)], 1.0);
        continue;
      }
      std::map<long, double> acc;
      expand(j, 1.0, acc);
      for (auto [k, c] : acc)
        if (c != 0.0) t.emplace_back(j, free_index[static_cast<std::size_t>(k)], c);
    }
    SpMat S(n0, nf);
    S.setFromTriplets(t.begin(), t.end());
    return S;
  }

 private:
  // acc += c * (z0_j expressed in the currently free coordinates).
  void expand(long j, double c, std::map<long, double>& acc) const {
    if (!is_slave(j)) {
      acc[j] += c;
      return;
    }
    for (auto [k, ck] : expr_[static_cast<std::size_t>(j)]) expand(k, c * ck, acc);
  }

  std::vector<SparseRow> expr_;
  std::vector<char> slave_;
};

}  // namespace

namespace detail {

/// 6-vector of body e from the active vector q (inactive components zero).
Vector6d body_vector(const Model& m, const Eigen::VectorXd& q, int e) {
  Vector6d v = Vector6d::Zero();
  const int na = m.dofs_per_element();
  for (int k = 0; k < na; ++k) v[m.active[static_cast<std::size_t>(k)]] = q[static_cast<long>(e) * na + k];
  return v;
}

/// Deformation of an SDE (local axes) under body motion q.
Vector6d deformation(const Model& m, const Sde& sd, const Eigen::VectorXd& q) {
  const Eigen::Vector3d ra = sd.point - m.elements[static_cast<std::size_t>(sd.a)].centre;
  if (sd.b == kGround) return sde_deformation(ra, body_vector(m, q, sd.a), ra, Vector6d::Zero(), sd.axes);
  return sde_deformation(ra, body_vector(m, q, sd.a), sd.point - m.elements[static_cast<std::size_t>(sd.b)].centre,
                         body_vector(m, q, sd.b), sd.axes);
}

RigidRows rigid_rows(const Model& m) {
  const int na = m.dofs_per_element();
  RigidRows out;
  // Active entries of a row over one body's 6-vector, as a sparse row over q.
  auto rows_of = [&](const Eigen::Matrix<double, 1, 6>& r, int body, SparseRow& row) {
    for (int k = 0; k < na; ++k) {
      const double v = r[m.active[static_cast<std::size_t>(k)]];
      if (v != 0.0) row.emplace_back(static_cast<long>(body) * na + k, v);
    }
  };
  for (std::size_t i = 0; i < m.sdes.size(); ++i) {
    const Sde& sd = m.sdes[i];
    std::vector<int> rigid;
    for (int c = 0; c < 6; ++c)
      if (std::isinf(sd.stiffness[c])) rigid.push_back(c);
    if (rigid.empty()) continue;
    const Matrix6d Rt = block_rotation(sd.axes).transpose();
    const Matrix6d Wa = Rt * attachment(sd.point - m.elements[static_cast<std::size_t>(sd.a)].centre);
    if (sd.b == kGround) {
      for (int c : rigid) {
        SparseRow row;
        rows_of(Wa.row(c), sd.a, row);
        if (row.empty()) continue;
        out.holds.push_back(std::move(row));
        out.hold_origin.emplace_back(static_cast<int>(i), c);
      }
    } else {
      const Matrix6d Wb = Rt * attachment(sd.point - m.elements[static_cast<std::size_t>(sd.b)].centre);
      for (int c : rigid) {
        SparseRow row;
        rows_of(-Wa.row(c), sd.a, row);
        rows_of(Wb.row(c), sd.b, row);
        if (!row.empty()) out.links.push_back(std::move(row));
      }
    }
  }
  return out;
}

std::vector<Triplet> element_triplets(const Model& m, bool damping) {
  const int na = m.dofs_per_element();
  std::vector<Triplet> t;
  if (!damping) t.reserve(static_cast<std::size_t>(m.sdes.size()) * 4 * na * na + m.couplings.size() * 16 * na * na);
  auto scatter_q = [&](const Eigen::MatrixXd& Ke, const std::vector<int>& bodies) {
    const int nb = static_cast<int>(bodies.size());
    for (int bi = 0; bi < nb; ++bi)
      for (int i = 0; i < na; ++i) {
        const long qi = static_cast<long>(bodies[static_cast<std::size_t>(bi)]) * na + i;
        for (int bj = 0; bj < nb; ++bj)
          for (int j = 0; j < na; ++j) {
            const double v = Ke(bi * na + i, bj * na + j);
            if (v != 0.0) t.emplace_back(qi, static_cast<long>(bodies[static_cast<std::size_t>(bj)]) * na + j, v);
          }
      }
  };
  for (const Sde& sd : m.sdes) {
    Vector6d k = damping ? sd.damping : sd.stiffness;
    for (int c = 0; c < 6; ++c)
      if (std::isinf(k[c])) k[c] = 0;  // rigid components are constraints, not stiffness
    if (!k.any()) continue;
    const Eigen::Vector3d ra = sd.point - m.elements[static_cast<std::size_t>(sd.a)].centre;
    if (sd.b == kGround) {
      scatter_q(restrict_dofs(sde_to_ground(ra, sd.axes, k), m.active), {sd.a});
    } else {
      const Eigen::Vector3d rb = sd.point - m.elements[static_cast<std::size_t>(sd.b)].centre;
      scatter_q(restrict_dofs(sde_stiffness(ra, rb, sd.axes, k), m.active), {sd.a, sd.b});
    }
  }
  if (damping) return t;
  std::map<const Eigen::MatrixXd*, Eigen::MatrixXd> restricted;  // shared blocks restricted once
  for (const Coupling& cp : m.couplings) {
    auto it = restricted.find(cp.stiffness.get());
    if (it == restricted.end()) it = restricted.emplace(cp.stiffness.get(), restrict_dofs(*cp.stiffness, m.active)).first;
    scatter_q(it->second, cp.elements);
  }
  return t;
}

SpMat over_q(const Model& m, const std::vector<Triplet>& t) {
  SpMat A(m.body_dofs(), m.body_dofs());
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

}  // namespace detail

System assemble(const Model& m) {
  m.check();
  const int na = m.dofs_per_element();
  const long nq = m.body_dofs();
  // Rigid components -> held rows (to ground) and constraint rows (between RFEs).
  const detail::RigidRows rigid = detail::rigid_rows(m);
  const std::vector<SparseRow>& holds = rigid.holds;
  const std::vector<SparseRow>& links = rigid.links;

  // Generalized coordinates of the builder (or q itself), then the held ones eliminated: q = T z.
  SpMat B;
  if (m.basis.cols() > 0) {
    B = m.basis;
  } else {
    B.resize(nq, nq);
    B.setIdentity();
  }
  const Eigen::SparseMatrix<double, Eigen::RowMajor> Brow = B;
  auto to_z0 = [&](const SparseRow& row) {
    std::map<long, double> acc;
    for (auto [i, c] : row)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(Brow, i); it; ++it)
        acc[it.col()] += c * it.value();
    return SparseRow(acc.begin(), acc.end());
  };
  System sys;
  Eliminator elim(B.cols());
  for (const auto& h : holds)
    if (elim.add(to_z0(h))) ++sys.held;
  std::vector<long> free_index;
  sys.T = B * elim.substitution(free_index);
  sys.T.makeCompressed();
  for (std::size_t j = 0; j < free_index.size(); ++j)
    if (free_index[j] >= 0) sys.origin.push_back(static_cast<long>(j));
  const long n = sys.T.cols();
  std::vector<int> element_group(m.elements.size(), -1);
  int groups = 0;
  for (long i = 0; i < n; ++i) {
    const int first = sys.T.outerIndexPtr()[i];
    if (first == sys.T.outerIndexPtr()[i + 1]) {  // moves no element: a group of its own
      sys.groups.push_back(groups++);
      continue;
    }
    int& g = element_group[static_cast<std::size_t>(sys.T.innerIndexPtr()[first] / na)];
    if (g < 0) g = groups++;
    sys.groups.push_back(g);
  }
  const Eigen::SparseMatrix<double, Eigen::RowMajor> Tr = sys.T;
  const int* tp = Tr.outerIndexPtr();
  const int* ti = Tr.innerIndexPtr();
  const double* tv = Tr.valuePtr();

  // Element matrices over q, then K_z = T' K T (T has few entries per row: the product costs
  // about nnz(K); scattering each element entry through T would cost that times the square of T's
  // row lengths).
  const std::vector<Triplet> tk = detail::element_triplets(m, false), tc = detail::element_triplets(m, true);
  Eigen::VectorXd mass(nq);
  for (std::size_t e = 0; e < m.elements.size(); ++e)
    for (int k = 0; k < na; ++k) {
      const int d = m.active[static_cast<std::size_t>(k)];
      const auto& r = m.elements[e];
      mass[static_cast<long>(e) * na + k] = d < 3 ? r.mass : r.inertia[d - 3];
    }
  const SpMat Tt = sys.T.transpose();
  auto reduce = [&](const std::vector<Triplet>& t) {
    SpMat Az = Tt * detail::over_q(m, t) * sys.T;
    Az.makeCompressed();
    return Az;
  };
  sys.K = reduce(tk);
  sys.C = reduce(tc);
  sys.M = Tt * mass.asDiagonal() * sys.T;
  sys.M.makeCompressed();

  // Rigid links between RFEs: constraint rows over z, normalised, dependent ones dropped.
  std::vector<Triplet> tg;
  long rows = 0;
  for (const SparseRow& link : links) {
    std::map<long, double> acc;
    double orig = 0;
    for (auto [i, c] : link) {
      orig += c * c;
      for (int p = tp[i]; p < tp[i + 1]; ++p) acc[ti[p]] += c * tv[p];
    }
    double norm2 = 0;
    for (auto [j, c] : acc) norm2 += c * c;
    if (norm2 <= 1e-24 * orig) {
      ++sys.redundant;
      continue;
    }
    const double scale = 1.0 / std::sqrt(norm2);
    for (auto [j, c] : acc)
      if (c != 0.0) tg.emplace_back(rows, j, c * scale);
    ++rows;
  }
  SpMat G(rows, n);
  G.setFromTriplets(tg.begin(), tg.end());
  const std::vector<long> dep = dependent_rows(G);
  if (!dep.empty()) {
    std::vector<long> newrow(static_cast<std::size_t>(rows), 0);
    for (long r : dep) newrow[static_cast<std::size_t>(r)] = -1;
    long nr = 0;
    for (auto& v : newrow)
      if (v == 0) v = nr++;
    std::vector<Triplet> kept;
    for (const auto& t : tg)
      if (newrow[static_cast<std::size_t>(t.row())] >= 0)
        kept.emplace_back(newrow[static_cast<std::size_t>(t.row())], t.col(), t.value());
    sys.redundant += static_cast<long>(dep.size());
    G.resize(nr, n);
    G.setFromTriplets(kept.begin(), kept.end());
  }
  sys.G = G;
  sys.G.makeCompressed();
  return sys;
}

std::string coordinate_name(const Model& m, const System& sys, long i) {
  const long j = sys.origin.at(static_cast<std::size_t>(i));
  return m.basis.cols() > 0 ? m.basis_names.at(static_cast<std::size_t>(j)) : m.dof_name(j);
}


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

NearRigid near_rigid_modes(const Model& m, const System& sys) {
  NearRigid out;
  out.Z.resize(sys.n(), 0);
  const double L = m.length_scale;
  std::vector<Eigen::VectorXd> cand;
  std::vector<std::string> names;
  rigid_candidates(m, cand, names);
  const long nc = static_cast<long>(cand.size());
  if (nc == 0) return out;
  // Internal deformation (SDEs between elements, couplings), as in free_rigid_modes, and the
  // energy of the finite springs to ground; a spring to ground that is rigid is a held support.
  // The ground springs are kept as rows sqrt(k) d' (d: the spring's deformation under each
  // candidate), not summed into d k d': springs of 1e19 and 1 N/m on one beam (pinned at one end
  // by the stiff one, rocking on the soft one) leave the soft pair in the rounding of the sum.
  Eigen::MatrixXd internal = Eigen::MatrixXd::Zero(nc, nc);
  std::vector<Eigen::RowVectorXd> ground_rows, ground_shape;
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
  if (ground_rows.empty()) return out;
  add_coupling_deformation(m, cand, internal);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(internal);
  if (es.info() != Eigen::Success) return out;
  // Combinations that deform nothing inside, representable over z (not held by a rigid support).
  SpMat TtT = sys.T.transpose() * sys.T;
  Eigen::SimplicialLDLT<SpMat> ldlt(TtT);
  if (ldlt.info() != Eigen::Success) return out;
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
  long r = static_cast<long>(zs.size());
  if (r == 0) return out;
  Eigen::MatrixXd Z(sys.n(), r), C(nc, r);
  for (long i = 0; i < r; ++i) {
    Z.col(i) = zs[static_cast<std::size_t>(i)];
    C.col(i) = coef[static_cast<std::size_t>(i)];
  }
  // Rayleigh-Ritz: K_r = B' B with B = [sqrt(k) d'] C, M_r = U' U. The eigenvalues of K_r c =
  // lambda M_r c are the squared singular values of B U^-1, taken by a QR with full pivoting on
  // the rows sorted by decreasing norm, then Jacobi: a row-graded matrix keeps its small singular
  // values to relative accuracy that way (Demmel and Veselic; Cox and Higham), where forming
  // B' B would lose every one below eps times the largest.
  // The free rigid motions (no spring deformed at all: free_rigid_modes' structural test, without
  // the stiffnesses) are left out first, so every singular value below is a near-rigid pair's,
  // however small the soft springs are against the stiff ones.
  {
    Eigen::MatrixXd W = Eigen::MatrixXd::Zero(r, r);
    for (const Eigen::RowVectorXd& g : ground_shape) {
      const Eigen::RowVectorXd gc = g * C;
      W.noalias() += gc.transpose() * gc;
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ws(W);
    if (ws.info() != Eigen::Success) return out;
    std::vector<long> held;
    const double held_floor = deformation_null_floor(ws.eigenvalues());
    for (long i = 0; i < r; ++i)
      if (ws.eigenvalues()[i] > held_floor) held.push_back(i);
    if (held.empty()) return out;
    Eigen::MatrixXd E(r, static_cast<long>(held.size()));
    for (std::size_t i = 0; i < held.size(); ++i) E.col(static_cast<long>(i)) = ws.eigenvectors().col(held[i]);
    C = C * E;
    Z = Z * E;
    r = static_cast<long>(held.size());
  }
  const Eigen::MatrixXd Mr = Z.transpose() * (sys.M * Z);
  const Eigen::LLT<Eigen::MatrixXd> llt(0.5 * (Mr + Mr.transpose()));
  if (llt.info() != Eigen::Success) return out;
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
  if (svd.info() != Eigen::Success) return out;
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
  // The ground springs' deformation functionals over z (body DOFs of element a, then T').
  if (!keep.empty()) {
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
  return out;
}

}  // namespace modalbench::rfem
