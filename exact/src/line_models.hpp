#pragma once
// Private to the exact beams: the beam and the bar as dimensionless line systems
// (numerics/line_system.hpp).

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "modalbench/exact/beams.hpp"
#include "modalbench/numerics/line_system.hpp"

namespace modalbench::exact::detail {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

/// Dimensionless Timoshenko line (xi = x / L, w_bar = w / L, forces scaled by EI / L^2, EI / L).
struct BendingLine {
  double s;       // EI / (kGA L^2)
  double r;       // rhoI / (rhoA L^2)
  double lam_to_Omega2;  // rhoA L^4 / EI: Omega^2 = lambda * this
  LineSystem sys;

  BendingLine(const BeamBending& b, EndSprings left, EndSprings right, const PointAttachments& points = {}) {
    if (!(b.EI > 0 && b.rhoA > 0 && b.L > 0 && b.kGA > 0 && b.rhoI >= 0))
      throw std::invalid_argument("beam properties must be positive");
    s = std::isinf(b.kGA) ? 0.0 : b.EI / (b.kGA * b.L * b.L);
    r = b.rhoI / (b.rhoA * b.L * b.L);
    lam_to_Omega2 = b.rhoA * std::pow(b.L, 4) / b.EI;
    const double kt = std::pow(b.L, 3) / b.EI, kr = b.L / b.EI;
    sys.m = 2;
    sys.left_spring = {scaled(left.translational, kt), scaled(left.rotational, kr)};
    sys.right_spring = {scaled(right.translational, kt), scaled(right.rotational, kr)};
    // Nodal terms: forces scaled by EI / L^2 and EI / L, w = L w_bar, lambda = omega^2.
    for (const PointAttachment& p : points)
      sys.attachments.push_back({p.x / b.L,
                                 {scaled(p.springs.translational, kt), scaled(p.springs.rotational, kr)},
                                 {p.mass * kt, p.inertia * kr}});
    const double ss = s, rr = r, c = lam_to_Omega2;
    sys.state_matrix = [ss, rr, c](double lambda) {
      const double O2 = lambda * c;
      Eigen::MatrixXd A = Eigen::MatrixXd::Zero(4, 4);
      // y = [w, phi, Q, M]
      A(0, 1) = 1.0; A(0, 2) = ss;
      A(1, 3) = 1.0;
      A(2, 0) = -O2;
      A(3, 1) = -rr * O2; A(3, 2) = -1.0;
      return A;
    };
    sys.max_wavenumber = [ss, rr, c](double lambda) {
      const double O2 = std::abs(lambda) * c;
      return std::sqrt(O2 * (ss + rr) + std::sqrt(O2));
    };
  }
  static double scaled(double k, double factor) { return std::isinf(k) ? kInf : k * factor; }
};

/// Dimensionless bar (xi = x / L, q unscaled, forces scaled by S / L).
struct BarLine {
  double lam_to_Omega2;
  LineSystem sys;
  BarLine(const Bar& b, double k_left, double k_right, const PointAttachments& points = {}) {
    if (!(b.S > 0 && b.mu > 0 && b.L > 0)) throw std::invalid_argument("bar properties must be positive");
    lam_to_Omega2 = b.mu * b.L * b.L / b.S;
    const double f = b.L / b.S;
    sys.m = 1;
    sys.left_spring = {std::isinf(k_left) ? kInf : k_left * f};
    sys.right_spring = {std::isinf(k_right) ? kInf : k_right * f};
    for (const PointAttachment& p : points)
      sys.attachments.push_back({p.x / b.L, {std::isinf(p.springs.translational) ? kInf : p.springs.translational * f},
                                 {p.mass * f}});
    const double c = lam_to_Omega2;
    sys.state_matrix = [c](double lambda) {
      Eigen::MatrixXd A(2, 2);
      A << 0.0, 1.0, -lambda * c, 0.0;
      return A;
    };
    sys.max_wavenumber = [c](double lambda) { return std::sqrt(std::abs(lambda) * c); };
  }
};

inline void note_unknowns(long* unknowns, const AssembledLine& a) {
  if (unknowns) *unknowns = std::max<long>(*unknowns, a.K.free_dofs());
}

}  // namespace modalbench::exact::detail
