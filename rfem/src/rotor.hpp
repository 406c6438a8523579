#pragma once
// Private to rfem: a spinning shaft (scene [rotor]) on the lateral model (v, w, theta_y, theta_z per
// rigid element). Per RFE with mass m, diametral inertia J_t (Jy = Jz) and polar J_p (its Jx: the
// section's rho I_p l under Timoshenko theory, the discs'):
//   stationary frame: M q'' + Omega G q' + K q = 0, G[theta_y, theta_z] = J_p = -G[theta_z, theta_y]
//     (the angular momentum J_p Omega n of the tilted axis n = e_x + theta_z e_y - theta_y e_z);
//   rotating frame (the shaft's own axes): M q'' + Omega C_r q' + (K - Omega^2 K_c) q = 0 with
//     C_r[v, w] = -2 m = -C_r[w, v], C_r[theta_y, theta_z] = -(2 J_t - J_p) = -C_r[theta_z, theta_y],
//     K_c = m on v, w and J_t - J_p on theta_y, theta_z (Coriolis and spin softening; the fixed
//     frame's J_t phi'' - i J_p Omega phi' + k phi = 0 with phi = chi e^{i Omega t}).
// ../shared/ROTORS.md 4 states the same per RFE; the signs here are re-derived for this code's axes.
#include <Eigen/SparseLU>
#include <complex>
#include <string>
#include <vector>

#include "modalbench/result.hpp"
#include "modalbench/rfem/model.hpp"
#include "modalbench/rfem/system.hpp"
#include "modalbench/scene.hpp"

namespace modalbench::rfem::detail {

/// The spin's matrices over z (q = T z): G (stationary), C_r and K_c (rotating).
struct RotorMatrices {
  SpMat G, Cr, Kc;
};
RotorMatrices rotor_matrices(const Model& model, const System& sys);

/// Why rfem gives no Campbell diagram for this rotor scene ("" where it does), from the scene alone.
std::string rotor_scene_refusal(const Scene& s);
/// The same for the model built (what the scene's test cannot see is checked again).
std::string campbell_refusal(const Scene& s, const Model& model, const System& sys);

/// The whirl roots at one spin: every eigenvalue pair +-lambda of the quadratic eigenproblem once,
/// ascending by |Im lambda|, the lowest `k`; each with its orbit sense and backward error.
struct WhirlRoots {
  std::vector<double> omega, growth, backward_error;
  std::vector<Whirl> whirl;
  /// Per root, per rigid element: v and w of its orbit (where the translations vanish, the tilt
  /// axis theta_z, -theta_y), unnormalized.
  std::vector<std::vector<std::complex<double>>> orbit_v, orbit_w;
  /// The companion-form vectors [x; lambda x] of the roots, summed (real and imaginary parts): the
  /// next spin's Arnoldi starts from it (a warm start along a sweep); restarts taken.
  Eigen::VectorXd start;
  long iterations = 0;
};
/// M z'' + C z' + K z = 0 by shift-invert Arnoldi on its first companion form (Spectra), one sparse
/// LU of K per call; the senses from the orbits of v and w at the rigid elements (a repeated root's
/// basis turned to diagonalize the orbit-sense form).
/// `lu` factors K (the stationary frame's serves every spin); `start` (2 n entries, or empty) is
/// the Arnoldi start vector (a previous spin's WhirlRoots::start).
WhirlRoots whirl_roots(const Model& model, const System& sys, const SpMat& K, const Eigen::SparseLU<SpMat>& lu,
                       const SpMat& C, int k, const Eigen::VectorXd& start = {});

/// The positive Omega with K x = Omega^2 B x (K positive definite, B symmetric, perhaps indefinite),
/// ascending: every one up to `top` and the next above, where there is one.
std::vector<double> synchronous_speeds(const SpMat& K, const SpMat& B, double top);

/// The Campbell diagram and critical speeds of scene.rotor on `model` (campbell_refusal empty).
Campbell rotor_campbell(const Scene& s, const Model& model, const System& sys, Summary& sum);

}  // namespace modalbench::rfem::detail
