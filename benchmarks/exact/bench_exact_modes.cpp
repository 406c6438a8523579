// Many modes of a beam from the exact back-end (issue "accuracy on demand": 1000 modes of the paper
// beam within 2 s): the wall time of `modes = k` without FRF or shapes, beside the cost model's
// estimate, and the highest frequency against dtfm's for the same k (a second method; dtfm's
// default mesh).
//
// Sample run:
//   build/benchmarks/exact/bench_exact_modes
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <string>

#include "modalbench/registry.hpp"
#include "modalbench/solver.hpp"

using namespace modalbench;

int main() {
  const Registry reg = make_default_registry();
  Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_fixed_beam.toml");
  s.request.frf.reset();
  s.request.shapes.reset();
  s.request.probes.clear();
  fmt::print("{:>6} {:>10} {:>10} {:>22} {:>18}\n", "modes", "time [s]", "estimate", "highest [rad/s]",
             "vs dtfm (rel.)");
  for (const int k : {100, 200, 500, 1000, 2000, 4000}) {
    s.request.modes = k;
    Options o;
    o.estimate_error = false;
    const auto t0 = std::chrono::steady_clock::now();
    const Result r = reg.get("exact").solve(s, Discretization{}, o);
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const Solver& dtfm = reg.get("dtfm");
    const Result d = dtfm.solve(s, dtfm.meshes(s, o).default_mesh, o);
    const double hi = r.frequencies_rad_s.empty() ? NAN : r.frequencies_rad_s.back();
    const double vs = d.frequencies_rad_s.size() == r.frequencies_rad_s.size() ? std::abs(d.frequencies_rad_s.back() / hi - 1)
                                                                                : NAN;
    fmt::print("{:>6} {:>10.3g} {:>10.3g} {:>22.12g} {:>18.2g}  {}\n", k, t, r.summary.diagnostic("estimated_time_s"),
               hi, vs, to_string(r.summary.status));
  }
}
