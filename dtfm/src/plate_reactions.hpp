#pragma once
// A dtfm plate's support reactions from its static solution (plate_reactions.cpp).
#include <vector>

#include "modalbench/dtfm/analysis.hpp"
#include "modalbench/result.hpp"

namespace modalbench::dtfm::detail {

/// One per supported edge (x0, xL, y0, yB), placed at its middle: the force (+z) and the moments
/// about the middle the support exerts on the plate; the corners go to the long edges (y0, yB).
std::vector<Reaction> plate_reactions(const Scene& s, const PrismModel& m, const FieldIntegrals& fi);

}  // namespace modalbench::dtfm::detail
