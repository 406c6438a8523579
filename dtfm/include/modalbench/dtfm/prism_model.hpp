#pragma once
// The discrete-continuous prism model (Hein): a beam's section cut into ny x nz prisms, or a
// plate cut into strips across its width, each prism continuous along x, neighbours joined
// by distributed spring layers. The operator of Eq. (32),
//   A02 q'' (time) + A20 q'' + A10 q' + A00 q = f,
// is built from an energy per unit length instead of the printed terms (docs/sources.md, P6):
//   U = 1/2 e^T P e + e^T X q + 1/2 q^T Q1 q,   e = q' + S q,   T = 1/2 qdot^T M qdot,
// e: the prisms' x-strains (u', v' - theta_z, w' + theta_y, theta_x', theta_y', theta_z'; a
// plate strip: w' + theta_y, theta_x', theta_y'), P = C^-1 their stiffness (C = compliance,
// 0 for a rigid strain: Euler-Bernoulli, Kirchhoff), Q1 the spring layers (Eq. (25)) and the
// supports along the long edges, X the layers' cross terms with the prisms' x-strains. Then
//   A02 = M,  A20 = -P,  A10 = R^T - R,  A00 = S^T P S + S^T X + X^T S + Q1,  R = P S + X,
// so A02, A20, A00 are symmetric and A10 is skew by construction, and the Hamiltonian state
// y = [q; f], f = P e + X q (the section forces, conjugate to q in the boundary terms) obeys
//   y' = [[-S~, C], [Q~ - omega^2 M, S~^T]] y,  S~ = S + C X,  Q~ = Q1 - X^T C X.
//
// Spring layers: a layer between prisms a and b deforms by the jump of the rigid-body motions
// of its two faces, delta = D(r_b) q_b - D(r_a) q_a (rigid_kinematics.hpp); integrated over
// the layer's height (normal E, shear G) this is exactly Eq. (25)'s six stiffnesses
// (c1..c6, with c6 -> 0 per unit length), so the springs come from `sde_stiffness`.
// Cross terms (LayerModel::Consistent): a strain that is the sum of a jump across the layer
// and an x-derivative in the prisms (beam: gamma_xz = du/dz + dw/dx across z-layers, gamma_xy
// across y-layers; plate: the twist kappa_xy = dpsi_x/dy + dpsi_y/dx) has energy (a + b)^2: the
// printed model keeps a^2 (layer) and b^2 (prism) and drops 2ab, which halves the shear (beam:
// prism and layer shear act in series) and the twist (plate). The layer keeps 2 a b_avg,
// b_avg = the mean of the two prisms' strains at the layer (energy stays positive:
// sum of layers b_avg^2 <= sum of prisms b^2). Normal strains split exactly as
//   1/2 E eps_xx^2 + 1/2 E' (eps_nn + nu eps_xx)^2,  E' = E / (1 - nu^2)   (beam layers),
//   1/2 D (1 - nu^2) k_x^2 + 1/2 D (k_y + nu k_x)^2                        (plate),
// the first part in the prisms, the second in the layers: a free surface or free edge then
// relaxes to the uniaxial / beam value and a clamp stiffens (Poisson), as in the continuum.
// Kirchhoff plates: strips rigid in transverse shear (exact), layers' gamma_yz by a penalty.
// A plate strip's kinetic energy is that of its rigid motion about its line (the paper's
// rho I_0x), which also cancels the layer scheme's leading dispersion error across the width.
//
// Beams: prisms are the cells of the division (cell-centred). `bending` and `planar` physics
// are plane x-z problems: all prisms across the width move together, so the model is 1 x nz
// (with nz > 1 bending needs the prisms' axial fields). Supported ends carry a rigid end plate
// (plane section at the support) on which the scene's springs act; a free end carries nothing.
// Plates: strips are centred on the n + 1 lines y_j = j b / n (edge strips half wide), so a long
// edge support holds the edge strip's fields; layers span the n intervals between lines.
//
// Usage:
//   PrismModel model = build_model(scene, Discretization::parse("2x2"), ModelOptions{});
//   Eigen::MatrixXd A10 = model.A10();   // skew
//   Eigen::MatrixXd A = model.state_matrix(omega * omega);

