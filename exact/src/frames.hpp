#pragma once
// Private to the exact back-end: a frame's kernels (frame_system.hpp assembles it).

#include <string>

#include "modalbench/result.hpp"
#include "modalbench/scene.hpp"
#include "modalbench/solver.hpp"

namespace modalbench::exact::detail {

/// What the frame's solve is estimated to cost (Solver::estimate).
ResourceEstimate frame_estimate(const Scene& s);
/// The method, in words (Summary::method).
std::string frame_method(const Scene& s);
/// request.modes natural frequencies of the frame: bisection on the Wittrick-Williams count.
void frame_modes(const Scene& s, Result& r);
/// Displacements at the probes, member stress resultants at member probes, reactions.
void frame_statics(const Scene& s, Result& r);

}  // namespace modalbench::exact::detail
