// The default path at the tolerance a user asks for (issue "accuracy on demand"): on the prism
// paper's plate as a Mindlin plate (kappa = 1, 8 modes) and its clamped-clamped Timoshenko beam
// (6 modes), each back-end's `modalbench solve SCENE --backend B` (the default mesh refined to the
// scene's tolerance) at tolerances 1e-2 ... 1e-5: status, mesh kept, which values it reports (the
// mesh's or the extrapolated ones), their estimate, the true error against exact (solved at 1e-10;
// the largest relative error over all requested modes, paired by family) and the wall time. Where
// CalculiX's `ccx` is installed, the element a practitioner would use (S8R shells, B32R beams) runs
// its own ladder in the same process, each rung timed once, and per tolerance the cheapest rung
// whose error meets it is set against the fastest default solve that met it: the ratio of the two
// times is the figure (absolute times depend on the machine). The peer elements tend to their own
// models (S8R and B32R expand into C3D20R bricks with ccx's own shear treatment: 1.5 % from the
// Mindlin plate with kappa = 1 and 0.5 % from the Timoshenko beam on their finest rungs), so a rung's
// error is its distance to the finest rung of its ladder: a lower bound of its discretization error,
// which can only favour CalculiX in the ratio.
//
// Sample runs:
//   build/benchmarks/accuracy/bench_tolerance_ladder          # both scenes, --max-time 60 per solve
//   build/benchmarks/accuracy/bench_tolerance_ladder 20 plate # a 20 s limit, the plate only
//   build/benchmarks/accuracy/bench_tolerance_ladder 200       # CalculiX's rungs up to 133x80 and 1024 (1e-5)
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "modalbench/harness/calculix.hpp"
#include "modalbench/harness/comparison.hpp"
#include "modalbench/registry.hpp"
#include "modalbench/solver.hpp"

using namespace modalbench;

namespace {

constexpr double kTolerances[] = {1e-2, 1e-3, 1e-4, 1e-5};

struct Case {
  std::string name;
  Scene scene;
};

std::vector<Case> cases(const std::string& filter) {
  const std::string dir = MODALBENCH_SCENES_DIR;
  Scene plate = load_scene(dir + "/paper_ss_plate.toml");
  plate.name = "paper plate, Mindlin (kappa = 1)";
  plate.theory = Theory::Mindlin;
  plate.material.kappa = 1.0;
  plate.loads.clear();
  plate.request.probes.clear();
  plate.request.frf.reset();
  plate.request.modes = 8;
  Scene beam = load_scene(dir + "/paper_fixed_beam.toml");
  beam.name = "paper beam, clamped-clamped Timoshenko";
  beam.loads.clear();
  beam.request.probes.clear();
  beam.request.frf.reset();
  beam.request.modes = 6;
  std::vector<Case> out;
  for (Case c : {Case{"plate", plate}, Case{"beam", beam}}) {
    validate(c.scene);
    if (c.name.find(filter) != std::string::npos) out.push_back(std::move(c));
  }
  return out;
}

/// The largest relative error of the run's frequencies over all the reference's modes, paired by
/// family (harness measure_errors); NaN where a mode has no pair.
double true_error(const Scene& s, const Reference& ref, const Result& r) {
  RunRecord rec;
  rec.result = r;
  measure_errors(s, ref, rec);
  double worst = 0;
  for (double e : rec.frequency_errors) worst = std::isfinite(e) ? std::max(worst, e) : kNotMeasured;
  return worst;
}

struct Row {
  std::string backend;
  double time_s = kNotMeasured, error = kNotMeasured;
  bool ok = false;
};

}  // namespace

