// The default path's refinement (solve_pipeline.hpp): the default mesh refined until its estimate,
// or its extrapolation's, meets the tolerance; each step sized from the estimate and the order.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <new>
#include <utility>

#include "solve_pipeline.hpp"

namespace modalbench::detail {

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
    const int steps = family_.refinement_steps;
    for (int step = 0; step < steps && !verdict_->second.empty() && !extrapolation_answers(w); ++step)
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

namespace {
/// The window's fourth mesh (4H), where it has one: it can confirm the estimate's order.
std::optional<MeshSolve> fourth_of(const RefinementWindow& w) {
  if (!w.third || !w.r3) return std::nullopt;
  return MeshSolve{w.r3->summary.mesh, w.ratio3, &*w.r3};
}
}  // namespace

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
  verdict_ = judge_discretization(scene_, coarse_->order, w.cur, MeshSolve{w.prev_spec, w.ratio_prev, &w.prev}, w.third,
                                  false, fourth_of(w));
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
  const double worst =
      std::max(std::isnan(e.frequencies) ? 0.0 : e.frequencies, std::isnan(e.deflections) ? 0.0 : e.deflections);
  // The mesh sized for its own estimate, or for the extrapolation's where that is the smaller step
  // (its error falls at the order left after extrapolation).
  double factor = 1.25 * std::pow(worst / scene_.request.tolerance, 1.0 / coarse_->order);
  if (const double fx = extrapolation_factor(w); fx < factor) factor = fx;
  factor = std::clamp(factor, 1.5, 4.0);
  const std::optional<Discretization> next =
      family_.finer_than(final_mesh_, std::isfinite(factor) ? factor : 4.0);
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
  verdict_ = judge_discretization(scene_, coarse_->order, w.cur, MeshSolve{w.prev_spec, ratio, &w.prev}, w.third, false,
                                  fourth_of(w));
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
    if (gives_forces(w.cur) || x->deflections.empty()) return kNotMeasured;
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

}  // namespace modalbench::detail
