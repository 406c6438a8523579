// Default solves (issue "the first hour"): every built-in scene with every back-end, as
// `modalbench solve SCENE --backend B` runs it (the default mesh refined to the scene's tolerance),
// with the mesh kept, the wall time, the first estimate, the plan (the estimate plus the
// refinement's calibrated predictions) and the plan against the time: a plan more than 3 times
// off either way is marked "!".
//
// Sample run:
//   build/benchmarks/accuracy/bench_default_solves           # every built-in scene
//   build/benchmarks/accuracy/bench_default_solves plate     # scenes whose file name contains "plate"
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "modalbench/harness/comparison.hpp"
#include "modalbench/registry.hpp"
#include "modalbench/solver.hpp"

using namespace modalbench;

int main(int argc, char** argv) {
  reuse_freed_memory();  // as the command line does (main.cpp)
  const std::string filter = argc > 1 ? argv[1] : "";
  std::vector<std::filesystem::path> files;
  for (const std::string& f : scene_files(MODALBENCH_SCENES_DIR))  // sorted
    if (std::filesystem::path(f).filename().string().find(filter) != std::string::npos) files.push_back(f);
  const Registry reg = make_default_registry();
  fmt::print("{:<30} {:<14} {:<16} {:>10} {:>9} {:>10} {:>10} {:>11}\n", "scene", "back-end", "status", "mesh kept",
             "time [s]", "first est.", "plan [s]", "plan / time");
  int off = 0, runs = 0;
  for (const auto& f : files) {
    const Scene s = load_scene(f.string());
    for (const std::string& name : reg.names()) {
      const Solver& b = reg.get(name);
      Options o;
      const auto t0 = std::chrono::steady_clock::now();
      const Result r = b.solve_default(s, o);
      const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const double first = r.summary.diagnostic("estimated_time_s"), plan = r.summary.diagnostic("estimated_time_planned_s");
      const double ratio = plan / t;
      // Under 0.1 s a cost model's constant terms dominate: not judged.
      const bool judged = std::isfinite(ratio) && t > 0.1;
      const bool miss = judged && (ratio > 3 || ratio < 1.0 / 3);
      runs += judged;
      off += miss;
      fmt::print("{:<30} {:<14} {:<16} {:>10} {:>9.3g} {:>10.3g} {:>10.3g} {:>10.3g}{}\n", f.stem().string(), name,
                 to_string(r.summary.status), r.summary.mesh, t, first, plan, ratio, miss ? " !" : "");
    }
  }
  fmt::print("\n{} of {} runs over 0.1 s have a plan more than 3 times off their time\n", off, runs);
}
