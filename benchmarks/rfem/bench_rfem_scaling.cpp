// Cost of the lowest modes against the number of DOFs (issue 3: about linear), four or more
// sizes each: Mindlin and Kirchhoff plates (8 modes), planar beams (10 modes).
//
// Sample runs:
//   build-rfem/benchmarks/rfem/bench_rfem_scaling      # median of 3 after a warm-up per size
//
// Each size runs in its own child process (peak memory per size).
#include <fmt/format.h>

#include <cstdlib>

#include "bench_common.hpp"
#include "modalbench/rfem/analysis.hpp"
#include "modalbench/rfem/builders.hpp"
#include "modalbench/rfem/system.hpp"

using namespace modalbench;
using namespace modalbench::rfem;

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 3;
  fmt::print("lowest modes: build + assemble + solve, median of {} after a warm-up\n", repeats);
  fmt::print("{:<28} {:>9} {:>10} {:>10} {:>12} {:>9}\n", "model", "DOFs", "wall s", "CPU s", "us per DOF", "peak MB");
  const Scene plate = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_ss_plate.toml");
  for (Theory th : {Theory::Mindlin, Theory::Kirchhoff})
    for (auto [nx, ny] : {std::pair{24, 14}, {49, 29}, {99, 59}, {141, 84}, {199, 119}}) {
      rfem_bench::in_child([&, nx = nx, ny = ny] {
        Scene s = plate;
        s.theory = th;
        PlateOptions po;
        po.nx = nx;
        po.ny = ny;
        long dofs = 0;
        const auto t = rfem_bench::time_it(
            [&] {
              const Model m = build_plate(s, po);
              const System sys = assemble(m);
              ModeOptions mo;
              mo.modes = 8;
              mo.method = EigenMethod::ShiftInvert;
              solve_modes(m, sys, mo);
              dofs = m.body_dofs();
            },
            repeats);
        fmt::print("{:<28} {:>9} {:>10.4f} {:>10.4f} {:>12.2f} {:>9.0f}\n",
                   fmt::format("plate {} {}x{}", to_string(th), nx + 1, ny + 1), dofs, t.median_s, t.cpu_median_s,
                   1e6 * t.median_s / static_cast<double>(dofs), rfem_bench::peak_mb());
      });
    }
  Scene beam = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_fixed_beam.toml");
  beam.physics = Physics::Planar;
  for (int n : {1250, 2500, 5000, 10000, 20000, 40000})
    rfem_bench::in_child([&] {
      long dofs = 0;
      const auto t = rfem_bench::time_it(
          [&] {
            const Model m = build_beam(beam, n);
            const System sys = assemble(m);
            ModeOptions mo;
            mo.modes = 10;
            mo.method = EigenMethod::ShiftInvert;
            solve_modes(m, sys, mo);
            dofs = m.body_dofs();
          },
          repeats);
      fmt::print("{:<28} {:>9} {:>10.4f} {:>10.4f} {:>12.2f} {:>9.0f}\n", fmt::format("beam planar n = {}", n), dofs,
                 t.median_s, t.cpu_median_s, 1e6 * t.median_s / static_cast<double>(dofs), rfem_bench::peak_mb());
    });
  return 0;
}
