#pragma once
// Exact beams and bars: the field equations as first-order Hamiltonian systems, solved by
// the exact dynamic stiffness of short pieces (numerics/line_system.hpp); natural
// frequencies come from the Wittrick-Williams count, so none is missed and repeated ones
// keep their multiplicity.
//
// Timoshenko, harmonic, with M = EI phi', Q = kGA (w' - phi):
//   w' = phi + Q/kGA,  phi' = M/EI,  M' = -Q - rhoI w^2 phi,  Q' = -rhoA w^2 w.
// Euler-Bernoulli as kGA -> inf, rhoI -> 0. End springs k_t (on w), k_r (on phi) in
// [0, inf]: Q(0) = k_t w(0), M(0) = k_r phi(0), Q(L) = -k_t w(L), M(L) = -k_r phi(L).
// Statics: the same system at omega = 0 with nodes at loads and probes (exact: the static
// solution between point loads is polynomial). Bars (axial, torsion): [u, N] alike.
//
// Sources: Timoshenko & Gere; Wittrick & Williams (1971).

#include <vector>

#include "modalbench/exact/types.hpp"
#include "modalbench/scene.hpp"

namespace modalbench::exact {

/// Bending in one plane. Euler-Bernoulli: kGA = inf and rhoI = 0.
struct BeamBending {
  double EI = 0;    ///< N*m^2
  double kGA = 0;   ///< N (inf for Euler-Bernoulli)
  double rhoA = 0;  ///< kg/m
  double rhoI = 0;  ///< kg*m (rotary inertia per length; 0 for Euler-Bernoulli)
  double L = 0;     ///< m
};
/// A bar: axial (S = EA, mu = rhoA) or torsion (S = GJ, mu = rho Ip).
struct Bar {
  double S = 0, mu = 0, L = 0;
};

/// A support or a mass between (or at) the ends of one line, at x (m): springs to ground
/// (`springs`: bending translational N/m and rotational N*m/rad; a bar uses `translational` for its
/// one DOF, N/m or N*m/rad), inf = held; a point mass (kg; a torsion bar: the polar inertia,
/// kg*m^2) and, in bending, a rotary inertia about the bending axis (kg*m^2). A node of the line.
struct PointAttachment {
  double x = 0;
  EndSprings springs{0.0, 0.0};
  double mass = 0, inertia = 0;
};
using PointAttachments = std::vector<PointAttachment>;

Frequencies beam_bending_frequencies(const BeamBending& beam, EndSprings left, EndSprings right, int k,
                                     const PointAttachments& points = {});
Frequencies bar_frequencies(const Bar& bar, double k_left, double k_right, int k, const PointAttachments& points = {});

/// A point action on a line: force (conjugate to w or u) and moment (about the axis
/// perpendicular to the bending plane, right-handed; for bending in x-z that is My).
struct LineLoad {
  double x = 0, force = 0, moment = 0;
};
/// A distributed load on a line over [x_from, x_to] (m), N/m (a bar in torsion: N*m/m), varying
/// linearly from q_from to q_to.
struct DistributedLineLoad {
  double x_from = 0, x_to = 0, q_from = 0, q_to = 0;
};
using DistributedLineLoads = std::vector<DistributedLineLoad>;
/// What a support of one line exerts on it under the static loads: force (N; a torsion bar: N*m)
/// and, in bending, moment (N*m, in the convention of the loads' `moment`), at x (m).
struct SupportReaction {
  double x = 0, force = 0, moment = 0;
};
struct BendingResponse {
  double w = 0;      ///< m
  double theta = 0;  ///< rad; = -phi for bending in x-z (theta_y), +phi in x-y (theta_z)
};
/// Static deflection of a beam in one plane at the probes (point loads, and distributed loads: their
/// ends and the probes then become nodes, and each segment's share is integrated by 4-point Gauss,
/// exact for the static fixed-end reactions, cubic in the point's position, times a linear load). `moment_sign` = -1 for x-z
/// (theta_y = -phi), +1 for x-y (theta_z = +dv/dx). Throws std::runtime_error naming the
/// mechanism if the supports do not restrain rigid motion.
std::vector<BendingResponse> beam_static(const BeamBending& beam, EndSprings left, EndSprings right,
                                         const std::vector<LineLoad>& loads, const std::vector<double>& probes,
                                         double moment_sign, long* unknowns = nullptr,
                                         const PointAttachments& points = {}, const DistributedLineLoads& dist = {},
                                         std::vector<SupportReaction>* reactions = nullptr);
/// Static displacement of a bar at the probes under point loads (force = Fx or Mx).
std::vector<double> bar_static(const Bar& bar, double k_left, double k_right, const std::vector<LineLoad>& loads,
                               const std::vector<double>& probes, long* unknowns = nullptr,
                               const PointAttachments& points = {}, const DistributedLineLoads& dist = {},
                               std::vector<SupportReaction>* reactions = nullptr);
/// Undamped receptance w(observe)/F(excite) of a beam in one plane at omega (exact).
/// `unknowns`, if given, is raised to the size of the system solved (as for the statics).
double beam_receptance(const BeamBending& beam, EndSprings left, EndSprings right, double excite, double observe,
                       double omega, long* unknowns = nullptr, const PointAttachments& points = {});

/// Bending properties of a scene's beam in x-z (about y) or x-y (about z), per its theory.
BeamBending bending_xz(const Scene& s);
BeamBending bending_xy(const Scene& s);

}  // namespace modalbench::exact
