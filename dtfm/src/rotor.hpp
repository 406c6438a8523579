#pragma once
// Private to dtfm: a spinning axisymmetric shaft (scene [rotor]) on the one-prism line. With
// r = v + i w and the section's tilt turning as one complex number, each whirl direction of a shaft
// on isotropic supports is a planar (x-z) prism line whose rotary inertia is changed per direction
// (as exact's whirl_line.hpp):
//   rho I omega^2 -> rho I omega^2 - s rho I_p Omega omega,   J_t omega^2 -> J_t omega^2 - s J_p Omega omega,
// s = +1 forward, -1 backward (PrismModel::G, PrismModel::whirl). Every quadratic form
// x' (K - omega^2 M + s omega Omega G) x has one positive root, so the Wittrick-Williams count of
// the segment dynamic stiffness (its J0 from the doubling) stays exact per direction. Synchronous
// whirl (omega = Omega, the critical speeds) is the planar line with rho I - s rho I_p and J_t - s J_p.
// Under Euler-Bernoulli theory the section has neither rotary inertia nor gyroscopic moment: only
// the discs have.
#include <string>

#include "modalbench/dtfm/analysis.hpp"
#include "modalbench/dtfm/prism_model.hpp"
#include "modalbench/result.hpp"
#include "modalbench/scene.hpp"

namespace modalbench::dtfm::detail {

/// Why dtfm gives no Campbell diagram for this rotor scene ("" where it does).
std::string rotor_refusal(const Scene& s);

/// The Campbell diagram and critical speeds of scene.rotor (rotor_refusal empty), on one prism per
/// section with these layer options and solve controls; a count that does not reproduce is raised
/// in `sum` as a numerical issue.
Campbell rotor_campbell(const Scene& s, const ModelOptions& mo, const SolveControls& ctl, Summary& sum);

}  // namespace modalbench::dtfm::detail
