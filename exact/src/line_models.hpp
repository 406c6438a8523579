#pragma once
// Private to the exact beams: the beam and the bar as dimensionless line systems
// (numerics/line_system.hpp).

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

#include "modalbench/exact/beams.hpp"
#include "modalbench/numerics/line_system.hpp"

namespace modalbench::exact::detail {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

/// Dimensionless Timoshenko line (xi = x / L, w_bar = w / L, forces scaled by EI / L^2, EI / L,
/// with EI, rhoA those of the first piece of a stepped beam).
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
    set_piece(b, b, sys.state_matrix, sys.max_wavenumber);
    if (b.varies) sys.variation = varying(b, b.varies);
    for (const BendingStep& st : b.steps) {
      if (!(st.EI > 0 && st.rhoA > 0 && st.kGA > 0 && st.rhoI >= 0 && st.x_from > 0 && st.x_from < b.L))
        throw std::invalid_argument("beam step properties must be positive, the step inside the beam");
      LinePiece piece;
      piece.xi_from = st.x_from / b.L;
      set_piece(b, b.at(st.x_from), piece.state_matrix, piece.max_wavenumber);
      if (st.varies) piece.variation = varying(b, st.varies);
      sys.steps.push_back(piece);
    }
  }
  /// A tapered piece's LineVariation: its state matrix at each xi (set_piece's, with the local
  /// properties) and the wavenumber bound of its comparison piece over [xi0, xi1].
  static LineVariation varying(const BeamBending& ref, const BendingVariation& v) {
    const BeamBending r{ref.EI, ref.kGA, ref.rhoA, ref.rhoI, ref.L};
    const auto as_beam = [r](const BendingProps& p) { return BeamBending{p.EI, p.kGA, p.rhoA, p.rhoI, r.L}; };
    return {[r, v, as_beam](double lambda, double xi) {
              std::function<Eigen::MatrixXd(double)> A;
              std::function<double(double)> p;
              set_piece(r, as_beam(v.at(xi * r.L)), A, p);
              return A(lambda);
            },
            [r, v, as_beam](double lambda, double xi0, double xi1) {
              std::function<Eigen::MatrixXd(double)> A;
              std::function<double(double)> p;
              set_piece(r, as_beam(v.bound(xi0 * r.L, xi1 * r.L)), A, p);
              return p(lambda);
            }};
  }
  /// The state matrix of a piece with properties `own`, in the units of the first piece `ref`:
  /// w' = phi + (EI0 / (kGA L^2)) Q, phi' = (EI0 / EI) M, Q' = -(rhoA / rhoA0) O2 w,
  /// M' = -(rhoI / (rhoA0 L^2)) O2 phi - Q, with O2 = lambda rhoA0 L^4 / EI0; its wavenumber bound
  /// is the piece's own (a diagonal scaling of the state leaves A's eigenvalues as they are).
  static void set_piece(const BeamBending& ref, const BeamBending& own,
                        std::function<Eigen::MatrixXd(double)>& state_matrix, std::function<double(double)>& wavenumber) {
    const double L2 = ref.L * ref.L, c = ref.rhoA * L2 * L2 / ref.EI;
    const double ss = std::isinf(own.kGA) ? 0.0 : ref.EI / (own.kGA * L2), inv_e = ref.EI / own.EI;
    const double a = own.rhoA / ref.rhoA, rr = own.rhoI / (ref.rhoA * L2);
    state_matrix = [ss, rr, c, inv_e, a](double lambda) {
      const double O2 = lambda * c;
      Eigen::MatrixXd A = Eigen::MatrixXd::Zero(4, 4);
      // y = [w, phi, Q, M]
      A(0, 1) = 1.0; A(0, 2) = ss;
      A(1, 3) = inv_e;
      A(2, 0) = -a * O2;
      A(3, 1) = -rr * O2; A(3, 2) = -1.0;
      return A;
    };
    const double s_own = std::isinf(own.kGA) ? 0.0 : own.EI / (own.kGA * L2), r_own = own.rhoI / (own.rhoA * L2);
    const double c_own = own.rhoA * L2 * L2 / own.EI / c;  // O2_own = O2 c_own
    wavenumber = [s_own, r_own, c_own, c](double lambda) {
      const double O2 = std::abs(lambda) * c * c_own;
      return std::sqrt(O2 * (s_own + r_own) + std::sqrt(O2));
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
    set_piece(b, b, sys.state_matrix, sys.max_wavenumber);
    if (b.varies) sys.variation = varying(b, b.varies);
    for (const BarStep& st : b.steps) {
      if (!(st.S > 0 && st.mu > 0 && st.x_from > 0 && st.x_from < b.L))
        throw std::invalid_argument("bar step properties must be positive, the step inside the bar");
      LinePiece piece;
      piece.xi_from = st.x_from / b.L;
      set_piece(b, b.at(st.x_from), piece.state_matrix, piece.max_wavenumber);
      if (st.varies) piece.variation = varying(b, st.varies);
      sys.steps.push_back(piece);
    }
  }
  /// A tapered piece's LineVariation (BendingLine::varying's).
  static LineVariation varying(const Bar& ref, const BarVariation& v) {
    const Bar r{ref.S, ref.mu, ref.L};
    return {[r, v](double lambda, double xi) {
              std::function<Eigen::MatrixXd(double)> A;
              std::function<double(double)> p;
              const BarProps at = v.at(xi * r.L);
              set_piece(r, Bar{at.S, at.mu, r.L}, A, p);
              return A(lambda);
            },
            [r, v](double lambda, double xi0, double xi1) {
              std::function<Eigen::MatrixXd(double)> A;
              std::function<double(double)> p;
              const BarProps lo = v.bound(xi0 * r.L, xi1 * r.L);
              set_piece(r, Bar{lo.S, lo.mu, r.L}, A, p);
              return p(lambda);
            }};
  }
  /// u' = (S0 / S) N, N' = -(mu / mu0) lambda c u in the first piece's units (as BendingLine).
  static void set_piece(const Bar& ref, const Bar& own, std::function<Eigen::MatrixXd(double)>& state_matrix,
                        std::function<double(double)>& wavenumber) {
    const double c = ref.mu * ref.L * ref.L / ref.S, inv_e = ref.S / own.S, a = own.mu / ref.mu;
    state_matrix = [c, inv_e, a](double lambda) {
      Eigen::MatrixXd A(2, 2);
      A << 0.0, inv_e, -a * lambda * c, 0.0;
      return A;
    };
    wavenumber = [k = c * a * inv_e](double lambda) { return std::sqrt(std::abs(lambda) * k); };
  }
};

/// Rigid translation and rotation in bending are restrained by two translational springs (at
/// distinct points), or one and a rotational one.
bool bending_restrained(EndSprings l, EndSprings r, const PointAttachments& points);

inline void note_unknowns(long* unknowns, const AssembledLine& a) {
  if (unknowns) *unknowns = std::max<long>(*unknowns, a.K.free_dofs());
}

}  // namespace modalbench::exact::detail