#include <Eigen/Dense>
#include <complex>
#include <memory>
#include <string>
#include <vector>

#include "modalbench/result.hpp"
#include "modalbench/scene.hpp"
#include "modalbench/solver.hpp"

namespace modalbench::dtfm {

/// How the spring layers between prisms are modelled.
enum class LayerModel {
  Consistent,  ///< Eq. (25) springs + cross terms (continuum-consistent energy); the default
  Staggered,   ///< beam: prisms rigid in shear where the section is cut, layers carry the shear; plate: = Consistent
  Paper,       ///< the printed model: Eq. (25) springs only, kappa G in the layers, beam moduli (E) in plates
};
std::string to_string(LayerModel);

struct ModelOptions {
  LayerModel layers = LayerModel::Consistent;
  /// Kirchhoff plates: the layers' transverse shear (gamma_yz = 0 in Kirchhoff theory) is a
  /// penalty of this many times 12 D / dy^3 per unit length (the bending stiffness of a strip of
  /// width dy); the relative error in omega^2 is below (k_y dy)^2 / (12 penalty), second order
  /// like the discretization. Larger values raise the evanescent wavenumbers (|p| ~ sqrt) and
  /// with them the rounding floor; 10 keeps 20-strip results as accurate as 100 does.
  double kirchhoff_penalty = 10.0;
};

/// A prism (beam cell) or strip (plate): reference point and section.
struct PrismGeometry {
  double y = 0, z = 0;           ///< reference point in the section (beam: cell centre; plate: line y_j)
  double width = 0, height = 0;  ///< cell size (plate: tributary width, plate thickness)
};

/// Conditions at one end of the line (x = 0 or x = L). The admissible end motions are
/// d = N a (N: orthonormal, m x n); everything orthogonal to N is held. The springs add
/// 1/2 a^T K a.
struct EndCondition {
  Eigen::MatrixXd N;  ///< m x n orthonormal basis of the admissible motions
  Eigen::MatrixXd K;  ///< n x n spring stiffness on the coordinates a
  std::string text;   ///< what it is, for messages
  /// m x m: point masses there, kinetic energy 1/2 qdot^T mass qdot over the fields (empty: none).
  Eigen::MatrixXd mass;
  /// m x m: the discs' polar inertia J_p on the bending rotation (a whirl line's, PrismModel::whirl).
  Eigen::MatrixXd gyro;
};

/// A beam's support or point mass between its ends (`[[supports.points]]`, `[[masses]]`): the
/// same form as an end's, at x. It acts on the section's resultant motion (the conjugate of the
/// point loads' spread, PrismModel::load_vector): on one prism, the beam's own w, theta, ...; on a
/// section cut into prisms, spread over them as a point load is (no rigid plate there).
struct PointCondition {
  double x = 0;
  EndCondition cond;
};

/// A piece of a stepped beam (one prism): its operator (the energy form's matrices) over
/// [previous piece's x_to, x_to].
struct PieceOperator {
  double x_to = 0;
  Eigen::MatrixXd M, C, S, X, Q1;
  Eigen::MatrixXd G;  ///< the piece's gyroscopic inertia (PrismModel::G); empty: none
};

/// A reflection of the section as a signed permutation of the fields: (Pi q)_k = sign_k q_{perm_k}.
struct Reflection {
  std::vector<int> perm;
  std::vector<int> sign;
};

/// A symmetry class: the fields' subspace with given reflection parities (orthonormal basis).
struct FieldClass {
  std::vector<int> parity;  ///< +1 / -1 per reflection
  Eigen::MatrixXd V;        ///< m x mc, orthonormal columns
  ModeFamily family = ModeFamily::Unknown;
  /// Rigid section motions that define the family (beam): columns over the fields; empty for plates.
  Eigen::MatrixXd family_motions;
};

struct PrismModel {
  SceneKind kind = SceneKind::Beam;
  LayerModel layers = LayerModel::Consistent;
  std::string description;         ///< e.g. "1x8 prisms, plane x-z (u, w, theta_y)"
  std::vector<std::string> notes;  ///< modelling decisions worth reporting (e.g. ny ignored)
  double length = 0;               ///< L (beam) or a (plate), m
  int ny = 1, nz = 1;              ///< beam: division used; plate: ny = number of strip lines
  std::vector<PrismGeometry> prisms;
  std::vector<int> field_prism, field_dof;  ///< per field: prism index and dofs::Index
  int m = 0;                                ///< number of fields
  // Energy form (see the file comment). C: compliance, 0 where a strain is rigid.
  Eigen::MatrixXd M, C, S, X, Q1;
  EndCondition ends[2];
  /// Beams: supports and point masses between the ends, by ascending x (those at an end are
  /// merged into `ends`).
  std::vector<PointCondition> points;
  /// Stepped beams: the operator of every piece after the first (M, C, S, X, Q1 above are the
  /// first piece's, over [0, first_piece_to]); empty for a uniform beam.
  std::vector<PieceOperator> steps;
  double first_piece_to = 0;
  /// One whirl direction of a spinning axisymmetric shaft (dtfm/src/rotor.cpp): the polar rotary
  /// inertia rho I_p per length on the bending rotation (m x m; empty: none; discs: EndCondition::gyro)
  /// and whirl = s Omega (s = +1 forward, -1 backward): the rotary inertia term lambda M becomes
  /// lambda M - s Omega sqrt(lambda) G, i.e. rho I omega^2 -> rho I omega^2 - s rho I_p Omega omega.
  Eigen::MatrixXd G;
  double whirl = 0;
  std::vector<Reflection> reflections;
  std::vector<FieldClass> classes;
  double translation_scale = 1;  ///< a length: translations are divided by it in the line solves
  double lambda_scale = 1;       ///< omega^2 scale (the first mode's order of magnitude)
  /// Plate: how many rigid-body motions (w = a + b x + c y) no edge support reaches; they are
  /// exact zeros of the model, which its count resolves only to rounding. -1 where an edge spring
  /// makes them near-rigid, and for beams (their classes carry their own rigid split).
  int rigid_body_motions = -1;
  /// Beam: rigid section motions over the fields (m x 6, columns U, V, W, Theta_x, Theta_y,
  /// Theta_z; zero columns where the physics has no such motion) and the section's weights.
  Eigen::MatrixXd rigid_motions;
  Eigen::MatrixXd section_weights;  ///< m x m diagonal: A_i on translations, I_i on rotations
  /// Plate with a long edge that holds something: the same model with both long edges free (their
  /// lines' fields all present), whose energy rows for the held fields give the edges' reactions.
  std::shared_ptr<const PrismModel> free_long_edges;

