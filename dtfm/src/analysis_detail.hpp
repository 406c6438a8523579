#pragma once
// Internal to the dtfm line analysis: a symmetry class as a scaled line problem, the assembled system.

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <type_traits>
#include <vector>

#include "modalbench/dtfm/analysis.hpp"
#include "modalbench/numerics/block_tridiagonal.hpp"

namespace modalbench::dtfm {

/// One symmetry class of the model as a line problem in scaled coordinates: translations
/// divided by a length (so that K's translation and rotation entries are comparable), energy
/// divided by sigma. q = W q_c, f_c = W^T f / sigma.
struct LineAnalysis::ClassLine {
  int index = 0, mc = 0;
  ModeFamily family = ModeFamily::Unknown;
  Eigen::MatrixXd W, Winv;
  Eigen::MatrixXd St, C, Qt, M;  // the operator (a stepped beam: its first piece's)
  Eigen::MatrixXd G;             // a whirl line's gyroscopic inertia, scaled like M (empty: none)
  double whirl = 0;              // s Omega (PrismModel::whirl)
  double sigma = 1;
  double length = 0;
  /// A node's conditions: an end's, or a support / point mass between the ends.
  struct End {
    Eigen::MatrixXd B;  // mc x mc orthogonal; the first n_free columns are the admissible motions
    int n_free = 0;
    bool identity = false;  // B = I (every motion admissible): the end blocks need no transformation
    Eigen::MatrixXd K;  // springs on those coordinates
    double x = 0;
    Eigen::MatrixXd Mc;       // point masses, mc x mc in class coordinates (W^T mass W, unscaled); empty: none
    Eigen::MatrixXd Mfields;  // the same over the fields (m x m), for participations
    Eigen::MatrixXd mass_scaled;  // B^T Mc B / sigma over the admissible motions (K - lambda this); empty: none
    Eigen::MatrixXd gyro_scaled;  // the discs' J_p the same way (K + whirl sqrt(lambda) this); empty: none
  } ends[2];
  std::vector<End> points;  // between the ends, by ascending x
  /// Stepped beams: the operator of every piece after the first, each from the previous one's
  /// x_to (the first over [0, first_to]).
  struct Piece {
    double x_to = 0;
    Eigen::MatrixXd St, C, Qt, M, G;
  };
  std::vector<Piece> steps;
  double first_to = 0;
  Eigen::MatrixXd family_motions;  // physical, m x r (beams)
  double re0 = -1, im0 = -1;       // wavenumber bounds at lambda = 0 (cached, over the pieces)

  int pieces() const { return 1 + static_cast<int>(steps.size()); }
  /// The piece holding the segment [xa, xb] (nodes sit at every step).
  int piece_of(double xa, double xb) const {
    const double mid = 0.5 * (xa + xb);
    if (steps.empty() || mid <= first_to) return 0;
    for (std::size_t k = 0; k < steps.size(); ++k)
      if (mid <= steps[k].x_to) return static_cast<int>(k) + 1;
    return static_cast<int>(steps.size());
  }
  const Eigen::MatrixXd& M_of(int piece) const { return piece == 0 ? M : steps[static_cast<std::size_t>(piece) - 1].M; }
  const Eigen::MatrixXd& St_of(int piece) const { return piece == 0 ? St : steps[static_cast<std::size_t>(piece) - 1].St; }
  const Eigen::MatrixXd& Qt_of(int piece) const { return piece == 0 ? Qt : steps[static_cast<std::size_t>(piece) - 1].Qt; }
  const Eigen::MatrixXd& C_of(int piece) const { return piece == 0 ? C : steps[static_cast<std::size_t>(piece) - 1].C; }
  const Eigen::MatrixXd& G_of(int piece) const { return piece == 0 ? G : steps[static_cast<std::size_t>(piece) - 1].G; }
  /// The whirl's coefficient of G at lambda: whirl sqrt(lambda) (0 without spin).
  template <class Scalar>
  Scalar whirl_term(Scalar lambda) const {
    if (whirl == 0.0) return Scalar(0);
    if constexpr (std::is_floating_point_v<Scalar>) return whirl * std::sqrt(std::max(lambda, Scalar(0)));
    else return whirl * std::sqrt(lambda);
  }
  /// Where steps and points need nodes.
  std::vector<double> required_nodes() const {
    std::vector<double> out;
    if (!steps.empty()) out.push_back(first_to);
    for (std::size_t k = 0; k + 1 < steps.size(); ++k) out.push_back(steps[k].x_to);
    for (const End& p : points) out.push_back(p.x);
    return out;
  }
  /// The conditions at node i of nodes x: an end's, a point's, or none.
  const End* condition_at(const std::vector<double>& x, std::size_t i) const {
    if (i == 0) return &ends[0];
    if (i + 1 == x.size()) return &ends[1];
    for (const End& p : points)
      if (std::abs(p.x - x[i]) <= 1e-12 * length) return &p;
    return nullptr;
  }

