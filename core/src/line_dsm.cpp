#include "modalbench/line_dsm.hpp"

#include <unsupported/Eigen/MatrixFunctions>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

namespace modalbench {

namespace {

// A cheap magnitude for balancing (|re| + |im| for complex: no hypot).
inline double magnitude(double v) { return std::abs(v); }
inline double magnitude(const std::complex<double>& v) { return std::abs(v.real()) + std::abs(v.imag()); }

// Diagonal similarity by powers of two (Parlett & Reinsch), in place; returns the scaling d
// with B_balanced = D^-1 B D, D = diag(d).
template <class Mat>
Eigen::VectorXd balance_in_place(Mat& B, int max_sweeps) {
  const Eigen::Index n = B.rows();
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(n);
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    bool changed = false;
    for (Eigen::Index i = 0; i < n; ++i) {
      double c = 0, r = 0;
      for (Eigen::Index j = 0; j < n; ++j)
        if (j != i) {
          c += magnitude(B(j, i));
          r += magnitude(B(i, j));
        }
      if (c == 0 || r == 0) continue;
      int e = 0;
      std::frexp(std::sqrt(r / c), &e);
      const double f = std::ldexp(1.0, e - 1);
      if (f != 1.0 && (c * f + r / f) < 0.95 * (c + r)) {
        B.col(i) *= f;
        B.row(i) /= f;
        scale[i] *= f;
        changed = true;
      }
    }
    if (!changed) break;
  }
  return scale;
}

// exp() is accurate relative to the norm of its argument; the state matrices mix entries
// of very different size (w, phi, Q, M), so balance first (diagonal similarity by powers
// of two, Parlett & Reinsch) and undo it afterwards: T = D exp(D^-1 A h D) D^-1.
template <class Mat>
Mat segment_dsm_impl(const Mat& A, double h, double* asymmetry, double* log_abs_det_tdf) {
  const Eigen::Index n2 = A.rows();
  if (A.cols() != n2 || n2 % 2 != 0) throw std::invalid_argument("state matrix must be square of even size");
  const Eigen::Index m = n2 / 2;
  Mat B = A * h;
  const Eigen::VectorXd scale = balance_in_place(B, 20);
  const Mat T = scale.asDiagonal() * Mat(B.exp()) * scale.cwiseInverse().asDiagonal();
  const auto Tdd = T.topLeftCorner(m, m), Tdf = T.topRightCorner(m, m);
  const auto Tfd = T.bottomLeftCorner(m, m), Tff = T.bottomRightCorner(m, m);
  Eigen::PartialPivLU<Mat> lu(Tdf);
  if (log_abs_det_tdf) {
    double l = 0;
    for (Eigen::Index i = 0; i < m; ++i) l += std::log(std::abs(lu.matrixLU()(i, i)));
    *log_abs_det_tdf = l;
  }
  const Mat TdfInvTdd = lu.solve(Mat(Tdd));
  const Mat TdfInv = lu.inverse();
  Mat K(n2, n2);
  K.topLeftCorner(m, m) = TdfInvTdd;
  K.topRightCorner(m, m) = -TdfInv;
  K.bottomLeftCorner(m, m) = Tfd - Tff * TdfInvTdd;
  K.bottomRightCorner(m, m) = Tff * TdfInv;
  if (asymmetry) *asymmetry = (K - K.transpose()).norm() / K.norm();
  // Symmetric in exact arithmetic; remove the rounding asymmetry so the LDL^T sees one matrix.
  return Mat(0.5 * (K + K.transpose()));
}

}  // namespace

Eigen::MatrixXd balanced(Eigen::MatrixXd B, int max_sweeps) {
  balance_in_place(B, max_sweeps);
  return B;
}

Eigen::MatrixXd segment_dynamic_stiffness(const Eigen::MatrixXd& A, double h, double* asymmetry,
                                          double* log_abs_det_tdf) {
  return segment_dsm_impl(A, h, asymmetry, log_abs_det_tdf);
}

Eigen::MatrixXcd segment_dynamic_stiffness(const Eigen::MatrixXcd& A, double h, double* asymmetry,
                                           double* log_abs_det_tdf) {
  return segment_dsm_impl(A, h, asymmetry, log_abs_det_tdf);
}

namespace detail {

/// LDL^T of a small symmetric block, with an eigen-decomposition fall-back when the
/// diagonal pivoting meets a zero or non-finite pivot.
struct SymFactor {
  Eigen::LDLT<Eigen::MatrixXd> ldlt;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig;
  bool use_eig = false;
  int negative = 0, zero = 0;
  double min_abs = std::numeric_limits<double>::infinity(), max_abs = 0;
  double log_abs = 0;  // log |det| of the block

