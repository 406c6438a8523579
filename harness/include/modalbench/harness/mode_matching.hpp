#pragma once
// Pairing the modes of a run with those of a reference.

#include <vector>

#include "modalbench/result.hpp"

namespace modalbench {

/// For every reference mode, the index of the matching mode of `run` (-1: none). Modes are
/// paired in order within each family, so a torsion mode is never paired with a bending one;
/// rigid-body modes are never paired. A run whose modes are all `unknown` is matched to the
/// non-rigid reference modes by index (and the caller should say so).
std::vector<int> match_modes(const std::vector<ModeFamily>& reference, const std::vector<ModeFamily>& run);

}  // namespace modalbench
