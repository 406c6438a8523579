// A dtfm plate's support reactions from its static solution (detail::plate_reactions).
//
// Short edges (x0, xL): the generalized forces their end conditions exert on the fields, summed
// into a resultant about the edge's middle with the rigid motions of the section (w_j = 1 for the
// force; w_j = y_j - b/2, theta_x = 1 for the moment about x; theta_y = 1 about y).
//
// Long edges (y0, yB): their held fields are not fields of the model, so their reactions come from
// virtual work. With the energy U = 1/2 e^T P e + e^T X q + 1/2 q^T Q1 q, e = q' + S q
// (prism_model.hpp), a variation dq that moves only the held fields of the edge's line as a rigid
// body (dq: w = 1; or w = -(x - a/2), theta_y = 1; or theta_x = 1) has de = 0, so the work the
// supports do on it is
//   R(dq) = int (X^T e + Q1 q)^T dq dx - int p^T dq dx,
// the rows of X and Q1 for the held fields taken from the model with the long edges free
// (PrismModel::free_long_edges), q the solution with the held fields zero, and
//   int e dx = q(a) - q(0) + S int q dx,   int (x - a/2) e dx = a/2 (q(a) + q(0)) - int q + S int (x - a/2) q,
// from the field integrals of the solve (FieldIntegrals). The forces of the short edges' end
// conditions on the held line (a corner) are part of it: the corners go to the long edges. Springs
// along an edge exert -k w per unit length.
#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>
#include <string>
#include <vector>

#include "plate_reactions.hpp"
#include "modalbench/dtfm/dtfm.hpp"
#include "modalbench/rigid_kinematics.hpp"

namespace modalbench::dtfm::detail {

namespace {

/// The resultant {Fz, Mx, My} about (xc, yc) of generalized forces F over the fields at x = xc.
std::array<double, 3> section_resultant(const PrismModel& m, const Eigen::VectorXd& F, double yc) {
  std::array<double, 3> r{0, 0, 0};
  for (int k = 0; k < m.m; ++k) {
    const double y = m.prisms[static_cast<std::size_t>(m.field_prism[static_cast<std::size_t>(k)])].y;
    switch (m.field_dof[static_cast<std::size_t>(k)]) {
      case dofs::Uz:
        r[0] += F[k];
        r[1] += (y - yc) * F[k];
        break;
      case dofs::Rx: r[1] += F[k]; break;
      case dofs::Ry: r[2] += F[k]; break;
      default: break;
    }
  }
  return r;
}

/// A reduced model's field vector in the free-edge model's fields (held fields zero).
Eigen::VectorXd embed(const PrismModel& m, const PrismModel& full, const Eigen::VectorXd& v) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(full.m);
  for (int k = 0; k < m.m; ++k)
    out[full.field(m.field_prism[static_cast<std::size_t>(k)], m.field_dof[static_cast<std::size_t>(k)])] = v[k];
  return out;
}

/// int p dx and int (x - a/2) p dx over the free-edge model's fields.
std::pair<Eigen::VectorXd, Eigen::VectorXd> load_integrals(const Scene& s, const PrismModel& full) {
  const double a = full.length;
  Eigen::VectorXd p0 = Eigen::VectorXd::Zero(full.m), p1 = Eigen::VectorXd::Zero(full.m);
  for (const PointLoad& l : s.all_point_loads()) {
    const Eigen::VectorXd f = full.load_vector(l);
    p0 += f;
    p1 += (l.x - a / 2) * f;
  }
  for (const DistributedLoad& d : s.all_distributed_loads()) {
    const Eigen::VectorXd f = full.pressure_vector(d);
    const double x1 = d.from[0], x2 = d.to[0];
    p0 += (x2 - x1) * f;
    p1 += 0.5 * ((x2 - a / 2) * (x2 - a / 2) - (x1 - a / 2) * (x1 - a / 2)) * f;
  }
  return {p0, p1};
}

/// The supports at points at x from the generalized forces of their node: each acts through the
/// spread of a point action at its (x, y) (PrismModel::load_vector: Fz, Mx, My on its two strip
/// lines), so the forces are S lambda with S the spreads of the components it restrains.
void add_point_reactions(const Scene& s, const PrismModel& m, double x, const Eigen::VectorXd& F,
                         std::vector<Reaction>& out) {
  std::vector<std::pair<std::size_t, int>> cols;  // (support, component 0: Fz, 1: Mx, 2: My)
  for (std::size_t i = 0; i < s.point_supports.size(); ++i) {
    const PointSupport& p = s.point_supports[i];
    if (std::abs(p.x - x) > 1e-12 * m.length) continue;
    if (p.support.translational > 0) cols.emplace_back(i, 0);
    if (p.support.rotational > 0) cols.emplace_back(i, 1), cols.emplace_back(i, 2);
  }
  if (cols.empty()) return;
  Eigen::MatrixXd S(m.m, static_cast<Eigen::Index>(cols.size()));
  for (std::size_t c = 0; c < cols.size(); ++c) {
    PointLoad unit;
    unit.y = s.point_supports[cols[c].first].y;
    (cols[c].second == 0 ? unit.Fz : cols[c].second == 1 ? unit.Mx : unit.My) = 1.0;
    S.col(static_cast<Eigen::Index>(c)) = m.load_vector(unit);
  }
  const Eigen::VectorXd lambda = S.colPivHouseholderQr().solve(F);
  for (std::size_t c = 0; c < cols.size(); ++c) {
    const PointSupport& p = s.point_supports[cols[c].first];
    const std::string name = "points[" + std::to_string(cols[c].first) + "]";
    auto it = std::find_if(out.begin(), out.end(), [&](const Reaction& r) { return r.support == name; });
    if (it == out.end()) it = out.insert(out.end(), Reaction{name, {p.x, p.y}, {0, 0, 0}, {0, 0, 0}});
    const double v = lambda[static_cast<Eigen::Index>(c)];
    if (cols[c].second == 0) it->force[2] = v;
    else it->moment[static_cast<std::size_t>(cols[c].second - 1)] = v;
  }
}

}  // namespace

