#pragma once
// The scenes and runs shared by the stiff and extreme cases (test_extremes_modes.cpp,
// test_extremes_statics.cpp).
#include <cmath>
#include <string>

#include "modalbench/registry.hpp"
#include "solve_options.hpp"

namespace modalbench::extremes {

inline const Registry& registry() {
  static const Registry r = make_default_registry();
  return r;
}

inline Result run(const std::string& backend, const Scene& s, const std::string& mesh = "") {
  const Solver& solver = registry().get(backend);
  Options o = testing::own_error_study();
  return solver.solve(s, mesh.empty() ? testing::default_mesh(solver, s) : Discretization::parse(mesh), o);
}

inline Support springs(double t, double r) {
  Support s;
  s.kind = "springs";
  s.translational = t;
  s.rotational = r;
  return s;
}

/// Euler-Bernoulli steel beam (issue 13, reproducer 3).
inline Scene eb_beam(double L, double b, double h, double E, double rho, Support x0, Support xL) {
  Scene s;
  s.name = "extreme-beam";
  s.kind = SceneKind::Beam;
  s.theory = Theory::EulerBernoulli;
  s.geometry = {L, b, h};
  s.material.E = E;
  s.material.nu = 0.3;
  s.material.G = E / 2.6;
  s.material.rho = rho;
  s.material.kappa = 5.0 / 6.0;
  s.x0 = x0;
  s.xL = xL;
  validate(s);
  return s;
}

inline double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

inline Scene scene_file(const std::string& file) { return load_scene(std::string(MODALBENCH_SCENES_DIR) + "/" + file); }

/// NAFEMS FV12 / FV16 geometry: a steel Kirchhoff plate 10 x 10 x 0.05 m with its edge supports.
inline Scene nafems_plate(const std::string& name, Support x0, Support xL, Support y0, Support yB, int modes) {
  Scene s;
  s.name = name;
  s.kind = SceneKind::Plate;
  s.theory = Theory::Kirchhoff;
  s.geometry = {10.0, 10.0, 0.05};
  s.material.E = 200e9;
  s.material.nu = 0.3;
  s.material.G = 200e9 / 2.6;
  s.material.rho = 8000;
  s.material.kappa = 5.0 / 6.0;
  s.x0 = x0;
  s.xL = xL;
  s.y0 = y0;
  s.yB = yB;
  s.request.modes = modes;
  validate(s);
  return s;
}

}  // namespace modalbench::extremes
