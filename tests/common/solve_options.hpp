#pragma once
// Solver options for tests, named for what the test does with the result.

#include "modalbench/solver.hpp"

namespace modalbench::testing {

/// A test that measures a mesh's error itself, against an independent reference (an exact
/// solution, an observed order): the solver's own coarse-mesh estimate is not made, as in the
/// comparison's timed runs, so a deliberately coarse mesh is judged by the test, not by the tolerance.
inline Options own_error_study() {
  Options o;
  o.estimate_error = false;
  return o;
}

/// As the command line solves a scene without --mesh: the default mesh, refined until the
/// solver's own error estimate meets the scene's tolerance.
inline Options as_without_mesh() {
  Options o;
  o.refine_to_tolerance = true;
  return o;
}

/// The back-end's default mesh for a scene (MeshFamily::default_mesh), for a test that solves on
/// it without the default path's refinement, or checks it.
inline Discretization default_mesh(const Solver& solver, const Scene& scene) {
  return solver.meshes(scene, Options{}).default_mesh;
}

}  // namespace modalbench::testing
