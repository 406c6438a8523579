// rfem support reactions: the forces the supports' SDEs to ground exert in a static solution.
// Finite components are -k times the motion of their point; a held component was eliminated from
// the solve, so its force is the multiplier that balances the unreduced model: over the builder's
// coordinates z0 (q = B z0),
//   B' (f_q - K_q q) = L' mu + H' lambda,
// L the rigid links between elements, H the holds, K_q the finite stiffness; solved in the least-
// squares sense (normal equations), exact where the rows are independent. A beam's stress resultants
// at its probes then follow from the reactions by the free body (beam_reactions).
#include "modalbench/rfem/analysis.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseQR>

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include "modalbench/equilibrium.hpp"
#include "modalbench/rfem/system.hpp"
#include "analysis_detail.hpp"
#include "system_detail.hpp"

namespace modalbench::rfem {

namespace {

/// The rigid rows as columns over z0 (rows over q times B), links first.
SpMat rows_over_z0(const detail::RigidRows& rows, const SpMat& B) {
  const Eigen::SparseMatrix<double, Eigen::RowMajor> Brow = B;
  std::vector<Eigen::Triplet<double>> t;
  long col = 0;
  auto add = [&](const detail::SparseRow& row) {
    std::map<long, double> acc;
    for (auto [i, c] : row)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(Brow, i); it; ++it) acc[it.col()] += c * it.value();
    for (auto [j, c] : acc)
      if (c != 0.0) t.emplace_back(j, col, c);
    ++col;
  };
  for (const auto& r : rows.links) add(r);
  for (const auto& r : rows.holds) add(r);
  SpMat At(B.cols(), col);
  At.setFromTriplets(t.begin(), t.end());
  At.makeCompressed();
  return At;
}

/// The columns of At (links first, then holds) that hold each element, by element.
std::map<int, std::vector<long>> holds_by_element(const Model& m, const detail::RigidRows& rows, long nl) {
  std::map<int, std::vector<long>> out;
  for (std::size_t h = 0; h < rows.holds.size(); ++h)
    out[m.sdes[static_cast<std::size_t>(rows.hold_origin[h].first)].a].push_back(nl + static_cast<long>(h));
  return out;
}

/// The columns `cols` of At as a dense matrix over the rows any of them touches.
Eigen::MatrixXd dense_columns(const SpMat& At, const std::vector<long>& cols) {
  std::map<long, long> slot;
  for (long c : cols)
    for (SpMat::InnerIterator it(At, c); it; ++it) slot.emplace(it.row(), 0);
  long k = 0;
  for (auto& [r, i] : slot) i = k++;
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(k, static_cast<long>(cols.size()));
  for (std::size_t j = 0; j < cols.size(); ++j)
    for (SpMat::InnerIterator it(At, cols[j]); it; ++it) G(slot.at(it.row()), static_cast<long>(j)) = it.value();
  return G;
}

/// Whether the last column of G depends on the others.
bool depends(const Eigen::MatrixXd& G) {
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(G);
  qr.setThreshold(1e-10);
  return qr.rank() < G.cols();
}

/// The rigid rows that repeat others, whose multipliers are set aside (zero): a hold that repeats
/// the other holds of its element (two edges on a plate's corner element, a support on a beam end's
/// element), and a link whose constraint the holds of its two elements already impose (between two
/// elements of a held plate edge). Their forces are not determined by the model's statics: the link's
/// moves force along the held edge (or between two edges through the corner element), which the
/// elastic limit does not fix either; with zero there, every edge's total is its elements' load plus
/// what the free elements pass to them. A minimum-norm solve instead routed 5 % of a rectangle's
/// load from its long edges to its short ones through the corners.
std::vector<bool> redundant_rows(const Model& m, const detail::RigidRows& rows, const SpMat& At) {
  const long nl = static_cast<long>(rows.links.size());
  std::vector<bool> out(static_cast<std::size_t>(At.cols()), false);
  const auto holds = holds_by_element(m, rows, nl);
  const int na = m.dofs_per_element();
  for (const auto& [element, cols] : holds)  // in order: the first holds stay
    for (std::size_t j = 1; j < cols.size(); ++j) {
      std::vector<long> trial;
      for (std::size_t k = 0; k <= j; ++k)
        if (k == j || !out[static_cast<std::size_t>(cols[k])]) trial.push_back(cols[k]);
      out[static_cast<std::size_t>(cols[j])] = depends(dense_columns(At, trial));
    }
  for (long l = 0; l < nl; ++l) {
    std::set<int> bodies;
    for (auto [i, c] : rows.links[static_cast<std::size_t>(l)]) bodies.insert(static_cast<int>(i / na));
    std::vector<long> trial;
    for (int b : bodies)
      if (auto it = holds.find(b); it != holds.end())
        for (long c : it->second)
          if (!out[static_cast<std::size_t>(c)]) trial.push_back(c);
    if (trial.empty()) continue;
    trial.push_back(l);
    out[static_cast<std::size_t>(l)] = depends(dense_columns(At, trial));
  }
  return out;
}

/// Solves At y = r0 in the least-squares sense by the normal equations over the rows that are not
/// redundant (their normal matrix is then regular); a hold set aside shares its element's force
/// with the others by their minimum-norm multipliers. `residual` gets ||At y - r0|| / scale (inf:
/// the normal matrix is singular still).
Eigen::VectorXd multipliers(const Model& m, const detail::RigidRows& rows, const SpMat& At, const Eigen::VectorXd& r0,
                            double scale, double& residual) {
  const long n = At.cols(), nl = static_cast<long>(rows.links.size());
  const std::vector<bool> redundant = redundant_rows(m, rows, At);
  std::vector<long> index;
  for (long j = 0; j < n; ++j)
    if (!redundant[static_cast<std::size_t>(j)]) index.push_back(j);
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t k = 0; k < index.size(); ++k)
    for (SpMat::InnerIterator it(At, index[k]); it; ++it) t.emplace_back(it.row(), static_cast<long>(k), it.value());
  SpMat Ak(At.rows(), static_cast<long>(index.size()));
  Ak.setFromTriplets(t.begin(), t.end());
  // Normal equations (A A') y = A r0 with A = Ak': banded like the model (a sparse QR of At took
  // seconds on a 20000-element beam); the residual below says what they achieved.
  const SpMat A = Ak.transpose();
  const SpMat N = A * Ak;
  Eigen::SimplicialLDLT<SpMat> ldlt(N);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(n);
  const double dmax = N.size() > 0 ? N.diagonal().cwiseAbs().maxCoeff() : 0.0;
  if (ldlt.info() != Eigen::Success || (ldlt.vectorD().array().abs() <= 1e-14 * dmax).any()) {
    residual = std::numeric_limits<double>::infinity();
    return y;
  }
  const Eigen::VectorXd rhs = A * r0;
  Eigen::VectorXd yk = ldlt.solve(rhs);
  yk += ldlt.solve(Eigen::VectorXd(rhs - N * yk));  // one refinement step
  for (std::size_t k = 0; k < index.size(); ++k) y[index[k]] = yk[static_cast<long>(k)];
  for (const auto& [element, cols] : holds_by_element(m, rows, nl)) {
    bool shared = false;
    for (long c : cols) shared = shared || redundant[static_cast<std::size_t>(c)];
    if (!shared) continue;
    const Eigen::MatrixXd G = dense_columns(At, cols);
    Eigen::VectorXd yg(static_cast<long>(cols.size()));
    for (std::size_t j = 0; j < cols.size(); ++j) yg[static_cast<long>(j)] = y[cols[j]];
    const Eigen::VectorXd even = G.completeOrthogonalDecomposition().solve(Eigen::VectorXd(G * yg));
    for (std::size_t j = 0; j < cols.size(); ++j) y[cols[j]] = even[static_cast<long>(j)];
  }
  residual = scale > 0 ? (At * y - r0).norm() / scale : 0.0;
  return y;
}

