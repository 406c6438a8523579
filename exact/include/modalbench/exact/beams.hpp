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

#include <functional>
#include <vector>

#include "modalbench/exact/types.hpp"
#include "modalbench/scene.hpp"

namespace modalbench::exact {

/// A beam's properties in one plane at a point (BeamBending's units).
struct BendingProps {
  double EI = 0, kGA = 0, rhoA = 0, rhoI = 0;
};
/// How a tapered piece's properties vary along it (empty: a uniform piece): `at(x)` at x (m), and
/// `bound(x0, x1)` a uniform comparison over [x0, x1] with EI and kGA at most their lowest there and
/// rhoA and rhoI at least their highest (numerics' LineVariation: it keeps the count exact).
struct BendingVariation {
  std::function<BendingProps(double x)> at;
  std::function<BendingProps(double x0, double x1)> bound;
  explicit operator bool() const { return static_cast<bool>(at); }
};
/// A piece of a stepped beam in one plane, from x_from (m) on: its properties (BeamBending's; a
/// tapered piece's at x_from, and `varies`).
struct BendingStep {
  double x_from = 0, EI = 0, kGA = 0, rhoA = 0, rhoI = 0;
  BendingVariation varies = {};
};
/// Bending in one plane. Euler-Bernoulli: kGA = inf and rhoI = 0. A stepped beam: these are the
/// first piece's properties, and `steps` the pieces after it (ascending x_from in (0, L)).
struct BeamBending {
  double EI = 0;    ///< N*m^2
  double kGA = 0;   ///< N (inf for Euler-Bernoulli)
  double rhoA = 0;  ///< kg/m
  double rhoI = 0;  ///< kg*m (rotary inertia per length; 0 for Euler-Bernoulli)
  double L = 0;     ///< m
  std::vector<BendingStep> steps = {};
  /// A tapered first piece (its properties above are those at x = 0).
  BendingVariation varies = {};
  /// The properties at x (as a uniform one-piece BeamBending of length L): the piece holding x's,
  /// a tapered piece's at x itself.
  BeamBending at(double x) const;
  /// Whether a piece tapers.
  bool tapered() const;
};
struct BarProps {
  double S = 0, mu = 0;
};
/// A tapered bar piece (BendingVariation's meaning: S at most its lowest, mu at least its highest).
struct BarVariation {
  std::function<BarProps(double x)> at;
  std::function<BarProps(double x0, double x1)> bound;
  explicit operator bool() const { return static_cast<bool>(at); }
};
/// A piece of a stepped bar from x_from (m) on.
struct BarStep {
  double x_from = 0, S = 0, mu = 0;
  BarVariation varies = {};
};
/// A bar: axial (S = EA, mu = rhoA) or torsion (S = GJ, mu = rho Ip); stepped and tapered as
/// BeamBending.
struct Bar {
  double S = 0, mu = 0, L = 0;
  std::vector<BarStep> steps = {};
  BarVariation varies = {};
  Bar at(double x) const;
  bool tapered() const;
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
  /// A smooth factor on that intensity at x (m; a tapered piece's weight: its area over its first
  /// area). Empty: 1.
  std::function<double(double)> factor = {};
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
  double M = 0;      ///< bending moment EI phi' (sagging positive: concave towards +w), N*m
  double Q = 0;      ///< shear force dM/dx, N (just beyond the probe: x + 0; at L, L - 0)
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
/// Static displacement of a bar at the probes under point loads (force = Fx or Mx); `forces`, if
/// given, gets the bar's force S u' there (N tension positive, or the torque N*m; x + 0 as above).
std::vector<double> bar_static(const Bar& bar, double k_left, double k_right, const std::vector<LineLoad>& loads,
                               const std::vector<double>& probes, long* unknowns = nullptr,
                               const PointAttachments& points = {}, const DistributedLineLoads& dist = {},
                               std::vector<SupportReaction>* reactions = nullptr, std::vector<double>* forces = nullptr);
/// Undamped receptance w(observe)/F(excite) of a beam in one plane at omega (exact).
/// `unknowns`, if given, is raised to the size of the system solved (as for the statics).
double beam_receptance(const BeamBending& beam, EndSprings left, EndSprings right, double excite, double observe,
                       double omega, long* unknowns = nullptr, const PointAttachments& points = {});

/// Bending properties of a scene's beam in x-z (about y) or x-y (about z), per its theory (a
/// stepped beam: piece by piece).
BeamBending bending_xz(const Scene& s);
BeamBending bending_xy(const Scene& s);
/// A scene's beam as an axial bar (EA, rho A) and as a torsion bar (GJ, rho Ip), piece by piece.
Bar axial_bar(const Scene& s);
Bar torsion_bar(const Scene& s);

}  // namespace modalbench::exact
