#include "modalbench/numerics/block_tridiagonal.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "modalbench/numerics/symmetric_factor.hpp"

namespace modalbench {

BlockTridiagonal::BlockTridiagonal(int nodes, int m)
    : m_(m),
      diag_(nodes, Eigen::MatrixXd::Zero(m, m)),
      lower_(std::max(nodes - 1, 0), Eigen::MatrixXd::Zero(m, m)),
      held_(nodes, std::vector<char>(m, 0)) {
  if (nodes < 1 || m < 1) throw std::invalid_argument("BlockTridiagonal needs nodes >= 1 and m >= 1");
}

void BlockTridiagonal::add_segment(int i, const Eigen::MatrixXd& k) {
  diag_[i] += k.topLeftCorner(m_, m_);
  diag_[i + 1] += k.bottomRightCorner(m_, m_);
  lower_[i] += k.bottomLeftCorner(m_, m_);
}

Eigen::VectorXd BlockTridiagonal::multiply(const Eigen::VectorXd& d) const {
  const int n = nodes();
  if (d.size() != static_cast<Eigen::Index>(n) * m_) throw std::invalid_argument("vector has the wrong size");
  Eigen::VectorXd out = Eigen::VectorXd::Zero(d.size());
  for (int i = 0; i < n; ++i) {
    const Eigen::Index a = static_cast<Eigen::Index>(i) * m_;
    out.segment(a, m_) += diag_[static_cast<std::size_t>(i)] * d.segment(a, m_);
    if (i + 1 < n) {
      const Eigen::MatrixXd& L = lower_[static_cast<std::size_t>(i)];  // block (i + 1, i)
      out.segment(a + m_, m_) += L * d.segment(a, m_);
      out.segment(a, m_) += L.transpose() * d.segment(a + m_, m_);
    }
  }
  return out;
}

std::vector<int> BlockTridiagonal::free_index(int node) const {
  std::vector<int> idx;
  for (int j = 0; j < m_; ++j)
    if (!held_[node][j]) idx.push_back(j);
  return idx;
}

int BlockTridiagonal::free_dofs() const {
  int n = 0;
  for (int i = 0; i < nodes(); ++i) n += static_cast<int>(free_index(i).size());
  return n;
}

namespace {
Eigen::MatrixXd pick(const Eigen::MatrixXd& M, const std::vector<int>& rows, const std::vector<int>& cols) {
  Eigen::MatrixXd out(rows.size(), cols.size());
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (std::size_t c = 0; c < cols.size(); ++c) out(r, c) = M(rows[r], cols[c]);
  return out;
}
}  // namespace

// Block LDL^T with a variable partition. Each pivot group covers consecutive nodes; a
// group's pivot block is the Schur complement of everything before it. When that block is
// nearly singular compared with its nodes' own stiffness (a substructure resonance, which
// elimination without pivoting would amplify), the next node joins the group and the
// pivoting inside the group's LDL^T takes care of it. The partition changes nothing in exact
// arithmetic (it is still a congruence), so the inertia count stays exact.
struct BlockTridiagonal::Factorization {
  struct Group {
    int first = 0, last = 0;      // node range
    std::vector<int> offset;      // start of each node's free DOFs inside the group
    Eigen::MatrixXd coupling;     // (next node free) x (group DOFs): only the last node's columns
    std::unique_ptr<SymFactor> pivot;
  };
  std::vector<Group> groups;
  std::vector<std::vector<int>> idx;
  int negative = 0, zero = 0;
  double min_abs = std::numeric_limits<double>::infinity(), max_abs = 0;
  double log_abs = 0;
};

BlockTridiagonal::Factorization BlockTridiagonal::factor() const {
  constexpr double kMergeBelow = 1e-8;
  constexpr int kMaxGroup = 16;
  Factorization F;
  const int n = nodes();
  F.idx.resize(n);
  for (int i = 0; i < n; ++i) F.idx[i] = free_index(i);
  Eigen::MatrixXd carry;  // Schur complement update for the next group's first node
  int i = 0;
  while (i < n) {
    Factorization::Group g;
    g.first = i;
    Eigen::MatrixXd S = pick(diag_[i], F.idx[i], F.idx[i]);
    if (carry.size() > 0) S -= carry;
    double node_scale = diag_[i].norm();
    g.offset = {0};
    int last = i;
    auto pivot = std::make_unique<SymFactor>(S);
    while (last + 1 < n && last - i + 1 < kMaxGroup && S.rows() > 0 &&
           (pivot->zero > 0 || pivot->min_abs < kMergeBelow * node_scale)) {
      // Join node last + 1 to the group.
      const int nx = last + 1;
      const int p = static_cast<int>(S.rows()), q = static_cast<int>(F.idx[nx].size());
      Eigen::MatrixXd S2 = Eigen::MatrixXd::Zero(p + q, p + q);
      S2.topLeftCorner(p, p) = S;
      const Eigen::MatrixXd L = pick(lower_[last], F.idx[nx], F.idx[last]);
      const int c0 = g.offset.back();
      S2.block(p, c0, q, L.cols()) = L;
      S2.block(c0, p, L.cols(), q) = L.transpose();
      S2.bottomRightCorner(q, q) = pick(diag_[nx], F.idx[nx], F.idx[nx]);
      g.offset.push_back(p);
      S = std::move(S2);
      node_scale = std::max(node_scale, diag_[nx].norm());
      last = nx;
      pivot = std::make_unique<SymFactor>(S);
    }
    g.last = last;
    F.negative += pivot->negative;
    F.zero += pivot->zero;
    F.log_abs += pivot->log_abs;
    if (S.rows() > 0) {
      F.min_abs = std::min(F.min_abs, pivot->min_abs);
      F.max_abs = std::max(F.max_abs, pivot->max_abs);
    }
    carry.resize(0, 0);
    if (last + 1 < n) {
      const Eigen::MatrixXd L = pick(lower_[last], F.idx[last + 1], F.idx[last]);
      g.coupling = Eigen::MatrixXd::Zero(L.rows(), S.rows());
      g.coupling.rightCols(L.cols()) = L;
      if (S.rows() > 0 && L.rows() > 0) carry = g.coupling * pivot->solve(g.coupling.transpose());
    }
    g.pivot = std::move(pivot);
    F.groups.push_back(std::move(g));
    i = last + 1;
  }
  return F;
}

BlockTridiagonal::Inertia BlockTridiagonal::inertia() const {
  const Factorization F = factor();
  Inertia in;
  in.negative = F.negative;
  in.zero = F.zero;
  in.min_abs_pivot_rel = F.max_abs > 0 ? F.min_abs / F.max_abs : 0.0;
  in.log_abs_det = F.log_abs;
  return in;
}

Eigen::VectorXd BlockTridiagonal::solve(const Eigen::VectorXd& f, double min_pivot_rel) const {
  const int n = nodes();
  if (f.size() != static_cast<Eigen::Index>(n) * m_) throw std::invalid_argument("right-hand side has the wrong size");
  const Factorization F = factor();
  if (F.zero > 0 || !(F.min_abs > min_pivot_rel * F.max_abs))
    throw std::runtime_error("dynamic stiffness matrix is singular to working precision (a mechanism, or omega at a natural frequency)");
  const std::size_t G = F.groups.size();
  // Forward: y_g = f_g - C_{g-1} S_{g-1}^-1 y_{g-1} (C couples group g-1 to g's first node).
  std::vector<Eigen::VectorXd> y(G);
  for (std::size_t g = 0; g < G; ++g) {
    const auto& grp = F.groups[g];
    const int size = static_cast<int>(grp.pivot ? (grp.offset.back() + F.idx[grp.last].size()) : 0);
    y[g] = Eigen::VectorXd::Zero(size);
    for (int nd = grp.first; nd <= grp.last; ++nd)
      for (std::size_t r = 0; r < F.idx[nd].size(); ++r)
        y[g][grp.offset[nd - grp.first] + r] = f[nd * m_ + F.idx[nd][r]];
    if (g > 0 && F.groups[g - 1].coupling.size() > 0) {
      const auto& prev = F.groups[g - 1];
      const Eigen::VectorXd corr = prev.coupling * prev.pivot->solve(y[g - 1]);
      y[g].head(corr.size()) -= corr;
    }
  }
  // Backward: x_g = S_g^-1 (y_g - C_g^T x_{g+1, first node}).
  Eigen::VectorXd d = Eigen::VectorXd::Zero(f.size());
  Eigen::VectorXd next;
  for (std::size_t g = G; g-- > 0;) {
    const auto& grp = F.groups[g];
    Eigen::VectorXd rhs = y[g];
    if (g + 1 < G && grp.coupling.size() > 0) rhs -= grp.coupling.transpose() * next.head(grp.coupling.rows());
    const Eigen::VectorXd x = grp.pivot->solve(rhs);
    for (int nd = grp.first; nd <= grp.last; ++nd)
      for (std::size_t r = 0; r < F.idx[nd].size(); ++r) d[nd * m_ + F.idx[nd][r]] = x[grp.offset[nd - grp.first] + r];
    next = x;
  }
  return d;
}

Eigen::MatrixXd BlockTridiagonal::dense_free() const {
  std::vector<int> offset(nodes() + 1, 0);
  for (int i = 0; i < nodes(); ++i) offset[i + 1] = offset[i] + static_cast<int>(free_index(i).size());
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(offset.back(), offset.back());
  for (int i = 0; i < nodes(); ++i) {
    auto idx = free_index(i);
    D.block(offset[i], offset[i], idx.size(), idx.size()) = pick(diag_[i], idx, idx);
    if (i > 0) {
      auto pidx = free_index(i - 1);
      Eigen::MatrixXd L = pick(lower_[i - 1], idx, pidx);
      D.block(offset[i], offset[i - 1], idx.size(), pidx.size()) = L;
      D.block(offset[i - 1], offset[i], pidx.size(), idx.size()) = L.transpose();
    }
  }
  return D;
}

}  // namespace modalbench