/// Where the holds of the edges pin the columns of the builder's basis they touch, each a point's w
/// (as many independent edge holds as columns touched: a Kirchhoff plate's held edges in corner-value
/// coordinates), their reactions need no multipliers: the force at each pinned point is the
/// generalized reaction -r0 there, unique whatever the holds' redundancy (an edge's 2 (n + 1) holds
/// pin its n + 2 values). A point pinned by the holds of several SDEs (a corner, held by two edges)
/// gives each an equal share. The holds of supports at points then take the rest by their
/// multipliers (least squares over the columns not pinned). Per SDE, held components only (global
/// axes, about its point); nothing where the edges do not pin their columns.
std::optional<std::map<int, SupportForce>> pinned_point_forces(const Model& m, const detail::RigidRows& rows,
                                                               const SpMat& Ah, const Eigen::VectorXd& r0,
                                                               double scale, double& residual) {
  if (m.basis_points.empty() || !rows.links.empty() || rows.holds.empty()) return std::nullopt;
  std::map<int, std::string> name_of;
  for (const auto& [sde, name] : m.supports) name_of[sde] = name;
  std::vector<long> edge_holds, point_holds;
  for (long h = 0; h < Ah.cols(); ++h) {
    const auto it = name_of.find(rows.hold_origin[static_cast<std::size_t>(h)].first);
    if (it == name_of.end()) return std::nullopt;  // a hold that stands for no scene support
    (it->second.rfind("points[", 0) == 0 ? point_holds : edge_holds).push_back(h);
  }
  std::map<long, std::set<int>> pinned_by;  // column -> SDEs whose edge holds touch it
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t k = 0; k < edge_holds.size(); ++k)
    for (SpMat::InnerIterator it(Ah, edge_holds[k]); it; ++it) {
      pinned_by[it.row()].insert(rows.hold_origin[static_cast<std::size_t>(edge_holds[k])].first);
      t.emplace_back(it.row(), static_cast<long>(k), it.value());
    }
  SpMat Ae(Ah.rows(), static_cast<long>(edge_holds.size()));
  Ae.setFromTriplets(t.begin(), t.end());
  Ae.makeCompressed();
  Eigen::SparseQR<SpMat, Eigen::COLAMDOrdering<int>> qr(Ae);
  if (qr.info() != Eigen::Success || static_cast<std::size_t>(qr.rank()) != pinned_by.size()) return std::nullopt;
  std::map<int, SupportForce> out;
  for (const auto& [sde, name] : m.supports) out[sde].sde = sde;
  Eigen::VectorXd rest = r0;
  for (const auto& [col, sdes] : pinned_by) {
    rest[col] = 0;
    const Eigen::Vector3d F(0, 0, -r0[col] / static_cast<double>(sdes.size()));
    const Eigen::Vector3d& P = m.basis_points[static_cast<std::size_t>(col)];
    for (int sde : sdes) {
      out[sde].force += F;
      out[sde].moment += (P - m.sdes[static_cast<std::size_t>(sde)].point).cross(F);
    }
  }
  if (!point_holds.empty()) {
    std::map<long, long> slot;  // the unpinned columns the point holds touch
    for (long h : point_holds)
      for (SpMat::InnerIterator it(Ah, h); it; ++it)
        if (!pinned_by.count(it.row())) slot.emplace(it.row(), 0);
    long k = 0;
    for (auto& [col, i] : slot) i = k++;
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(k, static_cast<long>(point_holds.size()));
    Eigen::VectorXd g(k);
    for (std::size_t j = 0; j < point_holds.size(); ++j)
      for (SpMat::InnerIterator it(Ah, point_holds[j]); it; ++it)
        if (auto sl = slot.find(it.row()); sl != slot.end()) G(sl->second, static_cast<long>(j)) = it.value();
    for (const auto& [col, i] : slot) g[i] = rest[col];
    const Eigen::VectorXd lambda = G.completeOrthogonalDecomposition().solve(g);
    const Eigen::VectorXd Gl = G * lambda;
    for (const auto& [col, i] : slot) rest[col] -= Gl[i];
    std::map<int, Vector6d> local;
    for (std::size_t j = 0; j < point_holds.size(); ++j) {
      const auto [sde, c] = rows.hold_origin[static_cast<std::size_t>(point_holds[j])];
      local.try_emplace(sde, Vector6d::Zero()).first->second[c] = -lambda[static_cast<long>(j)];
    }
    for (auto& [sde, F] : local) {
      const Sde& sd = m.sdes[static_cast<std::size_t>(sde)];
      out[sde].force += sd.axes * F.head<3>();
      out[sde].moment += sd.axes * F.tail<3>();
    }
  }
  residual = scale > 0 ? rest.norm() / scale : 0.0;
  return out;
}

