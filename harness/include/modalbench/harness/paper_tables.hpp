#pragma once
// Published columns of the prism paper (seeds/hein-…), with ERRATA.md applied, for the
// side-by-side tables of the report. Keyed by scene name.

#include <string>
#include <vector>

namespace modalbench {

struct PublishedColumn {
  std::string label;           ///< e.g. "paper: 4 prisms"
  std::vector<double> values;  ///< rad/s, mode by mode
  std::string note;            ///< provenance / caveat
};

struct PublishedTable {
  std::string title;
  std::vector<PublishedColumn> columns;
};

/// The published table for a scene, or an empty table (no columns) if none.
PublishedTable published_table(const std::string& scene_name);

}  // namespace modalbench
