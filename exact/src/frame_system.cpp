#include "frame_system.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "modalbench/numerics/symmetric_factor.hpp"

namespace modalbench::exact::detail {

namespace {

using Vec3 = std::array<double, 3>;

/// The springs of a node (0: none), per global DOF.
std::array<double, 6> node_springs(const Frame& f, int node) {
  std::array<double, 6> k{};
  for (const FrameSupport& s : f.supports)
    if (s.node == node)
      for (std::size_t g = 0; g < 6; ++g) k[g] = s.springs[g];
  return k;
}

/// A node's mass per global DOF: m on the translations, Jx, Jy, Jz on the rotations.
std::array<double, 6> node_inertia(const Frame& f, int node) {
  std::array<double, 6> m{};
  for (const FrameMass& pm : f.masses)
    if (pm.node == node) {
      for (std::size_t g = 0; g < 3; ++g) m[g] += pm.mass;
      m[3] += pm.Jx;
      m[4] += pm.Jy;
      m[5] += pm.Jz;
    }
  return m;
}

bool is_bending_rotation(int dof, bool spatial) { return dof == 4 || (spatial && dof == 5); }

}  // namespace

int scaled_nullity(const Eigen::MatrixXd& K) {
  if (K.rows() == 0) return 0;
  Eigen::VectorXd d = K.diagonal().cwiseAbs();
  for (Eigen::Index i = 0; i < d.size(); ++i) d(i) = d(i) > 0 ? 1.0 / std::sqrt(d(i)) : 1.0;
  const Eigen::MatrixXd Ks = d.asDiagonal() * K * d.asDiagonal();
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Ks, Eigen::EigenvaluesOnly).eigenvalues();
  const double top = ev.cwiseAbs().maxCoeff();
  return static_cast<int>((ev.array() < 1e-12 * top).count());
}

FrameSystem::FrameSystem(const Scene& scene) : scene_(scene), frame_(*scene.frame) {
  double point_masses = 0;
  for (const FrameMass& pm : frame_.masses) point_masses += pm.mass;
  for (const FrameMember& m : frame_.members) {
    fields_.push_back(member_fields(m, frame_.spatial, scene.theory, m.length));
    const Section p = m.properties();
    const double I = frame_.spatial ? std::min(p.Iy, p.Iz) : p.Iy;
    // A member's bending scale EI / (L^3 m), m its mass and every point mass (a heavy mass on a
    // slender member sets modes far below the member's own).
    const double s = m.material.E * I / (std::pow(m.length, 3) * (m.material.rho * p.A * m.length + point_masses));
    lambda_scale_ = std::min(lambda_scale_, s);
  }
  for (std::size_t k = 0; k < frame_.nodes.size(); ++k) {
    springs_.push_back(node_springs(frame_, static_cast<int>(k)));
    inertia_.push_back(node_inertia(frame_, static_cast<int>(k)));
  }
  number_nodes();
  number_members();
  for (std::size_t m = 0; m < frame_.members.size(); ++m) member_rows_.push_back(member_rows(m));
}

