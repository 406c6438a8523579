#pragma once
// The `rfem` back-end: the rigid finite element method (lumped model).
//
// The body is cut into rigid elements (RFEs) joined by massless spring-damping elements
// (SDEs). With q the RFE displacements and rotations (only the DOFs the scene needs: beam
// bending w, theta_y; planar u, w, theta_y; spatial all 6; plate w, theta_x, theta_y):
//   free vibration  K phi = w^2 M phi,   statics  K q = f,
//   FRF  (K (1 + i eta) + i w C - w^2 M) q = f,
// with K = sum over SDEs of G' Rb k Rb' G, G = [-D_a, D_b], D(r) = [[I, -[r]x], [0, I]]
// (core's rigid_kinematics.hpp), M = diag(m, m, m, Jx, Jy, Jz) per RFE. Rigid components are
// exact: held DOFs are eliminated, rigid links between RFEs are constraints (DESIGN.md 1.1).
// Sources: DESIGN.md 1.1; seeds/rfem-plate-appendix.txt Tables A1.1, A2.1 with ERRATA.md
// (rfem-plate section). Builders and their modelling choices: builders.hpp; solves: analysis.hpp.
//
// Meshes: beam "N" (segments of the primary division, N >= 1); plate "NXxNY" (fragments along
// x and y, each >= 2). Probes interpolate the motion of the RFE centres around P (linear along a
// beam, bilinear on a plate: the model's consistent displacement field); point loads act through
// the transpose; the point action's singular response (slope jump, r^2 ln r) is added in closed
// form (system.hpp, point_correction).
// Options ([backend.rfem] in the scene, --option on the command line): see option_specs().
//
// Usage:
//   modalbench::rfem::RfemSolver rfem;
//   Scene scene = load_scene("scenes/paper_fixed_beam.toml");
//   Result r = rfem.solve(scene, Discretization::parse("64"), Options{});
//   // r.frequencies_rad_s, r.mode_families, r.deflections, r.frf, r.summary (method, dofs,
//   // max_residual, timings_s: assembly, factorization, eigen, statics, frf)

#include <string>
#include <vector>

#include "modalbench/rfem/analysis.hpp"
#include "modalbench/rfem/model.hpp"
#include "modalbench/rfem/system.hpp"
#include "modalbench/solver.hpp"

namespace modalbench::rfem {

/// The first `count` modes (columns of Z over z, M-orthonormal; eigenvalues lambda) at the scene's
/// shape points, normalized and with their modal quantities (result.hpp, ModeShapes), and a beam's
/// moments where the shape request asks for them.
ModeShapes sample_shapes(const Scene& scene, const Model& model, const System& sys, const Eigen::MatrixXd& Z,
                         const Eigen::VectorXd& lambda, long count);

class RfemSolver final : public Solver {
 public:
  std::string name() const override { return "rfem"; }
  std::string description() const override {
    return "rigid finite element method (lumped): rigid elements joined by spring-damping elements";
  }
  Capability supports(const Scene& scene) const override;
  Discretization default_mesh(const Scene& scene) const override;
  std::vector<Discretization> mesh_ladder(const Scene& scene) const override;
  /// Beams 10,000 and 100,000 segments; plates 100 fragments along the longer side.
  std::vector<Discretization> stress_meshes(const Scene& scene) const override;

  /// eigen, dense_limit, tolerance, sturm_check, seed, frf_modes, beam_rigid_shear,
  /// plate_rigid_shear, plate_bending_correction (defaults and ranges in rfem.cpp).
  std::vector<OptionSpec> option_specs() const override;
  /// The coarser mesh of the self-check (halved counts, order 2).
  std::optional<CoarserMesh> coarser_mesh(const Scene& scene, const Discretization& mesh,
                                          const Options& options) const override;
  /// The default mesh refined towards the tolerance (counts times factor).
  std::optional<Discretization> finer_mesh(const Scene& scene, const Discretization& mesh, double factor) const override;
  int refinement_steps(const Scene& scene) const override;
  /// Peak memory and time of a request (fitted to measurements on a 2-core machine; see the .cpp).
  ResourceEstimate estimate(const Scene& scene, const Discretization& mesh, const Options& options) const override;

  /// The model for a scene and mesh (`options`: the builder options; null = defaults). Throws
  /// InputError (key "--mesh") for a bad mesh.
  static Model build(const Scene& scene, const Discretization& mesh, const ResolvedOptions* options = nullptr);

 protected:
  void do_solve(const Scene& scene, const Discretization& mesh, const Options& options,
                Result& result) const override;

 private:
  static void solve_statics(const Scene& s, const Model& model, const System& sys, Result& r);
  /// Fills r.frf; returns the method used. `modes`: modal superposition over them (null: direct).
  static std::string solve_frf(const Scene& s, const Model& model, const System& sys, const Modes* modes,
                               int frf_modes, const ResolvedOptions& options, Result& r);
};

}  // namespace modalbench::rfem
