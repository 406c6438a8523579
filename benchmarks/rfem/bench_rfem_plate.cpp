// Plate of 100 x 60 rigid elements (mesh 99x59 fragments: 6000 RFEs, 18,000 body DOFs; or the mesh
// given after the repeats, e.g. `5 168 120`), first 8
// modes. Target (issue 3): <= 0.5 s and <= 500 MB peak on this 2-core machine.
//
// Sample runs:
//   build-rfem/benchmarks/rfem/bench_rfem_plate            # Table 2 plate, Mindlin and Kirchhoff
//   build-rfem/benchmarks/rfem/bench_rfem_plate 5          # 5 timed repeats (default 5)
//   build/benchmarks/rfem/bench_rfem_plate 3 168 120       # 3 repeats on 168 x 120 fragments
//
// 1. For each theory and with / without the Sturm count, one child process: a warm-up, then
//    build + assemble + the 8 lowest modes, timed (median of repeats); phases of the last run.
// 2. The same through RfemSolver::solve (the `modalbench solve` path, modes only).
#include <fmt/format.h>

#include <cstdlib>

#include "bench_common.hpp"
#include "modalbench/exact/exact.hpp"
#include "modalbench/rfem/analysis.hpp"
#include "modalbench/rfem/builders.hpp"
#include "modalbench/rfem/rfem.hpp"
#include "modalbench/rfem/system.hpp"

using namespace modalbench;
using namespace modalbench::rfem;

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 5;
  const int nx = argc > 3 ? std::atoi(argv[2]) : 99, ny = argc > 3 ? std::atoi(argv[3]) : 59;
  const Scene base = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_ss_plate.toml");
  fmt::print("plate {} x {} x {} m, mesh {}x{} fragments = {} x {} RFEs, 8 lowest modes, median of {} after a warm-up\n",
             base.geometry.length, base.geometry.width, base.geometry.height, nx, ny, nx + 1, ny + 1, repeats);
  for (Theory theory : {Theory::Mindlin, Theory::Kirchhoff})
    for (bool sturm : {true, false})
      rfem_bench::in_child([&] {
        Scene s = base;
        s.theory = theory;
        PlateOptions po;
        po.nx = nx;
        po.ny = ny;
        Modes md;
        long n = 0, m = 0, body = 0;
        double t_build = 0, t_asm = 0;
        const auto t = rfem_bench::time_it(
            [&] {
              const auto t0 = std::chrono::steady_clock::now();
              const Model model = build_plate(s, po);
              const auto t1 = std::chrono::steady_clock::now();
              const System sys = assemble(model);
              const auto t2 = std::chrono::steady_clock::now();
              ModeOptions mo;
              mo.modes = 8;
              mo.sturm_check = sturm;
              md = solve_modes(model, sys, mo);
              n = sys.n();
              m = sys.m();
              body = model.body_dofs();
              t_build = std::chrono::duration<double>(t1 - t0).count();
              t_asm = std::chrono::duration<double>(t2 - t1).count();
            },
            repeats);
        const auto& mat = s.material;
        const auto ex = theory == Theory::Kirchhoff
                            ? exact::navier_frequencies(1.0, 0.6, s.plate_D(), mat.rho * 0.03, 8)
                            : exact::mindlin_ss_frequencies(1.0, 0.6, 0.03, mat.E, mat.nu, mat.G, mat.kappa, mat.rho, 8);
        fmt::print("\n{} plate, Sturm check {}: {} body DOFs, {} coordinates, {} multipliers\n", to_string(theory),
                   sturm ? "on" : "off", body, n, m);
        fmt::print("  wall median {:.3f} s (min {:.3f} s), CPU median {:.3f} s; peak RSS {:.0f} MB\n", t.median_s, t.min_s,
                   t.cpu_median_s, rfem_bench::peak_mb());
        fmt::print("  last run: build {:.3f} s, assembly {:.3f} s, factorizations {:.3f} s, eigen (Lanczos + checks) {:.3f} s\n",
                   t_build, t_asm, md.factor_seconds, md.eigen_seconds);
        fmt::print("  {}\n  rad/s:", md.method);
        for (long i = 0; i < md.lambda.size(); ++i) fmt::print(" {:.2f}", std::sqrt(md.lambda[i]));
        fmt::print("\n  error vs exact:");
        for (long i = 0; i < md.lambda.size(); ++i) fmt::print(" {:+.2e}", std::sqrt(md.lambda[i]) / ex[static_cast<std::size_t>(i)] - 1);
        fmt::print("\n");
      });
  rfem_bench::in_child([&] {
    Scene s = base;
    s.request.probes.clear();
    s.request.frf.reset();
    RfemSolver solver;
    Result r;
    const auto t = rfem_bench::time_it([&] { r = solver.solve(s, Discretization{{99, 59}}, Options{}); }, repeats);
    fmt::print("\nRfemSolver::solve (Kirchhoff, modes only, Sturm on): wall median {:.3f} s, status {}, peak RSS {:.0f} MB\n",
               t.median_s, to_string(r.summary.status), rfem_bench::peak_mb());
    const auto& ph = r.summary.timings_s;
    fmt::print("  build {:.3f} s, modes {:.3f} s, statics {:.3f} s, frf {:.3f} s\n", ph.build, ph.modes, ph.statics,
               ph.frf);
  });
  return 0;
}
