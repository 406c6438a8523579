#pragma once
// Internal to dtfm: a beam's tapered pieces as staircases of uniform prisms. dtfm's prisms are
// uniform (their distributed transfer functions have constant coefficients), so a tapered piece is
// cut into N equal steps, each the uniform piece with the section at its middle; the frequencies
// and deflections tend to the tapered beam's at second order in 1 / N (tests/solvers/test_tapered.cpp
// observes it), and the default path refines N to the tolerance with that order's estimate.
#include <string>

#include "modalbench/scene.hpp"
#include "modalbench/solver.hpp"

namespace modalbench::dtfm::detail {

/// The scene with each tapered piece cut into `steps` uniform pieces (the others as they are).
Scene staircase(const Scene& scene, int steps);

/// The steps per tapered piece of a tapered beam's mesh, N (each step's section is one prism, as on
/// stepped beams: the mesh's one count is its length, h = 1 / N); throws InputError naming --mesh
/// otherwise.
int staircase_steps(const Discretization& mesh);

/// A tapered beam's mesh of N steps per tapered piece: N.
Discretization staircase_mesh(int steps);

/// The least and most steps per tapered piece dtfm takes (beyond 512 its second-discretization
/// check of the count failed on the tapered tower's first mode, 1024 steps).
inline constexpr int kMinSteps = 2, kMaxSteps = 512;

}  // namespace modalbench::dtfm::detail
