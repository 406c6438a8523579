#pragma once
// Writes a comparison as report.md, a self-contained index.html (tables and inline SVG
// plots made by gnuplot), runs.csv, frequencies.csv and results.json (with the machine,
// compiler, build type and library versions).

#include <string>
#include <vector>

#include "modalbench/harness/comparison.hpp"

namespace modalbench {

struct ReportOptions {
  std::string title = "modalbench comparison report";
  std::string gnuplot = "gnuplot";  ///< the gnuplot executable; plots are skipped (and said so) if it fails
  std::vector<std::string> preface;  ///< extra paragraphs at the top (e.g. skipped references)
};

/// Writes the report into `dir` (created if needed). Returns the path of index.html.
std::string write_report(const std::vector<SceneComparison>& comparisons, const std::string& dir,
                         const ReportOptions& options);

/// Machine, compiler, build type and library versions, one "key: value" per entry.
std::vector<std::pair<std::string, std::string>> environment_info(const std::string& gnuplot);

}  // namespace modalbench
