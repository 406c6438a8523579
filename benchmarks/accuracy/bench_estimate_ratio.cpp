// Estimates against the truth (issue "accuracy on demand": an estimate systematically far above the
// true error makes the default path pay for meshes it does not need; one below it is worse): every
// built-in scene that `exact` solves in the scene's theory is the oracle of every other back-end's
// default solve (`modalbench solve SCENE --backend B`, the mesh refined to the scene's tolerance)
// whose model tends to that theory (exact solved at the tightest tolerance of 1e-10, 1e-8, 1e-6 its
// series meet). Per quantity the run's own estimate, its true error against
// exact and their ratio (>= 1: the estimate holds; "!" marks a ratio below 1):
//   frequencies  the largest relative error over the modes (rigid zeros skipped), paired in order
//                within each mode family the run gives;
//   deflections  the largest of u, v, w over the probes, relative to the largest |u|, |v|, |w|;
//   campbell     a rotor's whirl frequencies, paired by rank at each spin, relative to f + spin.
// A true error below 1e-13 (rounding) is not judged. The median and the least ratio per quantity
// close the table.
//
// Sample run:
//   build/benchmarks/accuracy/bench_estimate_ratio          # every built-in scene
//   build/benchmarks/accuracy/bench_estimate_ratio beam     # scenes whose file name contains "beam"
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "modalbench/harness/comparison.hpp"
#include "modalbench/registry.hpp"
#include "modalbench/rotor_scene.hpp"
#include "modalbench/solver.hpp"

using namespace modalbench;

namespace {

/// Per mode family the run gives (a back-end that solves fewer fields than the scene, e.g.
/// difference_eq's x-z chain on a lateral shaft, says so in its warnings), its modes in order
/// against exact's of that family.
double frequency_error(const Result& r, const Result& ref) {
  if (r.frequencies_rad_s.empty()) return NAN;
  auto of = [](const Result& x, ModeFamily fam) {
    std::vector<double> out;
    for (std::size_t i = 0; i < x.frequencies_rad_s.size(); ++i)
      if (x.mode_families[i] == fam) out.push_back(x.frequencies_rad_s[i]);
    return out;
  };
  double worst = 0;
  for (const ModeFamily fam : {ModeFamily::BendingXZ, ModeFamily::BendingXY, ModeFamily::Axial, ModeFamily::Torsion,
                               ModeFamily::Plate, ModeFamily::Unknown}) {
    const std::vector<double> f = of(r, fam), g = of(ref, fam);
    for (std::size_t i = 0; i < std::min(f.size(), g.size()); ++i)
      if (g[i] != 0) worst = std::max(worst, std::abs(f[i] / g[i] - 1));
  }
  return worst;
}

double deflection_error(const Result& r, const Result& ref) {
  if (r.deflections.size() != ref.deflections.size() || r.deflections.empty()) return NAN;
  double scale = 0, worst = 0;
  for (const Deflection& d : ref.deflections) scale = std::max({scale, std::abs(d.u), std::abs(d.v), std::abs(d.w)});
  for (std::size_t i = 0; i < r.deflections.size(); ++i) {
    const Deflection &a = r.deflections[i], &b = ref.deflections[i];
    worst = std::max({worst, std::abs(a.u - b.u), std::abs(a.v - b.v), std::abs(a.w - b.w)});
  }
  return scale > 0 ? worst / scale : NAN;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string filter = argc > 1 ? argv[1] : "";
  std::vector<std::filesystem::path> files;
  for (const std::string& f : scene_files(MODALBENCH_SCENES_DIR))  // sorted
    if (std::filesystem::path(f).filename().string().find(filter) != std::string::npos) files.push_back(f);
  const Registry reg = make_default_registry();
  fmt::print("{:<28} {:<14} {:<12} {:<15} {:>10} {:>10} {:>8}\n", "scene", "back-end", "quantity", "mesh kept", "estimate",
             "true", "ratio");
  std::map<std::string, std::vector<double>> ratios;
  for (const auto& f : files) {
    Scene s = load_scene(f.string());
    s.request.frf.reset();
    s.request.transient.reset();
    s.request.shapes.reset();
    Options o;
    // The reference at the tightest tolerance its series meet (a Navier statics series at the
    // scene's own tolerance leaves errors of its order in the reference itself).
    Result ref;
    for (const double tol : {1e-10, 1e-8, 1e-6, s.request.tolerance}) {
      Scene tight = s;
      tight.request.tolerance = tol;
      ref = reg.get("exact").solve(tight, {}, o);
      if (ref.ok()) break;
    }
    if (!ref.ok() || !ref.summary.converges_to_scene_theory) continue;
    for (const std::string& name : reg.names()) {
      if (name == "exact") continue;
      const Solver& b = reg.get(name);
      if (!b.supports(s).any()) continue;
      const Result r = b.solve_default(s, o);
      if (!r.summary.converges_to_scene_theory || r.summary.mesh == "-") continue;
      const ErrorEstimate& e = r.summary.error_estimate;
      // The estimate of the values reported: the extrapolation's where the result answers with it.
      const Extrapolation& x = r.extrapolated;
      const std::pair<const char*, std::pair<double, double>> rows[] = {
          {x.frequencies_reported ? "frequencies (x)" : "frequencies",
           {x.frequencies_reported ? x.frequency_error : e.frequencies, frequency_error(r, ref)}},
          {x.deflections_reported ? "deflections (x)" : "deflections",
           {x.deflections_reported ? x.deflection_error : e.deflections, deflection_error(r, ref)}},
          {"campbell", {e.campbell, campbell_difference(r.campbell, ref.campbell)}}};
      for (const auto& [q, v] : rows) {
        const auto [est, truth] = v;
        if (!std::isfinite(est) || !std::isfinite(truth)) continue;
        const bool judged = truth > 1e-13;
        const double ratio = est / truth;
        if (judged) ratios[q].push_back(ratio);
        fmt::print("{:<28} {:<14} {:<12} {:<15} {:>10.2g} {:>10.2g} {:>8}{}\n", f.stem().string(), name, q, r.summary.mesh,
                   est, truth, judged ? fmt::format("{:.3g}", ratio) : "-", judged && ratio < 1 ? " !" : "");
      }
    }
  }
  fmt::print("\n");
  for (auto& [q, v] : ratios) {
    std::sort(v.begin(), v.end());
    fmt::print("{:<12} {:>3} runs: median ratio {:.3g}, least {:.3g}{}\n", q, v.size(), v[v.size() / 2], v.front(),
               v.front() < 1 ? " (an estimate below the true error)" : "");
  }
}
