// Fast FRF sweep (issue 14, target: the 80 x 48 paper plate, 400 samples 0..12000 rad/s, loss
// factor 0.01: <= 0.5 s for the FRF, within 0.05 dB of the direct solve at every sample).
//
//   build/benchmarks/rfem/bench_rfem_frf        # 3 timed repeats after a warm-up
//   build/benchmarks/rfem/bench_rfem_frf 5
//
// For each mesh, in a child process each (peak memory its own): RfemSolver::solve of the FRF
// alone (no modes, no statics, no error estimate), frf_method = direct and = projected; the FRF
// phase's wall time (median; the 152 x 122 direct sweep once, it takes about two minutes), the
// projection's largest error bound and directly solved samples, and the largest deviation
// between the two sweeps in dB and relative.
//
// Measured on this 2-core machine (2026-11-25):
//   80x48    direct: FRF 14.39 s; projected: FRF 0.176 s, bound <= 9.5e-5, 0 samples direct;
//            deviation 9.2e-9 dB (1.6e-9 relative)
//   152x122  direct: FRF 114.8 s; projected: FRF 1.27 s, bound <= 9.6e-5, 0 samples direct;
//            deviation 3.2e-7 dB (5.4e-8 relative)
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <map>

#include "bench_common.hpp"
#include "modalbench/rfem/rfem.hpp"

using namespace modalbench;
using namespace modalbench::rfem;

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 3;
  Scene base = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_ss_plate.toml");
  base.request.modes = 0;
  base.request.probes.clear();
  base.loads.clear();
  base.material.loss_factor = 0.01;
  fmt::print("paper plate {} x {} m, FRF {} samples {}..{} rad/s, loss factor {}; median of {} after a warm-up\n",
             base.geometry.length, base.geometry.width, base.request.frf->points, base.request.frf->omega_min,
             base.request.frf->omega_max, base.material.loss_factor, repeats);
  for (const auto& [nx, ny] : {std::pair{80, 48}, std::pair{152, 122}}) {
    std::map<std::string, Result> runs;
    for (const char* how : {"direct", "projected"}) {
      // Each in a child for its own peak memory; the result comes back through a pipe as text.
      int fd[2];
      if (pipe(fd) != 0) return 1;
      rfem_bench::in_child([&] {
        close(fd[0]);
        Options o;
        o.estimate_error = false;
        o.backend = {{"frf_method", how}};
        RfemSolver solver;
        Result r;
        // The direct sweep of the large mesh takes minutes: one run, no warm-up.
        rfem_bench::Timing t;
        if (std::string(how) == "direct" && nx > 100) {
          const auto t0 = std::chrono::steady_clock::now();
          r = solver.solve(base, Discretization{{nx, ny}}, o);
          t.median_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        } else {
          t = rfem_bench::time_it([&] { r = solver.solve(base, Discretization{{nx, ny}}, o); }, repeats);
        }
        std::string line = fmt::format("{}x{} {:>9}: FRF {:.3f} s (solve wall median {:.3f} s), status {}, peak RSS {:.0f} MB",
                                       nx, ny, how, r.summary.timings_s.frf, t.median_s, to_string(r.summary.status),
                                       rfem_bench::peak_mb());
        if (std::string(how) == "projected")
          line += fmt::format(", largest error bound {:.2g}, {} sample(s) solved directly",
                              r.summary.diagnostic("frf_error_bound"), r.summary.diagnostic("frf_direct_samples"));
        line += "\n";
        for (const auto& s : r.frf) line += fmt::format("{:.17g} {:.17g} {:.17g}\n", s.omega_rad_s, s.receptance.real(), s.receptance.imag());
        FILE* out = fdopen(fd[1], "w");
        std::fputs(line.c_str(), out);
        std::fclose(out);
      });
      close(fd[1]);
      FILE* in = fdopen(fd[0], "r");
      char buf[4096];
      if (std::fgets(buf, sizeof buf, in)) fmt::print("{}", buf);
      Result& r = runs[how];
      double w = 0, re = 0, im = 0;
      while (std::fscanf(in, "%lf %lf %lf", &w, &re, &im) == 3) r.frf.push_back({w, {re, im}});
      std::fclose(in);
    }
    const auto& d = runs["direct"].frf;
    const auto& p = runs["projected"].frf;
    double db = 0, rel = 0;
    std::size_t paired = 0;
    for (std::size_t i = 0, j = 0; i < d.size() && j < p.size();) {
      if (d[i].omega_rad_s < p[j].omega_rad_s) { ++i; continue; }
      if (p[j].omega_rad_s < d[i].omega_rad_s) { ++j; continue; }
      db = std::max(db, std::abs(20 * std::log10(std::abs(p[j].receptance) / std::abs(d[i].receptance))));
      rel = std::max(rel, std::abs(p[j].receptance - d[i].receptance) / std::abs(d[i].receptance));
      ++paired, ++i, ++j;
    }
    fmt::print("{}x{}: {} samples paired; largest deviation {:.2e} dB, {:.2e} relative\n\n", nx, ny, paired, db, rel);
  }
  return 0;
}
