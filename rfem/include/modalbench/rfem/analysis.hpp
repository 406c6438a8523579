#pragma once
// Solves on an assembled rfem System: natural modes, static deflection, receptance FRFs.
//
// Modes: K z = w^2 M z subject to G z = 0. Free rigid-body modes are found structurally
// (free_rigid_modes) and reported as exact zeros; the flexible ones come from
//  - a dense generalized symmetric eigensolver on an orthonormal basis of
//    {z : G z = 0, R' M z = 0} when the problem is small, or
//  - Spectra's shift-invert Lanczos (SymGEigsShiftSolver, ShiftInvert mode) with the shift
//    sigma < 0 (K - sigma M is then positive definite even when K is singular: a shift at zero is
//    a known way to lose or invent modes), K - sigma M factored by CHOLMOD (no constraints) or the
//    saddle-point LDL' (constraints), the rigid modes deflated by M-orthogonal projection.
//    A Sturm count (Sylvester inertia of K - mu M, mu just above the last mode) proves that
//    no mode below it was missed; a shortfall triggers a larger Lanczos run.
// Every mode is checked by its residual ||K z - w^2 M z|| / ||K z|| (the constraint forces
// G' lambda projected out) and by its componentwise backward error
// ||K z - w^2 M z|| / || (|K| + w^2 |M|) |z| ||: the residual of a low mode of a fine, stiff
// model is bounded below by rounding times the condition (eps lambda_max / lambda), the
// backward error is not, so it is the one that decides trust. Modes are labelled by the DOF family that carries its kinetic energy
// (>= 95 %), `unknown` otherwise; inside a cluster of equal frequencies the basis is rotated
// to separate the families first.
// Statics: K z = f by sparse LDL' (saddle point with constraints). A free rigid-body motion
// is a mechanism: reported with the motions and the coordinates it moves.
// FRF: receptance g' (K (1 + i eta) + i w C - w^2 M)^{-1} f by a sparse LU per frequency
// (direct), or by modal superposition over a stated number of modes.

#include <complex>
#include <limits>
#include <string>
#include <vector>

#include "modalbench/rfem/system.hpp"

