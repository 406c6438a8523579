// The exact frame's statics: K(0) q = F, each member's fixed-end forces for its line loads, the
// members' states at the probes, and the reactions at the supported nodes with their balance.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "frame_system.hpp"

namespace modalbench::exact::detail {

namespace {

using Vec3 = std::array<double, 3>;

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

/// Global components of a member-axes 6-vector (translations, then rotations or moments).
std::array<double, 6> to_global(const MemberAxes& ax, const double* local) {
  std::array<double, 6> g{};
  for (std::size_t b = 0; b < 2; ++b)
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t j = 0; j < 3; ++j) g[3 * b + i] += ax[j][i] * local[3 * b + j];
  return g;
}

/// Sums of forces and of moments about the origin, with the sum of their sizes (the imbalance's scale).
struct Balance {
  Vec3 force{}, moment{};
  double scale = 0;
  void add(const Vec3& at, const Vec3& f, const Vec3& m) {
    const Vec3 r = cross(at, f);
    for (std::size_t i = 0; i < 3; ++i) {
      force[i] += f[i];
      moment[i] += m[i] + r[i];
    }
    scale += std::hypot(f[0], f[1], f[2]) + std::hypot(m[0], m[1], m[2]) + std::hypot(r[0], r[1], r[2]);
  }
  double relative() const {
    const double e = std::hypot(force[0], force[1], force[2]) + std::hypot(moment[0], moment[1], moment[2]);
    return scale > 0 ? e / scale : 0.0;
  }
};

}  // namespace

