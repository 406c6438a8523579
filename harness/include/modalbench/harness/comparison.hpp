#pragma once
// The comparison harness: every back-end that supports a scene runs over its ladder of
// discretizations; each requested quantity (modes, statics, FRF) is timed on its own (median of
// repeats after a warm-up). Two errors are kept apart:
// - discretization error: each run against its own model's converged limit -- the `exact`
//   back-end where the run's model tends to the scene's theory, otherwise the Richardson limit of
//   the back-end's own ladder, with its observed order and grid convergence index (GCI);
// - model error: that converged limit against the best reference of the scene (3D elasticity from
//   CalculiX bricks extrapolated over their ladder when they ran, else the exact theory).
// Modes are paired with the scene's reference by MAC on sampled shapes (mode_matching.hpp).
// `exact` and `dtfm` share the line system (numerics/line_system.hpp): their agreement is not an
// independent check of that kernel; rfem and difference_eq share no kernel with them.
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

/// The quantities a scene can ask for, each timed on its own.
enum class Quantity { Frequencies, Deflections, Frf };
inline constexpr Quantity kQuantities[] = {Quantity::Frequencies, Quantity::Deflections, Quantity::Frf};
std::string to_string(Quantity);  ///< frequencies, deflections, frf

/// Median wall time of each requested quantity solved alone (the scene with only that request), s:
/// model build + modes; build + statics; build + FRF. Set-up shared by two quantities (assembly, a
/// factorization) is so charged to each quantity that needs it. NaN where not requested.
struct QuantityTimes {
  double modes = kNaN, statics = kNaN, frf = kNaN;
  double of(Quantity q) const { return q == Quantity::Frequencies ? modes : q == Quantity::Deflections ? statics : frf; }
};

struct RunRecord {
  std::string backend;
  Discretization mesh;
  Result result;
  QuantityTimes time_s;    ///< per quantity
  double median_s = kNaN;  ///< the sum of the quantities' times (shared set-up counted in each)
  double spent_s = 0;      ///< wall time the harness spent on this rung (warm-up and repeats)
  int repeats = 0;         ///< timed solves per quantity
  // Differences from the scene's reference (NaN where not available): model and discretization
  // error together where the run's model is not the reference's (see the discretization errors below).
  std::vector<double> frequency_errors;  ///< per reference mode (relative)
  double max_frequency_error = kNaN;     ///< over the first min(6, modes) non-rigid reference modes
  double deflection_error = kNaN;        ///< max |w - w_ref| / max |w_ref| over probes
  double frf_error_db = kNaN;            ///< median |20 log10(|H| / |H_ref|)| over common samples
  /// The ModelLimit (its label) this run converges to, and the run's errors against it.
  std::string limit;
  double disc_frequency_error = kNaN;   ///< max relative error over the first min(6, modes) modes
  double disc_deflection_error = kNaN;  ///< max |w - w_lim| / max |w_lim| over the probes
  double disc_frf_error_db = kNaN;      ///< median |dB| difference (only against an exact limit)
  double disc_error(Quantity q) const {
    return q == Quantity::Frequencies ? disc_frequency_error : q == Quantity::Deflections ? disc_deflection_error : disc_frf_error_db;
  }
  bool matched_by_order = false;         ///< the run had no family labels: modes paired by order
  bool paired_by_mac = false;            ///< modes paired by MAC on the sampled shapes (else by family order)
  std::vector<int> match;                ///< per reference mode: the run's mode paired with it (-1: none)
  std::vector<double> pair_mac;          ///< per reference mode: the MAC of its pair (NaN: no shapes or no pair)
  int low_mac_pairs = 0;                 ///< pairs among the first min(6, modes) with MAC < kLowMac
  bool failed() const { return result.summary.status != Status::Success; }
};

