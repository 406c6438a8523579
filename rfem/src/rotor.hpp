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
// The signs are derived for this code's axes (the appendix's A3 gives the rotating beam's matrices).
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <complex>
#include <string>
#include <vector>

#include "modalbench/result.hpp"
#include "modalbench/rfem/model.hpp"
#include "modalbench/rfem/system.hpp"
#include "modalbench/scene.hpp"
#include "modalbench/solver.hpp"

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

/// The whirl roots from eigenpairs however found: `lambda` (each pair +-lambda once, ascending by
/// |lambda|) with their vectors x (columns of X); the lowest k, a repeated root's basis turned to
/// the orbits' senses, each with its backward error (computed here, or given per root).
WhirlRoots collect_roots(const Model& model, const System& sys, const SpMat& K, const SpMat& C, int k,
                         const std::vector<std::complex<double>>& lambda, const Eigen::MatrixXcd& X,
                         const std::vector<double>& backward_errors = {});

/// The stationary frame's sweep by projection (rotor_sweep.cpp): M x'' + Omega G x' + K x = 0 with
/// M, K positive definite and G skew is a gyroscopic system whose quadratic form
/// x* P(i w) x = x*Kx + w Omega x*(iG)x - w^2 x*Mx has one positive root per x, so its frequencies
/// obey a minmax principle (Voss & Werner 1982): a projection's j-th frequency is an upper bound of
/// the j-th. Per spin: the projected problem on a basis V (a dense Hermitian pencil of size 2 dim V),
/// its k lowest roots checked by their residuals in the K^-1 norm, which bound each root's
/// frequency relative to a true one (the pencil [[0, M], [-M, -Omega G]], diag(M, K) of
/// 1 / lambda), the basis enriched by K^-1 of the residuals of those over the bound (Voss's
/// nonlinear Arnoldi). K is factored once for the whole sweep.
class GyroscopicSweep {
 public:
  /// Factors K (Cholesky, the sweep's one factorization).
  GyroscopicSweep(const SpMat& M, const SpMat& G, const SpMat& K, int k);
  struct Roots {
    std::vector<std::complex<double>> lambda;  ///< i w, ascending
    Eigen::MatrixXcd X;                        ///< the vectors x
    std::vector<double> backward_error;        ///< per root (as collect_roots computes it)
    double bound = 0;                          ///< largest |w - w_true| / w_true bound of the k
    double next = 0;                           ///< the projection's (k+1)-th frequency (an upper bound)
    bool converged = false;                    ///< every root accepted within the step limit
  };
  /// Each root's frequency within this of a true one, relative; or, where its bound has stopped
  /// falling (by half in a step: the residual at its rounding floor, 1e-9 to 1e-8 on 300
  /// Euler-Bernoulli segments), within kFloorBound, its bound then reported as it is.
  static constexpr double kBound = 1e-9, kFloorBound = 1e-7;
  Roots solve(double spin);
  long solves() const { return solves_; }
  long largest_basis() const { return largest_; }

 private:
  bool add(const Eigen::VectorXd& v);
  void restart(const Eigen::MatrixXcd& keep);
  const SpMat &M_, &G_, &K_;
  double normM_, normG_, normK_;
  Eigen::SimplicialLLT<SpMat> llt_;
  int k_;
  long cap_, m_ = 0, solves_ = 0, largest_ = 0;
  Eigen::MatrixXd V_, Mr_, Gr_, Kr_;
};

/// Seconds per spin of the stationary sweep, by projection or by Arnoldi, on `coordinates` lateral
/// coordinates with k roots (bench_rfem_rotor, 6 roots: projected 0.65 ms at 484 coordinates, 1.4 ms
/// at 1996, 2.4 ms at 3988; Arnoldi 7 ms at 1996, 13 ms at 3988; the projection's dense step grows
/// like its basis, 6 k + 8, cubed: 20 roots on 404 coordinates took it 27 ms a spin, Arnoldi 5 ms).
double projected_seconds_per_spin(double coordinates, int k);
double arnoldi_seconds_per_spin(double coordinates, int k);
/// Whether the stationary frame's sweep is projected: campbell_method projected, or auto where the
/// projection is the cheaper (and the model has room for its start basis).
bool projected_sweep(const std::string& method, double coordinates, int k);

/// The number of whirl frequencies below sigma at a spin, stationary frame (the minmax principle
/// above): the negative eigenvalues of the Hermitian P(i sigma) = K - sigma^2 M + i sigma Omega G, by
/// an LDL' of its real form [[A, -B], [B, A]] (each eigenvalue twice). -1 where a pivot was zero.
long whirl_count(const SpMat& M, const SpMat& G, const SpMat& K, double spin, double sigma);

/// The positive Omega with K x = Omega^2 B x (K positive definite, B symmetric, perhaps indefinite),
/// ascending: every one up to `top` and the next above, where there is one.
std::vector<double> synchronous_speeds(const SpMat& K, const SpMat& B, double top);

/// The Campbell diagram and critical speeds of scene.rotor on `model` (campbell_refusal empty);
/// `opt`: rfem's campbell_method and sturm_check.
Campbell rotor_campbell(const Scene& s, const Model& model, const System& sys, const ResolvedOptions& opt, Summary& sum);

}  // namespace modalbench::rfem::detail
