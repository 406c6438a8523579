#pragma once
// Private to the exact back-end: a spinning shaft's Campbell diagram and critical speeds.
#include <string>

#include "modalbench/result.hpp"
#include "modalbench/scene.hpp"

namespace modalbench::exact::detail {

/// Why exact gives no Campbell diagram for this rotor scene ("" where it does): the stationary
/// frame and the rotating frame of an axisymmetric shaft (per whirl direction, whirl_line.hpp), and
/// the rotating frame of an asymmetric uniform Euler-Bernoulli shaft whose two planes share their
/// mode shapes (per mode, closed form); a rotor that its supports leave free is not solved.
std::string rotor_refusal(const Scene& s);

/// The Campbell diagram and critical speeds of scene.rotor (rotor_refusal empty); count
/// evaluations are added to `sum`'s diagnostics.
Campbell rotor_campbell(const Scene& s, Summary& sum);

}  // namespace modalbench::exact::detail