  explicit SymFactor(const Eigen::MatrixXd& S) {
    if (S.rows() == 0) return;
    ldlt.compute(S);
    bool good = ldlt.info() == Eigen::Success;
    if (good) {
      const Eigen::VectorXd d = ldlt.vectorD();
      for (Eigen::Index i = 0; i < d.size(); ++i)
        if (!std::isfinite(d[i]) || d[i] == 0.0) good = false;
      if (good) {
        for (Eigen::Index i = 0; i < d.size(); ++i) tally(d[i]);
        return;
      }
    }
    use_eig = true;
    eig.compute(S);
    const Eigen::VectorXd ev = eig.eigenvalues();
    const double scale = ev.cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i < ev.size(); ++i) {
      if (!std::isfinite(ev[i]) || std::abs(ev[i]) <= 1e-300 + 1e-15 * scale) ++zero;
      tally(ev[i]);
    }
  }
  void tally(double d) {
    if (d < 0) ++negative;
    log_abs += std::log(std::abs(d));
    min_abs = std::min(min_abs, std::abs(d));
    max_abs = std::max(max_abs, std::abs(d));
  }
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const {
    if (B.rows() == 0) return B;
    if (!use_eig) return ldlt.solve(B);
    Eigen::VectorXd inv = eig.eigenvalues();
    const double scale = inv.cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i < inv.size(); ++i) {
      const double e = inv[i];
      // A zero pivot: regularise so the elimination can go on; callers see `zero`.
      inv[i] = std::abs(e) <= 1e-15 * scale ? 1.0 / (1e-15 * scale + 1e-300) : 1.0 / e;
    }
    return eig.eigenvectors() * inv.asDiagonal() * (eig.eigenvectors().transpose() * B);
  }
};

}  // namespace detail
using detail::SymFactor;

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