  // Eq. (32) in the paper's form (A20 needs every strain deformable: throws otherwise).
  Eigen::MatrixXd A02() const { return M; }
  Eigen::MatrixXd A20() const;
  Eigen::MatrixXd A10() const;
  Eigen::MatrixXd A00() const;
  /// Hamiltonian state matrix at lambda = omega^2 (2m x 2m, x in metres).
  Eigen::MatrixXd state_matrix(double lambda) const;

  /// Generalized forces over the fields for a point action at x (the x is not used here).
  /// Beam: the section resultant (Fx..Mz) spread over the prisms by area / second moments
  /// (statically equivalent). Plate: Fz shared by the two strip lines around y (linear).
  Eigen::VectorXd load_vector(const PointLoad& load) const;
  /// Plate: the generalized forces per unit length along x of a pressure qz over the patch's y
  /// range, each strip line taking the pressure against its hat function (linear between lines,
  /// as a point load is shared): consistent with the strips' linear interpolation across y.
  Eigen::VectorXd pressure_vector(const DistributedLoad& pressure) const;
  /// Section response from the fields at one x: beam: the conjugate rigid-section motion;
  /// plate: w, theta_x, theta_y interpolated linearly between strip lines at y.
  Deflection section_response(const Eigen::VectorXd& q, double y) const;
  /// Observation row for w at (y): w = row . q.
  Eigen::RowVectorXd w_observer(double y) const;

  int field(int prism, int dof) const;  ///< field index, or -1 if not active
};

/// Builds the model for a scene. Beam mesh "NYxNZ" (or "N" = N x N), plate mesh "N" (strips).
/// Throws InputError(source "command line", key "--mesh") for a mesh this back-end cannot use.
PrismModel build_model(const Scene& scene, const Discretization& mesh, const ModelOptions& options = {});

}  // namespace modalbench::dtfm
