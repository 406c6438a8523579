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
// exact: held DOFs are eliminated, rigid links between RFEs are constraints.
// Sources: the rigid-element plate appendix's Tables A1.1, A2.1 with the corrections R1-R3 of
// docs/sources.md. Builders and their modelling choices: builders.hpp; solves: analysis.hpp.
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

#include <memory>
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
  /// Beams: N segments, about 32 per half-wave of the highest requested mode, features on element
  /// centres or cell boundaries; ladder N0 x 1..32; stress meshes 10,000 and 100,000 segments.
  /// Plates: NX x NY, about 10 fragments per half-wave, multiples of 8; ladder up to 8 x 10
  /// fragments; stress mesh 100 along the longer side. Coarser: halved counts (order 2, next 3);
  /// finer: x factor, or a plate's graded steps x 1.5, x 4/3 (6 refinement steps) where no point
  /// feature sits in its cells (meshes.cpp).
  MeshFamily meshes(const Scene& scene, const Options& options) const override;

  /// eigen, dense_limit, tolerance, sturm_check, seed, frf_modes, beam_rigid_shear,
  /// plate_rigid_shear, plate_bending_correction (defaults and ranges in rfem.cpp).
  std::vector<OptionSpec> option_specs() const override;
  /// Peak memory and time of a request (fitted to measurements on a 2-core machine; see the .cpp).
  ResourceEstimate estimate(const Scene& scene, const Discretization& mesh, const Options& options) const override;

  /// The model for a scene and mesh (`options`: the builder options; null = defaults). Throws
  /// InputError (key "--mesh") for a bad mesh.
  static Model build_model(const Scene& scene, const Discretization& mesh, const ResolvedOptions* options = nullptr);

 protected:
  /// The model assembled, with its kernels (rfem_kernels.cpp).
  std::unique_ptr<Kernels> build(const Scene& scene, const Discretization& mesh, const Options& options,
                                 Result& result) const override;
};

}  // namespace modalbench::rfem
