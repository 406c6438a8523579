#pragma once
// Internal: a spinning shaft on the regular Euler-Bernoulli chain, the rfem appendix's A3 case:
// the element's rotating-frame matrices (A3.1 as 2 L_e, A3.2 as -K_e) are its consistent
// translational mass, turned and scaled by the spin (whirl.hpp). The chain's mode shapes are shared
// by both bending planes where the ends are free, pinned, clamped or guided (the planes' stiffness
// matrices are then proportional) or the section is axisymmetric, so each mode's whirl is closed
// form and the cost stays independent of R. Seen from the ground the chain has no gyroscopic
// moment (an Euler-Bernoulli section has no rotary inertia): its frequencies do not change with
// the spin.
#include <string>

#include "modalbench/result.hpp"
#include "modalbench/scene.hpp"
#include "modalbench/solver.hpp"

namespace modalbench::difference_eq {

/// Why the chain gives no Campbell diagram for this rotor scene ("" where it does).
std::string rotor_refusal(const Scene& s);

/// The Campbell diagram and critical speeds of scene.rotor on R elements (rotor_refusal empty; in
/// the rotating frame the mass consistent: A3's matrices are the consistent mass's).
Campbell rotor_campbell(const Scene& s, long R, MassModel mass, Summary& sum);

}  // namespace modalbench::difference_eq
