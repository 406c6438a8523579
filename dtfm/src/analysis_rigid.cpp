// The rigid-body motions of an unsupported class line and the anchors that separate them from its
// elastic part (rigid_line): what a static solve of a near-mechanism needs.
#include <Eigen/Eigenvalues>
#include <unsupported/Eigen/MatrixFunctions>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "analysis_detail.hpp"
#include "modalbench/numerics/quadrature.hpp"

namespace modalbench::dtfm::detail {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();

/// The end's springs made diagonal: B's admissible columns turned to the springs' principal
/// directions (untouched when already diagonal, as on every beam's rigid end plate).
/// Returns whether it had to (then the small springs carry the rounding of the decomposition).
bool diagonalize_springs(LineAnalysis::ClassLine::End& end) {
  const int nf = end.n_free;
  if (nf == 0) return false;
  const Eigen::MatrixXd off = end.K - Eigen::MatrixXd(end.K.diagonal().asDiagonal());
  if (off.cwiseAbs().maxCoeff() == 0.0) return false;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(end.K);
  if (es.info() != Eigen::Success) return false;  // kept as it is: the split then declines (springs not diagonal)
  end.B.leftCols(nf) = (end.B.leftCols(nf) * es.eigenvectors()).eval();
  end.K = es.eigenvalues().cwiseMax(0.0).asDiagonal();
  return true;
}

}  // namespace

Eigen::MatrixXd RigidLine::phi(double x) const {
  const Eigen::MatrixXd X = -line.St * x;
  return Eigen::MatrixXd(X.exp()) * V0 * Rc;
}

Eigen::MatrixXd RigidLine::node_psi(double x, const LineAnalysis::ClassLine::End* e) const {
  const Eigen::MatrixXd p = phi(x);
  return e ? Eigen::MatrixXd(e->B.transpose() * p) : p;
}

Eigen::MatrixXd RigidLine::mass() const {
  const Eigen::Index r = V0.cols();
  Eigen::MatrixXd Mr = Eigen::MatrixXd::Zero(r, r);
  double from = 0;
  for (int k = 0; k < line.pieces(); ++k) {
    // Piece k over [from, top]: the first to first_to, the others to their own x_to.
    const double top = k == 0 ? line.first_to : line.steps[static_cast<std::size_t>(k) - 1].x_to;
    const Eigen::MatrixXd& M = line.M_of(k);
    for (Eigen::Index p = 0; p < r; ++p)
      for (Eigen::Index q = 0; q <= p; ++q) {
        const Integral in = integrate(
            [&](double x) {
              const Eigen::MatrixXd P = phi(x);
              return P.col(p).dot(M * P.col(q));
            },
            from, top, 1e-13);
        Mr(p, q) += in.value;
        if (q != p) Mr(q, p) += in.value;
      }
    from = top;
  }
  for (int k = 0; k < conditions(); ++k) {
    const auto& e = cond(k);
    if (e.mass_scaled.size() == 0) continue;
    const Eigen::MatrixXd ps = node_psi(e.x, &e).topRows(e.n_free);
    Mr += ps.transpose() * e.mass_scaled * ps;
  }
  return Mr;
}