void FrameSystem::number_nodes() {
  const std::vector<int> active = frame_.node_dofs();
  node_rows_.assign(frame_.nodes.size(), std::vector<Row>(6));
  for (std::size_t k = 0; k < frame_.nodes.size(); ++k) {
    const int node = static_cast<int>(k);
    const auto& springs = springs_[k];
    const auto& inertia = inertia_[k];
    std::vector<int> rotations;
    for (const int g : active) {
      if (std::isinf(springs[static_cast<std::size_t>(g)])) continue;  // held
      if (g < 3) node_rows_[k][static_cast<std::size_t>(g)].push_back({n_++, 1.0});
      else rotations.push_back(g);
    }
    if (rotations.empty()) continue;
    // What turns the node: members joined rigidly (every direction), hinged members' torsion
    // (about their axes), rotational springs and inertias (about theirs).
    Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
    for (const FrameMember& m : frame_.members)
      for (int e = 0; e < 2; ++e) {
        if (m.nodes[static_cast<std::size_t>(e)] != node) continue;
        if (!m.released[static_cast<std::size_t>(e)]) {
          C += Eigen::Matrix3d::Identity();
        } else if (frame_.spatial) {
          const Eigen::Vector3d ex(m.axes[0][0], m.axes[0][1], m.axes[0][2]);
          C += ex * ex.transpose();
        }
      }
    for (int g = 3; g < 6; ++g)
      if (springs[static_cast<std::size_t>(g)] > 0 || inertia[static_cast<std::size_t>(g)] > 0) C(g - 3, g - 3) += 1.0;
    const auto r = static_cast<Eigen::Index>(rotations.size());
    Eigen::MatrixXd Cr(r, r);
    for (Eigen::Index a = 0; a < r; ++a)
      for (Eigen::Index b = 0; b < r; ++b) Cr(a, b) = C(rotations[static_cast<std::size_t>(a)] - 3, rotations[static_cast<std::size_t>(b)] - 3);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Cr);
    const Eigen::Index kept = (es.eigenvalues().array() > 1e-9).count();
    if (kept == r) {  // every direction turns: the global axes themselves
      for (const int g : rotations) node_rows_[k][static_cast<std::size_t>(g)].push_back({n_++, 1.0});
      continue;
    }
    undefined_rotations_.push_back(frame_.nodes[k].id);
    for (Eigen::Index j = r - kept; j < r; ++j) {
      const int u = n_++;
      for (Eigen::Index a = 0; a < r; ++a)
        if (es.eigenvectors()(a, j) != 0.0)
          node_rows_[k][static_cast<std::size_t>(rotations[static_cast<std::size_t>(a)])].push_back({u, es.eigenvectors()(a, j)});
    }
  }
}

void FrameSystem::number_members() {
  own_rotations_.assign(frame_.members.size(), {});
  for (std::size_t m = 0; m < frame_.members.size(); ++m)
    for (std::size_t e = 0; e < 2; ++e)
      if (frame_.members[m].released[e])
        for (int j = 3; j < 6; ++j)
          own_rotations_[m][e].push_back({is_bending_rotation(j, frame_.spatial) ? n_++ : -1, 1.0});
}

std::vector<FrameSystem::Row> FrameSystem::member_rows(std::size_t member) const {
  const FrameMember& m = frame_.members[member];
  std::vector<Row> rows(kMemberDofs);
  for (std::size_t e = 0; e < 2; ++e)
    for (int j = 0; j < 6; ++j) {
      Row& row = rows[e * 6 + static_cast<std::size_t>(j)];
      if (m.released[e] && is_bending_rotation(j, frame_.spatial)) {
        row.push_back({own_rotations_[member][e][static_cast<std::size_t>(j - 3)].unknown, 1.0});
        continue;
      }
      // Local = axes * global, for the translations (j < 3) and the rotations alike.
      const int base = j < 3 ? 0 : 3;
      const Vec3& axis = m.axes[static_cast<std::size_t>(j % 3)];
      for (int g = 0; g < 3; ++g)
        if (axis[static_cast<std::size_t>(g)] != 0.0)
          for (const Term& t : node_rows(m.nodes[e])[static_cast<std::size_t>(base + g)])
            row.push_back({t.unknown, axis[static_cast<std::size_t>(g)] * t.c});
    }
  return rows;
}

std::vector<FrameSystem::Piece> FrameSystem::member_pieces(std::size_t member, double lambda) const {
  // As a line's count (line_system.cpp, count_below): a member whose doubling comes within
  // kCountPivot of a singular middle block (omega next to a clamped frequency of one of its
  // halvings, where the condensation loses digits and the count its sign) is cut unevenly,
  // sqrt(2) - 1 of the way, so that its pieces have other clamped frequencies; the cut is a node of
  // K(omega) (its own unknowns), so the count stays exact.
  constexpr double kCountPivot = 1e-4;
  std::vector<Piece> out;
  const FrameMember& m = frame_.members[member];
  std::function<void(double, double, int)> add = [&](double a, double b, int depth) {
    MemberStiffness ms = a == 0.0 && b == 1.0 ? member_stiffness(fields_[member], lambda)
                                              : member_stiffness(member_fields(m, frame_.spatial, scene_.theory, (b - a) * m.length), lambda);
    if (ms.min_pivot_scale < kCountPivot && ms.doubled && depth < 8) {
      const double cut = a + (b - a) * 0.41421356237309503;
      add(a, cut, depth + 1);
      add(cut, b, depth + 1);
      return;
    }
    out.push_back({a, b, std::move(ms)});
  };
  add(0.0, 1.0, 0);
  return out;
}

