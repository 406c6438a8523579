#pragma once
// Published columns for the side-by-side tables of the report, keyed by scene name: the prism
// paper (with its corrections, docs/sources.md) and the NAFEMS free-vibration benchmarks
// (NAFEMS R0015: FV5, FV12, FV16, FV52).

#include <string>
#include <vector>

#include "modalbench/result.hpp"

namespace modalbench {

struct PublishedColumn {
  std::string label;           ///< e.g. "paper: 4 prisms"
  std::vector<double> values;  ///< rad/s, mode by mode
  std::string note;            ///< provenance / caveat
};

struct PublishedTable {
  std::string title;
  std::vector<PublishedColumn> columns;
  /// Per row: the family of the mode it lists (the k-th row of a family is set beside our k-th
  /// mode of that family; `unknown`: a mode no model of ours has). Empty: bending modes of a beam,
  /// plate modes of a plate, in order.
  std::vector<ModeFamily> families = {};
};

/// The published table for a scene, or an empty table (no columns) if none.
PublishedTable published_table(const std::string& scene_name);

}  // namespace modalbench
