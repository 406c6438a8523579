#pragma once
// What the back-ends ask of a rotor scene ([rotor]) before they solve it, and how two Campbell
// diagrams of one scene compare: one definition for every back-end, the report and the benchmarks.
#include "modalbench/result.hpp"
#include "modalbench/scene.hpp"

namespace modalbench {

/// Every piece of the shaft has Iy = Iz (to 1e-12): its two bending planes are alike.
bool axisymmetric_shaft(const Scene& s);
/// Both ends free, pinned, clamped or guided (each spring 0 or held): with an asymmetric uniform
/// shaft, the two planes then share their mode shapes.
bool classical_ends(const Scene& s);
/// The supports hold the rotor's rigid motions: two translational springs, or one and a rotational
/// one (at the ends or between them). A free rotor's rigid whirl is not solved by any back-end.
bool rotor_held(const Scene& s);

/// The largest difference of two Campbell diagrams' whirl frequencies, paired by rank at each spin,
/// relative to |b's frequency| + spin; NaN where the spins or the counts differ.
double campbell_difference(const Campbell& a, const Campbell& b);

}  // namespace modalbench