Eigen::MatrixXd FrameSystem::assemble(double lambda, int* clamped_below, double* log_abs_det_tdf) const {
  std::vector<std::vector<Piece>> pieces;
  // The member's DOFs its fields carry: those of a cut's node.
  const std::vector<int> carried = frame_.spatial ? std::vector<int>{0, 1, 2, 3, 4, 5} : std::vector<int>{0, 2, 4};
  int size = n_;
  for (std::size_t m = 0; m < frame_.members.size(); ++m) {
    pieces.push_back(member_pieces(m, lambda));
    size += static_cast<int>((pieces.back().size() - 1) * carried.size());
  }
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(size, size);
  int j0 = 0, next = n_;
  double ld = 0;
  for (std::size_t m = 0; m < frame_.members.size(); ++m) {
    // Rows of each piece's end DOFs: the member's own at its ends, a cut's unknowns between.
    std::vector<Row> left(member_rows_[m].begin(), member_rows_[m].begin() + 6);
    for (std::size_t p = 0; p < pieces[m].size(); ++p) {
      std::vector<Row> right(6);
      if (p + 1 == pieces[m].size()) {
        right.assign(member_rows_[m].begin() + 6, member_rows_[m].end());
      } else {
        for (const int d : carried) right[static_cast<std::size_t>(d)] = {{next++, 1.0}};
      }
      const MemberStiffness& ms = pieces[m][p].ms;
      j0 += ms.clamped_below;
      ld += ms.log_abs_det_tdf;
      for (int a = 0; a < kMemberDofs; ++a)
        for (int b = 0; b < kMemberDofs; ++b) {
          const double v = ms.K(a, b);
          if (v == 0.0) continue;
          const Row& ra = a < 6 ? left[static_cast<std::size_t>(a)] : right[static_cast<std::size_t>(a - 6)];
          const Row& rb = b < 6 ? left[static_cast<std::size_t>(b)] : right[static_cast<std::size_t>(b - 6)];
          for (const Term& ta : ra)
            for (const Term& tb : rb) K(ta.unknown, tb.unknown) += ta.c * v * tb.c;
        }
      left = std::move(right);
    }
  }
  for (std::size_t k = 0; k < frame_.nodes.size(); ++k) {
    const auto& springs = springs_[k];
    const auto& inertia = inertia_[k];
    for (std::size_t g = 0; g < 6; ++g) {
      const double v = (std::isinf(springs[g]) ? 0.0 : springs[g]) - lambda * inertia[g];
      if (v == 0.0) continue;
      for (const Term& ta : node_rows_[k][g])
        for (const Term& tb : node_rows_[k][g]) K(ta.unknown, tb.unknown) += ta.c * v * tb.c;
    }
  }
  if (clamped_below) *clamped_below = j0;
  if (log_abs_det_tdf) *log_abs_det_tdf = ld;
  return K;
}

std::pair<int, double> FrameSystem::count_det(double lambda) const {
  int j0 = 0;
  double ld = 0;
  const Eigen::MatrixXd K = assemble(lambda, &j0, &ld);
  if (K.rows() == 0) return {j0, ld};
  const SymFactor f(K);
  return {j0 + f.negative, ld + f.log_abs};
}

int FrameSystem::rigid_motions() const { return scaled_nullity(assemble(0.0)); }

std::vector<std::vector<LocalLineLoad>> FrameSystem::local_loads() const {
  std::vector<std::vector<LocalLineLoad>> out(frame_.members.size());
  for (const FrameLineLoad& q : frame_.all_line_loads(scene_.gravity)) {
    const MemberAxes& ax = frame_.members[static_cast<std::size_t>(q.member)].axes;
    LocalLineLoad l;
    for (std::size_t e = 0; e < 2; ++e) {
      const Vec3 g = {q.qx[e], q.qy[e], q.qz[e]};
      l.qx[e] = ax[0][0] * g[0] + ax[0][1] * g[1] + ax[0][2] * g[2];
      l.qy[e] = ax[1][0] * g[0] + ax[1][1] * g[1] + ax[1][2] * g[2];
      l.qz[e] = ax[2][0] * g[0] + ax[2][1] * g[1] + ax[2][2] * g[2];
    }
    out[static_cast<std::size_t>(q.member)].push_back(l);
  }
  return out;
}

}  // namespace modalbench::exact::detail
