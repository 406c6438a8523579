// difference_eq benchmarks: the closed forms at R up to 1e6 against the assembled banded FE solve.
//
// Sample runs:
//   build/benchmarks/difference_eq/bench_difference_eq            # full tables (R = 1e6)
//   build/benchmarks/difference_eq/bench_difference_eq --quick    # smaller R, for a smoke run
//
// 1. Static deflection at every node, R = 1e6 (the paper's elastic beam: K0 = 40, Kf = 5, KR = 10):
//    the piecewise-cubic closed form vs the assembled banded LDL^T in double (same model, same
//    run) and in binary128 (the accuracy reference), with loads at 3 nodes and at every node.
// 2. The lowest 100 natural frequencies at R = 1e6 (consistent and lumped mass), and the cost of
//    the same at other R (it should not grow with R).
// Times are medians of repeats (std::chrono::steady_clock); the first (cold) static run is
// listed separately because it includes the page faults of the freshly allocated output.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <vector>

#include "modalbench/difference_eq/assembled.hpp"
#include "modalbench/difference_eq/statics.hpp"
#include "modalbench/difference_eq/vibration.hpp"

using namespace modalbench::difference_eq;
__extension__ typedef __float128 quad;

namespace {

double seconds(const std::function<void()>& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double median_time(const std::function<void()>& f, int repeats) {
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) t.push_back(seconds(f));
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

// The paper's Fig. 5 beam (scenes/lasecka_elastic_beam.toml): EI = 1.3333e7 N m^2, L = 4 m,
// K0 = 40, Kf = 5, KR = 10; rhoA = 7850 * 0.02.
RegularBeam lasecka_beam(long R) {
  const double EI = 2.0e11 * 0.1 * 0.2 * 0.2 * 0.2 / 12.0, L = 4.0;
  return RegularBeam{EI, 7850.0 * 0.02, L, R, 40.0 * EI / (L * L * L), 5.0 * EI / L, 10.0 * EI / (L * L * L), 0.0};
}

template <class V>
double rel_diff(const std::vector<double>& x, const std::vector<V>& ref) {
  double e = 0, s = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    e = std::max(e, std::abs(x[i] - static_cast<double>(ref[i])));
    s = std::max(s, std::abs(static_cast<double>(ref[i])));
  }
  return e / s;
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const long R = quick ? 100'000 : 1'000'000;
  const int reps = quick ? 3 : 7;

  std::printf("difference_eq benchmarks (median of %d repeats; binary128 = IEEE quad, software)\n\n", reps);
  std::printf("1. Static deflection and slope at every node (errors: max |w - w_ref| / max |w_ref|, w_ref from the\n"
              "   binary128 banded solve with 2 steps of iterative refinement; 'banded q' times the unrefined\n"
              "   binary128 solve; 'cold' includes first-touch page faults of the output arrays)\n");
  std::printf("%-9s %-14s %11s %11s %10s | %12s %10s | %10s | %9s\n", "R", "beam/loads", "closed cold",
              "closed warm", "error", "banded dbl", "error", "banded q", "residual");
  const std::vector<long> Rstat = quick ? std::vector<long>{10'000, 100'000} : std::vector<long>{10'000, 100'000, 1'000'000};
  for (long Rk : Rstat)
    for (int variant = 0; variant < 3; ++variant) {
    // The paper's elastic beam with 3 loads and with a load at every node; and the same beam
    // clamped-pinned (rigid supports), 3 loads.
    RegularBeam bk = lasecka_beam(Rk);
    if (variant == 2) {
      bk.k0 = bk.r0 = bk.kL = kInf;
      bk.rL = 0;
    }
    const char* name = variant == 0 ? "springs/3" : (variant == 1 ? "springs/all" : "cl-pinned/3");
    std::vector<NodalLoad> loads;
    if (variant == 1) {
      for (long r = 0; r <= Rk; ++r) loads.push_back({r, -10.0 * (1.0 + 0.5 * std::sin(1e-4 * static_cast<double>(r))), 0.0});
    } else {
      loads = {{Rk / 4, -1e4, 0.0}, {Rk / 2, -2e4, 0.0}, {3 * Rk / 4, 5e3, 0.0}};
    }
    {
      std::vector<quad> wq, sq;
      const double tq = seconds([&] { assembled::static_solve<quad>(bk, loads, wq, sq); });
      assembled::static_solve<quad>(bk, loads, wq, sq, 2);  // the reference: 2 refinement steps
      StaticSolution st;
      const double cold = seconds([&] { solve_static(bk, loads, StaticMethod::PiecewiseCubic, st); });
      const double warm = median_time([&] { solve_static(bk, loads, StaticMethod::PiecewiseCubic, st); }, reps);
      std::vector<double> wd, sd;
      char banded[64], berr[32];
      try {
        const double tb = median_time([&] { assembled::static_solve<double>(bk, loads, wd, sd); }, 3);
        std::snprintf(banded, sizeof banded, "%12.4f", tb);
        std::snprintf(berr, sizeof berr, "%10.2e", rel_diff(wd, wq));
      } catch (const std::exception&) {
        std::snprintf(banded, sizeof banded, "%12s", "zero pivot");
        std::snprintf(berr, sizeof berr, "%10s", "-");
      }
      std::printf("%-9ld %-14s %11.4f %11.4f %10.2e | %s %s | %10.3f | %9.2e\n", Rk, name, cold, warm, rel_diff(st.w, wq),
                  banded, berr, tq, static_residual(bk, loads, st));
    }
  }
  std::printf("  times in s; memory at R = 1e6: closed form 16 MB (w, slope); banded solve 96 MB (band, rhs, solution)\n");

  std::printf("\n2. Lowest 100 natural frequencies\n");
  std::printf("%-12s %-11s %12s %10s %10s %16s %16s\n", "R", "mass", "time [ms]", "counts", "det evals", "omega_1 [rad/s]",
              "omega_100 [rad/s]");
  const std::vector<long> Rs = quick ? std::vector<long>{100, 10'000, 100'000} : std::vector<long>{200, 10'000, 1'000'000, 10'000'000};
  for (long Rk : Rs)
    for (MassModel m : {MassModel::Consistent, MassModel::Lumped}) {
      const RegularBeam bk = lasecka_beam(Rk);
      Spectrum sp;
      const double t = median_time([&] { sp = natural_frequencies(bk, m, 100); }, reps);
      std::printf("%-12ld %-11s %12.3f %10ld %10ld %16.10g %16.10g\n", Rk, to_string(m).c_str(), 1e3 * t,
                  sp.count_evaluations, sp.determinant_evaluations, sp.omega_rad_s.front(), sp.omega_rad_s.back());
    }
  // Every frequency at R = 1e6 confirmed by the count just below and above it.
  {
    const RegularBeam b6 = lasecka_beam(R);
    const Spectrum sp = natural_frequencies(b6, MassModel::Consistent, 100);
    long bad = 0;
    for (std::size_t j = 0; j < sp.omega_rad_s.size(); ++j) {
      const double l = sp.omega_rad_s[j] * sp.omega_rad_s[j];
      bad += count_below(b6, MassModel::Consistent, l * (1 - 1e-10)) != static_cast<long>(j) ||
             count_below(b6, MassModel::Consistent, l * (1 + 1e-10)) != static_cast<long>(j + 1);
    }
    std::printf("  R = %ld: %zu frequencies, %ld not confirmed by the count at (1 -+ 1e-10) omega^2\n", R,
                sp.omega_rad_s.size(), bad);
  }
  return 0;
}
