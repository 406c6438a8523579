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
// x and y, each >= 2). Probes give the rigid-body motion u_P = D(r) q of the RFE that contains
// P (the mean over the RFEs sharing a cell boundary); point loads act on that RFE as D(r)' F.
//
// Usage:
//   modalbench::rfem::RfemSolver rfem;
//   Scene scene = load_scene("scenes/paper_fixed_beam.toml");
//   Result r = rfem.solve(scene, Discretization::parse("64"), Options{});
//   // r.frequencies_rad_s, r.mode_families, r.deflections, r.frf, r.summary (method, dofs,
//   // max_residual, timings_s: assembly, factorization, eigen, statics, frf)

#include <string>
#include <vector>

#include "modalbench/rfem/model.hpp"
#include "modalbench/solver.hpp"

namespace modalbench::rfem {

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

  /// The model for a scene and mesh. Throws InputError (key "--mesh") for a bad mesh.
  static Model build(const Scene& scene, const Discretization& mesh);

 protected:
  void do_solve(const Scene& scene, const Discretization& mesh, const Options& options,
                Result& result) const override;
};

}  // namespace modalbench::rfem
