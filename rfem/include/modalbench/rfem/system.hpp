#pragma once
// The assembled and reduced rfem system over generalized coordinates z (q = T z).
//
// Assembly: K = sum of SDE stiffnesses G' Rb k Rb' G (core's sde_stiffness) and couplings,
// C alike with the dampings, M = diag over the RFEs (all over the active body DOFs q).
// Reduction: rigid components to ground (held DOFs) are eliminated exactly by master-slave
// substitution (the slave is the coordinate with the largest coefficient; the others stay
// free), giving q = T z; then K_z = T' K T, M_z = T' M T, C_z = T' C T. Rigid components
// between two RFEs become constraint rows G z = 0 (Lagrange multipliers in every solve); rows
// made linearly dependent by the holds (e.g. a clamped corner of a Kirchhoff plate) are
// dropped after a rank-revealing sparse QR.

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <string>
#include <utility>
#include <vector>

#include "modalbench/rfem/model.hpp"
#include "modalbench/scene.hpp"

namespace modalbench::rfem {

struct System {
  SpMat K, M, C;  ///< over z, full symmetric storage
  SpMat G;        ///< independent constraint rows (unit 2-norm), m x n; m = 0 without rigid links
  SpMat T;        ///< q = T z
  std::vector<long> origin;        ///< per coordinate z: its index among the builder's coordinates
  /// Per coordinate z: the rigid element of its first entry in T (numbered 0, 1, ... in order of
  /// appearance). Fill-reducing orderings eliminate an element's coordinates together.
  std::vector<int> groups;
  long held = 0;                   ///< coordinates removed by rigid supports
  long redundant = 0;              ///< rigid constraints dropped as dependent
  long n() const { return static_cast<long>(K.rows()); }
  long m() const { return static_cast<long>(G.rows()); }
};

System assemble(const Model& model);

/// Name of coordinate i of z (e.g. "w[rfe 3]", or the builder's basis name).
std::string coordinate_name(const Model& model, const System& sys, long i);

/// RFEs whose cell contains P (relative tolerance 1e-9 of the length scale), each with weight
/// 1 / count: a point on a cell boundary belongs equally to the RFEs that share it.
std::vector<std::pair<int, double>> containing_elements(const Model& model, const Eigen::Vector3d& P);

/// The RFEs whose motion a point P follows, with weights: on a model with a centre grid the
/// (bi)linear interpolation weights of the (up to four) centres around P; otherwise the RFEs
/// containing P (1 / count each). Throws std::invalid_argument if P lies outside the body.
std::vector<std::pair<int, double>> point_weights(const Model& model, const Eigen::Vector3d& P);

/// Generalized force over z of a point action [F; M] (global) applied at P, the transpose of the
/// observation operator (so loads and probes are reciprocal): with a centre grid, sum_e w_e [F; M]
/// on the centres around P (point_weights); without, D(r)' [F; M] on the RFE containing P (split
/// equally on a cell boundary). Throws std::invalid_argument if P lies outside the body.
Eigen::VectorXd point_load(const Model& model, const System& sys, const Eigen::Vector3d& P, const Vector6d& action);

/// A point action [F; M] (global) at P.
using PointAction = std::pair<Eigen::Vector3d, Vector6d>;
/// The sum of point_load over many actions (one product with the basis at the end).
Eigen::VectorXd point_loads(const Model& model, const System& sys, const std::vector<PointAction>& actions);
/// The scene's distributed loads (line loads, pressures, self-weight: Scene::all_distributed_loads)
/// as point actions at Gauss points: each load is cut at the grid's centres, where the (bi)linear
/// weights of point_load are polynomials, and integrated there exactly (2 points per piece and
/// direction: a linear load times a linear weight), so the load vector is the consistent one.
/// Needs a centre grid (beams, plates).
std::vector<PointAction> distributed_actions(const Model& model, const Scene& scene);

/// Row r with r' z = component `comp` (0..5 of [u; theta]) of the motion of P: interpolated
/// between the centres around P (centre grid), or rigidly attached to the RFE containing P
/// (u_P = D(r) q; averaged on a cell boundary).
Eigen::VectorXd point_observer(const Model& model, const System& sys, const Eigen::Vector3d& P, int comp);

/// The part of the response at P (component `observed`, dofs::Index) to a unit point action at
/// Q (component `load`) that the interpolated observation of the interpolated load misses: the
/// model's singular kernels (Model::singularities) minus their interpolation. Add it to
/// point_observer(P)' z for a load at Q. Zero when the model has no singularity for the pair;
/// +inf for the deflection at a point load on a Mindlin plate (logarithmically infinite).
double point_correction(const Model& model, const Eigen::Vector3d& P, int observed, const Eigen::Vector3d& Q, int load);

/// Rigid-body motions of the whole model that no spring, support or coupling resists.
struct RigidModes {
  Eigen::MatrixXd Z;                 ///< n x r over z, M-orthonormal (Z' M Z = I)
  std::vector<std::string> motions;  ///< e.g. "translation z", one per candidate combination
};
/// Exact structural test: the six rigid motions of the model's elements (restricted to the
/// active DOFs) are tried against every SDE component with nonzero stiffness and every coupling;
/// the combinations that deform none of them are the free rigid modes.
RigidModes free_rigid_modes(const Model& model, const System& sys);

/// Near-rigid modes: rigid motions that deform no internal SDE or coupling but are restrained by
/// finite springs to ground only. Their eigenpairs are computed in that subspace (Rayleigh-Ritz
/// with the ground springs' energy and the mass), without forming K: a Lanczos or dense solve of
/// K loses them in the rounding of the elastic stiffness once the springs are 1e-12 of it (1e-6
/// N/m springs on a steel beam came out as 0). Relative accuracy O(k_springs / k_elastic).
struct NearRigid {
  Eigen::VectorXd lambda;  ///< ascending, > 0
  Eigen::MatrixXd Z;       ///< n x r over z, M-orthonormal
  /// Each finite spring to ground (component), as k and its deformation functional over z: the
  /// caller treats the stiff ones as constraints when it bounds the pairs' errors (filled only
  /// when there are near-rigid pairs).
  struct GroundSpring {
    double k = 0;
    Eigen::SparseVector<double> row;  ///< sparse: an edge of a plate has hundreds of springs
  };
  std::vector<GroundSpring> springs;
};
NearRigid near_rigid_modes(const Model& model, const System& sys);

}  // namespace modalbench::rfem
