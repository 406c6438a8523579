// Solver::solve: the one pipeline every back-end shares, as named steps —
//   check the request (validate, options, what the back-end can do),
//   plan the meshes of the error estimate,
//   estimate the resources (refused above the limits),
//   refine the default mesh to the tolerance,
//   solve the request on the mesh kept,
//   estimate the error (where the refinement did not),
//   extrapolate (and, on the default path, answer with the extrapolated values where their own
//   estimate meets the tolerance and the mesh's does not), the time history (request.transient,
//   by modal superposition),
//   and finish (nothing non-finite unflagged, timings).
// Each step is a member function of SolvePipeline; the state they pass on is its members.
#include "solve_internal.hpp"

#include "modalbench/extrapolation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <new>
#include <stdexcept>
#include <utility>

namespace modalbench {

namespace detail {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// The coarser solves of the error estimate (H, 2H, and 4H where the family extrapolates), kept
/// for the Richardson extrapolation (extrapolation.hpp).
struct KeptSolves {
  Result H, H2, H4;
  double ratio = kNotMeasured, ratio2 = kNotMeasured, ratio3 = kNotMeasured;
  bool three = false, four = false;
};

/// The last solves of the refinement, finest last: cur (h, judged), prev (H), r2 (2H, where
/// `third` names it) and r3 (4H, for the extrapolation's check).
struct RefinementWindow {
  Result cur, prev, r2;
  std::optional<Result> r3;
  std::optional<MeshSolve> third;
  std::string prev_spec;
  double ratio_prev = 2.0;          ///< prev -> cur
  double ratio3 = kNotMeasured;     ///< r3 -> r2
};

class SolvePipeline {
 public:
  SolvePipeline(const Solver& solver, const Scene& scene, const Discretization& mesh, const Options& options)
      : solver_(solver), scene_(scene), mesh_(mesh), opt_(options), final_mesh_(mesh) {}

  Result run();

 private:
  bool check_request();
  void plan_estimate_meshes();
  bool estimate_resources();
  void refine_mesh();
  void solve_request();
  void estimate_error();
  void record_estimate();
  void extrapolate();
  void choose_values();
  void transient();
  void finish();

  // Parts of the steps.
  RefinementWindow start_refinement();
  bool refinement_step(RefinementWindow& w, double& last_estimate, double& last_time);
  std::optional<Extrapolation> window_extrapolation(const RefinementWindow& w) const;
  bool extrapolation_answers(const RefinementWindow& w) const;
  double extrapolation_factor(const RefinementWindow& w) const;
  void keep_refinement_solves(RefinementWindow& w);
  Result solve_light(const Scene& sc, const Discretization& m) const;
  void solve_into(const Scene& sc, const Discretization& m, Result& x) const;
  std::optional<Result> solve_optional(const Discretization& m) const;
  double since_start() const { return seconds_since(t0_); }

  const Solver& solver_;
  Scene scene_;  // a copy: check_request removes what the back-end does not compute
  const Discretization& mesh_;
  Options opt_;
  Clock::time_point t0_ = Clock::now();
  Result result_;

  Capability cap_;
  std::vector<std::string> missing_;  ///< requested quantities the back-end does not compute
  Scene light_;                       ///< what the error estimate needs: modes and statics

  bool wants_estimate_ = false;
  bool check_is_finer_ = false;  ///< the mesh has no coarser one: it is checked against a finer one
  std::optional<CoarserMesh> coarse_, coarser2_, coarser3_;
  double memory_limit_ = 0;
  bool refused_ = false;  ///< refused before starting (resource limits): nothing to account for
  /// Why the statics were refused on a scene with a time history (its solves then go without
  /// probes: solve_into); empty while they are not.
  mutable std::string statics_refused_;