FrameSystem::Statics FrameSystem::statics() const {
  const Eigen::MatrixXd K = assemble(0.0);  // lambda = 0: no doubling, so no member is cut
  if (K.rows() != n_) throw std::logic_error("frame statics: K(0) has cut members");
  if (const int free = scaled_nullity(K); free > 0)
    throw std::runtime_error(fmt::format("mechanism: the supports and hinges leave {} rigid motion(s) of the frame "
                                         "free (K(0) is singular)",
                                         free));
  Eigen::VectorXd F = Eigen::VectorXd::Zero(n_);
  Balance bal;
  const std::vector<FrameLoad> node_loads = frame_.all_node_loads(scene_.gravity);
  for (const FrameLoad& p : node_loads) {
    for (std::size_t g = 0; g < 6; ++g)
      for (const Term& t : node_rows(p.node)[g]) F(t.unknown) += t.c * p.F[g];
    bal.add(frame_.nodes[static_cast<std::size_t>(p.node)].x, {p.F[0], p.F[1], p.F[2]}, {p.F[3], p.F[4], p.F[5]});
  }
  // A node moment in a direction nothing turns (every member hinged there) has nothing to resist it.
  for (const FrameLoad& p : node_loads)
    for (std::size_t g = 3; g < 6; ++g)
      if (p.F[g] != 0.0 && node_rows(p.node)[g].empty()) {
        bool held = false;
        for (const FrameSupport& s : frame_.supports) held = held || (s.node == p.node && std::isinf(s.springs[g]));
        if (!held)
          throw std::runtime_error(fmt::format("mechanism: a moment at node '{}' where every member is hinged and "
                                               "nothing else turns it",
                                               frame_.nodes[static_cast<std::size_t>(p.node)].id));
      }
  const auto loads = local_loads();
  std::vector<Eigen::VectorXd> fixed(frame_.members.size());
  for (std::size_t m = 0; m < frame_.members.size(); ++m) {
    fixed[m] = fixed_end_forces(fields_[m], loads[m]);
    for (int a = 0; a < kMemberDofs; ++a)
      for (const Term& t : member_rows_[m][static_cast<std::size_t>(a)]) F(t.unknown) -= t.c * fixed[m](a);
  }
  for (const FrameLineLoad& q : frame_.all_line_loads(scene_.gravity)) {
    const FrameMember& m = frame_.members[static_cast<std::size_t>(q.member)];
    // The line load's resultant and moment: linear intensity, 2-point Gauss exact.
    for (const double s : {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)}) {
      const auto at = [s](const std::array<double, 2>& v) { return v[0] + (v[1] - v[0]) * s; };
      const double w = 0.5 * m.length;
      bal.add(frame_.point_on(m, s), {w * at(q.qx), w * at(q.qy), w * at(q.qz)}, {0, 0, 0});
    }
  }
  const Eigen::VectorXd q = K.ldlt().solve(F);
  Statics out;
  if (!q.allFinite()) throw std::runtime_error("statics: the solve gave non-finite displacements");
  // No load on any unknown (every load on held DOFs): q = 0 exactly, nothing to be wrong.
  const double scale = K.norm() * q.norm() + F.norm();
  out.backward_error = scale > 0 ? (K * q - F).norm() / scale : 0.0;
  const auto value = [&q](const Row& row) {
    double v = 0;
    for (const Term& t : row) v += t.c * q(t.unknown);
    return v;
  };
  // Each member's end displacements and the forces its nodes exert on it, in its axes.
  std::vector<Eigen::VectorXd> d(frame_.members.size()), P(frame_.members.size());
  for (std::size_t m = 0; m < frame_.members.size(); ++m) {
    d[m] = Eigen::VectorXd(kMemberDofs);
    for (int a = 0; a < kMemberDofs; ++a) d[m](a) = value(member_rows_[m][static_cast<std::size_t>(a)]);
    P[m] = member_stiffness(fields_[m], 0.0).K * d[m] + fixed[m];
  }
  for (const FrameSupport& s : frame_.supports) {
    std::array<double, 6> r{};
    for (std::size_t m = 0; m < frame_.members.size(); ++m)
      for (std::size_t e = 0; e < 2; ++e)
        if (frame_.members[m].nodes[e] == s.node) {
          const auto g = to_global(frame_.members[m].axes, P[m].data() + 6 * e);
          for (std::size_t c = 0; c < 6; ++c) r[c] += g[c];
        }
    for (const FrameLoad& p : node_loads)
      if (p.node == s.node)
        for (std::size_t c = 0; c < 6; ++c) r[c] -= p.F[c];
    const std::vector<int> active = frame_.node_dofs();
    for (std::size_t c = 0; c < 6; ++c) {
      const bool carried = std::find(active.begin(), active.end(), static_cast<int>(c)) != active.end();
      if (!carried || s.springs[c] == 0.0) r[c] = 0.0;
      else if (!std::isinf(s.springs[c])) r[c] = -s.springs[c] * value(node_rows(s.node)[c]);
    }
    if (std::all_of(s.springs.begin(), s.springs.end(), [](double k) { return k == 0.0; })) continue;
    Reaction rc;
    rc.support = frame_.nodes[static_cast<std::size_t>(s.node)].id;
    rc.point = frame_.nodes[static_cast<std::size_t>(s.node)].x;
    rc.position = {rc.point[0], rc.point[2]};
    rc.force = {r[0], r[1], r[2]};
    rc.moment = {r[3], r[4], r[5]};
    bal.add(rc.point, rc.force, rc.moment);
    out.reactions.push_back(rc);
  }
  out.imbalance = bal.relative();
  for (const FrameProbe& p : frame_.probes) {
    std::array<double, 6> g{};
    if (p.node >= 0) {
      for (std::size_t c = 0; c < 6; ++c) g[c] = value(node_rows(p.node)[c]);
      out.probes.push_back(frame_deflection(frame_, p, g));
      continue;
    }
    const auto m = static_cast<std::size_t>(p.member);
    const MemberState st = member_state(fields_[m], loads[m], d[m], P[m], p.s);
    Deflection df = frame_deflection(frame_, p, to_global(frame_.members[m].axes, st.d.data()));
    df.has_forces = true;
    df.forces = st.forces;
    out.probes.push_back(df);
  }
  return out;
}

}  // namespace modalbench::exact::detail