/// What the runs of one back-end converge to, and how far that model is from the best reference.
struct ModelLimit {
  std::string label;    ///< the back-end, with "(own model)" / "(<theory>)" when it has runs of both kinds
  std::string backend;
  bool scene_theory = false;  ///< the runs tend to the scene's theory: the limit is the exact solution
  std::string source;         ///< "exact", "richardson(<back-end>, N meshes)", or "none: <why>"
  Reference values;           ///< the limit (frequency_uncertainty: absolute GCI)
  double order[3] = {kNaN, kNaN, kNaN};  ///< observed order per Quantity (frequencies: median over modes)
  double gci = kNaN;            ///< largest relative GCI over the first min(6, modes) frequencies (0: exact)
  double safety_factor = kNaN;  ///< of the GCI: 1.25 (asymptotic range) or 3
  std::string convergence_note;
  double model_error = kNaN;              ///< max over the first min(6, modes) modes: |limit / best - 1|
  double model_error_uncertainty = kNaN;  ///< relative: the limit's GCI plus the best reference's
};

/// A back-end's default solve of a scene's time history ([request.transient]): the mesh refined to
/// the scene's tolerance, the whole request.
struct TransientRun {
  std::string backend;
  Result result;
  /// The same mesh with a fixed number of modes (12, 24, 48, 96; the first round only): the peak
  /// of w at the first probe, and the run time, for the error against modes used and run time.
  struct ByModes {
    int modes = 0;
    double peak_w = 0, run_s = 0;
  };
  std::vector<ByModes> by_modes;
};

/// A back-end's default solve of a rotor scene's Campbell diagram ([rotor]): the mesh refined to the
/// scene's tolerance, the whole request.
struct RotorRun {
  std::string backend;
  Result result;
};

struct SceneComparison {
  Scene scene;
  Reference reference;  ///< the scene's theory (exact), else the best Richardson limit: MAC pairing, tables
  std::vector<RunRecord> runs;  ///< grouped by back-end, each ladder coarse -> fine
  std::vector<std::string> notes;
  Reference best;              ///< the highest-fidelity reference: 3D (CalculiX, Richardson) or `reference`
  std::string best_label;      ///< e.g. "3D elasticity: CalculiX C3D20R, Richardson of 4 meshes (GCI 2e-4)"
  std::vector<ModelLimit> limits;  ///< one per back-end and kind of limit
  /// Where the scene asks for a time history (left out of `scene`, whose runs are timed): the
  /// request, and each back-end's default solve of it.
  std::optional<TransientRequest> transient;
  std::vector<TransientRun> transients;
  /// Where the scene is a rotor (left out of `scene` too): its [rotor], and each back-end's default
  /// solve of its Campbell diagram.
  std::optional<Rotor> rotor;
  std::vector<RotorRun> rotor_runs;
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
  /// The clock the timings read, seconds (tests inject one; default: std::chrono::steady_clock).
  std::function<double()> clock;
};

/// Each back-end's default solve (refined to the tolerance, within twice the budget) of a scene
/// with a time history (transient_runs.cpp); empty for a scene without one.
std::vector<TransientRun> transient_runs(const Scene& scene, const Registry& registry, const CompareOptions& opt);

/// Each back-end's default solve (refined to the tolerance, within twice the budget) of a rotor
/// scene's Campbell diagram, where the back-end gives one (rotor_runs.cpp); empty for other scenes.
std::vector<RotorRun> rotor_runs(const Scene& scene, const Registry& registry, const CompareOptions& opt);

/// Runs the comparison on every scene. A back-end that throws or fails becomes a run marked
/// failed with its message, never a crash.
std::vector<SceneComparison> run_comparison(const std::vector<Scene>& scenes, const Registry& registry,
                                            const CompareOptions& options);

/// Fills the error fields of `run` against `ref` (exposed for tests).
void measure_errors(const Scene& scene, const Reference& ref, RunRecord& run);

/// Time of `q` alone in the cheapest run of the limit `label` (or of the back-end of that name)
/// whose discretization error of `q` is at most `target`, or NaN if none is.
double time_to_accuracy(const SceneComparison& c, const std::string& label, double target,
                        Quantity q = Quantity::Frequencies);

/// The model limits of a comparison's runs, their discretization errors and the model errors
/// (called by run_comparison; exposed for tests). Fills c.best, c.best_label, c.limits and each
/// run's `limit` and disc_* errors.
void analyse_limits(SceneComparison& c);

/// The mesh size of a discretization: (product of its counts)^(-1/dims); NaN without a mesh.
double mesh_h(const Discretization& d);

/// Built-in scenes: every *.toml in `dir`, sorted by file name.
std::vector<std::string> scene_files(const std::string& dir);

}  // namespace modalbench
