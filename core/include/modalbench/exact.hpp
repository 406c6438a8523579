#pragma once
// Exact references: continuous beams, bars and plates, solved without discretization error.
//
// Beams (Timoshenko; Euler-Bernoulli as kGA -> inf, rhoI -> 0), bars (axial, torsion):
//   the field equations are written as first-order Hamiltonian systems and solved by the
//   exact dynamic stiffness of short pieces (line_dsm.hpp); natural frequencies come from
//   the Wittrick-Williams count, so none is missed and repeated ones keep their multiplicity.
//   Timoshenko, harmonic, with M = EI phi', Q = kGA (w' - phi):
//     w' = phi + Q/kGA,  phi' = M/EI,  M' = -Q - rhoI w^2 phi,  Q' = -rhoA w^2 w.
//   End springs k_t (on w), k_r (on phi) in [0, inf]: Q(0) = k_t w(0), M(0) = k_r phi(0),
//   Q(L) = -k_t w(L), M(L) = -k_r phi(L).
//   Statics: the same system at omega = 0 with nodes at loads and probes (exact: the
//   static solution between point loads is polynomial).
// Plates:
//   Kirchhoff, all edges simply supported: Navier, omega_mn = pi^2 ((m/a)^2 + (n/b)^2) sqrt(D/(rho h)).
//   Kirchhoff, Levy: one pair of opposite edges simply supported, the others free, pinned,
//     clamped, guided or elastic: per half-wave number m the strip equation in the other
//     direction, by the same dynamic stiffness and count; the counts are summed over m.
//   Mindlin, all edges simply supported (hard): per (m, n) a 3x3 generalized eigenproblem in
//     (w, psi_x, psi_y), all three branches, plus the pure thickness-shear modes with m = 0
//     or n = 0; collected and sorted.
//
// Sources: Timoshenko & Gere; Wittrick & Williams (1971); Leissa, "Vibration of Plates"
// (NASA SP-160, 1969) for the Levy forms; Mindlin (1951) for the thick plate.

#include <array>
#include <complex>
#include <string>
#include <vector>

#include "modalbench/result.hpp"
#include "modalbench/scene.hpp"
#include "modalbench/solver.hpp"

namespace modalbench::exact {

/// Bending in one plane. Euler-Bernoulli: kGA = inf and rhoI = 0.
struct BeamBending {
  double EI = 0;    ///< N*m^2
  double kGA = 0;   ///< N (inf for Euler-Bernoulli)
  double rhoA = 0;  ///< kg/m
  double rhoI = 0;  ///< kg*m (rotary inertia per length; 0 for Euler-Bernoulli)
  double L = 0;     ///< m
};
struct EndSprings {
  double translational = 0;  ///< N/m, [0, inf]
  double rotational = 0;     ///< N*m/rad, [0, inf]
};
/// A bar: axial (S = EA, mu = rhoA) or torsion (S = GJ, mu = rho Ip).
struct Bar {
  double S = 0, mu = 0, L = 0;
};

struct Frequencies {
  std::vector<double> omega_rad_s;  ///< ascending, rigid-body modes as 0
  int rigid = 0;
  long count_evaluations = 0;
};

Frequencies beam_bending_frequencies(const BeamBending& beam, EndSprings left, EndSprings right, int k);
Frequencies bar_frequencies(const Bar& bar, double k_left, double k_right, int k);

/// A point action on a line: force (conjugate to w or u) and moment (about the axis
/// perpendicular to the bending plane, right-handed; for bending in x-z that is My).
struct LineLoad {
  double x = 0, force = 0, moment = 0;
};
struct BendingResponse {
  double w = 0;      ///< m
  double theta = 0;  ///< rad; = -phi for bending in x-z (theta_y), +phi in x-y (theta_z)
};
/// Static deflection of a beam in one plane at the probes. `moment_sign` = -1 for x-z
/// (theta_y = -phi), +1 for x-y (theta_z = +dv/dx). Throws std::runtime_error naming the
/// mechanism if the supports do not restrain rigid motion.
std::vector<BendingResponse> beam_static(const BeamBending& beam, EndSprings left, EndSprings right,
                                         const std::vector<LineLoad>& loads, const std::vector<double>& probes,
                                         double moment_sign);
/// Static displacement of a bar at the probes under point loads (force = Fx or Mx).
std::vector<double> bar_static(const Bar& bar, double k_left, double k_right, const std::vector<LineLoad>& loads,
                               const std::vector<double>& probes);
/// Undamped receptance w(observe)/F(excite) of a beam in one plane at omega (exact).
double beam_receptance(const BeamBending& beam, EndSprings left, EndSprings right, double excite, double observe,
                       double omega);

/// Kirchhoff plate, all edges simply supported (Navier).
std::vector<double> navier_frequencies(double a, double b, double D, double rho_h, int k);
/// Kirchhoff plate, all edges simply supported: receptance w(xo, yo) / F(xe, ye) at omega
/// (omega = 0: static flexibility) by the Navier double series over m, n <= `terms`, with
/// structural damping eta (omega_mn^2 -> omega_mn^2 (1 + i eta)). The series converges like
/// terms^-2 for the driving point; `tail` (if given) receives |S(terms) - S(terms / 2)|, a
/// bound on the truncation error.
std::complex<double> navier_receptance(double a, double b, double D, double rho_h, double eta, double xe, double ye,
                                       double xo, double yo, double omega, int terms, double* tail = nullptr);
/// Static deflection of a simply supported Kirchhoff plate at (x, y) under point forces,
/// with the slopes: returns {w, dw/dx, dw/dy}.
std::array<double, 3> navier_static(double a, double b, double D, const std::vector<std::array<double, 3>>& forces,
                                    double x, double y, int terms, double* tail = nullptr);

/// Mindlin plate, all edges simply supported (hard), every branch.
std::vector<double> mindlin_ss_frequencies(double a, double b, double h, double E, double nu, double G,
                                           double kappa, double rho, int k);
/// Kirchhoff plate with edges x = 0, a simply supported; `y0`, `yb` are the edges y = 0, b
/// (springs per unit length; pinned = {inf, 0}, clamped = {inf, inf}, free = {0, 0}).
Frequencies levy_frequencies(double a, double b, double D, double nu, double rho_h, EndSprings y0, EndSprings yb,
                             int k);

/// The `exact` back-end.
class ExactSolver final : public Solver {
 public:
  std::string name() const override { return "exact"; }
  std::string description() const override {
    return "exact continuum references: Timoshenko/Euler-Bernoulli beams, bars, Navier/Levy/Mindlin plates";
  }
  Capability supports(const Scene& scene) const override;
  Discretization default_mesh(const Scene&) const override { return {}; }

 protected:
  void do_solve(const Scene& scene, const Discretization& mesh, const Options& options,
                Result& result) const override;
};

/// Bending properties of a scene's beam in x-z (about y) or x-y (about z), per its theory.
BeamBending bending_xz(const Scene& s);
BeamBending bending_xy(const Scene& s);

}  // namespace modalbench::exact