std::optional<RigidLine> rigid_line(const LineAnalysis::ClassLine& c, double length) {
  if (c.family_motions.cols() == 0) return std::nullopt;
  RigidLine R;
  R.line = c;
  const int mc = c.mc;
  // The class's rigid section motions in class coordinates, orthonormal.
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(Eigen::MatrixXd(c.Winv * c.family_motions));
  const Eigen::MatrixXd Rq = qr.matrixQR().topRows(std::min<Eigen::Index>(mc, c.family_motions.cols()))
                                 .triangularView<Eigen::Upper>();
  int r = 0;
  const double rmax = Rq.diagonal().cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < Rq.rows(); ++i) r += std::abs(Rq(i, i)) > 1e-10 * rmax;
  if (r == 0 || r != Rq.rows()) return std::nullopt;
  R.V0 = qr.householderQ() * Eigen::MatrixXd::Identity(mc, r);
  R.Rc = Eigen::MatrixXd::Identity(r, r);
  // Rigid line motions d(x) = exp(-St x) V0 with zero section forces solve the static field
  // equations exactly when Qt annihilates them along the whole line (no layer deforms and nothing
  // ties the line to the ground); checked at both ends, else no split.
  // Every piece of a stepped line must carry them alike (the same kinematics St).
  for (int k = 1; k < c.pieces(); ++k)
    if ((c.St_of(k) - c.St).norm() > 1e-14 * std::max(1.0, c.St.norm())) return std::nullopt;
  for (int k = 0; k < c.pieces(); ++k) {
    const double qscale = c.Qt_of(k).norm();
    for (double x : {0.0, length}) {
      const Eigen::MatrixXd p = R.phi(x);
      if ((c.Qt_of(k) * p).norm() > 1e-12 * qscale * p.norm()) return std::nullopt;
    }
  }
  // A spring is none when it is exactly zero in the class (analysis_classes.cpp removes the
  // rounding of the class projection), or, on an end whose springs had to be diagonalized, below
  // the rounding of that eigen-decomposition.
  double k_zero = 0;
  for (int k = 0; k < R.conditions(); ++k) {
    auto& e = R.cond(k);
    const Eigen::MatrixXd B0 = e.B;
    if (!diagonalize_springs(e)) continue;
    k_zero = std::max(k_zero, 64.0 * kEps * e.K.norm());
    if (e.mass_scaled.size() > 0) {  // the masses turn with the coordinates
      const Eigen::MatrixXd T = B0.leftCols(e.n_free).transpose() * e.B.leftCols(e.n_free);
      e.mass_scaled = (T.transpose() * e.mass_scaled * T).eval();
    }
  }
  for (int k = 0; k < R.conditions(); ++k) {
    const auto& e = R.cond(k);
    const Eigen::MatrixXd off = e.K - Eigen::MatrixXd(e.K.diagonal().asDiagonal());
    if (e.n_free > 0 && off.cwiseAbs().maxCoeff() != 0.0) return std::nullopt;
  }
  // Candidates: every end coordinate, stiffest first (held ones first of all); the first r whose
  // rows of the rigid motions are independent become the anchors.
  struct Candidate {
    int end, coord;
    double k;
    Eigen::RowVectorXd row;
  };
  std::vector<Candidate> cand;
  for (int e = 0; e < R.conditions(); ++e) {
    const auto& end = R.cond(e);
    const Eigen::MatrixXd psi = R.node_psi(end.x, &end);
    for (int j = 0; j < mc; ++j) {
      double k = j < end.n_free ? end.K(j, j) : kInf;
      if (k <= k_zero) k = 0.0;
      cand.push_back({e, j, k, psi.row(j)});
    }
  }
  std::stable_sort(cand.begin(), cand.end(), [](const Candidate& a, const Candidate& b) { return a.k > b.k; });
  // Rows are compared with the largest one: a coordinate the rigid motions do not move (a held
  // one orthogonal to the end plate's motions) has a row of rounding, not a direction.
  double row_scale = 0;
  for (const Candidate& cd : cand) row_scale = std::max(row_scale, cd.row.norm());
  std::vector<Eigen::RowVectorXd> basis;
  Eigen::MatrixXd G(r, r);
  for (const Candidate& cd : cand) {
    if (static_cast<int>(R.anchors.size()) == r) break;
    Eigen::RowVectorXd v = cd.row;
    for (const auto& q : basis) v -= v.dot(q) * q;
    if (!(v.norm() > 1e-8 * row_scale)) continue;
    basis.push_back(v / v.norm());
    G.row(static_cast<Eigen::Index>(R.anchors.size())) = cd.row;
    R.anchors.push_back({cd.end, cd.coord, cd.k});
  }
  if (static_cast<int>(R.anchors.size()) != r) return std::nullopt;  // cannot happen: Phi(0) has rank r
  Eigen::FullPivLU<Eigen::MatrixXd> lu(G);
  if (!lu.isInvertible()) return std::nullopt;
  R.Rc = lu.inverse();
  // Held anchors stop their amplitude; an amplitude that no finite spring's row reaches is a
  // mechanism (structurally: the supports leave that rigid motion free).
  for (int a = 0; a < r; ++a) {
    if (std::isinf(R.anchors[static_cast<std::size_t>(a)].k)) continue;
    bool touched = false;
    for (int e = 0; e < R.conditions() && !touched; ++e) {
      const auto& end = R.cond(e);
      const Eigen::MatrixXd psi = R.node_psi(end.x, &end);
      for (int j = 0; j < end.n_free && !touched; ++j)
        touched = end.K(j, j) > k_zero && std::abs(psi(j, a)) > 1e-12 * row_scale * R.Rc.norm();
    }
    if (touched) R.free_a.push_back(a);
    else ++R.unrestrained;
  }
  R.k_zero = k_zero;
  return R;
}

RigidCondensed condense_rigid(const RigidLine& rl, BlockTridiagonal& K, const std::vector<double>& x) {
  const auto& c = rl.line;
  const int nn = static_cast<int>(x.size()), mc = c.mc;
  const Eigen::Index r = rl.V0.cols();
  RigidCondensed out;
  for (int i = 0; i < nn; ++i)
    out.psi.push_back(rl.node_psi(x[static_cast<std::size_t>(i)], c.condition_at(x, static_cast<std::size_t>(i))));
  for (const auto& an : rl.anchors) K.hold(rl.node_of(an.end, x), an.coord);
  out.B = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(nn) * mc, r);
  out.C = Eigen::MatrixXd::Zero(r, r);
  for (int end = 0; end < rl.conditions(); ++end) {
    const int nd = rl.node_of(end, x);
    if (nd < 0) throw std::logic_error("dtfm: a support or mass is not a node of the mesh");
    const auto& ce = rl.cond(end);
    for (int j = 0; j < ce.n_free; ++j) {
      const double k = ce.K(j, j);
      if (!(k > rl.k_zero)) continue;
      const Eigen::RowVectorXd p = out.psi[static_cast<std::size_t>(nd)].row(j);
      out.C.noalias() += k * p.transpose() * p;
      if (!rl.is_anchor(end, j)) out.B.row(static_cast<Eigen::Index>(nd) * mc + j) += k * p;
    }
  }
  const BlockTridiagonal::Inertia in = K.inertia();
  if (in.negative > 0 || in.zero > 0)
    throw std::runtime_error(fmt::format(
        "the {} family held at its rigid-motion anchors is not positive definite ({} negative, {} zero pivots): "
        "its elastic part cannot be separated",
        to_string(c.family), in.negative, in.zero));
  const Eigen::Index rf = static_cast<Eigen::Index>(rl.free_a.size());
  out.Y.resize(out.B.rows(), rf);
  out.S.resize(rf, rf);
  for (Eigen::Index q = 0; q < rf; ++q) out.Y.col(q) = K.solve(out.B.col(rl.free_a[static_cast<std::size_t>(q)]), 0.0);
  for (Eigen::Index p = 0; p < rf; ++p)
    for (Eigen::Index q = 0; q < rf; ++q)
      out.S(p, q) = out.C(rl.free_a[static_cast<std::size_t>(p)], rl.free_a[static_cast<std::size_t>(q)]) -
                    out.B.col(rl.free_a[static_cast<std::size_t>(p)]).dot(out.Y.col(q));
  return out;
}

}  // namespace modalbench::dtfm::detail
