#pragma once
// Whirl of a shaft mode shared by both bending planes, for back-ends whose spin terms reduce to the
// translational mass's Coriolis and spin softening (Euler-Bernoulli sections without discs, the
// appendix's A3: the rotating frame's 2 L_e and -K_e are the translational mass matrix, turned).
// In the rotating frame, with the planes' frequencies of the mode omega_v (x-y) and omega_w (x-z):
//   (lambda^2 + omega_v^2 - Omega^2)(lambda^2 + omega_w^2 - Omega^2) + 4 Omega^2 lambda^2 = 0.
// Seen from the ground such a mode does not change with the spin (no gyroscopic moment).
#include <array>
#include <functional>
#include <vector>

#include "modalbench/result.hpp"

namespace modalbench {

/// One root pair +-lambda: frequency |Im lambda| (rad/s), growth rate Re of the growing root (1/s),
/// and its orbit's sense.
struct WhirlRoot {
  double omega = 0, growth = 0;
  Whirl whirl = Whirl::None;
  Orbit orbit;  ///< at the shape points, where asked (else empty)
};

/// The orbit of an axisymmetric shaft's whirl whose planar shape is `phi` at the points: a circle,
/// w = -i v forward, +i v backward (normalized as Orbit says); `sense` Forward or Backward.
Orbit circular_orbit(const std::vector<double>& phi, Whirl sense);
/// Scales an orbit as Orbit says (the largest |v|^2 + |w|^2 is 1, v there real > 0).
void normalize(Orbit& o);

/// One whirl direction of an axisymmetric shaft, seen from the ground: its lowest frequencies
/// (rad/s, ascending) and, where orbits are asked, each one's planar shape at the points.
struct WhirlBranch {
  std::vector<double> omega;
  std::vector<std::vector<double>> shape;
};
/// The whirl roots of an axisymmetric shaft at `spin` in the scene's frame (at least the lowest k,
/// ascending), from its two whirl lines: `branch(sense, n)` gives direction sense's lowest n (+1
/// forward, -1 backward), `forward_below(omega)` how many forward frequencies lie below omega. From
/// the ground they are as they are; in the rotating frame the backward ones at omega_B + spin and
/// the forward ones at |omega_F - spin|, their sense by the sign, every forward one up to spin plus
/// the k-th root taken. Orbits: circles of the branches' shapes.
std::vector<WhirlRoot> axisymmetric_whirl(double spin, bool rotating, int k,
                                          const std::function<WhirlBranch(int sense, int n)>& branch,
                                          const std::function<int(double omega)>& forward_below);

/// The mode's two roots in the rotating frame at spin Omega (at spin 0: two planar orbits).
std::array<WhirlRoot, 2> rotating_frame_roots(double omega_v, double omega_w, double spin);

/// A Campbell point from the roots of several modes: the lowest k, ascending, with the point's
/// growth rates; `unstable` set where one grows.
CampbellPoint campbell_point(double spin, std::vector<WhirlRoot> roots, int k, bool& unstable);

}  // namespace modalbench