std::vector<Reaction> plate_reactions(const Scene& s, const PrismModel& m, const FieldIntegrals& fi) {
  std::vector<Reaction> out;
  const double a = s.geometry.length, b = s.geometry.width;
  for (const auto& [x, F] : fi.node_forces) {
    const bool at0 = std::abs(x) <= 1e-12 * a, atL = std::abs(x - a) <= 1e-12 * a;
    if (!at0 && !atL) {
      add_point_reactions(s, m, x, F, out);
      continue;
    }
    if (!(at0 && !s.x0.is_free()) && !(atL && !s.xL.is_free())) continue;
    const std::array<double, 3> r = section_resultant(m, F, b / 2);
    out.push_back({at0 ? "x0" : "xL", {x, b / 2}, {0, 0, r[0]}, {r[1], r[2], 0}});
  }
  const PrismModel* full = m.free_long_edges.get();
  Eigen::VectorXd rho0, rho1, p0, p1;
  if (full) {
    const Eigen::VectorXd Q = embed(m, *full, fi.q), XQ = embed(m, *full, fi.xq);
    const Eigen::VectorXd q0 = embed(m, *full, fi.q0), qL = embed(m, *full, fi.qL);
    const Eigen::VectorXd e0 = qL - q0 + full->S * Q, e1 = 0.5 * a * (qL + q0) - Q + full->S * XQ;
    rho0 = full->X.transpose() * e0 + full->Q1 * Q;
    rho1 = full->X.transpose() * e1 + full->Q1 * XQ;
    std::tie(p0, p1) = load_integrals(s, *full);
  }
  const int lines = m.ny;
  for (int side = 0; side < 2; ++side) {
    const Support& e = side == 0 ? s.y0 : s.yB;
    if (e.is_free()) continue;
    const int j = side == 0 ? 0 : lines - 1;
    const double y = side == 0 ? 0.0 : b;
    Reaction r{side == 0 ? "y0" : "yB", {a / 2, y}, {0, 0, 0}, {0, 0, 0}};
    // Held fields: the virtual work of the line's rigid motions.
    auto work0 = [&](int dof) { const int k = full->field(j, dof); return rho0[k] - p0[k]; };
    auto work1 = [&](int dof) { const int k = full->field(j, dof); return rho1[k] - p1[k]; };
    if (std::isinf(e.translational)) {
      r.force[2] = work0(dofs::Uz);
      r.moment[1] = -work1(dofs::Uz) + work0(dofs::Ry);
    }
    if (std::isinf(e.rotational)) r.moment[0] = work0(dofs::Rx);
    // Springs: -k times the field, per unit length.
    if (const int k = m.field(j, dofs::Uz); k >= 0 && e.translational > 0) {
      r.force[2] = -e.translational * fi.q[k];
      r.moment[1] = e.translational * fi.xq[k];
    }
    if (const int k = m.field(j, dofs::Rx); k >= 0 && e.rotational > 0) r.moment[0] = -e.rotational * fi.q[k];
    out.push_back(r);
  }
  return out;
}

}  // namespace modalbench::dtfm::detail
