#include "modalbench/numerics/complex_block_tridiagonal.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace modalbench {

// ---- ComplexBlockTridiagonal

ComplexBlockTridiagonal::ComplexBlockTridiagonal(int nodes, int m)
    : m_(m),
      diag_(nodes, Eigen::MatrixXcd::Zero(m, m)),
      lower_(std::max(nodes - 1, 0), Eigen::MatrixXcd::Zero(m, m)),
      held_(nodes, std::vector<char>(m, 0)) {
  if (nodes < 1 || m < 1) throw std::invalid_argument("ComplexBlockTridiagonal needs nodes >= 1 and m >= 1");
}

void ComplexBlockTridiagonal::add_segment(int i, const Eigen::MatrixXcd& k) {
  diag_[i] += k.topLeftCorner(m_, m_);
  diag_[i + 1] += k.bottomRightCorner(m_, m_);
  lower_[i] += k.bottomLeftCorner(m_, m_);
}

std::vector<int> ComplexBlockTridiagonal::free_index(int node) const {
  std::vector<int> idx;
  for (int j = 0; j < m_; ++j)
    if (!held_[node][j]) idx.push_back(j);
  return idx;
}

int ComplexBlockTridiagonal::free_dofs() const {
  int n = 0;
  for (int i = 0; i < nodes(); ++i) n += static_cast<int>(free_index(i).size());
  return n;
}

namespace {
Eigen::MatrixXcd pick_c(const Eigen::MatrixXcd& M, const std::vector<int>& rows, const std::vector<int>& cols) {
  Eigen::MatrixXcd out(rows.size(), cols.size());
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (std::size_t c = 0; c < cols.size(); ++c) out(r, c) = M(rows[r], cols[c]);
  return out;
}
}  // namespace

Eigen::MatrixXcd ComplexBlockTridiagonal::dense_free() const {
  std::vector<int> offset(nodes() + 1, 0);
  for (int i = 0; i < nodes(); ++i) offset[i + 1] = offset[i] + static_cast<int>(free_index(i).size());
  Eigen::MatrixXcd D = Eigen::MatrixXcd::Zero(offset.back(), offset.back());
  for (int i = 0; i < nodes(); ++i) {
    auto idx = free_index(i);
    D.block(offset[i], offset[i], idx.size(), idx.size()) = pick_c(diag_[i], idx, idx);
    if (i > 0) {
      auto pidx = free_index(i - 1);
      Eigen::MatrixXcd L = pick_c(lower_[i - 1], idx, pidx);
      D.block(offset[i], offset[i - 1], idx.size(), pidx.size()) = L;
      D.block(offset[i - 1], offset[i], pidx.size(), idx.size()) = L.transpose();
    }
  }
  return D;
}

