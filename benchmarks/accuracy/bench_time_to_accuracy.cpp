// Time to accuracy (issue 14): for each back-end, the cheapest run whose largest relative error
// over the first modes (8 on the paper plate, 6 on the beam and the cantilever) against the
// scene's reference is at most 1e-2, 1e-3, 1e-4 and 1e-5, with its mesh and peak memory. Each
// back-end is run two ways through Solver::solve (the `modalbench solve --mesh M` path):
//   mesh        the mesh alone (no error estimate: the time of the numbers themselves);
//   richardson  the mesh with its error estimate (its counts halved two or three times), reporting
//               the Richardson values and their estimate (Result::extrapolated): the time is that of
//               all the meshes.
// Scenes: the prism paper's plate as a Kirchhoff and as a Mindlin plate (kappa = 1; reference the
// exact Navier and Mindlin values), its clamped-clamped Timoshenko beam (exact Timoshenko), and
// NAFEMS FV16's cantilever 10 x 10 x 0.05 m plate (no exact solution: the reference is the
// Richardson value with the smallest estimate of dtfm on 64 strips and rfem on 256 x 256, its
// estimate printed; targets below ten times it are not judged).
//
// Sample runs:
//   build/benchmarks/accuracy/bench_time_to_accuracy          # every scene, 3 timed repeats
//   build/benchmarks/accuracy/bench_time_to_accuracy 5 plate  # scenes whose name contains "plate"
//
// 1. Each (scene, back-end, way, mesh) runs in a child process: a warm-up, then the median of
//    the repeats; its peak resident memory is the child's own.
// 2. A back-end's ladder stops at the first mesh that reaches 1e-5, or one that takes over 8 s.
#include <fmt/format.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <new>
#include <string>
#include <vector>

#include "modalbench/registry.hpp"
#include "modalbench/solver.hpp"

using namespace modalbench;

