#pragma once
// Private to the exact rotor: one whirl direction of an axisymmetric spinning shaft as a planar
// line. With r = v + i w and the tilt phi (the rotations as one complex number turning in the spin's
// sense), a shaft on isotropic supports whirling as e^{i omega t} obeys the planar Timoshenko
// equations with the rotary inertia of the section and of the discs changed per direction
// (derived from the angular momentum H = J_p Omega n + J_t (theta_y', theta_z') gives
// J_t theta_y'' + J_p Omega theta_z' = M_y, J_t theta_z'' - J_p Omega theta_y' = M_z):
//   rho I omega^2  ->  rho I omega^2 - s rho I_p Omega omega,   J_t omega^2  ->  J_t omega^2 - s J_p Omega omega,
// s = +1 for forward whirl (in the spin's sense), -1 for backward, omega > 0. The count stays exact:
// every quadratic form x' (K - omega^2 M + s omega Omega G) x has one positive root, where it falls.
// Synchronous whirl (omega = Omega: the critical speeds) makes the change a constant:
//   rho I - s rho I_p and J_t - s J_p, times omega^2.

#include "line_models.hpp"
#include "modalbench/scene.hpp"

namespace modalbench::exact::detail {

/// How the spin enters one whirl direction's line.
struct Whirling {
  int sense = +1;            ///< +1 forward, -1 backward
  double spin = 0;           ///< Omega, rad/s (not used when synchronous)
  bool synchronous = false;  ///< omega = Omega: the critical speeds' problem
};

/// The scene's shaft in x-z (Iy; axisymmetric: Iz alike) with its supports and discs, its rotary
/// inertias changed per `w`. Under Euler-Bernoulli theory the section has no rotary inertia and
/// no gyroscopic moment (only the discs do).
BendingLine whirl_line(const Scene& s, const Whirling& w);

/// The planar shape w(x) at `xs` of the whirl line's mode at `omega` (a root of whirl_line(s, w)):
/// the line's null vector carried along it by its transfer matrices (LineMode, line_system.hpp).
std::vector<double> whirl_shape(const Scene& s, const Whirling& w, double omega, const std::vector<double>& xs);

}  // namespace modalbench::exact::detail
