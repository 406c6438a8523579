#pragma once
// The rigid finite element model: rigid elements (RFEs) joined by spring-damping elements (SDEs).
//
// Each RFE carries q = [u; theta] at its reference point (its centre), restricted to the DOFs
// the scene needs (`active`, one of modalbench::dofs::k*), and a diagonal mass
// diag(m, m, m, Jx, Jy, Jz) (principal axes parallel to the global axes). An SDE joins RFE a to
// RFE b, or RFE a to ground, at a point P with local axes R and six stiffnesses / dampings
// (3 translational, 3 rotational, local); its stiffness is core's `sde_stiffness` /
// `sde_to_ground` (rigid_kinematics.hpp) restricted to the active DOFs. A stiffness of +inf is
// a rigid component: to ground it holds the component of P's motion (the DOF is eliminated,
// never penalised); between two RFEs it is an exact linear constraint (Lagrange multiplier).
// `Coupling`s are stiffness blocks over several RFEs that are not two-point springs (the plate
// builder's Poisson/twist correction per fragment).
//
// A builder may give generalized coordinates z with q = basis z that satisfy some rigid SDE
// components identically (the Euler-Bernoulli beam: the transverse displacements of the joints,
// which make the shear springs rigid exactly). Those components are then left at 0 stiffness.

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "modalbench/result.hpp"
#include "modalbench/rigid_kinematics.hpp"

namespace modalbench::rfem {

using SpMat = Eigen::SparseMatrix<double>;
inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr int kGround = -1;

/// A rigid element: mass, principal moments of inertia about its centre (global axes), and the
/// part of the body it stands for (`cell`, used to find the RFE that contains a probe or load).
struct RigidElement {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double mass = 0;                                     ///< kg
  Eigen::Vector3d inertia = Eigen::Vector3d::Zero();   ///< Jx, Jy, Jz, kg m^2
  Eigen::AlignedBox3d cell;                            ///< region of the body this RFE represents
  std::string label;                                   ///< e.g. "rfe 3", "rfe (2,5)"
};

/// A spring-damping element between RFEs `a` and `b` (b = kGround: to ground) at `point`.
struct Sde {
  int a = 0;
  int b = kGround;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  ///< columns: local axes in global coordinates
  Vector6d stiffness = Vector6d::Zero();               ///< local k1..k6 (N/m, N m/rad); +inf = rigid
  Vector6d damping = Vector6d::Zero();                 ///< local c1..c6 (N s/m, N m s/rad)
};

/// A stiffness block over several RFEs: `stiffness` is (6 n) x (6 n) over their full 6-DOF
/// vectors in the order of `elements` (restricted to the active DOFs on assembly). Shared, as
/// most blocks of a regular grid are equal.
struct Coupling {
  std::vector<int> elements;
  std::shared_ptr<const Eigen::MatrixXd> stiffness;
};

/// Beams and plates: the RFE centres form a tensor grid, centre (i, j) at (x[i], y[j], 0) being
/// element[i + x.size() * j] (a beam has y = {0}). A load or observation point between centres is
/// interpolated (bi)linearly from the centres around it: the interpolant is second-order
/// accurate, like the centres' own motion, where the rigid attachment to the one RFE containing
/// the point (its motion jumps at every SDE) is only first order. Empty for models without a
/// grid (boxes), which attach points rigidly.
struct CentreGrid {
  std::vector<double> x, y;  ///< ascending
  std::vector<int> element;
  bool empty() const { return x.empty(); }
};

/// The singular part S(P, Q) of the continuum's response at P (component `observed`) to a unit
/// point action at Q (component `load`), which no interpolation between centres carries:
///  - Kink: -c |x_P - x_Q| (beams: a second-order field with stiffness S has a slope jump 1/S under
///    its point action; c = 1 / (2 S): w under Fz for Timoshenko (S = kGA), u under Fx (EA), the
///    twist under Mx (GJ), the bending rotation under its moment (EI));
///  - Biharmonic: c r^2 ln r (Kirchhoff and Mindlin plates, c = 1 / (8 pi D)), or its derivative for
///    an observed rotation (theta_x = +d/dy, theta_y = -d/dx at P);
///  - ShearLog: -c ln r (Mindlin plates, c = 1 / (2 pi kappa G h)): infinite at r = 0.
/// point_correction adds S(P, Q) - (interpolation of S between the centres around P and Q), so a
/// response at or near a loaded point converges as the centres do.
struct PointSingularity {
  enum class Kind { Kink, Biharmonic, ShearLog };
  enum class Derivative { None, PlusDy, MinusDx };
  int observed = 0;  ///< dofs::Index
  int load = 0;      ///< dofs::Index
  Kind kind = Kind::Kink;
  double coefficient = 0;
  Derivative derivative = Derivative::None;
  /// For load points Q with x_from <= Q.x < x_to only (a stepped beam: one per piece).
  double x_from = -kInf, x_to = kInf;
};

struct Model {
  std::string description;             ///< one line: what was built
  std::vector<int> active;             ///< DOFs per RFE (dofs::kBendingXZ, ...)
  std::vector<RigidElement> elements;
  std::vector<Sde> sdes;
  std::vector<Coupling> couplings;
  CentreGrid grid;  ///< see CentreGrid (empty: rigid attachment)
  std::vector<PointSingularity> singularities;  ///< with a grid only
  /// Optional generalized coordinates: q = basis z (rows: active DOFs, element-major). Empty: z = q.
  SpMat basis;
  std::vector<std::string> basis_names;  ///< one per column of `basis`
  /// Where each column of `basis` is a transverse displacement w at a point: that point (empty
  /// otherwise). Where the holds pin such columns, their reactions are the forces there.
  std::vector<Eigen::Vector3d> basis_points;
  /// Which mode family each active DOF belongs to (parallel to `active`); Unknown if not meaningful.
  std::vector<ModeFamily> dof_family;
  double omega_hint = 0;    ///< rad/s, a characteristic low natural frequency (places the eigen shift)
  double length_scale = 1;  ///< m, converts rotations to displacements in tolerance checks
  double loss_factor = 0;   ///< structural damping eta: K (1 + i eta) in FRFs
  /// The SDEs to ground that stand for a scene's support, by index into `sdes`, with the support's
  /// name ("x0", "xL", "points[i]"): whose reactions are reported.
  std::vector<std::pair<int, std::string>> supports;

  int dofs_per_element() const { return static_cast<int>(active.size()); }
  long body_dofs() const { return static_cast<long>(elements.size()) * dofs_per_element(); }
  /// Index of DOF `d` (dofs::Index) in the active set, or -1.
  int local_index(int d) const;
  /// Name of body DOF i (e.g. "w[rfe 3]").
  std::string dof_name(long i) const;
  /// Throws std::invalid_argument naming the first inconsistency (indices, sizes, signs).
  void check() const;
};

/// Short name of a DOF index (u, v, w, theta_x, theta_y, theta_z).
std::string dof_symbol(int d);

}  // namespace modalbench::rfem
