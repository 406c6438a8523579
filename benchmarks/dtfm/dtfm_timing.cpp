// Timing of the dtfm back-end (median of repeats, Release): the targets and how the
// cost grows with the number of prisms and of modes.
//   4-prism fixed beam, first 6 modes        target <= 5 ms
//   10-strip plate, first 8 modes            target <= 50 ms
//   FRF of 400 points on the 10-strip plate  target <= 100 ms
//   40-strip plate, first 8 modes            target <= 150 ms (issue 14)
//   spatial 6x6 beam, first 6 modes          target <= 200 ms (issue 14)
// Sample run: build-dtfm/benchmarks/dtfm/bench_dtfm_timing
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "modalbench/dtfm/dtfm.hpp"

using namespace modalbench;
using namespace modalbench::dtfm;

namespace {

Scene scene(const char* file) { return load_scene(std::string(MODALBENCH_SCENES_DIR) + "/" + file); }

/// Median wall time of `fn` over `repeats` runs after one warm-up, seconds.
double median_time(const std::function<void()>& fn, int repeats) {
  fn();
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace

int main() {
  const Scene beam = scene("paper_fixed_beam.toml");
  const Scene plate = scene("paper_ss_plate.toml");
  fmt::print("dtfm timing (median of repeats, one warm-up; model build included)\n\n");

  long evals = 0;
  const double t_beam = median_time(
      [&] {
        const PrismModel m = build_model(beam, Discretization::parse("2x2"));
        LineAnalysis la(m);
        evals = la.modes(6, {ModeFamily::BendingXZ}).evaluations;
      },
      21);
  fmt::print("4-prism fixed beam (2x2), first 6 modes:  {:8.2f} ms  ({} count evaluations)  target <= 5 ms\n",
             t_beam * 1e3, evals);
  const double t_plate = median_time(
      [&] {
        const PrismModel m = build_model(plate, Discretization::parse("10"));
        LineAnalysis la(m);
        evals = la.modes(8).evaluations;
      },
      11);
  fmt::print("10-strip plate, first 8 modes:            {:8.2f} ms  ({} count evaluations)  target <= 50 ms\n",
             t_plate * 1e3, evals);
  std::vector<double> omegas;
  for (int i = 0; i < 400; ++i) omegas.push_back(12000.0 * i / 399);
  const double t_frf = median_time(
      [&] {
        const PrismModel m = build_model(plate, Discretization::parse("10"));
        LineAnalysis la(m);
        la.receptance({0.4, 0.2}, {0.4, 0.2}, omegas, 0.0);
      },
      5);
  fmt::print("10-strip plate, FRF 400 points:           {:8.2f} ms  target <= 100 ms\n", t_frf * 1e3);
  Scene damped = plate;
  damped.material.loss_factor = 0.02;
  const double t_frf_d = median_time(
      [&] {
        const PrismModel m = build_model(damped, Discretization::parse("10"));
        LineAnalysis la(m);
        la.receptance({0.4, 0.2}, {0.4, 0.2}, omegas, 0.02);
      },
      5);
  fmt::print("10-strip plate, FRF 400 points, damped:   {:8.2f} ms  (complex solves)\n", t_frf_d * 1e3);
  // The first k modes of a model (of the given families): median time over `repeats`, evaluations.
  auto time_modes = [&](const PrismModel& m, int k, const std::vector<ModeFamily>& fam, int repeats) {
    long ev = 0;
    const double t = median_time(
        [&] {
          LineAnalysis la(m);
          ev = la.modes(k, fam).evaluations;
        },
        repeats);
    return std::pair<double, long>{t, ev};
  };
  // The two dtfm targets.
  auto target_row = [&](const char* label, const PrismModel& m, int k, double target_ms) {
    const auto [t, ev] = time_modes(m, k, {}, 5);
    fmt::print("{:<42}{:8.2f} ms  ({} count evaluations)  target <= {:g} ms\n", label, t * 1e3, ev, target_ms);
  };
  target_row("40-strip plate, first 8 modes:", build_model(plate, Discretization::parse("40")), 8, 150);
  Scene spatial = beam;
  spatial.physics = Physics::Spatial;
  target_row("spatial 6x6 beam, first 6 modes:", build_model(spatial, Discretization::parse("6x6")), 6, 200);
  const DtfmSolver solver;
  const double t_full = median_time([&] { solver.solve(plate, Discretization::parse("10"), {}); }, 5);
  fmt::print("10-strip plate, whole scene (8 modes, statics, FRF): {:8.2f} ms\n\n", t_full * 1e3);

  fmt::print("cost vs number of prisms (first 8 modes):\n");
  fmt::print("  {:<28} {:>7} {:>10} {:>8}\n", "model", "fields", "time ms", "evals");
  auto row = [&](const std::string& label, const Scene& s, const char* mesh, int k, std::vector<ModeFamily> fam) {
    const PrismModel m = build_model(s, Discretization::parse(mesh));
    const auto [t, ev] = time_modes(m, k, fam, 3);
    fmt::print("  {:<28} {:>7} {:>10.2f} {:>8}\n", label, m.m, t * 1e3, ev);
  };
  for (const char* mesh : {"1x1", "2x2", "4x4", "8x8", "16x16"})
    row(std::string("beam (plane) ") + mesh, beam, mesh, 8, {ModeFamily::BendingXZ});
  for (const char* mesh : {"1x1", "2x2", "4x4", "6x6"}) row(std::string("beam (spatial) ") + mesh, spatial, mesh, 8, {});
  for (const char* mesh : {"4", "7", "10", "20", "40"}) row(std::string("plate ") + mesh + " strips", plate, mesh, 8, {});

  fmt::print("\ncost vs number of modes:\n");
  fmt::print("  {:<28} {:>7} {:>10} {:>8}\n", "model", "modes", "time ms", "evals");
  const PrismModel beam22 = build_model(beam, Discretization::parse("2x2"));
  for (int k : {6, 12, 25, 50, 100}) {
    const auto [t, ev] = time_modes(beam22, k, {ModeFamily::BendingXZ}, 3);
    fmt::print("  {:<28} {:>7} {:>10.2f} {:>8}\n", "beam 2x2", k, t * 1e3, ev);
  }
  const PrismModel plate10 = build_model(plate, Discretization::parse("10"));
  for (int k : {8, 16, 32, 64, 100}) {
    const auto [t, ev] = time_modes(plate10, k, {}, 3);
    fmt::print("  {:<28} {:>7} {:>10.2f} {:>8}\n", "plate 10 strips", k, t * 1e3, ev);
  }
  return 0;
}
