#pragma once
// Private to the exact frames: one member's exact dynamic stiffness in its own axes, its fixed-end
// forces under a line load, and its state between the ends.
//
// A member carries up to four independent fields in its principal axes, each a Hamiltonian line
// on xi = x / L in [0, 1] (segment_dynamic_stiffness.hpp), in dimensionless variables:
//   axial      [u / L, N / EA]:              u' = N, N' = -lambda rhoA L^2 / EA u
//   torsion    [theta_x, T L / GJ]:          as the axial one with GJ, rho Ip
//   bending xz [w / L, theta_y, Vz L^2 / EI, My L / EI] (theta_y = -w' for Euler-Bernoulli):
//              w' = -theta + s Vz, theta' = M, Vz' = -lambda rhoA L^4 / EI w, M' = Vz - lambda r theta
//   bending xy [v / L, theta_z, Vy L^2 / EI, Mz L / EI] (theta_z = +v'):
//              v' = theta + s Vy, theta' = M, Vy' = -lambda rhoA L^4 / EI v, M' = -Vy - lambda r theta
// with s = EI / (kGA L^2) and r = rho I L^2 / EI (both 0 for Euler-Bernoulli). The forces are the
// resultants on a face whose outward normal is +x (Vz, Vy shear forces along +z, +y; My, Mz, T the
// moments about +y, +z, +x): so the end forces the nodes exert on the member are
// [-f(0); f(1)] = K [d(0); d(1)], and each field's K is symmetric.

#include <Eigen/Dense>
#include <array>
#include <vector>

#include "modalbench/frame.hpp"
#include "modalbench/result.hpp"
#include "modalbench/scene.hpp"

namespace modalbench::exact::detail {

/// A member's end DOFs in its own axes: u, v, w, theta_x, theta_y, theta_z at its first node, then
/// at its second (12); a planar frame's members use u, w, theta_y of each end (6: indices 0, 2, 4).
inline constexpr int kMemberDofs = 12;

enum class FieldKind { Axial, Torsion, BendingXZ, BendingXY };

/// One field of a member.
struct MemberField {
  FieldKind kind = FieldKind::Axial;
  int m = 1;                     ///< displacements per end (1 or 2)
  std::array<int, 2> dofs{};     ///< its end DOFs among u, v, w, theta_x, theta_y, theta_z (the second unused for m = 1)
  std::array<double, 2> d_scale{};  ///< physical displacement = d_scale * dimensionless
  std::array<double, 2> f_scale{};  ///< physical force = f_scale * dimensionless
  double stiff = 0;   ///< EA, GJ or EI
  double inertia = 0; ///< rhoA, rho Ip or rhoA (bending)
  double rot_inertia = 0;  ///< bending: rho I (0 for Euler-Bernoulli)
  double shear = 0;   ///< bending: s = EI / (kGA L^2) (0 for Euler-Bernoulli)
  double L = 0;
  /// The dimensionless state matrix at lambda = omega^2.
  Eigen::MatrixXd state(double lambda) const;
};

/// The fields a member carries in the scene's physics and theory, over `length` (m) of it (the
/// whole member: its length; a piece of it: the piece's).
std::vector<MemberField> member_fields(const FrameMember& member, bool spatial, Theory theory, double length);

/// A member's dynamic stiffness at lambda in its own axes (kMemberDofs square, zero rows for the
/// DOFs its fields do not carry), its Wittrick-Williams J0 (clamped-clamped frequencies below
/// omega) and log |det Tdf| (smooth in lambda between its clamped frequencies, a constant offset
/// aside: it removes the poles of det K).
struct MemberStiffness {
  Eigen::MatrixXd K;
  int clamped_below = 0;
  double log_abs_det_tdf = 0;
  /// How near omega lies to a clamped frequency (a pole of K): the smallest of its fields'
  /// measures, a doubled field's LongSegment::min_pivot_scale (a halving's clamped frequency, as the
  /// doubling sees it), a closed form's |sin k| or |sech b - cos b|; and whether any field is past
  /// |p| = 1 (where the count may cut the member there).
  double min_pivot_scale = 1;
  bool doubled = false;
};
MemberStiffness member_stiffness(const std::vector<MemberField>& fields, double lambda);

/// A line load on a member in its own axes: N/m along local x, y, z at xi = 0 and xi = 1 (linear).
struct LocalLineLoad {
  std::array<double, 2> qx{}, qy{}, qz{};
};

/// The static forces (lambda = 0) the nodes exert on the member held at both ends under `loads`,
/// in its own axes (kMemberDofs): a fixed-end solution exact for linear intensities.
Eigen::VectorXd fixed_end_forces(const std::vector<MemberField>& fields, const std::vector<LocalLineLoad>& loads);

/// The static state at xi of a member with end displacements d (its own axes, kMemberDofs) and end
/// forces P = K(0) d + fixed_end_forces: displacements (u, v, w, theta_x, theta_y, theta_z) and the
/// stress resultants in InternalForces' convention (a beam's: N tension, My = EI w'', Qz = dMy/dx,
/// Mz = EI v'', Qy = dMz/dx, T), at xi + 0 (at xi = 1, 1 - 0).
struct MemberState {
  std::array<double, 6> d{};
  InternalForces forces;
};
MemberState member_state(const std::vector<MemberField>& fields, const std::vector<LocalLineLoad>& loads,
                         const Eigen::VectorXd& d, const Eigen::VectorXd& P, double xi);

}  // namespace modalbench::exact::detail
