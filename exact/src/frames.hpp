#pragma once
// Private to the exact back-end: a frame's kernels (frame_system.hpp assembles it).

#include "modalbench/result.hpp"
#include "modalbench/scene.hpp"

namespace modalbench::exact::detail {

/// request.modes natural frequencies of the frame: bisection on the Wittrick-Williams count.
void frame_modes(const Scene& s, Result& r);
/// Displacements at the probes, member stress resultants at member probes, reactions.
void frame_statics(const Scene& s, Result& r);

}  // namespace modalbench::exact::detail
