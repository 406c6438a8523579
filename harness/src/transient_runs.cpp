// Each back-end's default solve of a scene's time history, and its peak against the modes used,
// for the report (comparison.hpp).
#include "modalbench/harness/comparison.hpp"

#include <fmt/format.h>

namespace modalbench {

namespace {

/// The peak at the first probe with `modes` modes on `mesh` (one round: the tolerance is lifted).
std::optional<TransientRun::ByModes> with_modes(const Solver& s, const Scene& scene, const Discretization& mesh, int modes) {
  Scene sc = scene;
  sc.request.modes = modes;
  sc.request.tolerance = 1.0;
  sc.request.frf.reset();
  sc.request.shapes.reset();
  Options o;
  o.estimate_error = false;
  const Result r = s.solve(sc, mesh, o);
  if (r.transient.empty() || r.transient.modes_used < modes) return std::nullopt;
  return TransientRun::ByModes{r.transient.modes_used, r.transient.peaks[0].w, r.summary.total_time_s};
}

}  // namespace

std::vector<TransientRun> transient_runs(const Scene& scene, const Registry& registry, const CompareOptions& opt) {
  std::vector<TransientRun> out;
  if (!scene.request.transient) return out;
  for (const Solver* s : registry.all()) {
    if (!s->supports(scene).modes) continue;
    Options o;
    o.max_time_s = 2 * opt.budget_s;
    TransientRun run{s->name(), s->solve_default(scene, o), {}};
    const Summary& sum = run.result.summary;
    if (opt.progress)
      *opt.progress << fmt::format("[{}] {}: time history on mesh {}: {} ({:.3g} s)\n", scene.name, s->name(), sum.mesh,
                                   to_string(sum.status), sum.total_time_s);
    // The convergence in modes, on the mesh kept, while each run stays within a tenth of the budget.
    if (!run.result.transient.empty()) {
      const Discretization mesh = sum.mesh == "-" ? Discretization{} : Discretization::parse(sum.mesh);
      for (int m = 12; m <= (opt.quick ? 48 : 96); m *= 2) {
        const auto p = with_modes(*s, scene, mesh, m);
        if (!p) break;
        run.by_modes.push_back(*p);
        if (p->run_s > 0.1 * opt.budget_s) break;
      }
    }
    out.push_back(std::move(run));
  }
  return out;
}

}  // namespace modalbench
