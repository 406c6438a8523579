#pragma once
// The `dtfm` back-end: hybrid discrete-continuous prisms solved by distributed transfer
// functions (Hein, "A discrete-continuous method of mechanical system modelling"; seed
// with the corrections P1-P8 of docs/sources.md).
//
// Model (prism_model.hpp). The body is cut in two directions only: a beam's section into
// NY x NZ rectangular prisms, a plate into N strips across its width; each prism is continuous
// along x and carries the fields the scene needs (plane beam: u, w, theta_y; plate: w, theta_x,
// theta_y; spatial beam: all six, torsion with the prism's Saint-Venant constant). Prisms are
// joined by distributed spring layers (Eq. (25)) whose deformation is the jump of the rigid-body
// motion of their faces (rigid_kinematics.hpp); supports along a plate's long edges act on the
// edge strips; ends are clamped / pinned / free / springs per DOF (beams: through a rigid end
// plate). The result is Eq. (32), A02 q_tt + A20 q'' + A10 q' + A00 q = f, with A02, A20, A00
// symmetric and A10 skew, derived from the energy rather than transcribed (P6).
//
// Solution (analysis.hpp). Laplace/harmonic form y' = A(omega^2) y in the Hamiltonian state
// y = [q; f] (equivalent to Eq. (42), eta = [q; q'], but symmetric). The paper's closed form
// e^{F l} over the whole span (Eqs. (44)-(56)) overflows or loses every digit at high
// frequency or for stiff layers; instead the span is cut into segments with well-conditioned
// exp(A h), each turned into a segment dynamic stiffness, assembled into K(omega^2):
//   static deflection: K(0) d = f;  FRF (Eq. (51)'s transfer function between two points):
//   K(omega^2) d = f, damped with E -> E (1 + i eta) by a complex solve;  natural frequencies:
//   the Wittrick-Williams count (negative pivots of LDL^T; no clamped-segment term because the
//   segments are short) with bisection and a Brent polish on det K. Symmetry classes of the
//   section (reflections) are solved separately and give each mode its family.
//
// Assumptions: linear elasticity; prisms rigid in their section; beams without Poisson
// coupling (uniaxial prisms); plates with the plate's constitutive law (Kirchhoff or Mindlin).
//
// Usage:
//   DtfmSolver s;
//   Result r = s.solve(load_scene("scenes/paper_fixed_beam.toml"), Discretization::parse("2x2"), {});
//   // r.frequencies_rad_s, r.mode_families, r.deflections, r.frf, r.summary; with
//   // [request] shapes: r.mode_shapes (mass-normalized, LineAnalysis::mode_shapes)

#include <memory>
#include <string>
#include <vector>

#include "modalbench/dtfm/analysis.hpp"
#include "modalbench/dtfm/prism_model.hpp"
#include "modalbench/solver.hpp"

namespace modalbench::dtfm {

class DtfmSolver final : public Solver {
 public:
  explicit DtfmSolver(ModelOptions options = {}) : options_(options) {}
  std::string name() const override { return "dtfm"; }
  std::string description() const override {
    return "discrete-continuous prisms joined by spring layers, solved by distributed transfer functions "
           "(segment dynamic stiffness, Wittrick-Williams count)";
  }
  Capability supports(const Scene& scene) const override;
  /// Beam: one prism by default (the scene's beam theory itself, no discretization error); a
  /// section cut NY x NZ (ladder 1x1 ... 8x8, spatial up to 6x6) tends to 3D elasticity. Plate: N
  /// strips, about 6 per half-wave across the width, the points on strip lines; ladder 4 ... 40;
  /// coarser: halved counts (order 2; extrapolated at 4 where both strip ends are held); finer:
  /// strips times the factor (meshes.cpp).
  MeshFamily meshes(const Scene& scene, const Options& options) const override;
  /// layers, kirchhoff_penalty (defaults from the ModelOptions the solver was built with), rel_tol,
  /// im_h, re_h, family_threshold (SolveControls).
  std::vector<OptionSpec> option_specs() const override;
  /// Peak memory and time of a request (fitted to measurements on a 2-core machine; see the .cpp).
  ResourceEstimate estimate(const Scene& scene, const Discretization& mesh, const Options& options) const override;

 protected:
  /// The prism model and its line analysis, with its kernels (dtfm_kernels.cpp).
  std::unique_ptr<Kernels> build(const Scene& scene, const Discretization& mesh, const Options& options,
                                 Result& result) const override;

 private:
  ModelOptions options_;
};

}  // namespace modalbench::dtfm
