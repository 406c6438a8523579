// Each back-end's default solve of a rotor scene's Campbell diagram, for the report (comparison.hpp).
#include "modalbench/harness/comparison.hpp"

#include <fmt/format.h>

namespace modalbench {

std::vector<RotorRun> rotor_runs(const Scene& scene, const Registry& registry, const CompareOptions& opt) {
  std::vector<RotorRun> out;
  if (!scene.rotor) return out;
  for (const Solver* s : registry.all()) {
    if (!s->supports(scene).campbell) continue;
    Options o;
    o.max_time_s = 2 * opt.budget_s;
    RotorRun run{s->name(), s->solve_default(scene, o)};
    const Summary& sum = run.result.summary;
    if (opt.progress)
      *opt.progress << fmt::format("[{}] {}: Campbell diagram on mesh {}: {} ({:.3g} s)\n", scene.name, s->name(), sum.mesh,
                                   to_string(sum.status), sum.total_time_s);
    out.push_back(std::move(run));
  }
  return out;
}

}  // namespace modalbench
