#pragma once
// Internal to the rfem analysis: timing, the constraint projector, the dense flexible eigensolver.

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <optional>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "modalbench/frame.hpp"
#include "modalbench/rfem/analysis.hpp"
#include "modalbench/rfem/system.hpp"

namespace modalbench::rfem::detail {

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// max over columns of sum |A_ij| (the matrix 1-norm, for normwise backward errors).
inline double norm1(const SpMat& A) {
  double best = 0;
  for (int j = 0; j < A.outerSize(); ++j) {
    double c = 0;
    for (SpMat::InnerIterator it(A, j); it; ++it) c += std::abs(it.value());
    best = std::max(best, c);
  }
  return best;
}

/// r - G' (G G')^{-1} G r: removes the part of a force that the constraints carry.
class ConstraintProjector {
 public:
  explicit ConstraintProjector(const SpMat& G) : G_(G) {
    if (G.rows() == 0) return;
    const SpMat GGt = G * G.transpose();
    ldlt_.compute(GGt);
    if (ldlt_.info() != Eigen::Success) throw std::runtime_error("rfem: G G' factorization failed (dependent constraints)");
  }
  Eigen::VectorXd operator()(const Eigen::VectorXd& r) const {
    if (G_.rows() == 0) return r;
    return r - G_.transpose() * ldlt_.solve(G_ * r);
  }

 private:
  const SpMat& G_;
  Eigen::SimplicialLDLT<SpMat> ldlt_;
};

/// Makes the BLAS (OpenBLAS) allocate this thread's work buffer now, before the model takes the
/// memory: OpenBLAS reserves it on a thread's first level-3 call and, when that allocation fails,
/// retries forever instead of reporting it. Once per thread; the buffer is kept for later calls.
void reserve_blas_workspace();

struct Flexible {
  Eigen::VectorXd lambda;
  Eigen::MatrixXd Z;
};

// After the eigensolve of solve_modes (analysis_mode_checks.cpp): near-rigid pairs in place of
// those the solve left in the rounding of K (which modes, returned; said in `rigid_text`), the
// family labels, and every pair's residual, backward error and forward bound.
std::vector<char> take_near_rigid_pairs(const Model& model, const System& sys, long nr, Modes& out, std::string& rigid_text);
void label_families(const Model& model, const System& sys, long nr, Modes& out);
void measure_residuals(const System& sys, long nr, const std::vector<char>& near_rigid, Modes& out);

// Dense path of solve_modes (analysis_dense.cpp).
Flexible dense_flexible(const System& sys, const Eigen::MatrixXd& R, long want, double sigma, std::string& method);

/// A beam's support reactions (support_forces, into r.reactions) and, from them, the stress
/// resultants at the probes by the equilibrium of the free body left of each (equilibrium.hpp).
/// Not reported (a warning) where the multipliers do not balance the unreduced model to 1e-8.
void beam_reactions(const Scene& s, const Model& model, const System& sys, const Eigen::VectorXd& z,
                    const std::vector<PointAction>& actions, Result& r);
/// A frame's support reactions, one per supported node (the SDE to ground at its anchor), under the
/// loads fq over the body DOFs. Not reported (a warning) where the multipliers do not balance.
void frame_reactions(const Frame& f, const Model& model, const System& sys, const Eigen::VectorXd& z,
                     const Eigen::VectorXd& fq, Result& r);
/// The static solve's normwise backward error (from its relative residual) into `sum`: a diagnostic,
/// and a numerical issue above 1e-8.
void note_static_backward_error(const System& sys, const Eigen::VectorXd& f, const StaticSolution& st, Summary& sum);
/// A frame's statics on mesh n (frame_statics.cpp): node loads on the nodes' anchors, line loads by
/// two Gauss points per rigid element's share of its member (its cell), displacements at node probes
/// (the anchor's) and member probes (linear between the two element centres around it), reactions.
void frame_statics(const Scene& s, const Model& model, const System& sys, int n, Result& r);
/// A plate's support reactions: per edge (x0, xL, y0, yB: the sum of its SDEs' forces, with their
/// moment about the edge's middle, where the reaction is placed; the Kirchhoff corner forces fall in
/// the corner elements' SDEs of the two edges) and per support at a point. Not reported (a warning)
/// where the multipliers do not balance the unreduced model to 1e-8.
void plate_reactions(const Scene& s, const Model& model, const System& sys, const Eigen::VectorXd& z,
                     const std::vector<PointAction>& actions, Result& r);

/// The bending moments My of the first `count` modes (columns of Z, eigenvalues lambda) of a beam at
/// the points `at` (modal_moments.cpp): [mode][point], in Z's scaling. Nothing (and `why`) where a
/// mode's constraint forces do not balance the model to 1e-8, as for the statics' reactions.
std::optional<std::vector<std::vector<double>>> modal_moments(const Scene& s, const Model& model, const System& sys,
                                                              const Eigen::MatrixXd& Z, const Eigen::VectorXd& lambda,
                                                              long count, const std::vector<std::array<double, 2>>& at,
                                                              std::string& why);

}  // namespace modalbench::rfem::detail
