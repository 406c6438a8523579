#pragma once
// The comparison harness: every back-end that supports a scene runs over its ladder of
// discretizations; each run is timed (median of repeats after a warm-up) and its error is
// taken per quantity against a reference: the `exact` back-end where the scene has an exact
// solution, otherwise a Richardson extrapolation of the best-converging back-end, with its
// stated uncertainty.
//
// Usage:
//   CompareOptions opt;  opt.budget_s = 20;  opt.progress = &std::cerr;
//   std::vector<SceneComparison> c = run_comparison(scenes, registry, opt);
//   write_report(c, "report", ReportOptions{});      // report.hpp

#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "modalbench/harness/convergence.hpp"
#include "modalbench/harness/mode_matching.hpp"
#include "modalbench/result.hpp"
#include "modalbench/scene.hpp"
#include "modalbench/solver.hpp"

namespace modalbench {

/// What the errors were measured against.
struct Reference {
  std::string source;  ///< "exact", "richardson(<backend>)", or "none"
  std::vector<double> frequencies_rad_s;
  std::vector<ModeFamily> families;
  std::vector<double> frequency_uncertainty;  ///< absolute, rad/s (0 for exact)
  std::vector<Deflection> deflections;
  std::vector<Deflection> deflection_line;  ///< the exact static deflection on a fine grid (beams)
  std::vector<FrfSample> frf;
  ModeShapes shapes;  ///< the reference's mode shapes (exact, or the finest run of the extrapolated back-end)
};

/// MAC below which a pair of modes is flagged (report and runs table).
inline constexpr double kLowMac = 0.9;

struct RunRecord {
  std::string backend;
  Discretization mesh;
  Result result;
  double median_s = kNaN;  ///< median wall time of the timed repeats
  int repeats = 0;
  // Errors against the scene's reference (NaN where not available).
  std::vector<double> frequency_errors;  ///< per reference mode (relative)
  double max_frequency_error = kNaN;     ///< over the first min(6, modes) non-rigid reference modes
  double deflection_error = kNaN;        ///< max |w - w_ref| / max |w_ref| over probes
  double frf_error_db = kNaN;            ///< median |20 log10(|H| / |H_ref|)| over common samples
  bool matched_by_order = false;         ///< the run had no family labels: modes paired by order
  bool paired_by_mac = false;            ///< modes paired by MAC on the sampled shapes (else by family order)
  std::vector<int> match;                ///< per reference mode: the run's mode paired with it (-1: none)
  std::vector<double> pair_mac;          ///< per reference mode: the MAC of its pair (NaN: no shapes or no pair)
  int low_mac_pairs = 0;                 ///< pairs among the first min(6, modes) with MAC < kLowMac
  bool failed() const { return result.summary.status != Status::Success; }
};

struct SceneComparison {
  Scene scene;
  Reference reference;
  std::vector<RunRecord> runs;  ///< grouped by back-end, each ladder coarse -> fine
  std::vector<std::string> notes;
};

struct CompareOptions {
  double budget_s = 30.0;       ///< per scene and back-end: the ladder stops when exceeded
  double min_timing_s = 0.05;   ///< repeat a run until this much time was spent (>= 3 repeats)
  int max_repeats = 7;
  bool quick = false;           ///< one repeat, short ladders (tests)
  std::ostream* progress = nullptr;
  /// Mode shapes for MAC pairing: the untimed warm-up run of each rung asks for them (default
  /// sampling) when the scene does not; the timed repeats never do.
  bool shapes = true;
  /// Optional extra reference runs (e.g. CalculiX) appended as if they were a back-end.
  std::vector<std::function<std::vector<RunRecord>(const Scene&, std::ostream*)>> extra_references;
};

/// Runs the comparison on every scene. A back-end that throws or fails becomes a run marked
/// failed with its message, never a crash.
std::vector<SceneComparison> run_comparison(const std::vector<Scene>& scenes, const Registry& registry,
                                            const CompareOptions& options);

/// Fills the error fields of `run` against `ref` (exposed for tests).
void measure_errors(const Scene& scene, const Reference& ref, RunRecord& run);

/// Run time needed by `backend` to reach `max_frequency_error <= target` (first run of its
/// ladder that does), or NaN if none did.
double time_to_accuracy(const SceneComparison& c, const std::string& backend, double target);

/// Built-in scenes: every *.toml in `dir`, sorted by file name.
std::vector<std::string> scene_files(const std::string& dir);

}  // namespace modalbench
