#pragma once
// Internal: supports, springs and masses at nodes of the regular discrete beam, and distributed
// loads, by the paper's superposition (Lasecka: the closed form of the regular chain plus a small
// system for the unknown point actions).
//
// Statics (attached_statics.cpp): the closed-form solution u0 under the loads with the end
// supports alone, the closed-form responses u_j to a unit action at each restrained point DOF,
// and the point reactions X from (G + C) X = -u0(points), G_ij = u_j at DOF i, C = diag(1 / k)
// (0 where held); u = u0 + sum X_j u_j. Cost O(R (1 + point DOFs)). Distributed loads enter as
// their consistent nodal forces, which are their exact nodal equivalents for Hermite elements
// (the nodal values of the discrete beam are those of the Euler-Bernoulli beam); between nodes the
// loaded element adds its clamped-clamped particular solution to the Hermite interpolation.
//
// Vibration (attached_vibration.cpp): the nodes with attachments cut the chain into regular
// sub-chains, each a closed form (its 4x4 end dynamic stiffness and its clamped-clamped count);
// assembled over the attachment nodes with the springs and the masses (-omega^2 m on w, -omega^2 J
// on the slope), the Wittrick-Williams count is sum J0 + neg(K_nodes): exact, and its cost is
// independent of R. Frequencies by bisection on it; mode shapes by inverse iteration on the
// assembled banded model (the same discrete beam), which also checks each mode's residual.

#include <array>
#include <string>
#include <vector>

#include "modalbench/difference_eq/regular_beam.hpp"
#include "modalbench/difference_eq/statics.hpp"
#include "modalbench/difference_eq/vibration.hpp"
#include "modalbench/scene.hpp"

namespace modalbench::difference_eq {

/// A support and / or point mass at a node.
struct NodalAttachment {
  long node = 0;
  double k = 0;  ///< translational spring on w, N/m, [0, inf]
  double r = 0;  ///< rotational spring on the slope, N m/rad, [0, inf]
  double m = 0;  ///< mass, kg
  double J = 0;  ///< rotary inertia turning with the slope (Jy), kg m^2
};

/// A line load q(x) = q0 + (q1 - q0) (x - x0) / (x1 - x0) along +z over whole elements [e0, e1).
struct ElementLoad {
  long e0 = 0, e1 = 0;
  double x0 = 0, x1 = 0;  ///< m
  double q0 = 0, q1 = 0;  ///< N/m at x0 and x1
  double at(double x) const { return q0 + (q1 - q0) * (x - x0) / (x1 - x0); }
};

/// The scene's supports between the ends and point masses on mesh R (bending in x-z: w and the
/// slope; Jy). Throws InputError (the scene file, the key) for one that is not on a node.
std::vector<NodalAttachment> attachments_of(const Scene& s, long R);
/// The scene's line loads (qz) and, under gravity, the weight rho A g_z, on mesh R. Throws
/// InputError for a load whose ends are not nodes.
std::vector<ElementLoad> element_loads_of(const Scene& s, long R);
/// Node r with r L / R within 1e-9 L of x, or -1.
long node_at(double x, double L, long R);

/// The consistent (exact equivalent) nodal forces and moments of the line loads.
std::vector<NodalLoad> equivalent_nodal_loads(const RegularBeam& b, const std::vector<ElementLoad>& q);

/// Static solution with attachments (their springs; masses play no part). Reactions of the
/// point supports in `reactions` (force, moment conjugate to the slope, per attachment). Throws
/// Mechanism if the end supports alone leave the beam free (the superposition needs them).
StaticSolution solve_static_attached(const RegularBeam& b, const std::vector<NodalLoad>& loads,
                                     const std::vector<NodalAttachment>& at, StaticMethod method,
                                     std::vector<std::array<double, 2>>& reactions);

/// Relative residual of the assembled equations with the point reactions as loads, together with
/// the attachments' own laws (held: u = 0; spring: X = -k u).
double attached_static_residual(const RegularBeam& b, const std::vector<NodalLoad>& loads,
                                const std::vector<NodalAttachment>& at, const StaticSolution& s,
                                const std::vector<std::array<double, 2>>& reactions);

/// Deflection and slope at x: the Hermite interpolation plus the loaded element's clamped-clamped
/// particular solution.
std::array<double, 2> interpolate_loaded(const RegularBeam& b, const StaticSolution& s, const std::vector<ElementLoad>& q,
                                         double x);

/// Natural frequencies with attachments (rigid ones first, as zeros).
Spectrum natural_frequencies_attached(const RegularBeam& b, MassModel mass, const std::vector<NodalAttachment>& at, int k,
                                      std::string& problem);
/// The rigid motions no support reaches (nodal shapes, not normalized).
std::vector<ModeShape> rigid_shapes_attached(const RegularBeam& b, const std::vector<NodalAttachment>& at);
/// The same count by the assembled banded model's Sturm sequence (O(R)): an independent check.
long assembled_count_attached(const RegularBeam& b, MassModel mass, const std::vector<NodalAttachment>& at, double lambda);
/// Whether the same count in binary128 confirms lambda as the frequency number index + 1 (none
/// below lambda (1 - 1e-8), at least index + 1 below lambda (1 + 1e-8)): where double rounding
/// (the assembled model's condition grows like R^4) cannot resolve that window. O(R) software floats.
bool assembled_count_confirms(const RegularBeam& b, MassModel mass, const std::vector<NodalAttachment>& at,
                              double lambda, long index);
/// Number of natural frequencies with omega^2 < lambda (the sub-chain count).
long count_below_attached(const RegularBeam& b, MassModel mass, const std::vector<NodalAttachment>& at, double lambda);
/// The nodal mode shape at a natural frequency (inverse iteration on the assembled model) and its
/// normwise backward error in the assembled equations.
ModeShape mode_shape_attached(const RegularBeam& b, MassModel mass, const std::vector<NodalAttachment>& at,
                              double omega_rad_s, double& backward_error);

}  // namespace modalbench::difference_eq
