#pragma once
// Private to rfem: the pieces of the assembly (system.cpp) that the support reactions
// (reactions.cpp) need over the builder's body DOFs q, before any reduction.

#include <Eigen/SparseCore>
#include <utility>
#include <vector>

#include "modalbench/rfem/model.hpp"

namespace modalbench::rfem::detail {

using Triplet = Eigen::Triplet<double>;
using SparseRow = std::vector<std::pair<long, double>>;  // (index over q, coefficient)

/// 6-vector of body e from the active vector q (inactive components zero).
Vector6d body_vector(const Model& m, const Eigen::VectorXd& q, int e);
/// Deformation of an SDE (local axes) under body motion q.
Vector6d deformation(const Model& m, const Sde& sd, const Eigen::VectorXd& q);

/// The rigid SDE components as rows over q: each row is the component's deformation (local axes).
struct RigidRows {
  std::vector<SparseRow> holds;                  ///< components to ground
  std::vector<std::pair<int, int>> hold_origin;  ///< per hold: its SDE and component (0..5)
  std::vector<SparseRow> links;                  ///< components between two RFEs
};
RigidRows rigid_rows(const Model& m);

/// The finite stiffness (damping = false: with the couplings) or damping of every SDE, as
/// triplets over q (rigid components left out: they are rows of rigid_rows).
std::vector<Triplet> element_triplets(const Model& m, bool damping);
/// The generalized force over q of point actions (point_loads before the reduction to z).
Eigen::VectorXd point_loads_q(const Model& m, const std::vector<std::pair<Eigen::Vector3d, Vector6d>>& actions);
/// The builder's coordinates z0 (q = B z0): its basis, or q itself.
SpMat builder_basis(const Model& m);
/// The triplets as a q x q matrix.
SpMat over_q(const Model& m, const std::vector<Triplet>& t);

}  // namespace modalbench::rfem::detail