/// The held components' forces per SDE of a support (global axes, about its point), from the
/// multipliers of the rigid rows.
std::map<int, SupportForce> multiplier_forces(const Model& m, const detail::RigidRows& rows, const SpMat& At,
                                              const Eigen::VectorXd& r0, double scale, double& residual) {
  const long nl = static_cast<long>(rows.links.size());
  const Eigen::VectorXd y = multipliers(m, rows, At, r0, scale, residual);
  std::map<int, Vector6d> local;
  for (const auto& [sde, name] : m.supports) local[sde] = Vector6d::Zero();
  for (std::size_t h = 0; h < rows.holds.size(); ++h) {
    const auto [sde, c] = rows.hold_origin[h];
    if (auto it = local.find(sde); it != local.end()) it->second[c] = -y[nl + static_cast<long>(h)];
  }
  std::map<int, SupportForce> out;
  for (const auto& [sde, F] : local) {
    const Sde& sd = m.sdes[static_cast<std::size_t>(sde)];
    out[sde] = {sde, sd.axes * F.head<3>(), sd.axes * F.tail<3>()};
  }
  return out;
}

}  // namespace

SupportForces support_forces(const Model& m, const System& sys, const Eigen::VectorXd& z,
                             const std::vector<PointAction>& actions) {
  return support_forces_q(m, sys, z, detail::point_loads_q(m, actions));
}

