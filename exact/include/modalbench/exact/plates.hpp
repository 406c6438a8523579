#pragma once
// Exact plates.
//   Kirchhoff, all edges simply supported: Navier, omega_mn = pi^2 ((m/a)^2 + (n/b)^2) sqrt(D/(rho h)).
//   Kirchhoff, Levy: one pair of opposite edges simply supported, the others free, pinned,
//     clamped, guided or elastic: per half-wave number m the strip equation in the other
//     direction, by the exact dynamic stiffness and count (numerics/line_system.hpp); the
//     counts are summed over m.
//   Mindlin, all edges simply supported (hard): per (m, n) a 3x3 generalized eigenproblem in
//     (w, psi_x, psi_y), all three branches, plus the pure thickness-shear modes with m = 0
//     or n = 0; collected and sorted.
//
// Sources: Leissa, "Vibration of Plates" (NASA SP-160, 1969) for the Levy forms; Mindlin
// (1951) for the thick plate.

#include <array>
#include <complex>
#include <utility>
#include <vector>

#include "modalbench/exact/types.hpp"
#include "modalbench/numerics/line_system.hpp"

namespace modalbench::exact {

/// Kirchhoff plate, all edges simply supported (Navier).
std::vector<double> navier_frequencies(double a, double b, double D, double rho_h, int k);
/// Kirchhoff plate, all edges simply supported: receptance w(xo, yo) / F(xe, ye) at omega
/// (omega = 0: static flexibility) by the Navier double series over m, n <= `terms`, with
/// structural damping eta (omega_mn^2 -> omega_mn^2 (1 + i eta)). The series converges like
/// terms^-2 for the driving point; `tail` (if given) receives |S(terms) - S(terms / 2)|, a
/// bound on the truncation error.
std::complex<double> navier_receptance(double a, double b, double D, double rho_h, double eta, double xe, double ye,
                                       double xo, double yo, double omega, int terms, double* tail = nullptr);
/// The same over m <= M, n <= N; `tail` gets |S(M, N) - S(M / 2, N / 2)|.
std::complex<double> navier_receptance(double a, double b, double D, double rho_h, double eta, double xe, double ye,
                                       double xo, double yo, double omega, int M, int N, double* tail);
/// M x N about terms^2 terms with M / a = N / b: the truncation at one wavenumber in both directions
/// (a square plate: terms x terms; a 30 x 0.6 m strip at 300: 2121 x 42, where 300 x 300 leaves
/// the long direction 50 times less resolved than the short one).
std::pair<int, int> navier_balanced_terms(double a, double b, int terms);
/// A uniform pressure p (Pa, along +z) over the patch [x1, x2] x [y1, y2] of a plate.
struct PressurePatch {
  double x1 = 0, x2 = 0, y1 = 0, y2 = 0, p = 0;
};
/// Static deflection of a simply supported Kirchhoff plate at (x, y) under point forces {x, y, Fz}
/// and pressure patches, with the slopes: returns {w, dw/dx, dw/dy}. A patch's load coefficient is
/// (4 p / a b) (a / m pi) (cos(m pi x1/a) - cos(m pi x2/a)) (b / n pi) (cos(n pi y1/b) - cos(n pi y2/b)).
/// `curvature`, if given, gets {w_xx, w_yy, w_xy} there and `curvature_tail` the largest of their
/// |S(terms) - S(terms / 2)| (the moments' series converge slower than w's, and not at all under a
/// point force at (x, y), where Kirchhoff's moments are infinite).
std::array<double, 3> navier_static(double a, double b, double D, const std::vector<std::array<double, 3>>& forces,
                                    double x, double y, int terms, double* tail = nullptr,
                                    const std::vector<PressurePatch>& patches = {},
                                    std::array<double, 3>* curvature = nullptr, double* curvature_tail = nullptr);
/// The same over m <= M, n <= N (navier_balanced_terms); the tails against S(M / 2, N / 2).
std::array<double, 3> navier_static(double a, double b, double D, const std::vector<std::array<double, 3>>& forces,
                                    double x, double y, int M, int N, double* tail,
                                    const std::vector<PressurePatch>& patches, std::array<double, 3>* curvature,
                                    double* curvature_tail);

/// The reactions of a simply supported Kirchhoff plate under the same loads (plate_reactions.cpp):
/// Levy single series whose strips are solved in closed form, terms doubled from 64 until the
/// estimated truncation error is below tolerance / 10 of the total load or max_terms is reached.
struct NavierReactions {
  /// Edges x = 0, x = a, y = 0, y = b: the total Kirchhoff effective shear the support exerts (N,
  /// +z) and its first moment about the edge's middle along the edge (N m), corners excluded.
  std::array<double, 4> edge_force{}, edge_first_moment{};
  /// The corner forces at (0,0), (a,0), (0,b), (a,b) (N, +z; they hold the corners down).
  std::array<double, 4> corner{};
  int terms = 0;                      ///< series terms per direction
  double tail = 0, tail_relative = 0; ///< truncation estimate, N and relative to the total load
};
NavierReactions navier_reactions(double a, double b, double D, double nu, const std::vector<std::array<double, 3>>& forces,
                                 const std::vector<PressurePatch>& patches, double tolerance, int max_terms = 1 << 18);

/// Mindlin plate, all edges simply supported (hard), every branch.
std::vector<double> mindlin_ss_frequencies(double a, double b, double h, double E, double nu, double G,
                                           double kappa, double rho, int k);
/// Kirchhoff plate with edges x = 0, a simply supported; `y0`, `yb` are the edges y = 0, b
/// (springs per unit length; pinned = {inf, 0}, clamped = {inf, inf}, free = {0, 0}).
Frequencies levy_frequencies(double a, double b, double D, double nu, double rho_h, EndSprings y0, EndSprings yb,
                             int k);

/// A Navier mode w = sin(m pi x / a) sin(n pi y / b).
struct NavierMode {
  double omega = 0;  ///< rad/s
  int m = 0, n = 0;
};
/// The k lowest Navier modes, ascending (ties in order of m).
std::vector<NavierMode> navier_modes(double a, double b, double D, double rho_h, int k);

/// The Levy strip of half-wave number m as a line system on y_bar = y / b in [0, 1]: state
/// [W_bar, W_bar', F_w, F_theta], W_bar = W / b, lambda = omega^2 (see plates.cpp).
LineSystem levy_strip(double a, double b, double D, double nu, double rho_h, EndSprings y0, EndSprings yb, int m);
/// How many strips m = 1, 2, ... can have a natural frequency below sqrt(lambda).
int levy_strip_count(double a, double D, double nu, double rho_h, double lambda);

}  // namespace modalbench::exact
