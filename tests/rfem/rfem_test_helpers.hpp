#pragma once
// Scenes built in code and small helpers shared by the rfem tests.

#include <cmath>
#include <string>
#include <vector>

#include "modalbench/exact/exact.hpp"
#include "modalbench/rfem/analysis.hpp"
#include "modalbench/rfem/builders.hpp"
#include "modalbench/rfem/system.hpp"
#include "modalbench/scene.hpp"

namespace rfem_test {

using namespace modalbench;

inline constexpr double inf = std::numeric_limits<double>::infinity();

inline Support springs(double translational, double rotational, double axial = 0, double torsional = 0) {
  Support s;
  s.kind = "springs";
  s.translational = translational;
  s.rotational = rotational;
  s.axial = axial;
  s.torsional = torsional;
  return s;
}

/// A steel beam L x b x h along x.
inline Scene beam_scene(Physics physics, Theory theory, const Support& x0, const Support& xL, double L = 1.0,
                        double b = 0.05, double h = 0.1, double kappa = 5.0 / 6.0) {
  Scene s;
  s.name = "test-beam";
  s.source = "test";
  s.kind = SceneKind::Beam;
  s.physics = physics;
  s.theory = theory;
  s.geometry = {L, b, h};
  s.material.E = 2.1e11;
  s.material.nu = 0.3;
  s.material.G = s.material.E / (2 * (1 + s.material.nu));
  s.material.rho = 7850;
  s.material.kappa = kappa;
  s.x0 = x0;
  s.xL = xL;
  validate(s);
  return s;
}

/// The plate of the prism paper's Table 2 (1 x 0.6 x 0.03 m, nu = 0.3, rho = 8000; P2).
inline Scene plate_scene(Theory theory, const Support& x0, const Support& xL, const Support& y0, const Support& yB) {
  Scene s;
  s.name = "test-plate";
  s.source = "test";
  s.kind = SceneKind::Plate;
  s.physics = Physics::Bending;
  s.theory = theory;
  s.geometry = {1.0, 0.6, 0.03};
  s.material.E = 2.0e11;
  s.material.nu = 0.3;
  s.material.G = s.material.E / (2 * (1 + s.material.nu));
  s.material.rho = 8000;
  s.material.kappa = 5.0 / 6.0;
  s.x0 = x0;
  s.xL = xL;
  s.y0 = y0;
  s.yB = yB;
  validate(s);
  return s;
}

inline exact::EndSprings end(const Support& s) { return {s.translational, s.rotational}; }

/// The lowest `k` natural frequencies (rad/s) of a model, rigid ones as 0.
inline std::vector<double> frequencies(const rfem::Model& m, int k, rfem::EigenMethod method = rfem::EigenMethod::Auto,
                                       rfem::Modes* keep = nullptr) {
  const rfem::System sys = rfem::assemble(m);
  rfem::ModeOptions o;
  o.modes = k;
  o.method = method;
  rfem::Modes md = rfem::solve_modes(m, sys, o);
  std::vector<double> w;
  for (long i = 0; i < md.lambda.size(); ++i) w.push_back(std::sqrt(std::max(0.0, md.lambda[i])));
  if (keep) *keep = std::move(md);
  return w;
}

inline double rel(double a, double b) { return std::abs(a / b - 1.0); }

/// Least-squares slope of -log(error) against log(count): the observed order of a ladder whose
/// error is not monotone on every rung (points between nodes sit at varying fractions of a cell).
inline double fitted_order(const std::vector<double>& counts, const std::vector<double>& errors) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(counts.size());
  for (std::size_t i = 0; i < counts.size(); ++i) {
    const double x = std::log(counts[i]), y = -std::log(std::abs(errors[i]));
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/// Observed order from errors on meshes h and h/2.
inline double order(double e_coarse, double e_fine) { return std::log2(std::abs(e_coarse) / std::abs(e_fine)); }

}  // namespace rfem_test