SupportForces support_forces_q(const Model& m, const System& sys, const Eigen::VectorXd& z, const Eigen::VectorXd& fq) {
  const Eigen::VectorXd q = sys.T * z;
  const SpMat B = detail::builder_basis(m);
  const Eigen::VectorXd f0 = B.transpose() * fq;
  const SpMat Kq = detail::over_q(m, detail::element_triplets(m, false));
  const Eigen::VectorXd r0 = f0 - B.transpose() * (Kq * q);
  const detail::RigidRows rows = detail::rigid_rows(m);
  SupportForces out;
  const Eigen::VectorXd terms = SpMat(B.cwiseAbs()).transpose() * (SpMat(Kq.cwiseAbs()) * q.cwiseAbs() + fq.cwiseAbs());
  std::map<int, SupportForce> held;
  if (!rows.links.empty() || !rows.holds.empty()) {
    const SpMat At = rows_over_z0(rows, B);
    const double scale = std::max(f0.norm(), r0.norm());
    out.rounding = scale > 0 ? std::numeric_limits<double>::epsilon() * terms.norm() / scale : 0.0;
    // The holds' columns alone (pinned_point_forces runs only where there are no links).
    const SpMat Ah = At.rightCols(static_cast<long>(rows.holds.size()));
    if (auto pinned = pinned_point_forces(m, rows, Ah, r0, scale, out.residual)) held = std::move(*pinned);
    else held = multiplier_forces(m, rows, At, r0, scale, out.residual);
    if (!std::isfinite(out.residual)) return out;
  }
  // In the order of model.supports (a plate's edges: thousands of SDEs, looked up, not searched):
  // the held components' forces, then the finite ones'.
  for (const auto& [sde, name] : m.supports) {
    const Sde& sd = m.sdes[static_cast<std::size_t>(sde)];
    // The deformation of an SDE to ground is minus its point's motion: the spring's force on the
    // model, -k times the motion, is k times the deformation.
    const Vector6d d = detail::deformation(m, sd, q);
    Vector6d F = Vector6d::Zero();
    for (int c = 0; c < 6; ++c)
      if (!std::isinf(sd.stiffness[c])) F[c] = sd.stiffness[c] * d[c];
    SupportForce s{sde, sd.axes * F.head<3>(), sd.axes * F.tail<3>()};
    if (auto it = held.find(sde); it != held.end()) {
      s.force += it->second.force;
      s.moment += it->second.moment;
    }
    out.forces.push_back(s);
  }
  return out;
}

namespace {

/// support_forces with its residual and rounding floor as diagnostics; nothing (and a warning
/// saying why) where the multipliers do not balance the unreduced model to 1e-8 or, where the
/// balance's own terms are larger (stiff springs carrying small motions), to 64 times its rounding
/// floor: beyond that the balance failed, within it the reactions carry that floor's rounding.
std::optional<SupportForces> balanced_support_forces(const Model& model, const System& sys, const Eigen::VectorXd& z,
                                                     const Eigen::VectorXd& fq, Result& r) {
  SupportForces sf = support_forces_q(model, sys, z, fq);
  r.summary.set_diagnostic("reaction_residual", sf.residual);
  r.summary.set_diagnostic("reaction_rounding_floor", sf.rounding);
  const double allowed = std::max(1e-8, 64.0 * sf.rounding);
  if (sf.residual <= allowed) return sf;
  r.summary.warnings.push_back(fmt::format("support reactions not reported: the constraint forces balance the model "
                                           "only to {:.2g}, above {:.2g} (64 times the balance's rounding floor, at "
                                           "least 1e-8)",
                                           sf.residual, allowed));
  return std::nullopt;
}

}  // namespace