  template <class Scalar>
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> state(Scalar lambda, int piece = 0) const {
    using Mat = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
    Mat A(2 * mc, 2 * mc);
    A.topLeftCorner(mc, mc) = (-St_of(piece)).template cast<Scalar>();
    A.topRightCorner(mc, mc) = C_of(piece).template cast<Scalar>();
    A.bottomLeftCorner(mc, mc) = Qt_of(piece).template cast<Scalar>() - lambda * M_of(piece).template cast<Scalar>();
    if (whirl != 0.0 && G_of(piece).size() > 0)
      A.bottomLeftCorner(mc, mc) += whirl_term(lambda) * G_of(piece).template cast<Scalar>();
    A.bottomRightCorner(mc, mc) = St_of(piece).transpose().template cast<Scalar>();
    return A;
  }
};

namespace detail {

/// How many times a segment of length h is halved down to base pieces no longer than h_base
/// (long_segment_dynamic_stiffness' levels): the discretization a mesh gives that segment.
inline int doubling_levels(double h, double h_base) {
  return std::max(0, static_cast<int>(std::ceil(std::log2(h / h_base) - 1e-9)));
}


/// A distributed load on one segment of a class line: y' = A y + g0 + g1 s (s from the segment's
/// left node), g = [0; -p(x)], p the class's load per unit length (linear within the segment).
struct SegmentLoad {
  Eigen::VectorXd g0, g1;
};

/// y_p(t) with y_p' = A y_p + g0 + g1 s, y_p(0) = 0: the last column of the exponential of the
/// augmented matrix [[A, g1, g0], [0, 0, 1], [0, 0, 0]] t (t of either sign).
Eigen::VectorXd particular(const Eigen::MatrixXd& A, const SegmentLoad& ld, double t);

/// Adds to `out` a class's share of the static solution's field integrals (FieldIntegrals):
/// int q dx and int (x - L/2) q dx by 8-point Gauss on every segment, the state at each point
/// carried from the segment's left node by exp(A t) with the segment's load's particular solution
/// (segments no longer than a base piece: exp(A t) stays well conditioned); the transfer matrices
/// are formed once per segment length and load. And the forces of the nodes' conditions. `d`,
/// `f`: the class's nodal solution and loads (nodes with conditions in their B coordinates).
void integrate_fields(const LineAnalysis::ClassLine& c, const std::vector<double>& x, double h_base,
                      const Eigen::VectorXd& d, const Eigen::VectorXd& f,
                      const std::vector<std::optional<SegmentLoad>>& loads, FieldIntegrals& out);

struct AssemblyInfo {
  int clamped_below = 0;   // sum of the segments' J0
  double log_poles = 0;    // sum of the segments' log |det Tdf|
  double min_pivot_rel = 1;
};

/// The rigid-body motions of a class line without its supports, and the anchors that separate
/// them from the elastic part (analysis_rigid.cpp), for static solves of near-mechanisms.
///
/// The class's rigid section motions V0 (its family motions) carried along x with zero section
/// forces, d(x) = exp(-St x) V0, solve the static field equations exactly when Qt annihilates
/// them (no layer deforms, nothing ties the line to the ground): K(0) times them is zero
/// analytically. The ends' springs are made diagonal (the admissible end coordinates turned to
/// their principal directions); the end coordinates are taken stiffest first (held ones first)
/// and the first r with independent rows of the rigid motions become the anchors, the rigid basis
/// having unit value at one anchor and zero at the others. The line is then d_i = Psi_i a + e_i
/// with e = 0 at the anchors: the elastic part sees the line held at its anchors (positive
/// definite), the amplitudes a see the springs only, and nothing is lost in the rounding of
/// K_int + K_springs (a beam rocking on springs 1e-8 of EI / L^3 about a support of 1e12 EI / L^3).
/// In anchor order the condensed r x r matrix is graded from the stiffest spring down.
struct RigidLine {
  LineAnalysis::ClassLine line;  ///< the class line with diagonal end springs (the coordinates solved)
  Eigen::MatrixXd V0;            ///< mc x r: orthonormal rigid section motions at x = 0
  Eigen::MatrixXd Rc;            ///< r x r: phi(x) = exp(-St x) V0 Rc is 1 at one anchor, 0 at the others
  struct Anchor {
    int end = 0, coord = 0;  ///< condition (cond(end)) and its coordinate (column of its B)
    double k = 0;            ///< its spring (inf: held; 0: none)
  };
  /// The line's node conditions: 0 and 1 its ends, 2 + i its i-th point.
  int conditions() const { return 2 + static_cast<int>(line.points.size()); }
  const LineAnalysis::ClassLine::End& cond(int k) const {
    return k == 0 ? line.ends[0] : k == 1 ? line.ends[1] : line.points[static_cast<std::size_t>(k) - 2];
  }
  LineAnalysis::ClassLine::End& cond(int k) {
    return k == 0 ? line.ends[0] : k == 1 ? line.ends[1] : line.points[static_cast<std::size_t>(k) - 2];
  }
  /// The node of condition k among nodes x.
  int node_of(int k, const std::vector<double>& x) const {
    if (k == 0) return 0;
    const int nn = static_cast<int>(x.size());
    if (k == 1) return nn - 1;
    for (int i = 1; i + 1 < nn; ++i)
      if (std::abs(x[static_cast<std::size_t>(i)] - cond(k).x) <= 1e-12 * line.length) return i;
    return -1;
  }
  std::vector<Anchor> anchors;  ///< r of them, stiffest first
  std::vector<int> free_a;      ///< amplitudes a spring restrains (not held), in anchor order
  int unrestrained = 0;         ///< amplitudes no support reaches: a mechanism
  double k_zero = 0;            ///< springs at or below this are none (0 unless an end was diagonalized)