int main(int argc, char** argv) {
  reuse_freed_memory();  // as the command line does (main.cpp)
  const double max_time = argc > 1 ? std::atof(argv[1]) : 60.0;
  const std::string filter = argc > 2 ? argv[2] : "";
  const Registry reg = make_default_registry();
  const std::string ccx = calculix_version("ccx").empty() ? "" : "ccx";
  const std::string work = (std::filesystem::temp_directory_path() / "modalbench_bench_tolerance_ladder").string();
  std::filesystem::create_directories(work);
  for (const Case& c : cases(filter)) {
    Scene tight = c.scene;
    tight.request.tolerance = 1e-10;
    const Result ex = reg.get("exact").solve(tight, {}, Options{});
    if (!ex.ok()) {
      fmt::print("{}: exact failed ({}): skipped\n", c.scene.name, ex.summary.message);
      continue;
    }
    Reference ref;
    ref.source = "exact";
    ref.frequencies_rad_s = ex.frequencies_rad_s;
    ref.families = ex.mode_families;
    fmt::print("\n{} ({} modes; reference exact at 1e-10)\n", c.scene.name, c.scene.request.modes);
    fmt::print("{:<9} {:<14} {:<14} {:<10} {:<13} {:>10} {:>10} {:>9}\n", "tolerance", "back-end", "status", "mesh kept",
               "values", "estimate", "true err", "time [s]");
    std::map<double, std::vector<Row>> met;
    for (const double tol : kTolerances) {
      Scene s = c.scene;
      s.request.tolerance = tol;
      for (const std::string& name : reg.names()) {
        if (name == "exact") continue;
        const Solver& b = reg.get(name);
        if (!b.supports(s).modes) continue;
        Options o;
        o.max_time_s = max_time;
        const auto t0 = std::chrono::steady_clock::now();
        const Result r = b.solve_default(s, o);
        const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const bool x = r.extrapolated.frequencies_reported;
        const double est = r.frequency_estimate();
        const double err = true_error(s, ref, r);
        fmt::print("{:<9.0e} {:<14} {:<14} {:<10} {:<13} {:>10.2g} {:>10.2g} {:>9.3g}{}\n", tol, name,
                   to_string(r.summary.status), r.summary.mesh, x ? "extrapolated" : "mesh", est, err, t,
                   r.summary.converges_to_scene_theory ? "" : "  (another theory)");
        met[tol].push_back({name, t, err, r.ok() && err <= tol && r.summary.converges_to_scene_theory});
      }
    }
    if (ccx.empty()) {
      fmt::print("CalculiX: ccx not installed: no side-by-side figure\n");
      continue;
    }
    if (const std::string why = calculix_peer_unsupported_reason(c.scene); !why.empty()) {
      fmt::print("CalculiX {}: {}\n", calculix_peer_element(c.scene), why);
      continue;
    }
    // The peer's ladder, each rung once, until a rung meets the tightest tolerance or takes longer
    // than the limit.
    std::vector<Row> peer;
    std::vector<Result> rungs;
    fmt::print("CalculiX {} ladder:\n", calculix_peer_element(c.scene));
    // The harness's ladder, and finer rungs for the 1e-5 rung and a finer one to measure it
    // against, as far as the time limit lets them run: a plate's S8R converges at about fourth
    // order here (53x32 is 6.3e-5 from 80x48: 107x64 and 133x80), a beam's B32R at about second
    // (64 elements 8e-5 from 128: 256 to 1024).
    std::vector<Discretization> ladder = calculix_peer_ladder(c.scene);
    if (c.scene.is_plate())
      for (int n : {64, 80})
        ladder.push_back({{std::max(2, static_cast<int>(std::lround(n * c.scene.geometry.length / c.scene.geometry.width))), n}});
    else
      for (int n : {256, 512, 1024}) ladder.push_back({{n}});
    for (const Discretization& m : ladder) {
      const RunRecord rec = calculix_peer_run(c.scene, m, ccx, work);
      if (!rec.result.ok()) {
        fmt::print("  {:<10} {}: {}\n", m.spec(), to_string(rec.result.summary.status), rec.result.summary.message);
        break;
      }
      peer.push_back({m.spec(), rec.median_s, kNotMeasured, true});
      rungs.push_back(rec.result);
      if (!(rec.median_s <= max_time / 4)) break;  // the next rung would take several times longer
    }
    if (rungs.size() < 2) continue;
    Reference finest;
    finest.source = "the finest rung";
    finest.frequencies_rad_s = rungs.back().frequencies_rad_s;
    finest.families = rungs.back().mode_families;
    for (std::size_t i = 0; i < peer.size(); ++i) {
      const bool last = i + 1 == peer.size();
      peer[i].error = last ? kNotMeasured : true_error(c.scene, finest, rungs[i]);
      fmt::print("  {:<10} to the finest rung {:>9.2g}, to exact {:>9.2g}  time {:.3g} s\n", peer[i].backend, peer[i].error,
                 true_error(c.scene, ref, rungs[i]), peer[i].time_s);
    }
    for (const double tol : kTolerances) {
      const Row* fast = nullptr;
      for (const Row& r : met[tol])
        if (r.ok && (!fast || r.time_s < fast->time_s)) fast = &r;
      const Row* cx = nullptr;
      for (const Row& r : peer)
        if (r.ok && r.error <= tol && (!cx || r.time_s < cx->time_s)) cx = &r;
      fmt::print("  tolerance {:.0e}: fastest default solve within it {}; CalculiX {} {}; ratio {}\n", tol,
                 fast ? fmt::format("{} {:.3g} s", fast->backend, fast->time_s) : "none",
                 calculix_peer_element(c.scene), cx ? fmt::format("{} {:.3g} s", cx->backend, cx->time_s) : "none on its ladder",
                 fast && cx ? fmt::format("{:.3g}x", cx->time_s / fast->time_s) : "-");
    }
  }
}