/// A beam's support reactions (support_forces) and, from them, the stress resultants at the probes
/// by the equilibrium of the free body left of each (equilibrium.hpp). Not reported where the
/// multipliers do not balance the unreduced model to 1e-8.
void detail::beam_reactions(const Scene& s, const Model& model, const System& sys, const Eigen::VectorXd& z,
                            const std::vector<PointAction>& actions, Result& r) {
  const std::optional<SupportForces> checked = balanced_support_forces(model, sys, z, detail::point_loads_q(model, actions), r);
  if (!checked) return;
  const SupportForces& sf = *checked;
  for (std::size_t i = 0; i < sf.forces.size(); ++i) {
    const SupportForce& f = sf.forces[i];
    const Sde& sd = model.sdes[static_cast<std::size_t>(f.sde)];
    r.reactions.push_back({model.supports[i].second, {sd.point.x(), 0.0}, {f.force.x(), f.force.y(), f.force.z()},
                           {f.moment.x(), f.moment.y(), f.moment.z()}});
  }
  for (Deflection& d : r.deflections) {
    d.forces = free_body_forces(s, r.reactions, d.position[0]);
    d.has_forces = true;
  }
}

void detail::frame_reactions(const Frame& f, const Model& model, const System& sys, const Eigen::VectorXd& z,
                             const Eigen::VectorXd& fq, Result& r) {
  const std::optional<SupportForces> checked = balanced_support_forces(model, sys, z, fq, r);
  if (!checked) return;
  for (std::size_t i = 0; i < checked->forces.size(); ++i) {
    const SupportForce& sf = checked->forces[i];
    const std::string& id = model.supports[i].second;
    const auto node = std::find_if(f.nodes.begin(), f.nodes.end(), [&](const FrameNode& n) { return n.id == id; });
    Reaction rc;
    rc.support = id;
    rc.point = node->x;
    rc.position = {rc.point[0], rc.point[2]};
    rc.force = {sf.force.x(), sf.force.y(), sf.force.z()};
    rc.moment = {sf.moment.x(), sf.moment.y(), sf.moment.z()};
    r.reactions.push_back(rc);
  }
}

void detail::plate_reactions(const Scene& s, const Model& model, const System& sys, const Eigen::VectorXd& z,
                             const std::vector<PointAction>& actions, Result& r) {
  const std::optional<SupportForces> checked = balanced_support_forces(model, sys, z, detail::point_loads_q(model, actions), r);
  if (!checked) return;
  const SupportForces& sf = *checked;
  const double a = s.geometry.length, b = s.geometry.width;
  const std::map<std::string, Eigen::Vector3d> middles = {
      {"x0", {0, b / 2, 0}}, {"xL", {a, b / 2, 0}}, {"y0", {a / 2, 0, 0}}, {"yB", {a / 2, b, 0}}};
  for (std::size_t i = 0; i < sf.forces.size(); ++i) {
    const std::string& name = model.supports[i].second;
    const Sde& sd = model.sdes[static_cast<std::size_t>(sf.forces[i].sde)];
    const auto mid = middles.find(name);
    const Eigen::Vector3d at = mid != middles.end() ? mid->second : sd.point;
    // The SDE's force at its point, moved to the reaction's point.
    const Eigen::Vector3d F = sf.forces[i].force, M = sf.forces[i].moment + (sd.point - at).cross(F);
    auto it = std::find_if(r.reactions.begin(), r.reactions.end(), [&](const Reaction& e) { return e.support == name; });
    if (it == r.reactions.end()) {
      r.reactions.push_back({name, {at.x(), at.y()}, {0, 0, 0}, {0, 0, 0}});
      it = r.reactions.end() - 1;
    }
    for (int c = 0; c < 3; ++c) {
      it->force[static_cast<std::size_t>(c)] += F[c];
      it->moment[static_cast<std::size_t>(c)] += M[c];
    }
  }
}

}  // namespace modalbench::rfem
