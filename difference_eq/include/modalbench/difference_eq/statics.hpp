#pragma once
// Static closed forms of the regular discrete beam under nodal forces and moments.
//
// Decomposition (the paper's settlement superposition, generalised to four springs):
//   u = u_cc + N d,
// where u_cc is the response of the beam with all four end DOFs held (clamped-clamped, the
// "rigid-support problem"), N d is the field of the end displacements d = (w0, psi0, wL, psiL)
// (the solution of Delta^4 w = 0 with those end values: the Hermite cubic, the paper's
// (13)-(15) generalised), and d closes the 4x4 superelement equation
//   (K_L + S) d = f_eq,   K_L = EI/L^3 [[12, 6L, -12, 6L], ...],  f_eq = -(reactions of u_cc),
// S = diag(kappa0, chi0, kappaL, chiL) (held DOFs removed). The 4x4 is solved as a ratio
// of multilinear polynomials in the springs with exact integer minors of K_L (Cramer's
// rule expanded over spring subsets; the paper's (21) is this for three springs), so
// springs from 1e-6 to 1e12 (and 0, inf) keep full relative accuracy.
//
// Two ways to get u_cc (both exact for the discrete model, which for nodal loads coincides
// with the continuous Euler-Bernoulli solution at the nodes):
//  * PiecewiseCubic (default, O(R + loads)): between loaded nodes Delta^4 w = 0, so the
//    clamped-clamped discrete Green's function is a cubic in r on each side of the load:
//    w(xi) = (P L^3/EI) (1-s)^2 xi^2 (3s - (1+2s) xi)/6 for xi <= s (mirror for xi >= s),
//    and its s-derivative for a moment. Every node is evaluated from running sums of the
//    per-load cubic coefficients (one sweep from each end), in xi = r/R and 1 - xi.
//  * EigenfunctionExpansion (O(R^2), the paper's path): the clamped-pinned eigenfunction
//    expansion (7) with alpha_k^2, W_{r,k}, Phi_{r,k} in closed form (mu_k, nu_k), nodal
//    moments through Phi_{r,k} plus the local rotation Green's function (w held), then the
//    cubic settlement (15) of the end rotation at r = R that turns pinned into clamped.
//
// Source: M. Lasecka, Eqs. (1)-(24) (seed lasecka-difference-equation-beam-pl.txt).

#include <array>
#include <string>
#include <vector>

#include "modalbench/difference_eq/regular_beam.hpp"

namespace modalbench::difference_eq {

enum class StaticMethod { PiecewiseCubic, EigenfunctionExpansion };
std::string to_string(StaticMethod);

struct StaticSolution {
  std::vector<double> w;      ///< deflection at nodes 0..R, m
  std::vector<double> slope;  ///< dw/dx at nodes 0..R, rad
  /// Support actions on the beam (force, moment conjugate to slope) at (x=0: F, M; x=L: F, M).
  std::array<double, 4> reactions{};
  /// Largest eigenvalue of the dimensionless support flexibility (K_L + S)^-1 in units of
  /// L^3/EI (translations) and L/EI (rotations); O(1) for a well supported beam, huge near
  /// a mechanism (deflections are then dominated by rigid-body motion).
  double support_flexibility = 0;
  /// Condition number of the free part of K_L + S (2-norm), from accurate extreme eigenvalues.
  double support_condition = 0;
  /// support_flexibility above kNearMechanismFlexibility: the supports restrain rigid-body motion
  /// only weakly and the deflections are dominated by it (and scale with the springs' compliance).
  bool near_mechanism = false;
  std::vector<std::string> warnings;
};

/// Largest R accepted by the O(R^2) eigenfunction route.
inline constexpr long kMaxEigenfunctionR = 50000;

/// Above this support flexibility (in units of L^3/EI) the statics are a near-mechanism (StaticSolution).
inline constexpr double kNearMechanismFlexibility = 1e4;

/// Nodal deflections and slopes for nodal loads. Throws Mechanism if the springs leave a
/// rigid-body motion free, std::invalid_argument for bad input.
StaticSolution solve_static(const RegularBeam& beam, const std::vector<NodalLoad>& loads,
                            StaticMethod method = StaticMethod::PiecewiseCubic);
/// The same, writing into `out` (its storage is reused: no page faults on repeated solves).
void solve_static(const RegularBeam& beam, const std::vector<NodalLoad>& loads, StaticMethod method,
                  StaticSolution& out);

/// Relative residual ||K u - f||_inf / (||K||_inf ||u||_inf + ||f||_inf) of the assembled FE
/// equations (held DOFs excluded), evaluated element by element in O(R).
double static_residual(const RegularBeam& beam, const std::vector<NodalLoad>& loads, const StaticSolution& s);

/// Deflection and slope at x in [0, L] by Hermite interpolation of the element's nodal
/// values (exact for nodal loads: the element is unloaded, its solution cubic).
std::array<double, 2> interpolate(const RegularBeam& beam, const StaticSolution& s, double x);

}  // namespace modalbench::difference_eq
