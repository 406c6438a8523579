#pragma once
// Stress resultants of a beam from the equilibrium of a free body: what acts on [0, x] (the
// support reactions there, the point loads, the distributed loads) is balanced by the resultants
// at the cut. A back-end that gives reactions but no fields between its nodes (rfem) gets its
// resultants this way, with the loads' own jumps (exact at a point load) and the accuracy of its
// reactions.

#include <vector>

#include "modalbench/result.hpp"
#include "modalbench/scene.hpp"

namespace modalbench {

/// The resultants at x of a beam scene (result.hpp, InternalForces conventions: My = EI w'',
/// Qz = dMy/dx, ...) from `reactions` (Result::reactions: what each support exerts, global axes)
/// and the scene's loads (Scene::all_point_loads, all_distributed_loads) on [0, x]: the point
/// actions at x count (x + 0), except at the right end (L - 0). Distributed loads are integrated
/// exactly (linear intensities).
InternalForces free_body_forces(const Scene& scene, const std::vector<Reaction>& reactions, double x);

}  // namespace modalbench
