#pragma once
// The `exact` back-end: continuum references solved without discretization error.
// Beams and bars (beams.hpp): Timoshenko / Euler-Bernoulli bending in one or two planes,
// axial and torsional bars, any end springs. Plates (plates.hpp): Kirchhoff Navier and Levy,
// Mindlin simply supported. Each is selected from the scene's kind, theory and supports.
//
// Usage:
//   ExactSolver exact;
//   Result r = exact.solve(load_scene("scenes/paper_fixed_beam.toml"), {}, Options{});

#include <memory>
#include <string>

#include "modalbench/exact/beams.hpp"
#include "modalbench/exact/plates.hpp"
#include "modalbench/solver.hpp"

namespace modalbench::exact {

class ExactSolver final : public Solver {
 public:
  std::string name() const override { return "exact"; }
  std::string description() const override {
    return "exact continuum references: Timoshenko/Euler-Bernoulli beams, bars, Navier/Levy/Mindlin plates";
  }
  Capability supports(const Scene& scene) const override;
  /// No mesh: the empty one everywhere, neither coarser nor finer.
  MeshFamily meshes(const Scene&, const Options&) const override { return MeshFamily::single({}); }
  /// navier_static_terms (2000), navier_frf_terms (300): truncation of the Navier double series.
  std::vector<OptionSpec> option_specs() const override;
  /// Time and memory of a request, from the number of modes, loads and FRF samples (see the .cpp).
  ResourceEstimate estimate(const Scene& scene, const Discretization& mesh, const Options& options) const override;

 protected:
  /// The scene's exact references as kernels (exact_solver.cpp); a mesh is invalid input.
  std::unique_ptr<Kernels> build(const Scene& scene, const Discretization& mesh, const Options& options,
                                 Result& result) const override;
};

}  // namespace modalbench::exact
