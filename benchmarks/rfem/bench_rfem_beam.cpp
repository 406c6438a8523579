// Planar beam with 10,000 segments (30,000 body DOFs): first 10 modes (target <= 0.2 s) and the
// static solve (target <= 20 ms).
//
// Sample runs:
//   build-rfem/benchmarks/rfem/bench_rfem_beam        # the paper's fixed beam (Timoshenko), planar
//   build-rfem/benchmarks/rfem/bench_rfem_beam 9      # 9 timed repeats (default 7)
//
// 1. Modes: build + assemble + 10 lowest modes (median of repeats after a warm-up), in a child.
// 2. Statics: the solve alone (mechanism check, LDL' factorization, solve) on the assembled
//    system, and build + assemble + solve end to end.
// 3. The same for a slender Euler-Bernoulli beam (exact rigid-shear basis).
#include <fmt/format.h>

#include <cstdlib>

#include "bench_common.hpp"
#include "modalbench/exact/exact.hpp"
#include "modalbench/rfem/analysis.hpp"
#include "modalbench/rfem/builders.hpp"
#include "modalbench/rfem/system.hpp"

using namespace modalbench;
using namespace modalbench::rfem;

namespace {

void run(const Scene& s, const char* label, int repeats) {
  const int n = 10000;
  rfem_bench::in_child([&] {
    Modes md;
    long dofs = 0;
    const auto t = rfem_bench::time_it(
        [&] {
          const Model m = build_beam(s, n);
          const System sys = assemble(m);
          ModeOptions mo;
          mo.modes = 10;
          md = solve_modes(m, sys, mo);
          dofs = sys.n();
        },
        repeats);
    const auto ex = exact::beam_bending_frequencies(exact::bending_xz(s), {s.x0.translational, s.x0.rotational},
                                                    {s.xL.translational, s.xL.rotational}, 10);
    fmt::print("\n{}: {} segments, {} coordinates, 10 lowest modes\n", label, n, dofs);
    fmt::print("  build + assemble + modes: wall median {:.4f} s (min {:.4f} s), CPU median {:.4f} s; peak RSS {:.0f} MB\n",
               t.median_s, t.min_s, t.cpu_median_s, rfem_bench::peak_mb());
    fmt::print("  last run: factorizations {:.4f} s, eigen {:.4f} s; {}\n  rad/s:", md.factor_seconds, md.eigen_seconds,
               md.method);
    for (long i = 0; i < md.lambda.size(); ++i) fmt::print(" {:.2f}[{}]", std::sqrt(md.lambda[i]), to_string(md.family[static_cast<std::size_t>(i)]));
    fmt::print("\n  bending modes vs exact:");
    int b = 0;
    for (long i = 0; i < md.lambda.size(); ++i)
      if (md.family[static_cast<std::size_t>(i)] == ModeFamily::BendingXZ)
        fmt::print(" {:+.1e}", std::sqrt(md.lambda[i]) / ex.omega_rad_s[static_cast<std::size_t>(b++)] - 1);
    fmt::print("\n");
  });
  rfem_bench::in_child([&] {
    const Model m = build_beam(s, n);
    const System sys = assemble(m);
    Eigen::VectorXd f = Eigen::VectorXd::Zero(sys.n());
    for (const auto& p : s.loads) {
      Vector6d a;
      a << p.Fx, p.Fy, p.Fz, p.Mx, p.My, p.Mz;
      f += point_load(m, sys, {p.x, 0, 0}, a);
    }
    StaticSolution st;
    const auto t = rfem_bench::time_it([&] { st = solve_static(m, sys, f); }, repeats);
    const auto te = rfem_bench::time_it(
        [&] {
          const Model m2 = build_beam(s, n);
          const System s2 = assemble(m2);
          Eigen::VectorXd f2 = Eigen::VectorXd::Zero(s2.n());
          for (const auto& p : s.loads) {
            Vector6d a;
            a << p.Fx, p.Fy, p.Fz, p.Mx, p.My, p.Mz;
            f2 += point_load(m2, s2, {p.x, 0, 0}, a);
          }
          st = solve_static(m2, s2, f2);
        },
        repeats);
    fmt::print("  static solve (mechanism check + LDL' + solve): wall median {:.4f} s (min {:.4f} s); residual {:.1e}\n",
               t.median_s, t.min_s, st.residual);
    fmt::print("  build + assemble + static solve: wall median {:.4f} s; peak RSS {:.0f} MB\n", te.median_s, rfem_bench::peak_mb());
  });
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 7;
  fmt::print("median of {} timed runs after a warm-up\n", repeats);
  Scene paper = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_fixed_beam.toml");
  paper.physics = Physics::Planar;
  run(paper, "paper fixed beam, planar Timoshenko", repeats);
  Scene slender = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/lasecka_elastic_beam.toml");
  slender.physics = Physics::Planar;
  slender.x0.axial = kRigid;
  run(slender, "elastically supported beam (Lasecka), planar Euler-Bernoulli", repeats);
  return 0;
}
