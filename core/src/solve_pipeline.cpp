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
// Each step is a member function of SolvePipeline (solve_pipeline.hpp); the state they pass on is its
// members. The refinement is in solve_refinement.cpp.
#include "solve_pipeline.hpp"

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
  family_ = solver_.meshes(scene_, opt_);
  coarse_ = family_.coarser_than(mesh_);
  if (!coarse_)
    if (const std::optional<Discretization> f = family_.finer_than(mesh_, 2.0)) {
      coarse_ = CoarserMesh{*f, static_cast<double>(f->counts[0]) / mesh_.counts[0], family_.order};
      check_is_finer_ = true;
    }
  if (coarse_ && !check_is_finer_) coarser2_ = family_.coarser_than(coarse_->mesh);
  if (coarser2_ && std::isfinite(coarse_->next_order)) coarser3_ = family_.coarser_than(coarser2_->mesh);
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
/// (statics_refused_ says why).
void SolvePipeline::solve_into(const Scene& sc, const Discretization& m, Result& x) const {
  const bool optional_statics = scene_.request.transient && !sc.request.probes.empty();
  if (optional_statics && !statics_refused_.empty()) {
    Scene modes_only = sc;
    modes_only.request.probes.clear();
    run_kernels(solver_, modes_only, m, opt_, x, nullptr);
    return;
  }
  std::string refused;
  run_kernels(solver_, sc, m, opt_, x, optional_statics ? &refused : nullptr);
  if (!refused.empty()) statics_refused_ = refused;
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
    std::optional<MeshSolve> third, fourth;
    std::optional<Result> cr3;
    if (coarser2_) {
      cr2 = solve_light(light_, coarser2_->mesh);
      third = MeshSolve{coarser2_->mesh.spec(), coarser2_->ratio, &cr2};
      if (coarser3_) cr3 = solve_optional(coarser3_->mesh);
      if (cr3) fourth = MeshSolve{coarser3_->mesh.spec(), coarser3_->ratio, &*cr3};
    }
    verdict_ = judge_discretization(scene_, coarse_->order, result_, MeshSolve{coarse_->mesh.spec(), coarse_->ratio, &cr},
                                    third, check_is_finer_, fourth);
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
      if (cr3) {
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

Result Solver::solve_default(const Scene& scene, Options options) const {
  options.refine_to_tolerance = true;
  Discretization mesh;
  try {
    mesh = meshes(scene, options).default_mesh;
  } catch (const InputError& e) {
    Result r;
    r.summary.raise(Status::InvalidInput, e.what());
    return r;
  }
  return solve(scene, mesh, options);
}

}  // namespace modalbench
