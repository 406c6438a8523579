#pragma once
// difference_eq: closed-form solutions of the regular discrete Euler-Bernoulli beam.
//
// What it solves. A beam cut into R identical Hermite-cubic elements (stiffness (1) of
// M. Lasecka's paper, consistent or lumped mass) on end springs kappa0, chi0, kappaL, chiL,
// each in [0, inf]. Node equilibrium is a pair of constant-coefficient difference equations
// (paper, (3)-(5)), so the discrete model is solved in closed form instead of by assembling
// and factorising its matrices:
//  * statics (statics.hpp): clamped-clamped response (discrete Green's function, piecewise
//    cubic in r; or the paper's eigenfunction expansion (7)) + the cubic settlement field of
//    the four end displacements, closed by a 4x4 spring system solved as exact ratios of
//    multilinear polynomials in the springs (the paper's (20)-(22) generalised);
//  * free vibration (vibration.hpp): a 4x4 characteristic determinant in the
//    difference-equation roots mu, nu (size independent of R, scaled hyperbolic functions),
//    an exact Wittrick-Williams count, mode-by-mode bracketing and Brent polishing;
//  * the paper's own case reproduced formula by formula (lasecka.hpp).
// For nodal loads the nodal values of the Hermite model are those of the continuous
// Euler-Bernoulli beam; frequencies converge like R^-4 (consistent) or R^-2 (lumped).
//
// Assumptions: bending in x-z only (axial, torsion and x-y bending are not modelled);
// Euler-Bernoulli (a Timoshenko scene is solved without shear and rotary inertia, and the
// result says so); loads on nodes; no FRF.
//
// Source: M. Lasecka, seed lasecka-difference-equation-beam-pl.txt, Eqs. (1)-(24); errata in
// lasecka.hpp and docs/sources.md (L1, L2).
//
// Usage:
//   modalbench::difference_eq::DifferenceEqSolver s;
//   Scene scene = load_scene("scenes/lasecka_elastic_beam.toml");
//   Result r = s.solve(scene, Discretization::parse("64"), Options{});   // --mesh R
//   // library level:
//   RegularBeam b{EI, rhoA, L, R, k0, r0, kL, rL};
//   StaticSolution st = solve_static(b, {{R / 2, -1e3, 0.0}});
//   Spectrum sp = natural_frequencies(b, MassModel::Consistent, 100);

#include <memory>
#include <string>
#include <vector>

#include "modalbench/difference_eq/lasecka.hpp"
#include "modalbench/difference_eq/regular_beam.hpp"
#include "modalbench/difference_eq/statics.hpp"
#include "modalbench/difference_eq/vibration.hpp"
#include "modalbench/solver.hpp"

namespace modalbench::difference_eq {

/// The regular discrete beam of a scene (bending in x-z, Euler-Bernoulli) with R elements.
RegularBeam beam_of(const Scene& scene, long R);

/// The `difference_eq` back-end: mesh "R" (elements, one integer >= 1).
class DifferenceEqSolver final : public Solver {
 public:
  struct Config {
    StaticMethod static_method = StaticMethod::PiecewiseCubic;  ///< the eigenfunction path is O(R^2)
    long residual_check_max_R = 20000;  ///< mode-shape eigen-residuals up to this R (O(R) per mode)
  };
  DifferenceEqSolver() = default;
  explicit DifferenceEqSolver(Config c) : config_(c) {}

  std::string name() const override { return "difference_eq"; }
  std::string description() const override {
    return "closed-form regular discrete Euler-Bernoulli beam (Hermite elements, difference equations)";
  }
  Capability supports(const Scene& scene) const override;
  /// Default: the smallest multiple of every load's and probe's denominator (in units of L) with
  /// R >= max(32, 8 modes) (64 when the positions are not commensurate); ladder R = base ... 4096;
  /// theory mesh on Euler-Bernoulli beams in bending only (elsewhere model error); stress meshes
  /// the ladder's top and the largest grid multiple up to 10^6; coarser R/2 where loads stay on
  /// nodes (order 4 with consistent mass, 2 lumped); finer R times the factor.
  MeshFamily meshes(const Scene& scene, const Options& options) const override;
  /// static_method, residual_check_max_R (defaults from the Config the solver was built with).
  std::vector<OptionSpec> option_specs() const override;
  /// Peak memory and time of a request (fitted to measurements on a 2-core machine; see the .cpp).
  ResourceEstimate estimate(const Scene& scene, const Discretization& mesh, const Options& options) const override;

 protected:
  /// The regular chain with its loads on nodes, and its kernels (difference_eq_kernels.cpp).
  std::unique_ptr<Kernels> build(const Scene& scene, const Discretization& mesh, const Options& options,
                                 Result& result) const override;

 public:
  /// Mode shapes at the scene's sample points for the reported frequencies (the first `rigid`
  /// of them rigid-body modes), normalized in the model's own mass matrix with the scene's point
  /// masses (shapes.cpp).
  static ModeShapes shapes(const Scene& s, const RegularBeam& beam, MassModel mass, const std::vector<double>& omega,
                           int rigid);

 private:

  Config config_;
};

}  // namespace modalbench::difference_eq
