// Each back-end's default solve of a scene's time history, for the report (comparison.hpp).
#include "modalbench/harness/comparison.hpp"

#include <fmt/format.h>

namespace modalbench {

std::vector<TransientRun> transient_runs(const Scene& scene, const Registry& registry, const CompareOptions& opt) {
  std::vector<TransientRun> out;
  if (!scene.request.transient) return out;
  for (const Solver* s : registry.all()) {
    if (!s->supports(scene).modes) continue;
    Options o;
    o.refine_to_tolerance = true;
    o.max_time_s = 2 * opt.budget_s;
    TransientRun run{s->name(), s->solve(scene, s->default_mesh(scene), o)};
    if (opt.progress)
      *opt.progress << fmt::format("[{}] {}: time history on mesh {}: {} ({:.3g} s)\n", scene.name, s->name(),
                                   run.result.summary.mesh, to_string(run.result.summary.status),
                                   run.result.summary.total_time_s);
    out.push_back(std::move(run));
  }
  return out;
}

}  // namespace modalbench