  Discretization final_mesh_;
  std::optional<Verdict> verdict_;
  std::vector<std::string> estimate_warnings_;
  std::string refined_note_;
  double estimate_time_ = 0;
  /// The run time the request was planned at: the first estimate, then each refinement step's
  /// prediction (calibrated on the solves before it).
  double planned_s_ = 0;
  double last_full_s_ = 0;  ///< the plan's share for the whole request on the latest mesh
  void compare_time_with_plan();
  KeptSolves kept_;
  /// The refinement's last solve, where the light scene is the whole request (no FRF, shapes or
  /// time history): the request's solve on the mesh kept, not repeated.
  std::optional<Result> kept_fine_;
};

Result SolvePipeline::run() {
  map_stack_pages();
  auto& sum = result_.summary;
  sum.mesh = mesh_.spec();
  try {
    if (check_request()) {
      plan_estimate_meshes();
      if (estimate_resources()) {
        refine_mesh();
        solve_request();
        estimate_error();
        extrapolate();
        choose_values();
        record_estimate();
        transient();
      }
    }
  } catch (const InputError& e) {
    sum.raise(Status::InvalidInput, e.what());
  } catch (const std::bad_alloc&) {
    sum.raise(Status::ResourceLimit, solver_.name() + ": out of memory (std::bad_alloc): the request is too large "
                                     "for this machine; use a coarser mesh or fewer modes");
  } catch (const std::exception& e) {
    sum.raise(Status::NumericalIssue, solver_.name() + " failed: " + e.what());
  }
  finish();
  return std::move(result_);
}

/// Validates the scene and the options; false (Status::Unsupported, said why) where the back-end
/// computes nothing of what is requested. What it leaves out is said after the solve.
bool SolvePipeline::check_request() {
  auto& sum = result_.summary;
  validate(scene_);
  opt_.resolved = resolve_options(solver_, scene_, opt_);
  sum.method_requested = opt_.resolved.given();
  cap_ = solver_.supports(scene_);
  const auto& rq = scene_.request;
  if (rq.modes > 0 && !cap_.modes) missing_.push_back("natural frequencies");
  if (!rq.probes.empty() && !cap_.statics) missing_.push_back("static deflections");
  if (rq.frf && !cap_.frf) missing_.push_back("FRF");
  const bool rotor = scene_.rotor.has_value();
  if (rotor && !cap_.campbell) missing_.push_back("Campbell diagram ([rotor])");
  const bool wants_something = rq.modes > 0 || !rq.probes.empty() || rq.frf.has_value() || rotor;
  const bool can_something = (rq.modes > 0 && cap_.modes) || (!rq.probes.empty() && cap_.statics) ||
                             (rq.frf && cap_.frf) || (rotor && cap_.campbell);
  if (!cap_.any() || (wants_something && !can_something)) {
    sum.raise(Status::Unsupported, cap_.reason.empty() ? "nothing requested is supported" : cap_.reason);
    return false;
  }
  // What the back-end does not compute is not asked of it (a partial answer, e.g. statics of the
  // point loads alone where the distributed ones are not modelled, would pass for the whole).
  if (!cap_.modes) {
    scene_.request.modes = 0;
    scene_.request.shapes.reset();
  }
  if (!cap_.statics) scene_.request.probes.clear();
  if (!cap_.frf) scene_.request.frf.reset();
  if (!cap_.campbell) scene_.rotor.reset();
  if (rq.transient && !cap_.modes) {
    missing_.push_back("transient response (it superposes modes)");
    scene_.request.transient.reset();
  }
  light_ = scene_;
  light_.request.frf.reset();
  light_.request.shapes.reset();
  light_.request.transient.reset();
  return true;
}

/// The coarser meshes of the error estimate: H, 2H (the estimate takes the larger of two pairs),
/// and 4H where the family extrapolates (CoarserMesh::next_order: it checks the extrapolated
/// values' own order). A mesh too coarse to have a coarser one (1 beam segment, a 2 x 2 plate)
/// is checked against a finer one instead.
void SolvePipeline::plan_estimate_meshes() {
  const auto& rq = scene_.request;
  wants_estimate_ = opt_.estimate_error && (rq.modes > 0 || !rq.probes.empty()) && !mesh_.counts.empty();
  if (!wants_estimate_) return;
  coarse_ = solver_.coarser_mesh(scene_, mesh_, opt_);
  if (!coarse_)
    if (const std::optional<Discretization> f = solver_.finer_mesh(scene_, mesh_, 2.0)) {
      coarse_ = CoarserMesh{*f, static_cast<double>(f->counts[0]) / mesh_.counts[0], solver_.mesh_order(scene_, opt_)};
      check_is_finer_ = true;
    }
  if (coarse_ && !check_is_finer_) coarser2_ = solver_.coarser_mesh(scene_, coarse_->mesh, opt_);
  if (coarser2_ && std::isfinite(coarse_->next_order)) coarser3_ = solver_.coarser_mesh(scene_, coarser2_->mesh, opt_);
}

/// The request's estimated peak memory and run time (the estimate's coarser meshes included);
/// false (Status::ResourceLimit, said why) where either exceeds its limit.
bool SolvePipeline::estimate_resources() {
  auto& sum = result_.summary;
  ResourceEstimate est = solver_.estimate(scene_, mesh_, opt_);
  // With a refinement the whole request runs once, on the mesh kept: what it costs beyond the
  // first mesh's light solve is the share a refinement step replaces.
  last_full_s_ = std::max(0.0, est.seconds - solver_.estimate(light_, mesh_, opt_).seconds);
  for (const std::optional<CoarserMesh>* c : {&coarse_, &coarser2_, &coarser3_})
    if (*c) {
      const ResourceEstimate ce = solver_.estimate(light_, (*c)->mesh, opt_);
      est.bytes = std::max(est.bytes, ce.bytes);
      est.seconds += ce.seconds;
    }
  // The result's output on top of the solve: an FRF sample or a mode shape value held in the result
  // and written as JSON (its document and text) took about 800 bytes (1e6 FRF samples peaked at
  // 786 MB with --json against a 0.87 MB estimate of the solve alone).
  const auto& rq = scene_.request;
  const double samples = (rq.frf ? static_cast<double>(rq.frf->points) : 0.0) +
                         (rq.shapes ? static_cast<double>(rq.modes) * static_cast<double>(scene_.shape_points().size()) *
                                          static_cast<double>(scene_.shape_components().size())
                                    : 0.0);
  est.bytes += 800.0 * samples;
  // The time history's first modal solve (its later rounds are planned as they start).
  if (rq.transient) {
    const ResourceEstimate te = solver_.estimate(transient_modal_scene(scene_, transient_first_modes(scene_)), mesh_, opt_);
    est.seconds += te.seconds;
    est.bytes = std::max(est.bytes, te.bytes);
  }
  if (est.bytes > 0) sum.set_diagnostic("estimated_memory_bytes", est.bytes);
  if (est.seconds > 0) sum.set_diagnostic("estimated_time_s", est.seconds);
  planned_s_ = est.seconds;
  memory_limit_ = opt_.max_memory_bytes > 0 ? opt_.max_memory_bytes : default_memory_limit();
  if (est.bytes > memory_limit_)
    sum.raise(Status::ResourceLimit,
              fmt::format("{}: refused before allocating: estimated peak memory {} ({}) exceeds the limit of {} ({}); "
                          "raise it with --max-memory GB, or use a coarser mesh or fewer modes, loads or samples",
                          solver_.name(), gigabytes(est.bytes), est.basis, gigabytes(memory_limit_),
                          opt_.max_memory_bytes > 0 ? "as set" : "80 % of the memory this process may use"));
  if (est.seconds > opt_.max_time_s)
    sum.raise(Status::ResourceLimit,
              fmt::format("{}: refused before starting: estimated run time {:.3g} s ({}) exceeds the limit of {:.3g} s; "
                          "raise it with --max-time S, or use a coarser mesh or fewer modes, loads or samples",
                          solver_.name(), est.seconds, est.basis, opt_.max_time_s));
  refused_ = sum.status == Status::ResourceLimit;
  return !refused_;
}

Result SolvePipeline::solve_light(const Scene& sc, const Discretization& m) const {
  const auto ts = Clock::now();
  Result x;
  x.summary.mesh = m.spec();
  solve_into(sc, m, x);
  x.summary.total_time_s = seconds_since(ts);
  return x;
}

/// The back-end's solve of `sc` into `x`. A time history needs only the modes: where the statics
/// are refused (a free structure is a mechanism), this and every later solve go without the probes
/// (statics_refused_ says why); anything else fails again without them.
void SolvePipeline::solve_into(const Scene& sc, const Discretization& m, Result& x) const {
  const bool drop = scene_.request.transient && !sc.request.probes.empty();
  if (drop && !statics_refused_.empty()) {
    Scene modes_only = sc;
    modes_only.request.probes.clear();
    solver_.do_solve(modes_only, m, opt_, x);
    return;
  }
  const Result before = x;
  std::string refused;
  std::exception_ptr thrown;
  try {
    solver_.do_solve(sc, m, opt_, x);
    if (drop && x.summary.status == Status::InvalidInput) refused = x.summary.message;
  } catch (const InputError& e) {
    if (!drop) throw;
    refused = e.what();
    thrown = std::current_exception();
  }
  if (refused.empty()) return;
  Result retry = before;
  Scene modes_only = sc;
  modes_only.request.probes.clear();
  solver_.do_solve(modes_only, m, opt_, retry);
  if (retry.summary.status == Status::InvalidInput) {  // not the statics: the first answer stands
    if (thrown) std::rethrow_exception(thrown);
    return;
  }
  x = std::move(retry);
  statics_refused_ = refused;
}

/// The fourth mesh's solve: optional, so a failure only leaves the extrapolation with three.
std::optional<Result> SolvePipeline::solve_optional(const Discretization& m) const {
  try {
    return solve_light(light_, m);
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

/// The default mesh (no --mesh): refine it until the estimate meets the tolerance (light solves
/// only; the whole request is then solved once on the mesh kept). A failed solve of the
/// refinement leaves the request to the default mesh, whose own check says what it can.
void SolvePipeline::refine_mesh() {
  if (!coarse_ || !opt_.refine_to_tolerance) return;
  const auto tc = Clock::now();
  try {
    RefinementWindow w = start_refinement();
    // How far the estimates are from what this machine does: later steps are predicted with it.
    double last_estimate = solver_.estimate(light_, final_mesh_, opt_).seconds, last_time = w.cur.summary.total_time_s;
    for (int step = 0; step < 3 && !verdict_->second.empty() && !extrapolation_answers(w); ++step)
      if (!refinement_step(w, last_estimate, last_time)) break;
    keep_refinement_solves(w);
    if (w.cur.summary.status != Status::Success && w.cur.summary.status != Status::NotConverged)
      estimate_warnings_.push_back(fmt::format("a solve on mesh {} of the refinement was {}: {}", final_mesh_.spec(),
                                               to_string(w.cur.summary.status), w.cur.summary.message));
    estimate_time_ = seconds_since(tc);
    const auto& rq = scene_.request;
    if (!rq.frf && !rq.shapes && !rq.transient) {
      estimate_time_ -= w.cur.summary.total_time_s;  // the request's own solve, not the estimate's
      kept_fine_ = std::move(w.cur);
      planned_s_ -= last_full_s_;  // the plan's whole request on the mesh kept is that solve
      last_full_s_ = 0;
    }
    // Provenance of the mesh and its estimate, not a doubt about them: said in the estimate's note.
    if (final_mesh_.spec() != mesh_.spec())
      refined_note_ = fmt::format("default mesh {} refined to {} to meet the tolerance {:.2g}", mesh_.spec(),
                                  final_mesh_.spec(), scene_.request.tolerance);
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    estimate_warnings_.push_back(std::string("refinement of the default mesh abandoned: ") + e.what());
    verdict_.reset();
    kept_fine_.reset();
    final_mesh_ = mesh_;
  }
}

/// The first solves of the refinement (4H, 2H, H and h, coarse to fine) and the verdict on h.
RefinementWindow SolvePipeline::start_refinement() {
  RefinementWindow w;
  if (coarser2_) {
    if (coarser3_) {
      w.r3 = solve_optional(coarser3_->mesh);
      w.ratio3 = coarser3_->ratio;
    }
    w.r2 = solve_light(light_, coarser2_->mesh);
    w.third = MeshSolve{coarser2_->mesh.spec(), coarser2_->ratio, &w.r2};
  }
  w.prev = solve_light(light_, check_is_finer_ ? mesh_ : coarse_->mesh);
  w.cur = solve_light(light_, check_is_finer_ ? coarse_->mesh : mesh_);
  w.ratio_prev = coarse_->ratio;
  w.prev_spec = check_is_finer_ ? mesh_.spec() : coarse_->mesh.spec();
  verdict_ = judge_discretization(scene_, coarse_->order, w.cur, MeshSolve{w.prev_spec, w.ratio_prev, &w.prev}, w.third);
  if (check_is_finer_) final_mesh_ = coarse_->mesh;
  return w;
}

/// One refinement: a finer mesh sized from the estimate and the order, solved and judged; false
/// where the refinement stops (rounding past the tolerance, no finer mesh, over the limits, or a
/// finer solve that fails the back-end's own checks), said in a warning where it is a limit.
bool SolvePipeline::refinement_step(RefinementWindow& w, double& last_estimate, double& last_time) {
  const ErrorEstimate& e = verdict_->first;
  // Rounding beyond the tolerance: a finer mesh would only make it worse.
  if (e.frequencies_solve > scene_.request.tolerance) return false;
  const double worst = std::max(std::isnan(e.frequencies) ? 0.0 : e.frequencies, std::isnan(e.deflections) ? 0.0 : e.deflections);
  // The mesh sized for its own estimate, or for the extrapolation's where that is the smaller step
  // (its error falls at the order left after extrapolation).
  double factor = 1.25 * std::pow(worst / scene_.request.tolerance, 1.0 / coarse_->order);
  if (const double fx = extrapolation_factor(w); fx < factor) factor = fx;
  factor = std::clamp(factor, 1.5, 4.0);
  const std::optional<Discretization> next = solver_.finer_mesh(scene_, final_mesh_, std::isfinite(factor) ? factor : 4.0);
  if (!next) return false;
  const ResourceEstimate ne = solver_.estimate(scene_, *next, opt_);
  // The estimates calibrated on the last solve, both ways once it is long enough to be measured
  // (rfem's plates ran 6 to 9 times under their estimates, and the plan stayed that far off).
  double calibration = last_estimate > 0 && last_time > last_estimate ? last_time / last_estimate : 1.0;
  if (last_estimate > 0 && last_time >= 0.05) calibration = std::clamp(last_time / last_estimate, 0.05, 1e3);
  // The next light solve (modes and statics), then the whole request on it (FRF and shapes too),
  // each from its own estimate: twice the whole request's planned the rfem paper plate at 82 s
  // for a run of 3.2 s (its 400 FRF samples counted in the light solve as well).
  const double light_estimate = solver_.estimate(light_, *next, opt_).seconds;
  const double light = light_estimate * calibration;
  const double full = ne.seconds * calibration;
  const double predicted = light + full;
  if (ne.bytes > memory_limit_ || since_start() + predicted > opt_.max_time_s) {
    estimate_warnings_.push_back(fmt::format(
        "refinement stopped at mesh {}: the next, {}, is estimated at {} and {:.3g} s (after {:.3g} s), over the "
        "limits (--max-memory, --max-time)",
        final_mesh_.spec(), next->spec(), gigabytes(ne.bytes), predicted, since_start()));
    return false;
  }
  const double ratio = static_cast<double>(next->counts[0]) / final_mesh_.counts[0];
  // The plan: this step's light solve, and the whole request once, on the mesh kept (the latest):
  // the previous mesh's whole-request share replaced.
  planned_s_ += light + (full - last_full_s_);
  last_full_s_ = full;
  Result trial = solve_light(light_, *next);
  // A finer mesh whose solve fails the back-end's own checks is not taken: the mesh kept is the
  // last one that passed them, with its estimate (and its not-converged verdict).
  if (severity(trial.summary.status) >= severity(Status::NumericalIssue) &&
      severity(w.cur.summary.status) < severity(Status::NumericalIssue)) {
    estimate_warnings_.push_back(fmt::format("refinement stopped at mesh {}: the next, {}, failed the back-end's own "
                                             "checks ({}: {})",
                                             final_mesh_.spec(), next->spec(), to_string(trial.summary.status),
                                             trial.summary.message));
    return false;
  }
  w.r3 = w.third ? std::optional<Result>(std::move(w.r2)) : std::nullopt;
  w.ratio3 = w.third ? w.third->ratio : kNotMeasured;
  w.r2 = std::move(w.prev);
  w.third = MeshSolve{w.prev_spec, w.ratio_prev, &w.r2};
  w.prev = std::move(w.cur);
  w.prev_spec = final_mesh_.spec();
  w.ratio_prev = ratio;
  w.cur = std::move(trial);
  last_estimate = light_estimate;
  last_time = w.cur.summary.total_time_s;
  verdict_ = judge_discretization(scene_, coarse_->order, w.cur, MeshSolve{w.prev_spec, ratio, &w.prev}, w.third);
  final_mesh_ = *next;
  return true;
}

/// Whether the window's extrapolation (its finest three meshes, and the fourth where there is one)
/// answers what the finest mesh's estimate leaves over the tolerance: the refinement stops there.
std::optional<Extrapolation> SolvePipeline::window_extrapolation(const RefinementWindow& w) const {
  if (!w.third) return std::nullopt;
  const ExtrapolationMesh fourth{w.r3 ? &*w.r3 : nullptr, w.ratio3};
  return richardson_extrapolate(w.cur, {&w.prev, w.ratio_prev}, {&w.r2, w.third->ratio}, coarse_->order,
                                coarse_->next_order, w.cur.summary.diagnostic("frequency_solve_error_bound"),
                                w.r3 ? &fourth : nullptr);
}

bool SolvePipeline::extrapolation_answers(const RefinementWindow& w) const {
  const std::optional<Extrapolation> x = window_extrapolation(w);
  if (!x) return false;
  const ReportedValues v = extrapolated_answers(scene_, w.cur, *x, verdict_->first);
  return (v.frequencies || v.deflections) && problems_left(verdict_->second, v).empty();
}

/// The refinement factor at which the extrapolated values' estimate is predicted to meet the
/// tolerance: 1.1 (e / tol)^(1/s), s the order assumed to remain after extrapolation; NaN where the
/// window does not extrapolate everything over the tolerance.
double SolvePipeline::extrapolation_factor(const RefinementWindow& w) const {
  const std::optional<Extrapolation> x = window_extrapolation(w);
  if (!x || !(x->next_order > coarse_->order)) return kNotMeasured;
  const ErrorEstimate& e = verdict_->first;
  const double tol = scene_.request.tolerance;
  double worst = 0;
  if (!(e.frequencies <= tol) && scene_.request.modes > 0) {
    if (x->frequencies_rad_s.empty()) return kNotMeasured;
    worst = std::max(worst, x->frequency_error);
  }
  if (!(e.deflections <= tol) && !scene_.request.probes.empty()) {
    const bool forces = std::any_of(w.cur.deflections.begin(), w.cur.deflections.end(), [](const Deflection& d) { return d.has_forces; });
    if (forces || x->deflections.empty()) return kNotMeasured;
    worst = std::max(worst, x->deflection_error);
  }
  if (std::isfinite(e.campbell) && !(e.campbell <= tol)) return kNotMeasured;
  return 1.1 * std::pow(worst / tol, 1.0 / x->next_order);
}

/// The refinement's coarser solves, kept for the extrapolation (three or four meshes).
void SolvePipeline::keep_refinement_solves(RefinementWindow& w) {
  if (!w.third) return;
  kept_.three = true;
  kept_.ratio = w.ratio_prev;
  kept_.ratio2 = w.third->ratio;
  kept_.H = std::move(w.prev);
  kept_.H2 = std::move(w.r2);
  if (w.r3) {
    kept_.four = true;
    kept_.ratio3 = w.ratio3;
    kept_.H4 = std::move(*w.r3);
  }
}

/// The whole request on the mesh kept; what the back-end does not compute is said.
void SolvePipeline::solve_request() {
  auto& sum = result_.summary;
  sum.mesh = final_mesh_.spec();
  if (kept_fine_ && sum.status == Status::Success) {
    // The refinement's last solve is this request's: taken with what the pipeline noted before it.
    Result x = std::move(*kept_fine_);
    kept_fine_.reset();
    x.summary.method_requested = sum.method_requested;
    for (const auto& [name, value] : sum.diagnostics) x.summary.set_diagnostic(name, value);
    x.summary.warnings.insert(x.summary.warnings.begin(), sum.warnings.begin(), sum.warnings.end());
    x.summary.mesh = sum.mesh;
    result_ = std::move(x);
  } else {
    solve_into(scene_, final_mesh_, result_);
  }
  if (!statics_refused_.empty())
    sum.warnings.push_back("not computed: static deflections (" + statics_refused_ +
                           "); the time history runs without the static correction");
  if (!missing_.empty()) {
    std::string what;
    for (const auto& m : missing_) what += (what.empty() ? "" : ", ") + m;
    sum.warnings.push_back("not computed: " + what + (cap_.reason.empty() ? "" : " (" + cap_.reason + ")"));
  }
}

/// The error estimate where the refinement gave none (a mesh given, or no refinement): the
/// coarser meshes solved and judged against the result (and kept for the extrapolation).
void SolvePipeline::estimate_error() {
  auto& sum = result_.summary;
  if (!(coarse_ && !verdict_ && severity(sum.status) < severity(Status::ResourceLimit))) {
    if (!mesh_.counts.empty() && !opt_.estimate_error) sum.error_estimate.note = "not estimated (switched off by the caller)";
    return;
  }
  const auto tc = Clock::now();
  try {
    Result cr = solve_light(light_, coarse_->mesh);
    Result cr2;
    std::optional<MeshSolve> third;
    if (coarser2_) {
      cr2 = solve_light(light_, coarser2_->mesh);
      third = MeshSolve{coarser2_->mesh.spec(), coarser2_->ratio, &cr2};
    }
    verdict_ = judge_discretization(scene_, coarse_->order, result_, MeshSolve{coarse_->mesh.spec(), coarse_->ratio, &cr},
                                    third, check_is_finer_);
    for (const Result* c : {&std::as_const(cr), &std::as_const(cr2)})
      if (c->summary.status != Status::Success && !(c == &cr2 && !coarser2_))
        estimate_warnings_.push_back(fmt::format("the coarser mesh {} of the error estimate was {}: {}",
                                                 c->summary.mesh, to_string(c->summary.status), c->summary.message));
    if (third) {
      kept_.three = true;
      kept_.ratio = coarse_->ratio;
      kept_.ratio2 = coarser2_->ratio;
      kept_.H = std::move(cr);
      kept_.H2 = std::move(cr2);
      if (coarser3_)
        if (std::optional<Result> cr3 = solve_optional(coarser3_->mesh)) {
          kept_.four = true;
          kept_.ratio3 = coarser3_->ratio;
          kept_.H4 = std::move(*cr3);
        }
    }
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    sum.error_estimate.note = std::string("no estimate: the coarser mesh failed: ") + e.what();
    sum.raise(Status::NotConverged, fmt::format("no discretization error estimate: the coarser mesh {} failed ({})",
                                                coarse_->mesh.spec(), e.what()));
  }
  estimate_time_ += seconds_since(tc);
}

/// The verdict into the summary: the estimate, its provenance, and a not-converged status for
/// what exceeds the tolerance. Without a mesh to compare with (exact segments: a one-prism dtfm
/// beam), the solve's own bound is the estimate.
void SolvePipeline::record_estimate() {
  auto& sum = result_.summary;
  if (verdict_) {
    sum.error_estimate = verdict_->first;
    if (!refined_note_.empty()) sum.error_estimate.note = refined_note_ + "; " + sum.error_estimate.note;
    for (const auto& p : verdict_->second) sum.raise(Status::NotConverged, p);
  } else if (wants_estimate_ && !coarse_) {
    const double solve = sum.diagnostic("frequency_solve_error_bound");
    if (std::isfinite(solve)) {
      sum.error_estimate.frequencies = sum.error_estimate.frequencies_solve = solve;
      sum.error_estimate.tolerance = scene_.request.tolerance;
      sum.error_estimate.note = "no discretization error to estimate (exact segments): the solve's own bound";
    } else if (sum.diagnostic("exact_segments") == 1.0) {
      sum.error_estimate.note = "no discretization error to estimate (exact segments); the solve states no bound";
    } else {
      // Said, not left blank: a discretization whose error nothing measured (difference_eq with
      // points that are nodes of no coarser or finer chain).
      const std::string why =
          fmt::format("{} offers no second mesh for this scene besides {}", solver_.name(), final_mesh_.spec());
      sum.error_estimate.note = "not estimated: " + why;
      sum.warnings.push_back("no discretization error estimate: " + why);
    }
  }
}

/// Richardson extrapolation from the kept coarser solves (extrapolation.hpp).
void SolvePipeline::extrapolate() {
  auto& sum = result_.summary;
  if (kept_.three && coarse_) {
    const ExtrapolationMesh fourth{&kept_.H4, kept_.ratio3};
    result_.extrapolated = richardson_extrapolate(result_, {&kept_.H, kept_.ratio}, {&kept_.H2, kept_.ratio2}, coarse_->order,
                                                  coarse_->next_order, sum.diagnostic("frequency_solve_error_bound"),
                                                  kept_.four ? &fourth : nullptr);
  }
  for (auto& w : estimate_warnings_) sum.warnings.push_back(std::move(w));
  sum.timings_s.error_estimate = estimate_time_;
}

/// On the default path (the default mesh refined to the tolerance), the extrapolated values answer
/// where their own estimate meets the tolerance and the mesh's does not, and nothing else the
/// estimate judges is left over it: the result reports them (its extrapolation keeps the mesh's),
/// says so in the estimate's note, and the status follows their estimate.
void SolvePipeline::choose_values() {
  if (!opt_.refine_to_tolerance || !verdict_ || verdict_->second.empty() || result_.extrapolated.empty()) return;
  const ReportedValues v = extrapolated_answers(scene_, result_, result_.extrapolated, verdict_->first);
  if (!(v.frequencies || v.deflections)) return;
  std::vector<std::string> left = problems_left(verdict_->second, v);
  if (!left.empty()) return;
  report_extrapolated(result_, v);
  verdict_->second = std::move(left);
  const Extrapolation& x = result_.extrapolated;
  std::string what;
  if (v.frequencies) what = fmt::format("frequencies (estimate {:.2g})", x.frequency_error);
  if (v.deflections)
    what += fmt::format("{}deflections (estimate {:.2g})", what.empty() ? "" : " and ", x.deflection_error);
  verdict_->first.note = fmt::format("reported values: the Richardson extrapolation's {} of meshes {}, whose estimate "
                                     "meets the tolerance {:.2g} where the mesh's own does not; ",
                                     what, x.meshes, scene_.request.tolerance) +
                         verdict_->first.note;
}

/// The time history on the mesh kept (transient/superposition.cpp): its failure is the
/// transient's alone, said with the status it had.
void SolvePipeline::transient() {
  auto& sum = result_.summary;
  if (!scene_.request.transient || severity(sum.status) >= severity(Status::ResourceLimit)) return;
  try {
    planned_s_ += solve_transient(
        scene_, [&](const Scene& sc) { return solve_light(sc, final_mesh_); },
        [&](const Scene& sc) { return solver_.estimate(sc, final_mesh_, opt_).seconds; }, opt_.max_time_s - since_start(),
        result_);
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    sum.raise(Status::NumericalIssue, std::string("transient: ") + e.what());
  }
}

/// Nothing non-finite leaves a solver unflagged; every mode has a family; memory and time noted.
void SolvePipeline::finish() {
  auto& sum = result_.summary;
  if (refused_) {
    sum.total_time_s = since_start();
    return;
  }
  bool finite = true;
  for (double w : result_.frequencies_rad_s) finite = finite && std::isfinite(w);
  for (const auto& d : result_.deflections)
    for (double v : {d.u, d.v, d.w, d.theta_x, d.theta_y, d.theta_z}) finite = finite && std::isfinite(v);
  for (const auto& f : result_.frf) finite = finite && std::isfinite(std::abs(f.receptance));
  for (const auto& probe : result_.transient.values)
    for (const auto& history : probe)
      for (double v : history) finite = finite && std::isfinite(v);
  for (const auto& history : result_.transient.moments)
    for (double v : history) finite = finite && std::isfinite(v);
  for (const auto& peaks : {result_.transient.peaks, result_.transient.moment_peaks})
    for (const auto& p : peaks) finite = finite && std::isfinite(p.w) && std::isfinite(p.time_s);
  for (const auto& p : result_.campbell.points)
    for (const auto* v : {&p.frequencies_rad_s, &p.growth_rates_1_s})
      finite = finite && std::all_of(v->begin(), v->end(), [](double x) { return std::isfinite(x); });
  if (!finite && sum.status == Status::Success) sum.raise(Status::NumericalIssue, "non-finite value in the result");
  if (finite && severity(sum.status) < severity(Status::ResourceLimit))
    for (std::string& w : plausibility_warnings(scene_, result_)) sum.warnings.push_back(std::move(w));
  if (result_.mode_families.size() != result_.frequencies_rad_s.size())
    result_.mode_families.resize(result_.frequencies_rad_s.size(), ModeFamily::Unknown);
  if (sum.diagnostic("estimated_memory_bytes") > 0) sum.set_diagnostic("process_peak_resident_bytes", peak_resident_bytes());
  sum.total_time_s = since_start();
  compare_time_with_plan();
}

/// The run time against the plan: the plan (first estimate plus the refinement's predictions) is
/// reported, and a run more than 3 times longer says so, with what the estimate covered: a
/// back-end's cost model that misses is then seen, not hidden behind a refusal threshold.
void SolvePipeline::compare_time_with_plan() {
  auto& sum = result_.summary;
  if (!(planned_s_ > 0)) return;
  sum.set_diagnostic("estimated_time_planned_s", planned_s_);
  const double t = sum.total_time_s;
  if (t > 3.0 * planned_s_ && t > 1.0)
    sum.warnings.push_back(fmt::format(
        "run time {:.3g} s, {:.0f} times the estimate of {:.3g} s ({}): {}'s cost model underestimates this "
        "request; --max-time judges the estimate, not the run",
        t, t / planned_s_, planned_s_,
        final_mesh_.spec() != mesh_.spec() ? fmt::format("the first mesh {} and the refinement to {}", mesh_.spec(), final_mesh_.spec())
                                           : fmt::format("mesh {} with its error estimate", mesh_.spec()),
        solver_.name()));
}

}  // namespace detail

Result Solver::solve(const Scene& scene, const Discretization& mesh, const Options& options) const {
  return detail::SolvePipeline(*this, scene, mesh, options).run();
}

}  // namespace modalbench
