#pragma once
// Private to the exact back-end: a beam scene's supports between the ends and point masses as
// each of its lines sees them, and the lines' support reactions gathered back per support.
#include <vector>

#include "modalbench/exact/beams.hpp"
#include "modalbench/result.hpp"
#include "modalbench/scene.hpp"

namespace modalbench::exact {

/// The scene's point supports and masses as seen by one line: bending in x-z (w, theta_y: Jy),
/// in x-y (v, theta_z: Jz), axial (u), torsion (theta_x: Jx).
PointAttachments line_points(const Scene& s, ModeFamily line);

/// The lines' support reactions (bending x-z, axial, bending x-y, torsion) per support in global
/// axes: x-z gives Fz and My, the axial bar Fx, x-y Fy and Mz, the torsion bar Mx.
std::vector<Reaction> gather_reactions(const Scene& s, const std::vector<SupportReaction>& xz,
                                       const std::vector<SupportReaction>& axial,
                                       const std::vector<SupportReaction>& xy,
                                       const std::vector<SupportReaction>& torsion);

}  // namespace modalbench::exact
