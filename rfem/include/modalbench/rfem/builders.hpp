#pragma once
// Builders: a Scene (or a box spec) -> an rfem Model.
//
// Beam (n segments of length d = L / n, the primary division). One SDE at each segment's middle
// x = (j + 1/2) d with k = [EA, kGA, kGA, GJ, EI_y, EI_z] / d. The secondary
// division cuts the beam at the SDEs: n + 1 RFEs centred at the nodes x = j d, interior ones of
// length d, the two end ones of length d / 2 (mass rho A l; Jx = rho Ip l; Jy = m l^2/12 + rho Iy l
// and Jz alike, the rho I l terms only for Timoshenko scenes). End supports are SDEs to ground at
// the end points with the scene's springs; +inf holds the component exactly (eliminated).
// Euler-Bernoulli scenes: the shear springs are rigid, exactly (no penalty), in one of two ways:
//  - Multipliers (default): the rigid shear components are linear constraints between
//    neighbouring RFEs, solved with Lagrange multipliers (system.hpp). The unknowns stay the
//    RFE displacements and rotations, so the matrices keep the conditioning of a second-order
//    operator (~ n^2).
//  - JointCoordinates: the generalized coordinates are the transverse displacements of the end
//    points and of the n joints (a Hencky chain): every shear deformation vanishes identically.
//    Exact too, but the stiffness becomes a fourth difference (condition ~ n^4): the lowest
//    eigenvalues lose all accuracy near n = 10^4 in double precision. Kept as an independent
//    second method for tests.
//
// Plate (nx x ny fragments of the primary division, Delta_l = a / nx, Delta_b = b / ny; the plate
// appendix with R1-R3 of docs/sources.md): RFEs at the fragment corners, types 1-4 with full,
// half and quarter masses (Table A2.1); each fragment's stiffness goes into four SDEs along its
// sides with the factor 1/2 of Table A1.1, an interior side collecting both fragments' halves.
// Shear springs use the scene's multiplicative kappa (Table A1.1 divides by kappa = 1.2 = 1/(5/6)).
// Kirchhoff scenes: the transverse shear springs are rigid, exactly, in one of two ways:
//  - JointCoordinates (default for plates): the coordinates are values c_pq on the grid of the
//    plate's edges and the cells' side midpoints, the tensor product of the beam's joint
//    coordinates: each RFE's w and slopes are the mean value and mean slopes of the bilinear
//    field through its four c, so every side midpoint (where the SDE sits) moves by the same c
//    from both RFEs. One combination ((-1)^(p+q) inside, 0 on the edges) moves no RFE; c at the
//    first inner corner is fixed at 0 to remove it. About a third of the unknowns of the
//    multiplier form and no saddle point (a positive definite pencil for CHOLMOD); the price is
//    a fourth-difference stiffness (condition ~ n^4 against n^2): a rounding floor of order
//    eps max(nx, ny)^4 on the frequencies (measured against the multiplier form: 1.2e-10 at
//    40x24 and 99x59), far below the discretization error of such meshes (~1e-4 at 100).
//  - Multipliers: the rigid shear components are constraints with Lagrange multipliers, as for
//    the beam. Kept as the second exact method for tests.
// Mindlin scenes: shear springs kappa G h, and rotary inertia m h^2 / 12 added.
// Edges: free, simply supported, clamped or elastic; the support of an edge RFE is an SDE to
// ground at its centre (on the edge) with the per-length springs times its share of the edge.
// `bending_correction` (default on) adds, per fragment, the Poisson coupling and the Mindlin
// twist form that two-point springs cannot represent (see plate_fragment_correction); without
// it the model is Table A1.1 as printed and converges to a plate without Poisson coupling.
//
// Box: nx x ny x nz rigid cubes of edge `edge`, face neighbours joined by an SDE at the shared
// face centre (k = [E d, kappa G d, kappa G d, G J/d, E d^3/12, E d^3/12], J of a square section).
// A held face x = 0 joins each face cube to ground at its face centre through the half cube
// (twice the link stiffness), so the face, not the cube centre, is where the body is held.

#include <Eigen/Dense>

#include "modalbench/frame.hpp"
#include "modalbench/rfem/model.hpp"
#include "modalbench/scene.hpp"

namespace modalbench::rfem {

enum class RigidShear { Multipliers, JointCoordinates };
struct BeamOptions {
  RigidShear rigid_shear = RigidShear::Multipliers;  ///< Euler-Bernoulli scenes only
};
/// Beam scene -> model with `segments` >= 1 primary segments. Throws std::invalid_argument.
Model build_beam(const Scene& scene, int segments, const BeamOptions& options = {});

struct PlateOptions {
  int nx = 10, ny = 6;             ///< fragments along x (length a) and y (width b), each >= 1
  bool bending_correction = true;  ///< per-fragment Poisson coupling and Mindlin twist form
  RigidShear rigid_shear = RigidShear::JointCoordinates;  ///< Kirchhoff scenes only (corner values)
};
/// Plate scene -> model. Throws std::invalid_argument.
Model build_plate(const Scene& scene, const PlateOptions& options);

/// The per-fragment correction (24 x 24 over the full 6-DOF vectors of the corners BL, BR, TL,
/// TR): D A [nu (gx gy' + gy gx') - (1 - nu)/2 (ga + gb)(ga + gb)'], with the fragment-averaged
/// curvatures kx = -d(theta_y)/dx (gx), ky = d(theta_x)/dy (gy) and twists d(theta_x)/dx (ga),
/// d(theta_y)/dy (gb). Added to the side springs it makes the fragment energy
/// D A / 2 [kx^2 + ky^2 + 2 nu kx ky + (1 - nu)/2 kxy^2] (+ non-negative hourglass terms).
Eigen::MatrixXd plate_fragment_correction(double D, double nu, double dl, double db);

/// Frame scene -> model: each member cut into frame_member_segments(n) segments (n on the shortest
/// member, the others in proportion to their length, rounded), built as a beam (rigid elements at
/// its nodes, half-length ends, SDEs at the segments' middles in the member's axes); at each frame
/// node the members' end elements are joined by rigid links to one of them (the anchor: a member
/// joined rigidly, where there is one), a hinged end's link leaving its bending rotations free; the
/// node's support acts on the anchor, its point mass is added to it. Throws std::invalid_argument
/// for a member inclined to the global axes (frame_refusal).
Model build_frame(const Scene& scene, int n);
/// Why rfem cannot build this frame ("" if it can): a member not along a global axis (its rigid
/// elements' inertia tensor would not be diagonal in global axes).
std::string frame_refusal(const Scene& scene);
/// The segments of member `member` on mesh n: n times its length over the shortest member's, rounded
/// (at least n).
int frame_member_segments(const Frame& frame, std::size_t member, int n);
/// Where build_frame puts a frame's rigid elements on mesh n: per member its first element (the
/// one at its first node; element first + j sits at s = j / segments) and its segments; per node
/// its anchor element (the one its support and mass act on, which its loads and probes use) and
/// whether that is a hinged member end (every member hinged there).
struct FrameLayout {
  std::vector<int> first, segments, anchor;
  std::vector<bool> anchor_released;
};
FrameLayout frame_layout(const Frame& frame, int n);

struct BoxSpec {
  int nx = 1, ny = 1, nz = 1;  ///< cubes along x, y, z
  double edge = 0.1;           ///< m
  Material material;           ///< E, G, rho, kappa used
  bool clamp_x0 = false;       ///< hold the face x = 0 (through the half cubes; else free)
};
Model build_box(const BoxSpec& spec);

}  // namespace modalbench::rfem
