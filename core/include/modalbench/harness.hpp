#pragma once
// The comparison harness: every back-end that supports a scene, on that scene, against the
// exact reference; written out as Markdown, HTML and JSON.

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "modalbench/result.hpp"
#include "modalbench/scene.hpp"
#include "modalbench/solver.hpp"

namespace modalbench {

struct RunRecord {
  std::string backend;
  Discretization mesh;
  Result result;
};

struct SceneReport {
  Scene scene;
  std::vector<RunRecord> runs;  ///< the exact reference (if any) first
};

struct CompareOptions {
  std::filesystem::path out_dir = "report";
  std::ostream* progress = nullptr;  ///< where progress lines go (stderr from the CLI)
};

/// Runs every solver of `registry` on every scene and writes report.md, index.html and
/// results.json into `options.out_dir`. Returns the reports.
std::vector<SceneReport> compare(const std::vector<Scene>& scenes, const Registry& registry,
                                 const CompareOptions& options);

/// Built-in scenes: every *.toml in `dir`, sorted by file name.
std::vector<std::filesystem::path> scene_files(const std::filesystem::path& dir);

}  // namespace modalbench
