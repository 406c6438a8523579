#pragma once
// Private to core: the solve pipeline's state and steps (solve_pipeline.cpp: the steps in order;
// solve_refinement.cpp: the default mesh refined to the tolerance).
#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "modalbench/extrapolation.hpp"
#include "solve_internal.hpp"

namespace modalbench::detail {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

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

  MeshFamily family_;  ///< the back-end's meshes for the scene (where an estimate is wanted)
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

}  // namespace modalbench::detail
