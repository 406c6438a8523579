#pragma once
// Rigid-body attachment kinematics shared by rfem (spring-damping elements between rigid
// elements) and dtfm (distributed spring layers between prisms).
//
// A body with reference point c has generalized displacement q = [u; theta] (3 translations,
// 3 small rotations, global axes). A point P rigidly attached to it moves by
//   [u_P; theta_P] = D(r) q,   D(r) = [[I, -[r]x], [0, I]],   r = P - c,
// where [r]x is the cross-product matrix ([r]x v = r x v; u_P = u + theta x r = u - [r]x theta).
// A spring-damping element (SDE) joining body a to body b at P with local axes R (columns: the
// local axes in global coordinates) and six stiffnesses k (3 translational, 3 rotational, local)
// deforms by  delta = R^T (D_b q_b - D_a q_a)  (R applied block-diagonally) and adds
//   G^T Rb k Rb^T G,   G = [-D_a, D_b],  Rb = blkdiag(R, R)
// to the stiffness matrix over [q_a; q_b]; a damper alike. To ground: D_a q_a with the sign
// irrelevant: D_a^T Rb k Rb^T D_a.
//
// Usage:
//   auto K12 = sde_stiffness(P - c_a, P - c_b, Eigen::Matrix3d::Identity(), k);   // 12 x 12
//   auto Kab = restrict_dofs(K12, dofs::kBendingXZ);                              // 4 x 4 (w, theta_y per body)

#include <Eigen/Dense>
#include <vector>

namespace modalbench {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Matrix12d = Eigen::Matrix<double, 12, 12>;

/// DOF indices within a body's 6-vector, and the active sets scenes use.
namespace dofs {
enum Index : int { Ux = 0, Uy = 1, Uz = 2, Rx = 3, Ry = 4, Rz = 5 };
inline const std::vector<int> kBendingXZ = {Uz, Ry};           ///< beam bending in x-z
inline const std::vector<int> kPlanarXZ = {Ux, Uz, Ry};        ///< axial + bending in x-z
inline const std::vector<int> kPlate = {Uz, Rx, Ry};           ///< plate bending
inline const std::vector<int> kSpatial = {Ux, Uy, Uz, Rx, Ry, Rz};
inline const std::vector<int> kLateral = {Uy, Uz, Ry, Rz};     ///< a rotor's bending in x-y and x-z
}  // namespace dofs

/// [r]x: the matrix with [r]x v = r x v.
Eigen::Matrix3d skew(const Eigen::Vector3d& r);
/// D(r) = [[I, -[r]x], [0, I]]: displacement of the point at offset r from the body's reference.
Matrix6d attachment(const Eigen::Vector3d& r);
/// D(r) q without forming D: [u + theta x r; theta].
Vector6d attached_motion(const Eigen::Vector3d& r, const Vector6d& q);
/// Deformation R^T (D(r_bP) q_b - D(r_aP) q_a) of an SDE in its local axes (to ground: q_b = 0).
Vector6d sde_deformation(const Eigen::Vector3d& r_aP, const Vector6d& q_a, const Eigen::Vector3d& r_bP,
                         const Vector6d& q_b, const Eigen::Matrix3d& R);
/// Stiffness (or damping) of an SDE between bodies a and b, over [q_a; q_b] (12 x 12).
Matrix12d sde_stiffness(const Eigen::Vector3d& r_aP, const Eigen::Vector3d& r_bP, const Eigen::Matrix3d& R,
                        const Vector6d& k);
/// Stiffness of an SDE from body a to ground (6 x 6).
Matrix6d sde_to_ground(const Eigen::Vector3d& r_aP, const Eigen::Matrix3d& R, const Vector6d& k);
/// Keeps the rows/columns of the active DOFs, per body: a (6 n) x (6 n) matrix over n bodies
/// becomes (a n) x (a n) with a = active.size(), body-major.
Eigen::MatrixXd restrict_dofs(const Eigen::MatrixXd& full, const std::vector<int>& active);

}  // namespace modalbench