namespace modalbench::rfem {

enum class EigenMethod { Auto, Dense, ShiftInvert };

struct ModeOptions {
  int modes = 0;                 ///< lowest modes wanted, rigid ones included
  EigenMethod method = EigenMethod::Auto;
  long dense_limit = 40;         ///< Auto: dense up to this many coordinates (see solve_modes)
  double tolerance = 1e-10;      ///< Lanczos relative tolerance
  bool sturm_check = true;       ///< count the eigenvalues below the last mode (sparse path)
  double backward_error_warning = 1e-10;  ///< above this, pairs are refined (Lanczos) or re-solved (dense fall-back)
  unsigned seed = 20240917u;     ///< Lanczos start vector
};

struct Modes {
  Eigen::VectorXd lambda;          ///< w^2, ascending; rigid modes exactly 0
  Eigen::MatrixXd Z;               ///< M-orthonormal shapes over z
  std::vector<ModeFamily> family;
  std::vector<double> residuals;   ///< relative eigen-residual per mode
  std::vector<double> backward_errors;  ///< componentwise backward error per mode
  int rigid = 0;
  std::string method;              ///< what was actually used, with the convergence record
  long iterations = 0;             ///< Lanczos restarts (0 for dense)
  /// Lanczos: the shift sigma, rad^2/s^2 (its relative tolerance is on 1/(lambda - sigma), so a
  /// pair's eigenvalue is converged to tolerance (lambda - sigma) / lambda); 0 on the dense path.
  double shift = 0;
  long operations = 0;             ///< operator applications (solves)
  long sturm_count = -1;           ///< eigenvalues below the check point; -1 if not checked
  double max_residual = 0;
  double max_backward_error = 0;
  /// First-order bound on each mode's relative eigenvalue error from the solve (rounding):
  /// (backward error + eps) x componentwise condition; 0 for rigid modes, near-rigid ones excluded
  /// (near_rigid_bound).
  std::vector<double> forward_bounds;
  double max_forward_bound = 0;
  /// Near-rigid pairs (Rayleigh-Ritz in the rigid subspace): largest Kato-Temple bound on their
  /// relative eigenvalue error (0 when there are none).
  double near_rigid_bound = 0;
  bool converged = true;
  std::vector<std::string> warnings;
  std::vector<std::string> fallbacks;  ///< each fall-back taken, with why
  double factor_seconds = 0, eigen_seconds = 0;
};

/// Throws std::runtime_error on a failed factorization of a matrix that must be definite. With
/// EigenMethod::Auto, Lanczos pairs whose backward error misses the check are solved again by the
/// dense path (refined) where that is affordable (up to kDenseFallbackLimit coordinates), and the
/// better set is kept; a fall-back taken is recorded.
Modes solve_modes(const Model& model, const System& sys, const ModeOptions& options);
/// Coordinates up to which the dense path is affordable as a fall-back (measured: 0.3 s at 510).
inline constexpr long kDenseFallbackLimit = 600;

struct StaticSolution {
  bool ok = false;
  bool mechanism = false;
  std::string message;   ///< reason when !ok (mechanism: motions and free coordinates named)
  Eigen::VectorXd z;
  double residual = 0;   ///< ||K z - f|| / ||f|| (constraint forces projected out)
  int near_mechanism = 0;  ///< rigid motions held only by soft springs, split off in the solve
  double factor_seconds = 0, solve_seconds = 0;
};
StaticSolution solve_static(const Model& model, const System& sys, const Eigen::VectorXd& f);

/// What one SDE to ground exerts on the model in a static solution: force (N) and moment (N*m),
/// global axes, at the SDE's point.
struct SupportForce {
  int sde = 0;
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
};
struct SupportForces {
  std::vector<SupportForce> forces;  ///< one per SDE of model.supports, in that order
  /// || B'(f - K q) - (links' mu + holds' lambda) || / || B' f ||: how far the multipliers found
  /// balance the unreduced model (rounding; larger where the rigid components are redundant).
  double residual = 0;
  /// The rounding floor of that balance, on the same scale: eps times || |B'| (|K| |q| + |f|) ||, the
  /// size of the terms whose difference B'(f - K q) is (huge where stiff springs carry small motions:
  /// a slender Timoshenko beam's shear springs). A residual within a small multiple of it is rounding.
  double rounding = 0;
};
/// The support reactions of the static solution z under the point actions (`actions`, as given to
/// point_loads): finite components are -k times the motion of their point; held ones are the multipliers
/// of the equilibrium of the unreduced model over the builder's coordinates (least squares over
/// the rigid rows: links between elements and holds to ground), so K's reduction is not undone.
SupportForces support_forces(const Model& model, const System& sys, const Eigen::VectorXd& z,
                             const std::vector<PointAction>& actions);
/// The same for loads given over the body DOFs q (fq, as detail::point_loads_q gives them).
SupportForces support_forces_q(const Model& model, const System& sys, const Eigen::VectorXd& z, const Eigen::VectorXd& fq);

struct FrfResult {
  std::vector<double> omega;                      ///< samples kept
  std::vector<std::complex<double>> receptance;   ///< g' x / unit force
  long skipped = 0;                               ///< singular samples (on a natural frequency, w = 0 of a free body)
  std::string method;
  double factor_seconds = 0;
  /// frf_projected: the largest bound on |H - H_direct| / |H| over the samples it kept (NaN: none
  /// made), and how many samples it solved directly because their bound missed the target.
  double max_error_bound = std::numeric_limits<double>::quiet_NaN();
  long direct_samples = 0;
  std::vector<double> error_bounds;  ///< frf_projected: per sample kept, its bound (NaN: solved directly)
};
/// Direct: one sparse LU of the (saddle-point) dynamic stiffness per frequency.
FrfResult frf_direct(const Model& model, const System& sys, const Eigen::VectorXd& f, const Eigen::VectorXd& g,
                     const std::vector<double>& omegas);
/// A sweep of many frequencies at about the cost of one eigen solve (issue 14): the Galerkin
/// projection of K (1 + i eta) - w^2 M onto every mode below 2 w_max (their number from a Sturm
/// count) and four load-dependent Ritz vectors (K - s M)^-1 (M (K - s M)^-1)^j f, s < 0, which
/// carry the quasi-static response of the modes left out. Each sample's error is bounded from its
/// residual r = D x - f: the projection is Galerkin, so r has no component on the modes kept, and
/// |g' D^-1 r| <= ||g_out||_M^-1 ||r||_M^-1 / (sigma - w^2), where g_out is g less its part on the
/// modes kept and sigma = (2 w_max)^2 bounds the first mode left out from below (Sturm). The
/// residual norm is a small quadratic form per sample (r = (1 + i eta) S y - f_perp, with S the Ritz
/// residuals), so the bound costs O(p^2) per sample. A sample whose bound exceeds `target` times
/// |H| is solved directly. Viscous dampers (C != 0) are outside it: false, and `out` untouched,
/// also when more than `max_modes` modes lie below 2 w_max or a factorization fails.
struct ProjectedFrfOptions {
  double target = 1e-4;  ///< relative bound on |H - H_direct| a sample must meet
  long max_modes = 400;
  ModeOptions modes;     ///< eigensolver options (modes is set here)
};
bool frf_projected(const Model& model, const System& sys, const Eigen::VectorXd& f, const Eigen::VectorXd& g,
                   const std::vector<double>& omegas, const ProjectedFrfOptions& options, FrfResult& out);
/// Modal superposition over the given modes (all of `modes`).
FrfResult frf_modal(const Model& model, const System& sys, const Modes& modes, const Eigen::VectorXd& f,
                    const Eigen::VectorXd& g, const std::vector<double>& omegas);

/// Kinetic-energy share of each mode family in body motion q (indexed by ModeFamily).
std::vector<double> family_shares(const Model& model, const Eigen::VectorXd& q);

}  // namespace modalbench::rfem
