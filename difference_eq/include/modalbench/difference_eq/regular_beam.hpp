#pragma once
// The regular discrete beam shared by every closed form of the difference_eq back-end.
//
// An Euler-Bernoulli beam (EI, rho A, length L) cut into R identical two-node Hermite-cubic
// elements of length a = L / R; nodes r = 0..R at x_r = r a. Each node carries the
// deflection w_r (along +z) and the slope psi_r = dw/dx. The paper (Lasecka) writes the
// scaled rotation phi_r = a psi_r and the scaled nodal moment m_r = M_r / a; then the
// element stiffness (paper, Eq. (1), with its row 4 read as [6 2 -6 4] -- printed
// [-6 2 -6 4], which is not symmetric) is
//   K_e = EI / a^3 [[12, 6, -12, 6], [6, 4, -6, 2], [-12, -6, 12, -6], [6, 2, -6, 4]]
// acting on (w_1, phi_1, w_2, phi_2) -> (P_1, m_1, P_2, m_2).
//
// Sign conventions: a nodal moment here is conjugate to the slope (does work C psi). For a
// scene bending in x-z (theta_y = -dw/dx, My right-handed about +y) that is C = -My and
// theta_y = -psi; the solver converts.
//
// End springs act on w and psi at x = 0 and x = L, each in [0, inf] (inf = held).

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace modalbench::difference_eq {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

/// A regular discrete Euler-Bernoulli beam: R identical Hermite-cubic elements on [0, L].
struct RegularBeam {
  double EI = 0;    ///< bending stiffness, N m^2 (> 0)
  double rhoA = 0;  ///< mass per length, kg/m (> 0 for vibration; unused by statics)
  double L = 0;     ///< length, m (> 0)
  long R = 1;       ///< number of elements, 1 <= R <= kMaxElements
  double k0 = 0;    ///< translational spring at x = 0, N/m, [0, inf]
  double r0 = 0;    ///< rotational spring at x = 0 (on the slope), N m/rad, [0, inf]
  double kL = 0;    ///< translational spring at x = L, N/m, [0, inf]
  double rL = 0;    ///< rotational spring at x = L, N m/rad, [0, inf]

  static constexpr long kMaxElements = 20'000'000;

  double a() const { return L / static_cast<double>(R); }
  /// Dimensionless springs K = kappa L^3 / EI (translational), Kr = chi L / EI (rotational),
  /// in the order (w0, psi0, wL, psiL).
  double dimensionless_spring(int dof) const;
  /// Throws std::invalid_argument naming the violated constraint.
  void validate(bool need_mass) const;
};

/// A nodal action: a force along +z and a moment conjugate to the slope dw/dx.
struct NodalLoad {
  long node = 0;       ///< 0..R
  double force = 0;    ///< N
  double moment = 0;   ///< N m (= -My for bending in x-z)
};

/// The supports do not restrain rigid-body motion (a static solve has no unique answer).
class Mechanism : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Number of rigid-body modes (0, 1 or 2) left free by the end springs: a rigid motion
/// w = c + rho x is resisted by every non-zero spring that sees it.
int rigid_body_modes(const RegularBeam& beam);

}  // namespace modalbench::difference_eq