Eigen::VectorXd BlockTridiagonal::solve(const Eigen::VectorXd& f) const {
  const int n = nodes();
  if (f.size() != static_cast<Eigen::Index>(n) * m_) throw std::invalid_argument("right-hand side has the wrong size");
  const Factorization F = factor();
  if (F.zero > 0 || !(F.min_abs > 1e-14 * F.max_abs))
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

int AssembledLine::node_at(double x) const {
  for (std::size_t i = 0; i < xi.size(); ++i)
    if (xi[i] == x) return static_cast<int>(i);
  throw std::invalid_argument("no node at xi = " + std::to_string(x));
}

AssembledLine assemble(const LineSystem& sys, double lambda) {
  const int m = sys.m;
  if (static_cast<int>(sys.left_spring.size()) != m || static_cast<int>(sys.right_spring.size()) != m)
    throw std::invalid_argument("LineSystem: end springs must have m entries");
  // Breakpoints: 0, the required interior nodes, 1; each gap cut so that |p| h <= 1.
  std::vector<double> breaks = {0.0, 1.0};
  for (double x : sys.nodes_at) {
    if (!(x >= 0.0 && x <= 1.0)) throw std::invalid_argument("LineSystem: node outside [0, 1]");
    breaks.push_back(x);
  }
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  const double p = std::max(sys.max_wavenumber(lambda), 1e-12);
  if (!std::isfinite(p)) throw std::runtime_error("LineSystem: wavenumber bound is not finite");
  std::vector<double> xi = {0.0};
  for (std::size_t g = 0; g + 1 < breaks.size(); ++g) {
    const double len = breaks[g + 1] - breaks[g];
    const double pieces = std::ceil(len * p);
    if (pieces > 1e7) throw std::runtime_error("LineSystem: more than 1e7 segments needed at this frequency");
    const int n = std::max(1, static_cast<int>(pieces));
    for (int j = 1; j < n; ++j) xi.push_back(breaks[g] + len * j / n);
    xi.push_back(breaks[g + 1]);
  }
  AssembledLine out{BlockTridiagonal(static_cast<int>(xi.size()), m), xi};
  const Eigen::MatrixXd A = sys.state_matrix(lambda);
  // Equal-length pieces share one segment matrix.
  double last_h = -1;
  Eigen::MatrixXd k_seg;
  for (std::size_t i = 0; i + 1 < xi.size(); ++i) {
    const double h = xi[i + 1] - xi[i];
    if (std::abs(h - last_h) > 1e-15 * h) {
      k_seg = segment_dynamic_stiffness(A, h);
      last_h = h;
    }
    out.K.add_segment(static_cast<int>(i), k_seg);
  }
  const int last = static_cast<int>(xi.size()) - 1;
  for (int j = 0; j < m; ++j) {
    if (std::isinf(sys.left_spring[j])) out.K.hold(0, j);
    else out.K.add_diagonal(0, j, sys.left_spring[j]);
    if (std::isinf(sys.right_spring[j])) out.K.hold(last, j);
    else out.K.add_diagonal(last, j, sys.right_spring[j]);
  }
  return out;
}

int count_below(const LineSystem& sys, double lambda) { return assemble(sys, lambda).K.inertia().negative; }

std::vector<double> slice_spectrum(const std::function<int(double)>& count, int k, double lambda_lo,
                                   double lambda_hint, double rel_tol, SliceStats* stats) {
  std::vector<double> out;
  if (k <= 0) return out;
  long evals = 0;
  auto N = [&](double lam) {
    ++evals;
    return count(lam);
  };
  const int n_lo = N(lambda_lo);
  const int want = n_lo + k;
  double hi = std::max(std::abs(lambda_hint), std::abs(lambda_lo));
  if (!(hi > lambda_lo)) hi = lambda_lo + std::abs(lambda_hint);
  int n_hi = N(hi);
  for (int grow = 0; n_hi < want; ++grow) {
    if (grow > 400 || !std::isfinite(hi))
      throw std::runtime_error("spectrum slicing: could not bracket " + std::to_string(k) + " eigenvalues");
    hi = lambda_lo + 2.0 * (hi - lambda_lo);
    n_hi = N(hi);
  }
  const double abs_tol = rel_tol * 1e-8 * std::abs(lambda_hint);
  struct Interval { double lo, hi; int n_lo, n_hi; };
  std::vector<Interval> stack = {{lambda_lo, hi, n_lo, n_hi}};
  std::vector<std::pair<double, int>> found;  // value, multiplicity
  while (!stack.empty()) {
    Interval iv = stack.back();
    stack.pop_back();
    if (iv.n_lo >= want || iv.n_hi == iv.n_lo) continue;
    const double width = iv.hi - iv.lo;
    if (width <= std::max(rel_tol * std::max(std::abs(iv.lo), std::abs(iv.hi)), abs_tol)) {
      found.emplace_back(0.5 * (iv.lo + iv.hi), std::min(iv.n_hi, want) - iv.n_lo);
      continue;
    }
    const double mid = 0.5 * (iv.lo + iv.hi);
    const int n_mid = N(mid);
    if (n_mid < iv.n_lo || n_mid > iv.n_hi)
      throw std::runtime_error("spectrum slicing: count is not monotonic (numerical breakdown near lambda = " +
                               std::to_string(mid) + ")");
    stack.push_back({mid, iv.hi, n_mid, iv.n_hi});
    stack.push_back({iv.lo, mid, iv.n_lo, n_mid});
  }
  std::sort(found.begin(), found.end());
  for (auto& [v, mult] : found)
    for (int j = 0; j < mult; ++j) out.push_back(v);
  out.resize(std::min<std::size_t>(out.size(), k));
  if (stats) stats->count_evaluations += evals;
  return out;
}

LineSpectrum lowest_eigenvalues(const LineSystem& sys, int k, double lambda_hint, SliceStats* stats) {
  LineSpectrum out;
  const double delta = kRigidThreshold * std::abs(lambda_hint);
  auto N = [&](double lam) { return count_below(sys, lam); };
  const int below = N(-delta);
  if (below != 0)
    throw std::runtime_error("the system has " + std::to_string(below) +
                             " negative eigenvalue(s) omega^2 < 0: it is unstable, not a vibrating structure");
  out.rigid = std::min(N(delta), k);
  out.lambdas.assign(out.rigid, 0.0);
  auto rest = slice_spectrum(N, k - out.rigid, delta, lambda_hint, 1e-13, stats);
  out.lambdas.insert(out.lambdas.end(), rest.begin(), rest.end());
  if (stats) stats->count_evaluations += 2;
  return out;
}

namespace {

/// Brent's method (zeroin) on g over [a, b] with g(a), g(b) of opposite signs; stops early
/// when `stalled` becomes true (g reached its rounding floor).
template <class G>
double brent_root(G&& g, double a, double b, double ga, double gb, double tol, const bool& stalled) {
  double c = a, gc = ga, d = b - a, e = d;
  for (int iter = 0; iter < 200; ++iter) {
    if ((gb > 0) == (gc > 0)) {
      c = a;
      gc = ga;
      d = e = b - a;
    }
    if (std::abs(gc) < std::abs(gb)) {
      a = b; b = c; c = a;
      ga = gb; gb = gc; gc = ga;
    }
    const double tol1 = 4.0 * std::numeric_limits<double>::epsilon() * std::abs(b) + 0.5 * tol;
    const double xm = 0.5 * (c - b);
    if (std::abs(xm) <= tol1 || gb == 0.0) return b;
    if (std::abs(e) >= tol1 && std::abs(ga) > std::abs(gb)) {
      const double s = gb / ga;
      double p, q;
      if (a == c) {
        p = 2.0 * xm * s;
        q = 1.0 - s;
      } else {
        const double qq = ga / gc, r = gb / gc;
        p = s * (2.0 * xm * qq * (qq - r) - (b - a) * (r - 1.0));
        q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
      }
      if (p > 0) q = -q;
      p = std::abs(p);
      if (2.0 * p < std::min(3.0 * xm * q - std::abs(tol1 * q), std::abs(e * q))) {
        e = d;
        d = p / q;
      } else {
        d = xm;
        e = d;
      }
    } else {
      d = xm;
      e = d;
    }
    a = b;
    ga = gb;
    b += std::abs(d) > tol1 ? d : (xm > 0 ? tol1 : -tol1);
    gb = g(b);
    if (stalled) return b;
  }
  return b;
}

}  // namespace

std::vector<double> slice_interval_polished(const std::function<CountDet(double)>& eval, double lambda_lo,
                                            double lambda_hi, double rel_tol, double abs_tol, SliceStats* stats) {
  std::vector<double> out;
  if (!(lambda_hi > lambda_lo)) return out;
  long evals = 0;
  auto E = [&](double lam) {
    ++evals;
    return eval(lam);
  };
  struct Interval {
    double lo, hi;
    CountDet a, b;
  };
  std::vector<Interval> stack = {{lambda_lo, lambda_hi, E(lambda_lo), E(lambda_hi)}};
  if (stack[0].b.count < stack[0].a.count)
    throw std::runtime_error("spectrum slicing: count decreases between lambda_lo and lambda_hi");
  auto narrow = [&](double lo, double hi) {
    return hi - lo <= std::max(rel_tol * std::max(std::abs(lo), std::abs(hi)), abs_tol);
  };
  std::vector<std::pair<double, int>> found;
  while (!stack.empty()) {
    Interval iv = stack.back();
    stack.pop_back();
    const int n = iv.b.count - iv.a.count;
    if (n <= 0) continue;
    if (narrow(iv.lo, iv.hi)) {
      found.emplace_back(0.5 * (iv.lo + iv.hi), n);
      continue;
    }
    if (n == 1 && std::isfinite(iv.a.log_abs_det) && std::isfinite(iv.b.log_abs_det)) {
      // Isolated: the signed determinant changes sign exactly once in (lo, hi).
      const int n_lo = iv.a.count;
      const double ref = std::max(iv.a.log_abs_det, iv.b.log_abs_det);
      auto signed_det = [&](const CountDet& cd) {
        if (cd.count != n_lo && cd.count != n_lo + 1)
          throw std::runtime_error("spectrum slicing: count is not monotonic (numerical breakdown)");
        const double mag = std::exp(std::clamp(cd.log_abs_det - ref, -600.0, 600.0));
        return cd.count == n_lo ? mag : -mag;
      };
      // Near the root the determinant reaches its rounding floor: the same value again at a
      // different lambda means further steps only sample noise.
      bool stalled = false;
      std::vector<double> seen = {iv.a.log_abs_det, iv.b.log_abs_det};
      auto g = [&](double lam) {
        const CountDet cd = E(lam);
        if (std::find(seen.begin(), seen.end(), cd.log_abs_det) != seen.end()) stalled = true;
        seen.push_back(cd.log_abs_det);
        return signed_det(cd);
      };
      const double tol = std::max(rel_tol * std::max(std::abs(iv.lo), std::abs(iv.hi)), abs_tol);
      const double root = brent_root(g, iv.lo, iv.hi, signed_det(iv.a), signed_det(iv.b), tol, stalled);
      found.emplace_back(std::clamp(root, iv.lo, iv.hi), 1);
      continue;
    }
    const double mid = 0.5 * (iv.lo + iv.hi);
    const CountDet cm = E(mid);
    if (cm.count < iv.a.count || cm.count > iv.b.count)
      throw std::runtime_error("spectrum slicing: count is not monotonic (numerical breakdown near lambda = " +
                               std::to_string(mid) + ")");
    stack.push_back({mid, iv.hi, cm, iv.b});
    stack.push_back({iv.lo, mid, iv.a, cm});
  }
  std::sort(found.begin(), found.end());
  for (auto& [v, mult] : found)
    for (int j = 0; j < mult; ++j) out.push_back(v);
  if (stats) stats->count_evaluations += evals;
  return out;
}

// ---- Long segments by doubling

namespace {
/// One doubling step on a symmetric segment matrix [K11 K12; K12^T K22] in place:
/// condense the middle node of two copies. `X` and `rhs` are work space.
template <class Mat, class Solver>
void double_in_place(Mat& K, const Solver& solve, Eigen::Index m, Mat& rhs, Mat& X) {
  rhs.resize(m, 2 * m);
  rhs.leftCols(m) = K.bottomLeftCorner(m, m);  // K21
  rhs.rightCols(m) = K.topRightCorner(m, m);   // K12
  X = solve(rhs);                              // [S^-1 K21, S^-1 K12]
  Mat out(2 * m, 2 * m);
  out.topLeftCorner(m, m) = K.topLeftCorner(m, m);
  out.topLeftCorner(m, m).noalias() -= K.topRightCorner(m, m) * X.leftCols(m);
  out.topRightCorner(m, m).noalias() = -K.topRightCorner(m, m) * X.rightCols(m);
  out.bottomLeftCorner(m, m).noalias() = -K.bottomLeftCorner(m, m) * X.leftCols(m);
  out.bottomRightCorner(m, m) = K.bottomRightCorner(m, m);
  out.bottomRightCorner(m, m).noalias() -= K.bottomLeftCorner(m, m) * X.rightCols(m);
  K = 0.5 * (out + out.transpose());
}
}  // namespace

LongSegment long_segment_dynamic_stiffness(const Eigen::MatrixXd& A, double h, int levels) {
  if (levels < 0) throw std::invalid_argument("long_segment_dynamic_stiffness: levels must be >= 0");
  LongSegment out;
  out.K = segment_dynamic_stiffness(A, std::ldexp(h, -levels), &out.asymmetry, &out.log_abs_det_tdf);
  const Eigen::Index m = out.K.rows() / 2;
  Eigen::MatrixXd rhs, X;
  for (int level = 0; level < levels; ++level) {
    const SymFactor f(Eigen::MatrixXd(out.K.bottomRightCorner(m, m) + out.K.topLeftCorner(m, m)));
    out.clamped_below = 2 * out.clamped_below + f.negative;
    out.log_abs_det_tdf = 2 * out.log_abs_det_tdf + f.log_abs;
    if (f.max_abs > 0) out.min_pivot_rel = std::min(out.min_pivot_rel, f.min_abs / f.max_abs);
    double_in_place(out.K, [&](const Eigen::MatrixXd& B) { return f.solve(B); }, m, rhs, X);
  }
  return out;
}

LongSegmentC long_segment_dynamic_stiffness(const Eigen::MatrixXcd& A, double h, int levels) {
  if (levels < 0) throw std::invalid_argument("long_segment_dynamic_stiffness: levels must be >= 0");
  LongSegmentC out;
  out.K = segment_dynamic_stiffness(A, std::ldexp(h, -levels), &out.asymmetry);
  const Eigen::Index m = out.K.rows() / 2;
  Eigen::MatrixXcd rhs, X;
  for (int level = 0; level < levels; ++level) {
    const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(Eigen::MatrixXcd(out.K.bottomRightCorner(m, m) + out.K.topLeftCorner(m, m)));
    // Pivot ratio as a cheap near-singularity indicator (rcond would cost extra solves).
    const Eigen::VectorXcd d = lu.matrixLU().diagonal();
    double lo = std::numeric_limits<double>::infinity(), hi = 0;
    for (Eigen::Index i = 0; i < d.size(); ++i) {
      const double a = std::abs(d[i].real()) + std::abs(d[i].imag());
      lo = std::min(lo, a);
      hi = std::max(hi, a);
    }
    if (hi > 0) out.min_pivot_rel = std::min(out.min_pivot_rel, lo / hi);
    double_in_place(out.K, [&](const Eigen::MatrixXcd& B) { return Eigen::MatrixXcd(lu.solve(B)); }, m, rhs, X);
  }
  return out;
}

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
