#include "supernodal_ldlt.hpp"

#include <cholmod.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <future>
#include <numeric>
#include <stdexcept>

namespace modalbench::rfem::detail {

namespace {
// Eigen's dense kernels, not the BLAS: the two threads call them at once, and OpenBLAS 0.3.21's
// level 3 from two threads gave wrong factors (the Mindlin plate, 168 x 120: "not positive
// definite" at a shift below the spectrum; right with the same calls on one thread).
using Stride = Eigen::OuterStride<>;

/// Unblocked LDL' of the leading nscol x nscol block of a supernode (column-major, leading
/// dimension ld), in place: L below the diagonal, 1 on it, D out. False at a zero or non-finite pivot.
bool factor_diagonal_block(double* a, int nscol, int ld, double* d, std::vector<double>& w) {
  w.resize(static_cast<std::size_t>(nscol));
  for (int j = 0; j < nscol; ++j) {
    double* cj = a + static_cast<std::ptrdiff_t>(j) * ld;
    double dj = cj[j];
    for (int k = 0; k < j; ++k) {
      const double* ck = a + static_cast<std::ptrdiff_t>(k) * ld;
      const double wk = ck[j] * d[k];
      dj -= wk * ck[j];
      for (int i = j + 1; i < nscol; ++i) cj[i] -= ck[i] * wk;
    }
    if (!(dj != 0.0) || !std::isfinite(dj)) return false;
    d[j] = dj;
    cj[j] = 1.0;
    for (int i = j + 1; i < nscol; ++i) cj[i] /= dj;
  }
  return true;
}
}  // namespace

SupernodalLdlt::SupernodalLdlt() = default;
SupernodalLdlt::~SupernodalLdlt() = default;

bool SupernodalLdlt::analyze(const Eigen::SparseMatrix<double>& upper) {
  if (!upper.isCompressed() || upper.rows() != upper.cols()) throw std::invalid_argument("SupernodalLdlt: square compressed matrix expected");
  const int n = static_cast<int>(upper.rows());
  n_ = n;
  super_.clear();
  if (n == 0) return false;
  cholmod_common c;
  cholmod_start(&c);
  c.print = 0;
  c.nmethods = 1;
  c.method[0].ordering = CHOLMOD_GIVEN;
  c.postorder = 0;  // the order is the caller's: every multiplier after its primal unknowns
  c.supernodal = CHOLMOD_AUTO;
  cholmod_sparse A{};
  A.nrow = A.ncol = static_cast<std::size_t>(n);
  A.nzmax = static_cast<std::size_t>(upper.nonZeros());
  A.p = const_cast<int*>(upper.outerIndexPtr());
  A.i = const_cast<int*>(upper.innerIndexPtr());
  A.x = nullptr;
  A.stype = 1;
  A.itype = CHOLMOD_INT;
  A.xtype = CHOLMOD_PATTERN;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;
  std::vector<int> natural(static_cast<std::size_t>(n));
  std::iota(natural.begin(), natural.end(), 0);
  cholmod_factor* L = cholmod_analyze_p(&A, natural.data(), nullptr, 0, &c);
  bool usable = L != nullptr && L->is_super;
  if (usable) {
    const int* perm = static_cast<const int*>(L->Perm);
    for (int k = 0; k < n && usable; ++k) usable = perm[k] == k;
  }
  if (usable) {
    const auto ns = static_cast<std::ptrdiff_t>(L->nsuper);
    const int* sup = static_cast<const int*>(L->super);
    const int* pi = static_cast<const int*>(L->pi);
    const int* px = static_cast<const int*>(L->px);
    const int* s = static_cast<const int*>(L->s);
    super_.assign(sup, sup + ns + 1);
    pi_.assign(pi, pi + ns + 1);
    px_.assign(px, px + ns + 1);
    rows_.assign(s, s + pi[ns]);
    Lx_.assign(static_cast<std::size_t>(px[ns]), 0.0);
  }
  if (L) cholmod_free_factor(&L, &c);
  cholmod_finish(&c);
  if (!usable) {
    super_.clear();
    return false;
  }
  const auto nsuper = static_cast<int>(super_.size()) - 1;
  column_super_.assign(static_cast<std::size_t>(n), 0);
  max_update_ = 0;
  for (int s = 0; s < nsuper; ++s) {
    for (int j = super_[s]; j < super_[s + 1]; ++j) column_super_[static_cast<std::size_t>(j)] = s;
    max_update_ = std::max(max_update_, pi_[s + 1] - pi_[s]);
  }
  // The lower triangle by columns: upper entry (r, c), r <= c, is A(c, r), in column r.
  low_start_.assign(static_cast<std::size_t>(n) + 1, 0);
  for (int p = 0; p < upper.nonZeros(); ++p) ++low_start_[static_cast<std::size_t>(upper.innerIndexPtr()[p]) + 1];
  for (int j = 0; j < n; ++j) low_start_[static_cast<std::size_t>(j) + 1] += low_start_[static_cast<std::size_t>(j)];
  low_row_.resize(static_cast<std::size_t>(upper.nonZeros()));
  low_src_.resize(static_cast<std::size_t>(upper.nonZeros()));
  std::vector<int> fill(low_start_.begin(), low_start_.end() - 1);
  for (int col = 0; col < n; ++col)
    for (int p = upper.outerIndexPtr()[col]; p < upper.outerIndexPtr()[col + 1]; ++p) {
      const auto q = static_cast<std::size_t>(fill[static_cast<std::size_t>(upper.innerIndexPtr()[p])]++);
      low_row_[q] = col;
      low_src_[q] = p;
    }
  D_.resize(n);
  plan_split();
  return true;
}

void SupernodalLdlt::plan_split() {
  const int nsuper = static_cast<int>(super_.size()) - 1;
  std::vector<int> parent(static_cast<std::size_t>(nsuper), -1);
  std::vector<std::vector<int>> children(static_cast<std::size_t>(nsuper));
  std::vector<double> weight(static_cast<std::size_t>(nsuper), 0.0);
  std::vector<int> roots;
  for (int s = 0; s < nsuper; ++s) {
    const int nscol = super_[s + 1] - super_[s], nsrow = pi_[s + 1] - pi_[s];
    weight[static_cast<std::size_t>(s)] += static_cast<double>(nsrow) * nscol;
    if (nsrow > nscol) {
      const int p = column_super_[static_cast<std::size_t>(rows_[static_cast<std::size_t>(pi_[s] + nscol)])];
      parent[static_cast<std::size_t>(s)] = p;
      children[static_cast<std::size_t>(p)].push_back(s);
      weight[static_cast<std::size_t>(p)] += weight[static_cast<std::size_t>(s)];
    } else {
      roots.push_back(s);
    }
  }
  double total = 0;
  for (int r : roots) total += weight[static_cast<std::size_t>(r)];
  // Down the chain of single children from the root: the separators; then the subtrees below it,
  // heaviest first, each to the lighter of the two threads.
  std::vector<char> part(static_cast<std::size_t>(nsuper), -1);
  std::vector<int> below = roots;
  while (below.size() == 1) {
    part[static_cast<std::size_t>(below[0])] = 0;
    below = children[static_cast<std::size_t>(below[0])];
  }
  std::sort(below.begin(), below.end(), [&](int a, int b) { return weight[static_cast<std::size_t>(a)] > weight[static_cast<std::size_t>(b)]; });
  double load[2] = {0, 0};
  for (int c : below) {
    const int k = load[0] <= load[1] ? 0 : 1;
    part[static_cast<std::size_t>(c)] = static_cast<char>(k + 1);
    load[k] += weight[static_cast<std::size_t>(c)];
  }
  for (int s = nsuper - 1; s >= 0; --s)
    if (part[static_cast<std::size_t>(s)] < 0) part[static_cast<std::size_t>(s)] = part[static_cast<std::size_t>(parent[static_cast<std::size_t>(s)])];
  // Worth a thread where both shares are a fifth of the factor or more, and the factor is large
  // enough for the solve to outlast starting one (a Mindlin plate of 84 x 60 fragments and up;
  // 56 x 40 is below).
  split_ = total >= 1e6 && std::min(load[0], load[1]) >= 0.2 * total;
  for (auto& v : part_) v.clear();
  top_column_.assign(static_cast<std::size_t>(n_), 0);
  if (!split_) {  // one part, every supernode
    part_[0].resize(static_cast<std::size_t>(nsuper));
    std::iota(part_[0].begin(), part_[0].end(), 0);
    return;
  }
  for (int s = 0; s < nsuper; ++s) {
    part_[static_cast<std::size_t>(part[static_cast<std::size_t>(s)])].push_back(s);
    if (part[static_cast<std::size_t>(s)] == 0)
      for (int j = super_[s]; j < super_[s + 1]; ++j) top_column_[static_cast<std::size_t>(j)] = 1;
  }
  for (auto& share : top_share_) share.assign(static_cast<std::size_t>(n_), 0.0);
}

/// The lists of the left-looking factorization: every finished supernode d waits in the list of
/// the supernode its next rows (from lpos[d] on) belong to, until that one takes its update. Each
/// thread links into lists of its own (`head` of the part it runs); `next` and `lpos` are per
/// supernode, written only by the thread that owns it.
struct SupernodalLdlt::Lists {
  std::vector<int> head[3], next, lpos;
};

/// The factorization's scratch space of one thread.
struct SupernodalLdlt::Scratch {
  std::vector<int> map;
  Aligned W, C;
  std::vector<double> w;
};

bool SupernodalLdlt::factor_part(const std::vector<int>& part, int own, const double* av, Lists& l, Scratch& ws) {
  std::vector<int>& head = l.head[own];
  auto link = [&](int d) {  // d joins the list of the supernode of its next row below lpos
    const int row_at = pi_[d] + l.lpos[static_cast<std::size_t>(d)];
    if (row_at >= pi_[d + 1]) return;
    const int anc = column_super_[static_cast<std::size_t>(rows_[static_cast<std::size_t>(row_at)])];
    l.next[static_cast<std::size_t>(d)] = head[static_cast<std::size_t>(anc)];
    head[static_cast<std::size_t>(anc)] = d;
  };
  std::vector<int>& map = ws.map;
  for (int s : part) {
    const int k1 = super_[s], k2 = super_[s + 1], nscol = k2 - k1;
    const int psi = pi_[s], nsrow = pi_[s + 1] - psi;
    double* Ls = Lx_.data() + px_[s];
    for (int k = 0; k < nsrow; ++k) map[static_cast<std::size_t>(rows_[static_cast<std::size_t>(psi + k)])] = k;
    std::fill(Ls, Ls + static_cast<std::ptrdiff_t>(nsrow) * nscol, 0.0);
    for (int j = k1; j < k2; ++j)
      for (int p = low_start_[static_cast<std::size_t>(j)]; p < low_start_[static_cast<std::size_t>(j) + 1]; ++p)
        Ls[static_cast<std::ptrdiff_t>(j - k1) * nsrow + map[static_cast<std::size_t>(low_row_[static_cast<std::size_t>(p)])]] +=
            av[low_src_[static_cast<std::size_t>(p)]];
    // Updates from every descendant whose pattern reaches these columns (a separator's come from
    // the lists of all three parts; a subtree's from its own).
    for (int from = 0; from < 3; ++from) {
      if (from != own && own != 0) continue;
      for (int d = l.head[from][static_cast<std::size_t>(s)]; d >= 0;) {
        const int dnext = l.next[static_cast<std::size_t>(d)];
        const int ndcol = super_[d + 1] - super_[d], pdi = pi_[d], ndrow = pi_[d + 1] - pdi;
        const int pdi1 = pdi + l.lpos[static_cast<std::size_t>(d)];
        int pdi2 = pdi1;
        while (pdi2 < pdi + ndrow && rows_[static_cast<std::size_t>(pdi2)] < k2) ++pdi2;
        const int ndrow1 = pdi2 - pdi1, ndrow2 = pdi + ndrow - pdi1;
        const double* Ld = Lx_.data() + px_[d] + (pdi1 - pdi);
        const double* Dd = D_.data() + super_[d];
        ws.W.resize(static_cast<std::size_t>(ndrow1) * static_cast<std::size_t>(ndcol));
        for (int k = 0; k < ndcol; ++k)
          for (int i = 0; i < ndrow1; ++i)
            ws.W[static_cast<std::size_t>(k) * static_cast<std::size_t>(ndrow1) + static_cast<std::size_t>(i)] =
                Ld[static_cast<std::ptrdiff_t>(k) * ndrow + i] * Dd[k];
        ws.C.resize(static_cast<std::size_t>(ndrow2) * static_cast<std::size_t>(ndrow1));
        {
          const Eigen::Map<const Eigen::MatrixXd, 0, Stride> A(Ld, ndrow2, ndcol, Stride(ndrow));
          const Eigen::Map<const Eigen::MatrixXd> B(ws.W.data(), ndrow1, ndcol);
          Eigen::Map<Eigen::MatrixXd> Cm(ws.C.data(), ndrow2, ndrow1);
          Cm.noalias() = A * B.transpose();
        }
        for (int j = 0; j < ndrow1; ++j) {
          double* target = Ls + static_cast<std::ptrdiff_t>(rows_[static_cast<std::size_t>(pdi1 + j)] - k1) * nsrow;
          const double* cj = ws.C.data() + static_cast<std::ptrdiff_t>(j) * ndrow2;
          for (int i = j; i < ndrow2; ++i) target[map[static_cast<std::size_t>(rows_[static_cast<std::size_t>(pdi1 + i)])]] -= cj[i];
        }
        l.lpos[static_cast<std::size_t>(d)] = pdi2 - pdi;
        link(d);
        d = dnext;
      }
    }
    if (!factor_diagonal_block(Ls, nscol, nsrow, D_.data() + k1, ws.w)) return false;
    if (const int nrest = nsrow - nscol; nrest > 0) {
      {
        const Eigen::Map<const Eigen::MatrixXd, 0, Stride> L11(Ls, nscol, nscol, Stride(nsrow));
        Eigen::Map<Eigen::MatrixXd, 0, Stride> L21(Ls + nscol, nrest, nscol, Stride(nsrow));
        L11.triangularView<Eigen::UnitLower>().transpose().solveInPlace<Eigen::OnTheRight>(L21);
      }
      for (int j = 0; j < nscol; ++j) {
        double* cj = Ls + static_cast<std::ptrdiff_t>(j) * nsrow + nscol;
        const double inv = 1.0 / D_[k1 + j];
        for (int i = 0; i < nrest; ++i) cj[i] *= inv;
      }
    }
    l.lpos[static_cast<std::size_t>(s)] = nscol;
    link(s);
  }
  return true;
}

bool SupernodalLdlt::factorize(const Eigen::SparseMatrix<double>& upper) {
  if (super_.empty()) throw std::logic_error("SupernodalLdlt::factorize without a supernodal analysis");
  if (upper.rows() != n_ || upper.nonZeros() != static_cast<long>(low_row_.size()))
    throw std::invalid_argument("SupernodalLdlt: matrix pattern differs from the analysed one");
  const auto nsuper = super_.size() - 1;
  const double* av = upper.valuePtr();
  Lists l;
  for (auto& h : l.head) h.assign(nsuper, -1);
  l.next.assign(nsuper, -1);
  l.lpos.assign(nsuper, 0);
  Scratch main, second;
  main.map.assign(static_cast<std::size_t>(n_), 0);
  if (split_) {
    // The two subtrees side by side (each reads and writes only its own supernodes, links into its
    // own lists), the separators after.
    second.map.assign(static_cast<std::size_t>(n_), 0);
    auto other = std::async(std::launch::async, [&] { return factor_part(part_[2], 2, av, l, second); });
    const bool ok1 = factor_part(part_[1], 1, av, l, main);
    if (!other.get() || !ok1) return false;
  }
  return factor_part(part_[0], 0, av, l, main);
}

void SupernodalLdlt::forward(const std::vector<int>& part, double* x, double* t, double* top) const {
  for (int s : part) {
    const int k1 = super_[s], nscol = super_[s + 1] - k1, psi = pi_[s], nsrow = pi_[s + 1] - psi, nrest = nsrow - nscol;
    const double* Ls = Lx_.data() + px_[s];
    const Eigen::Map<const Eigen::MatrixXd, 0, Stride> L11(Ls, nscol, nscol, Stride(nsrow));
    Eigen::Map<Eigen::VectorXd> xs(x + k1, nscol);
    L11.triangularView<Eigen::UnitLower>().solveInPlace(xs);
    if (nrest == 0) continue;
    const Eigen::Map<const Eigen::MatrixXd, 0, Stride> L21(Ls + nscol, nrest, nscol, Stride(nsrow));
    Eigen::Map<Eigen::VectorXd>(t, nrest).noalias() = L21 * xs;
    const int* below = rows_.data() + psi + nscol;
    if (top)  // a subtree's thread: its share for the separators kept apart
      for (int i = 0; i < nrest; ++i) (top_column_[static_cast<std::size_t>(below[i])] ? top[below[i]] : x[below[i]]) -= t[i];
    else
      for (int i = 0; i < nrest; ++i) x[below[i]] -= t[i];
  }
}

void SupernodalLdlt::backward(const std::vector<int>& part, double* x, double* t) const {
  for (auto it = part.rbegin(); it != part.rend(); ++it) {
    const int s = *it;
    const int k1 = super_[s], nscol = super_[s + 1] - k1, psi = pi_[s], nsrow = pi_[s + 1] - psi, nrest = nsrow - nscol;
    const double* Ls = Lx_.data() + px_[s];
    Eigen::Map<Eigen::VectorXd> xs(x + k1, nscol);
    if (nrest > 0) {
      for (int i = 0; i < nrest; ++i) t[i] = x[rows_[static_cast<std::size_t>(psi + nscol + i)]];
      const Eigen::Map<const Eigen::MatrixXd, 0, Stride> L21(Ls + nscol, nrest, nscol, Stride(nsrow));
      xs.noalias() -= L21.transpose() * Eigen::Map<const Eigen::VectorXd>(t, nrest);
    }
    const Eigen::Map<const Eigen::MatrixXd, 0, Stride> L11(Ls, nscol, nscol, Stride(nsrow));
    L11.triangularView<Eigen::UnitLower>().transpose().solveInPlace(xs);
  }
}

void SupernodalLdlt::solve_in_place(double* x) const {
  const auto m = static_cast<std::size_t>(std::max(max_update_, 1));
  work_.resize(m);
  std::future<void> other;
  if (split_) {
    // The two subtrees side by side (they touch no column of each other's), the separators after.
    work2_.resize(m);
    other = std::async(std::launch::async, [&] { forward(part_[2], x, work2_.data(), top_share_[1].data()); });
    forward(part_[1], x, work_.data(), top_share_[0].data());
    other.get();
    for (long j = 0; j < n_; ++j)
      if (top_column_[static_cast<std::size_t>(j)]) {
        x[j] += top_share_[0][static_cast<std::size_t>(j)] + top_share_[1][static_cast<std::size_t>(j)];
        top_share_[0][static_cast<std::size_t>(j)] = top_share_[1][static_cast<std::size_t>(j)] = 0.0;
      }
  }
  forward(part_[0], x, work_.data(), nullptr);
  for (long i = 0; i < n_; ++i) x[i] /= D_[i];
  backward(part_[0], x, work_.data());
  if (split_) {
    other = std::async(std::launch::async, [&] { backward(part_[2], x, work2_.data()); });
    backward(part_[1], x, work_.data());
    other.get();
  }
}

}  // namespace modalbench::rfem::detail