namespace {

constexpr std::array<double, 4> kTargets{1e-2, 1e-3, 1e-4, 1e-5};

struct Measured {
  bool ok = false;
  double error = NAN, estimate = NAN, median_s = NAN, peak_mb = NAN;
};

/// Runs `f` in a child process and returns what it wrote into shared memory.
Measured in_child(const std::function<Measured()>& f) {
  auto* shared = static_cast<Measured*>(mmap(nullptr, sizeof(Measured), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0));
  new (shared) Measured{};
  std::fflush(stdout);
  const pid_t pid = fork();
  if (pid == 0) {
    Measured m = f();
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    m.peak_mb = static_cast<double>(u.ru_maxrss) / 1024.0;
    shared->ok = m.ok;
    shared->error = m.error;
    shared->estimate = m.estimate;
    shared->median_s = m.median_s;
    shared->peak_mb = m.peak_mb;
    _exit(0);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  Measured out;
  out.ok = shared->ok;
  out.error = shared->error;
  out.estimate = shared->estimate;
  out.median_s = shared->median_s;
  out.peak_mb = shared->peak_mb;
  munmap(shared, sizeof(Measured));
  return out;
}

double max_rel_error(const std::vector<double>& f, const std::vector<double>& ref, std::size_t modes) {
  if (f.size() < modes || ref.size() < modes) return NAN;
  double worst = 0;
  for (std::size_t i = 0; i < modes; ++i) worst = std::max(worst, std::abs(f[i] / ref[i] - 1.0));
  return worst;
}

struct Case {
  std::string label;
  Scene scene;
  std::vector<double> reference;
  double reference_uncertainty = 0;  ///< relative
  std::string reference_source;
  std::map<std::string, std::vector<std::string>> meshes;  ///< per back-end, coarse to fine
};

Scene frequencies_only(Scene s, int modes) {
  s.request.modes = modes;
  s.request.probes.clear();
  s.request.frf.reset();
  s.request.shapes.reset();
  s.loads.clear();
  return s;
}

/// The scenes and their meshes per back-end, coarse to fine.
std::vector<Case> make_cases(const std::string& dir) {
  std::vector<Case> cases;
  {
    Case k;
    k.label = "paper plate, Kirchhoff";
    k.scene = frequencies_only(load_scene(dir + "/paper_ss_plate.toml"), 8);
    k.meshes["rfem"] = {"20x12", "40x24", "80x48", "120x72", "160x96", "240x144"};
    k.meshes["dtfm"] = {"8", "16", "24", "32", "48", "64"};
    cases.push_back(k);
    k.label = "paper plate, Mindlin (kappa = 1)";
    k.scene.theory = Theory::Mindlin;
    cases.push_back(k);
  }
  {
    Case k;
    k.label = "paper fixed beam, Timoshenko";
    k.scene = frequencies_only(load_scene(dir + "/paper_fixed_beam.toml"), 6);
    k.meshes["rfem"] = {"16", "32", "64", "128", "256", "512", "1024"};
    k.meshes["dtfm"] = {"1x1"};
    k.meshes["difference_eq"] = {"16", "32", "64", "128", "256"};
    cases.push_back(k);
  }
  {
    Case k;
    k.label = "cantilever plate 10 x 10 x 0.05 m (NAFEMS FV16)";
    k.scene = frequencies_only(load_scene(dir + "/nafems_fv16_cantilever_plate.toml"), 6);
    k.meshes["rfem"] = {"16x16", "32x32", "64x64", "96x96", "128x128", "192x192"};
    k.meshes["dtfm"] = {"8", "16", "24", "32", "48", "64"};
    cases.push_back(k);
  }
  return cases;
}

/// The case's reference frequencies and where they come from.
void find_reference(const Registry& reg, Case& k) {
  // The reference, in a child process too: the parent stays small, so that every run's child
  // (a fork of it) starts from the same few MB and its peak is its own.
  struct ReferenceOut {
    int n = 0;
    double f[64] = {};
    double uncertainty = 0;
    char source[512] = {};
  };
  auto* ref = static_cast<ReferenceOut*>(
      mmap(nullptr, sizeof(ReferenceOut), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0));
  new (ref) ReferenceOut{};
  std::fflush(stdout);
  if (const pid_t pid = fork(); pid == 0) {
    std::vector<double> values;
    double uncertainty = 0;
    std::string source;
    const Solver& exact = reg.get("exact");
    if (exact.supports(k.scene).modes) {
      const Result r = exact.solve(k.scene, {}, Options{});
      if (r.ok()) {
        values = r.frequencies_rad_s;
        source = "exact";
      }
    }
    if (values.empty()) {
      // No exact solution: the extrapolated values with the smallest estimate of their own error.
      for (const auto& [backend, spec] : {std::pair<std::string, std::string>{"dtfm", "64"}, {"rfem", "256x256"}}) {
        const Result r = reg.get(backend).solve(k.scene, Discretization::parse(spec), Options{});
        const Extrapolation& x = r.extrapolated;
        if (x.frequencies_rad_s.empty() || !(values.empty() || x.frequency_error < uncertainty)) continue;
        values = x.frequencies_rad_s;
        uncertainty = x.frequency_error;
        source = fmt::format("{} {}, Richardson of meshes {} (its estimate {:.1e}, {})", backend, spec, x.meshes,
                             x.frequency_error, to_string(r.summary.status));
      }
    }
    ref->n = static_cast<int>(std::min<std::size_t>(values.size(), 64));
    for (int i = 0; i < ref->n; ++i) ref->f[i] = values[static_cast<std::size_t>(i)];
    ref->uncertainty = uncertainty;
    std::snprintf(ref->source, sizeof ref->source, "%s", source.c_str());
    _exit(0);
  } else {
    int status = 0;
    waitpid(pid, &status, 0);
  }
  k.reference.assign(ref->f, ref->f + ref->n);
  k.reference_uncertainty = ref->uncertainty;
  k.reference_source = ref->source;
  munmap(ref, sizeof(ReferenceOut));
}

/// False (and a line saying so) where the back-end's model is not the scene's theory.
bool converges_to_scene_theory(const Solver& s, const Case& k, const std::string& backend, const std::string& coarsest) {
  // A back-end whose model is not the scene's theory converges elsewhere: its error here is
  // model error, not the cost of accuracy.
  Options o;
  o.estimate_error = false;
  const Result probe = s.solve(k.scene, Discretization::parse(coarsest), o);
  if (!probe.summary.converges_to_scene_theory) {
    fmt::print("{:<14} (its model is not the scene's {} theory: not timed to accuracy)\n", backend,
               to_string(k.scene.theory));
    return false;
  }
  return true;
}

/// One mesh's run in a child process: the median time of the repeats after a warm-up, its error.
Measured time_mesh(const Solver& s, const Case& k, const Discretization& mesh, bool richardson, int repeats) {
  return in_child([&] {
    Measured out;
    Options o;
    o.estimate_error = richardson;
    std::vector<double> times;
    Result r;
    for (int i = 0; i <= repeats; ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      r = s.solve(k.scene, mesh, o);
      if (i > 0) times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    std::sort(times.begin(), times.end());
    out.median_s = times[times.size() / 2];
    const auto& f = richardson ? r.extrapolated.frequencies_rad_s : r.frequencies_rad_s;
    out.ok = severity(r.summary.status) <= severity(Status::NotConverged) && !f.empty();
    out.error = max_rel_error(f, k.reference, static_cast<std::size_t>(k.scene.request.modes));
    out.estimate = richardson ? r.extrapolated.frequency_error : r.summary.error_estimate.frequencies;
    return out;
  });
}

/// One table row: the meshes coarse to fine, each target's cell the cheapest run that reached it.
void print_ladder(const Solver& s, const Case& k, const std::string& backend, const std::vector<std::string>& meshes,
                  bool richardson, int repeats) {
  std::array<std::string, 4> cell;
  cell.fill("-");
  std::string last;
  for (const auto& spec : meshes) {
    const Discretization mesh = Discretization::parse(spec);
    const Measured m = time_mesh(s, k, mesh, richardson, repeats);
    last = fmt::format("{} {}: error {:.2e}, {:.3g} s, {:.0f} MB{}", spec, richardson ? "richardson" : "mesh", m.error,
                       m.median_s, m.peak_mb, m.ok ? "" : " (failed or not extrapolated)");
    if (m.ok)
      for (std::size_t t = 0; t < kTargets.size(); ++t)
        if (cell[t] == "-" && m.error <= kTargets[t] && kTargets[t] >= 10 * k.reference_uncertainty)
          cell[t] = fmt::format("{:.3g} s ({}, {:.0f} MB)", m.median_s, spec, m.peak_mb);
    if ((m.ok && m.error <= kTargets.back()) || !(m.median_s < 8.0)) break;
  }
  for (std::size_t t = 0; t < kTargets.size(); ++t)
    if (kTargets[t] < 10 * k.reference_uncertainty) cell[t] = "(reference too coarse)";
  fmt::print("{:<14} {:<11} {:>26} {:>26} {:>26} {:>26}\n", backend, richardson ? "richardson" : "mesh", cell[0], cell[1],
             cell[2], cell[3]);
  fmt::print("{:<26} finest tried: {}\n", "", last);
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  const std::string only = argc > 2 ? argv[2] : "";
  const Registry reg = make_default_registry();
  std::vector<Case> cases = make_cases(MODALBENCH_SCENES_DIR);

  fmt::print("Time to accuracy: largest relative error of the first modes against the reference; each entry is the\n"
             "cheapest run reaching the target: median wall time of {} repeat(s) after a warm-up (mesh, peak resident MB).\n"
             "'mesh': the mesh alone; 'richardson': the mesh and its counts halved two or three times, the extrapolated values.\n",
             repeats);
  for (auto& k : cases) {
    if (!only.empty() && k.label.find(only) == std::string::npos) continue;
    find_reference(reg, k);
    fmt::print("\n## {} ({} modes; reference: {})\n", k.label, k.scene.request.modes,
               k.reference_source.empty() ? "none" : k.reference_source);
    if (k.reference.empty()) continue;
    fmt::print("{:<14} {:<11} {:>26} {:>26} {:>26} {:>26}\n", "back-end", "way", "1e-2", "1e-3", "1e-4", "1e-5");
    for (const auto& [backend, meshes] : k.meshes) {
      const Solver& s = reg.get(backend);
      if (!converges_to_scene_theory(s, k, backend, meshes.front())) continue;
      for (const bool richardson : {false, true}) {
        if (richardson && meshes.size() == 1) continue;  // a mesh with no coarser ones (dtfm's exact one-prism beam)
        print_ladder(s, k, backend, meshes, richardson, repeats);
      }
    }
  }
  return 0;
}
