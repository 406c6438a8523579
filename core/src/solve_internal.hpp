#pragma once
// What the steps of Solver::solve (solve_pipeline.cpp) share inside core: the options in force,
// the process's resources, and the verdict on a result's discretization error. Not installed.
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "modalbench/result.hpp"
#include "modalbench/scene.hpp"
#include "modalbench/solver.hpp"

namespace modalbench::detail {

/// The back-end's options for one solve: its specs' defaults, then the scene's [backend.NAME]
/// table, then the command line; throws InputError (source, key, reason) on an unknown key or a
/// value out of its spec.
ResolvedOptions resolve_options(const Solver& solver, const Scene& scene, const Options& options);

/// The back-end's model of `scene` on `mesh` and its kernels for what the scene asks, in order
/// (kernels.hpp), into `r`: each timed into its phase, with its own status (Summary::steps). With
/// `statics_refused`, statics the back-end refuses as invalid input (a mechanism) are dropped
/// from the result as if no probe had been asked, and the reason is put there.
void run_kernels(const Solver& solver, const Scene& scene, const Discretization& mesh, const Options& options,
                 Result& r, std::string* statics_refused);

/// Maps the first pages of this thread's stack now (resources.cpp says why).
void map_stack_pages();
/// Peak resident memory of this process so far (VmHWM), bytes; NaN where unknown.
double peak_resident_bytes();
/// "1.23 GB".
std::string gigabytes(double bytes);

/// Warnings (never a status) for results outside what the model means: material values far from
/// engineering materials in SI, deflections beyond the small-deflection range, modes shorter than
/// the depth under Euler-Bernoulli or Kirchhoff theory (plausibility.cpp).
std::vector<std::string> plausibility_warnings(const Scene& scene, const Result& result);

/// A solve of the error estimate: its mesh, how much coarser it is than the next finer one, and
/// its result.
struct MeshSolve {
  std::string spec;
  double ratio = 2.0;
  const Result* result = nullptr;
};

/// An error estimate and what of it exceeds the scene's tolerance (one sentence per quantity, each
/// starting with the quantity's name and a colon: "frequencies:", "deflections:", "Campbell:").
using Verdict = std::pair<ErrorEstimate, std::vector<std::string>>;

/// The quantities a result answers with their extrapolated values (reported_values.cpp).
struct ReportedValues {
  bool frequencies = false, deflections = false;
};
/// Those whose mesh estimate `e` exceeds the tolerance and whose extrapolated estimate (`x`, from
/// the meshes of `fine`'s estimate) meets it; deflections only where the result gives no stress
/// resultants (judged with them, not extrapolated).
ReportedValues extrapolated_answers(const Scene& scene, const Result& fine, const Extrapolation& x,
                                    const ErrorEstimate& e);
/// Whether a result gives stress resultants at its probes (judged with the deflections, not extrapolated).
bool gives_forces(const Result& r);
/// The verdict's problems left once those quantities are answered by their extrapolated values.
std::vector<std::string> problems_left(const std::vector<std::string>& problems, const ReportedValues& v);
/// Puts the extrapolated values of those quantities into the result (r.extrapolated keeps the mesh's).
void report_extrapolated(Result& r, const ReportedValues& v);

/// The discretization error of `fine` (result.hpp, ErrorEstimate) from `coarse` and, where given,
/// `coarser` (the next coarser mesh). With other_is_finer, `coarse` is in fact a finer mesh (the
/// judged one has no coarser): the roles of the pair swap and `coarser` is not used. `coarsest`
/// (the mesh coarser than `coarser`, where there is one) can confirm the frequencies' order: Roache's
/// factor of safety 1.25 instead of 3 where it does (discretization_error.cpp, Gci).
Verdict judge_discretization(const Scene& scene, double order, const Result& fine, const MeshSolve& coarse,
                             const std::optional<MeshSolve>& coarser = std::nullopt, bool other_is_finer = false,
                             const std::optional<MeshSolve>& coarsest = std::nullopt);

/// The back-end's solve of a scene on the mesh kept (the transient's modal solves), and its
/// estimated run time, s.
using ModalSolve = std::function<Result(const Scene&)>;
using ModalEstimate = std::function<double(const Scene&)>;

/// The modes the transient starts with: request.modes, at least 12.
int transient_first_modes(const Scene& scene);
/// The transient's modal solve of `modes` + 1 modes (one kept back as the first neglected): the
/// shapes at the probes and the load points, nothing else.
Scene transient_modal_scene(const Scene& scene, int modes);
/// The scene's request.transient (transient/superposition.cpp): modes solved with `solve`,
/// superposed with the static correction from result.deflections; fills result.transient and
/// raises what it finds on result.summary. Throws std::runtime_error where the modal solve fails.
/// The modes double (at most 4 times) while the estimate exceeds the tolerance and a round fits
/// in time_left_s. Returns the estimated time of the rounds after the first (planned by the caller).
double solve_transient(const Scene& scene, const ModalSolve& solve, const ModalEstimate& estimate, double time_left_s,
                       Result& result);

}  // namespace modalbench::detail
