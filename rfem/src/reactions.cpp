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

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <map>
#include <optional>
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

}  // namespace

SupportForces support_forces(const Model& m, const System& sys, const Eigen::VectorXd& z,
                             const std::vector<PointAction>& actions) {
  const Eigen::VectorXd q = sys.T * z, fq = detail::point_loads_q(m, actions);
  const SpMat B = detail::builder_basis(m);
  const Eigen::VectorXd f0 = B.transpose() * fq;
  const Eigen::VectorXd r0 = f0 - B.transpose() * (detail::over_q(m, detail::element_triplets(m, false)) * q);
  const detail::RigidRows rows = detail::rigid_rows(m);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(static_cast<long>(rows.links.size() + rows.holds.size()));
  SupportForces out;
  if (y.size() > 0) {
    // Normal equations (A A') y = A r0 with A = At': A A' is banded like the model (a sparse QR
    // of At took seconds on a 20000-element beam); the residual below says what they achieved.
    const SpMat At = rows_over_z0(rows, B);
    const SpMat A = At.transpose();
    const SpMat N = A * At;
    const Eigen::VectorXd rhs = A * r0;
    Eigen::SimplicialLDLT<SpMat> ldlt(N);
    const double dmax = N.diagonal().cwiseAbs().maxCoeff();
    const bool regular = ldlt.info() == Eigen::Success && (ldlt.vectorD().array() > 1e-14 * dmax).all();
    if (regular) {
      y = ldlt.solve(rhs);
    } else {
      // Redundant holds (two edges hold a plate's corner element; a support on an end's element):
      // the multipliers are not unique, their forces are. The minimum-norm ones, which share a
      // redundant force equally: (N + mu I) y = A r0 refined (each step shrinks the error of a
      // component of singular value s by mu / (s^2 + mu)); the residual below says how well.
      SpMat Nr = N;
      for (Eigen::Index i = 0; i < Nr.rows(); ++i) Nr.coeffRef(i, i) += 1e-12 * dmax;
      ldlt.compute(Nr);
      if (ldlt.info() != Eigen::Success) {
        out.residual = std::numeric_limits<double>::infinity();
        return out;
      }
      y = ldlt.solve(rhs);
      for (int step = 0; step < 4; ++step) y += ldlt.solve(Eigen::VectorXd(rhs - N * y));
    }
    const double scale = std::max(f0.norm(), r0.norm());
    out.residual = scale > 0 ? (At * y - r0).norm() / scale : 0.0;
  }
  // Per SDE to ground: the held components' multipliers, then the finite ones.
  std::map<int, Vector6d> local;
  for (const auto& [sde, name] : m.supports) local[sde] = Vector6d::Zero();
  const long nl = static_cast<long>(rows.links.size());
  for (std::size_t h = 0; h < rows.holds.size(); ++h) {
    const auto [sde, c] = rows.hold_origin[h];
    if (auto it = local.find(sde); it != local.end()) it->second[c] = -y[nl + static_cast<long>(h)];
  }
  // In the order of model.supports (a plate's edges: thousands of SDEs, looked up, not searched).
  for (const auto& [sde, name] : m.supports) {
    Vector6d& F = local.at(sde);
    const Sde& sd = m.sdes[static_cast<std::size_t>(sde)];
    // The deformation of an SDE to ground is minus its point's motion: the spring's force on the
    // model, -k times the motion, is k times the deformation.
    const Vector6d d = detail::deformation(m, sd, q);
    for (int c = 0; c < 6; ++c)
      if (!std::isinf(sd.stiffness[c])) F[c] = sd.stiffness[c] * d[c];
    SupportForce s;
    s.sde = sde;
    s.force = sd.axes * F.head<3>();
    s.moment = sd.axes * F.tail<3>();
    out.forces.push_back(s);
  }
  return out;
}

namespace {

/// support_forces with its residual as a diagnostic; nothing (and a warning saying why) where the
/// multipliers do not balance the unreduced model to 1e-8.
std::optional<SupportForces> balanced_support_forces(const Model& model, const System& sys, const Eigen::VectorXd& z,
                                                     const std::vector<PointAction>& actions, Result& r) {
  SupportForces sf = support_forces(model, sys, z, actions);
  r.summary.set_diagnostic("reaction_residual", sf.residual);
  if (sf.residual <= 1e-8) return sf;
  r.summary.warnings.push_back(fmt::format("support reactions not reported: the constraint forces balance the model "
                                           "only to {:.2g}",
                                           sf.residual));
  return std::nullopt;
}

}  // namespace

/// A beam's support reactions (support_forces) and, from them, the stress resultants at the probes
/// by the equilibrium of the free body left of each (equilibrium.hpp). Not reported where the
/// multipliers do not balance the unreduced model to 1e-8.
void detail::beam_reactions(const Scene& s, const Model& model, const System& sys, const Eigen::VectorXd& z,
                            const std::vector<PointAction>& actions, Result& r) {
  const std::optional<SupportForces> checked = balanced_support_forces(model, sys, z, actions, r);
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

void detail::plate_reactions(const Scene& s, const Model& model, const System& sys, const Eigen::VectorXd& z,
                             const std::vector<PointAction>& actions, Result& r) {
  const std::optional<SupportForces> checked = balanced_support_forces(model, sys, z, actions, r);
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