  /// Rigid basis in class coordinates at x (mc x r).
  Eigen::MatrixXd phi(double x) const;
  /// The same in a node's coordinates (those of its conditions' B, if any).
  Eigen::MatrixXd node_psi(double x, const LineAnalysis::ClassLine::End* e) const;
  /// The rigid amplitudes' mass r x r (class units: int Phi^T M Phi dx and the point masses).
  Eigen::MatrixXd mass() const;
  bool is_anchor(int end, int coord) const {
    for (const auto& a : anchors)
      if (a.end == end && a.coord == coord) return true;
    return false;
  }
};
/// The split of class line `c` on [0, length], or nothing where the class has no rigid motions of
/// its own (plates; lines tied to the ground).
std::optional<RigidLine> rigid_line(const LineAnalysis::ClassLine& c, double length);

/// The line split at lambda = 0 ([[E, B], [B^T, C]] [e; a], K_int Psi = 0 analytically and never
/// formed): E = K_int + the springs, held at the anchors; B = the non-anchor springs' forces of the
/// rigid motions; C = Psi^T K_springs Psi; and the condensed rigid block over the free amplitudes.
struct RigidCondensed {
  std::vector<Eigen::MatrixXd> psi;  ///< per node: the rigid basis in the node's coordinates (mc x r)
  Eigen::MatrixXd B;                 ///< nodes * mc x r
  Eigen::MatrixXd C;                 ///< r x r
  Eigen::MatrixXd Y;                 ///< E^-1 B over the free amplitudes (nodes * mc x rf)
  Eigen::MatrixXd S;                 ///< C - B^T E^-1 B over the free amplitudes (rf x rf, anchor order: graded)
};
/// `K`: the assembled K(0) of rl.line on nodes x; its anchors are held here, and K is then E.
/// Throws std::runtime_error if E is not positive definite.
RigidCondensed condense_rigid(const RigidLine& rl, BlockTridiagonal& K, const std::vector<double>& x);

/// Field values (physical) at every node from a class solution d (nodes x mc, nodes with conditions in their B coordinates).
template <class Vec>
std::vector<Vec> to_fields(const LineAnalysis::ClassLine& c, const Vec& d, const std::vector<double>& x) {
  const int nn = static_cast<int>(x.size());
  using Scalar = typename Vec::Scalar;
  std::vector<Vec> q(nn);
  for (int i = 0; i < nn; ++i) {
    Vec dc = d.segment(static_cast<Eigen::Index>(i) * c.mc, c.mc);
    if (const auto* e = c.condition_at(x, static_cast<std::size_t>(i))) dc = e->B.template cast<Scalar>() * dc;
    q[i] = c.W.template cast<Scalar>() * dc;
  }
  return q;
}

}  // namespace detail

struct LineAnalysis::Assembled {
  BlockTridiagonal K;
  detail::AssemblyInfo info;
};

}  // namespace modalbench::dtfm