// Block elimination K = L U with groups of consecutive nodes as pivots (as in the real
// factorization): a group whose pivot block is nearly singular (reciprocal condition below
// 1e-10) takes in the next node, and partial pivoting inside the group handles it.
Eigen::VectorXcd ComplexBlockTridiagonal::solve(const Eigen::VectorXcd& f) const {
  constexpr double kMergeBelow = 1e-10;
  constexpr int kMaxGroup = 16;
  const int n = nodes();
  if (f.size() != static_cast<Eigen::Index>(n) * m_) throw std::invalid_argument("right-hand side has the wrong size");
  std::vector<std::vector<int>> idx(n);
  for (int i = 0; i < n; ++i) idx[i] = free_index(i);
  struct Group {
    int first = 0, last = 0;
    std::vector<int> offset;
    Eigen::MatrixXcd coupling;  // (next node free) x (group DOFs)
    Eigen::PartialPivLU<Eigen::MatrixXcd> lu;
    int size = 0;
  };
  std::vector<Group> groups;
  Eigen::MatrixXcd carry;
  for (int i = 0; i < n;) {
    Group g;
    g.first = i;
    Eigen::MatrixXcd S = pick_c(diag_[i], idx[i], idx[i]);
    if (carry.size() > 0) S -= carry;
    g.offset = {0};
    int last = i;
    auto rcond_of = [](const Eigen::MatrixXcd& M, Eigen::PartialPivLU<Eigen::MatrixXcd>& lu) {
      if (M.rows() == 0) return 1.0;
      lu.compute(M);
      const double rc = lu.rcond();
      return std::isfinite(rc) ? rc : 0.0;
    };
    double rc = rcond_of(S, g.lu);
    while (last + 1 < n && last - i + 1 < kMaxGroup && S.rows() > 0 && rc < kMergeBelow) {
      const int nx = last + 1;
      const int p = static_cast<int>(S.rows()), q = static_cast<int>(idx[nx].size());
      Eigen::MatrixXcd S2 = Eigen::MatrixXcd::Zero(p + q, p + q);
      S2.topLeftCorner(p, p) = S;
      const Eigen::MatrixXcd L = pick_c(lower_[last], idx[nx], idx[last]);
      const int c0 = g.offset.back();
      S2.block(p, c0, q, L.cols()) = L;
      S2.block(c0, p, L.cols(), q) = L.transpose();
      S2.bottomRightCorner(q, q) = pick_c(diag_[nx], idx[nx], idx[nx]);
      g.offset.push_back(p);
      S = std::move(S2);
      last = nx;
      rc = rcond_of(S, g.lu);
    }
    if (S.rows() > 0 && !(rc > 1e-15))
      throw std::runtime_error("complex dynamic stiffness matrix is singular to working precision");
    g.last = last;
    g.size = static_cast<int>(S.rows());
    carry.resize(0, 0);
    if (last + 1 < n) {
      const Eigen::MatrixXcd L = pick_c(lower_[last], idx[last + 1], idx[last]);
      g.coupling = Eigen::MatrixXcd::Zero(L.rows(), S.rows());
      g.coupling.rightCols(L.cols()) = L;
      if (S.rows() > 0 && L.rows() > 0) carry = g.coupling * g.lu.solve(Eigen::MatrixXcd(g.coupling.transpose()));
    }
    groups.push_back(std::move(g));
    i = last + 1;
  }
  const std::size_t G = groups.size();
  std::vector<Eigen::VectorXcd> y(G);
  for (std::size_t g = 0; g < G; ++g) {
    const auto& grp = groups[g];
    y[g] = Eigen::VectorXcd::Zero(grp.size);
    for (int nd = grp.first; nd <= grp.last; ++nd)
      for (std::size_t r = 0; r < idx[nd].size(); ++r) y[g][grp.offset[nd - grp.first] + r] = f[nd * m_ + idx[nd][r]];
    if (g > 0 && groups[g - 1].coupling.size() > 0 && groups[g - 1].size > 0) {
      const auto& prev = groups[g - 1];
      const Eigen::VectorXcd corr = prev.coupling * prev.lu.solve(y[g - 1]);
      y[g].head(corr.size()) -= corr;
    }
  }
  Eigen::VectorXcd d = Eigen::VectorXcd::Zero(f.size());
  Eigen::VectorXcd next;
  for (std::size_t g = G; g-- > 0;) {
    const auto& grp = groups[g];
    Eigen::VectorXcd rhs = y[g];
    if (g + 1 < G && grp.coupling.size() > 0) rhs -= grp.coupling.transpose() * next.head(grp.coupling.rows());
    const Eigen::VectorXcd x = grp.size > 0 ? Eigen::VectorXcd(grp.lu.solve(rhs)) : rhs;
    for (int nd = grp.first; nd <= grp.last; ++nd)
      for (std::size_t r = 0; r < idx[nd].size(); ++r) d[nd * m_ + idx[nd][r]] = x[grp.offset[nd - grp.first] + r];
    next = x;
  }
  return d;
}

}  // namespace modalbench
