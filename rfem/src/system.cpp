#include "modalbench/rfem/system.hpp"

#include "modalbench/rfem/factor.hpp"
#include "system_detail.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

namespace modalbench::rfem {

namespace {

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

SpMat builder_basis(const Model& m) {
  if (m.basis.cols() > 0) return m.basis;
  SpMat I(m.body_dofs(), m.body_dofs());
  I.setIdentity();
  return I;
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
  const SpMat B = detail::builder_basis(m);
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


}  // namespace modalbench::rfem
