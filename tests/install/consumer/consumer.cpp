// Solves a clamped-clamped Timoshenko beam with rfem through the installed package and checks
// its first frequency against the exact back-end (Table 1 of the prism paper: 6211.15 rad/s).
#include <cmath>
#include <cstdio>

#include "modalbench/registry.hpp"
#include "modalbench/rfem/rfem.hpp"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const modalbench::Scene scene = modalbench::load_scene(argv[1]);
  const modalbench::Registry reg = modalbench::make_default_registry();
  const auto rf = reg.get("rfem").solve(scene, modalbench::Discretization::parse("256"), {});
  const auto ex = reg.get("exact").solve(scene, {}, {});
  if (!rf.ok() || !ex.ok() || rf.frequencies_rad_s.empty()) return 1;
  const double err = std::abs(rf.frequencies_rad_s[0] / ex.frequencies_rad_s[0] - 1);
  std::printf("rfem 256: %.6f rad/s, exact %.6f rad/s, relative error %.2e\n", rf.frequencies_rad_s[0],
              ex.frequencies_rad_s[0], err);
  return err < 1e-3 ? 0 : 1;
}
