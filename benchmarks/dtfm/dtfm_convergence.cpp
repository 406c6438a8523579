// Convergence of the dtfm prism model: beam sections 1x1 ... 8x8 against the 3D values
// (docs/sources.md, P8) and plates 4 ... 40 strips against the exact plate, for each layer model.
#include <fmt/format.h>

#include <string>
#include <vector>

#include "modalbench/dtfm/dtfm.hpp"
#include "modalbench/exact/exact.hpp"

using namespace modalbench;
using namespace modalbench::dtfm;

int main(int argc, char** argv) {
  const std::string which = argc > 1 ? argv[1] : "all";
  if (which == "all" || which == "beam") {
    const Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_fixed_beam.toml");
    const double ref3d[] = {6079.75, 13380.23, 21900.37, 30888.10, 40216.80, 43225.29};
    for (LayerModel lm : {LayerModel::Consistent, LayerModel::Staggered, LayerModel::Paper}) {
      fmt::print("beam, layers = {}\n", to_string(lm));
      for (const char* mesh : {"1x1", "1x2", "1x4", "1x8", "1x16"}) {
        ModelOptions o;
        o.layers = lm;
        const PrismModel mdl = build_model(s, Discretization::parse(mesh), o);
        LineAnalysis la(mdl);
        const auto ml = la.modes(6, {ModeFamily::BendingXZ});
        fmt::print("  {:>5}", mesh);
        for (std::size_t i = 0; i < ml.omega_rad_s.size(); ++i)
          fmt::print(" {:10.2f} ({:+6.2f}%)", ml.omega_rad_s[i], 100 * (ml.omega_rad_s[i] / ref3d[i] - 1));
        fmt::print("  evals {}\n", ml.evaluations);
      }
    }
  }
  if (which == "all" || which == "plate") {
    Scene base = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_ss_plate.toml");
    const double a = base.geometry.length, b = base.geometry.width;
    const double D = base.plate_D(), rho_h = base.material.rho * base.geometry.height;
    struct Case {
      const char* name;
      const char* y0;
      const char* yB;
    };
    for (const Case& c : {Case{"SS-SS-SS-SS", "pinned", "pinned"}, Case{"SS-C-SS-C", "clamped", "clamped"},
                          Case{"SS-F-SS-F", "free", "free"}, Case{"SS-C-SS-F", "clamped", "free"}}) {
      Scene s = base;
      s.y0 = Support::named(c.y0);
      s.yB = Support::named(c.yB);
      const auto ex = exact::levy_frequencies(a, b, D, s.material.nu, rho_h, {s.y0.translational, s.y0.rotational},
                                              {s.yB.translational, s.yB.rotational}, 8);
      fmt::print("plate {} exact:", c.name);
      for (double w : ex.omega_rad_s) fmt::print(" {:9.1f}", w);
      fmt::print("\n");
      for (LayerModel lm : {LayerModel::Consistent, LayerModel::Paper}) {
        for (const char* mesh : {"4", "7", "10", "20", "40"}) {
          ModelOptions o;
          o.layers = lm;
          const PrismModel mdl = build_model(s, Discretization::parse(mesh), o);
          LineAnalysis la(mdl);
          const auto ml = la.modes(8);
          fmt::print("  {:>10} {:>3}", to_string(lm), mesh);
          double worst = 0;
          for (std::size_t i = 0; i < ml.omega_rad_s.size(); ++i) {
            const double e = 100 * (ml.omega_rad_s[i] / ex.omega_rad_s[i] - 1);
            worst = std::max(worst, std::abs(e));
            fmt::print(" {:9.1f}", ml.omega_rad_s[i]);
          }
          fmt::print("  max|err| {:6.2f}%  evals {}\n", worst, ml.evaluations);
        }
      }
    }
  }
  return 0;
}
