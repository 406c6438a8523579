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

/// The modal assurance criterion of mode `i` of `a` and mode `j` of `b` (shapes sampled at the
/// same points): |x.y|^2 / ((x.x)(y.y)) over the translations (u, v, w) and the twist times
/// `twist_length` (a beam section's radius of gyration; 0 ignores the twist). NaN if either
/// vector is zero or the samples differ.
double mac(const ModeShapes& a, std::size_t i, const ModeShapes& b, std::size_t j, double twist_length);
/// MAC[reference mode][run mode].
std::vector<std::vector<double>> mac_matrix(const ModeShapes& reference, const ModeShapes& run, double twist_length);

/// Pairs by MAC: candidates are pairs of the same family (either one `unknown` pairs with any
/// elastic family; rigid modes never), taken greedily by descending MAC, each run mode once.
/// Returns, per reference mode, the run mode (-1: none).
std::vector<int> match_modes_by_mac(const std::vector<ModeFamily>& reference, const std::vector<ModeFamily>& run,
                                    const std::vector<std::vector<double>>& mac);

}  // namespace modalbench
