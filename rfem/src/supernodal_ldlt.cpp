#include "supernodal_ldlt.hpp"

#include <cholmod.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

extern "C" {
void dgemm_(const char* ta, const char* tb, const int* m, const int* n, const int* k, const double* alpha, const double* a,
            const int* lda, const double* b, const int* ldb, const double* beta, double* c, const int* ldc);
void dtrsm_(const char* side, const char* uplo, const char* ta, const char* diag, const int* m, const int* n,
            const double* alpha, const double* a, const int* lda, double* b, const int* ldb);
void dgemv_(const char* t, const int* m, const int* n, const double* alpha, const double* a, const int* lda,
            const double* x, const int* incx, const double* beta, double* y, const int* incy);
void dtrsv_(const char* uplo, const char* trans, const char* diag, const int* n, const double* a, const int* lda, double* x,
            const int* incx);
}

namespace modalbench::rfem::detail {

namespace {
const int kOne = 1;
const double kPlus = 1.0, kZero = 0.0, kMinus = -1.0;

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
  return true;
}

bool SupernodalLdlt::factorize(const Eigen::SparseMatrix<double>& upper) {
  if (super_.empty()) throw std::logic_error("SupernodalLdlt::factorize without a supernodal analysis");
  if (upper.rows() != n_ || upper.nonZeros() != static_cast<long>(low_row_.size()))
    throw std::invalid_argument("SupernodalLdlt: matrix pattern differs from the analysed one");
  const int nsuper = static_cast<int>(super_.size()) - 1;
  const double* av = upper.valuePtr();
  std::vector<int> map(static_cast<std::size_t>(n_), 0), head(static_cast<std::size_t>(nsuper), -1),
      next(static_cast<std::size_t>(nsuper), -1), lpos(static_cast<std::size_t>(nsuper), 0);
  std::vector<double> W, C, w;
  auto link = [&](int d) {  // d joins the list of the supernode of its next row below lpos
    const int row_at = pi_[d] + lpos[static_cast<std::size_t>(d)];
    if (row_at >= pi_[d + 1]) return;
    const int anc = column_super_[static_cast<std::size_t>(rows_[static_cast<std::size_t>(row_at)])];
    next[static_cast<std::size_t>(d)] = head[static_cast<std::size_t>(anc)];
    head[static_cast<std::size_t>(anc)] = d;
  };
  for (int s = 0; s < nsuper; ++s) {
    const int k1 = super_[s], k2 = super_[s + 1], nscol = k2 - k1;
    const int psi = pi_[s], nsrow = pi_[s + 1] - psi;
    double* Ls = Lx_.data() + px_[s];
    for (int k = 0; k < nsrow; ++k) map[static_cast<std::size_t>(rows_[static_cast<std::size_t>(psi + k)])] = k;
    std::fill(Ls, Ls + static_cast<std::ptrdiff_t>(nsrow) * nscol, 0.0);
    for (int j = k1; j < k2; ++j)
      for (int p = low_start_[static_cast<std::size_t>(j)]; p < low_start_[static_cast<std::size_t>(j) + 1]; ++p)
        Ls[static_cast<std::ptrdiff_t>(j - k1) * nsrow + map[static_cast<std::size_t>(low_row_[static_cast<std::size_t>(p)])]] +=
            av[low_src_[static_cast<std::size_t>(p)]];
    // Updates from every descendant whose pattern reaches these columns.
    for (int d = head[static_cast<std::size_t>(s)]; d >= 0;) {
      const int dnext = next[static_cast<std::size_t>(d)];
      const int ndcol = super_[d + 1] - super_[d], pdi = pi_[d], ndrow = pi_[d + 1] - pdi;
      const int pdi1 = pdi + lpos[static_cast<std::size_t>(d)];
      int pdi2 = pdi1;
      while (pdi2 < pdi + ndrow && rows_[static_cast<std::size_t>(pdi2)] < k2) ++pdi2;
      const int ndrow1 = pdi2 - pdi1, ndrow2 = pdi + ndrow - pdi1;
      const double* Ld = Lx_.data() + px_[d] + (pdi1 - pdi);
      const double* Dd = D_.data() + super_[d];
      W.resize(static_cast<std::size_t>(ndrow1) * static_cast<std::size_t>(ndcol));
      for (int k = 0; k < ndcol; ++k)
        for (int i = 0; i < ndrow1; ++i)
          W[static_cast<std::size_t>(k) * static_cast<std::size_t>(ndrow1) + static_cast<std::size_t>(i)] =
              Ld[static_cast<std::ptrdiff_t>(k) * ndrow + i] * Dd[k];
      C.resize(static_cast<std::size_t>(ndrow2) * static_cast<std::size_t>(ndrow1));
      dgemm_("N", "T", &ndrow2, &ndrow1, &ndcol, &kPlus, Ld, &ndrow, W.data(), &ndrow1, &kZero, C.data(), &ndrow2);
      for (int j = 0; j < ndrow1; ++j) {
        double* target = Ls + static_cast<std::ptrdiff_t>(rows_[static_cast<std::size_t>(pdi1 + j)] - k1) * nsrow;
        const double* cj = C.data() + static_cast<std::ptrdiff_t>(j) * ndrow2;
        for (int i = j; i < ndrow2; ++i) target[map[static_cast<std::size_t>(rows_[static_cast<std::size_t>(pdi1 + i)])]] -= cj[i];
      }
      lpos[static_cast<std::size_t>(d)] = pdi2 - pdi;
      link(d);
      d = dnext;
    }
    if (!factor_diagonal_block(Ls, nscol, nsrow, D_.data() + k1, w)) return false;
    if (const int nrest = nsrow - nscol; nrest > 0) {
      dtrsm_("R", "L", "T", "U", &nrest, &nscol, &kPlus, Ls, &nsrow, Ls + nscol, &nsrow);
      for (int j = 0; j < nscol; ++j) {
        double* cj = Ls + static_cast<std::ptrdiff_t>(j) * nsrow + nscol;
        const double inv = 1.0 / D_[k1 + j];
        for (int i = 0; i < nrest; ++i) cj[i] *= inv;
      }
    }
    lpos[static_cast<std::size_t>(s)] = nscol;
    link(s);
  }
  return true;
}

void SupernodalLdlt::solve_in_place(double* x) const {
  const int nsuper = static_cast<int>(super_.size()) - 1;
  work_.resize(static_cast<std::size_t>(std::max(max_update_, 1)));
  double* t = work_.data();
  for (int s = 0; s < nsuper; ++s) {
    const int k1 = super_[s], nscol = super_[s + 1] - k1, psi = pi_[s], nsrow = pi_[s + 1] - psi, nrest = nsrow - nscol;
    const double* Ls = Lx_.data() + px_[s];
    dtrsv_("L", "N", "U", &nscol, Ls, &nsrow, x + k1, &kOne);
    if (nrest == 0) continue;
    dgemv_("N", &nrest, &nscol, &kPlus, Ls + nscol, &nsrow, x + k1, &kOne, &kZero, t, &kOne);
    for (int i = 0; i < nrest; ++i) x[rows_[static_cast<std::size_t>(psi + nscol + i)]] -= t[i];
  }
  for (long i = 0; i < n_; ++i) x[i] /= D_[i];
  for (int s = nsuper - 1; s >= 0; --s) {
    const int k1 = super_[s], nscol = super_[s + 1] - k1, psi = pi_[s], nsrow = pi_[s + 1] - psi, nrest = nsrow - nscol;
    const double* Ls = Lx_.data() + px_[s];
    if (nrest > 0) {
      for (int i = 0; i < nrest; ++i) t[i] = x[rows_[static_cast<std::size_t>(psi + nscol + i)]];
      dgemv_("T", &nrest, &nscol, &kMinus, Ls + nscol, &nsrow, t, &kOne, &kPlus, x + k1, &kOne);
    }
    dtrsv_("L", "T", "U", &nscol, Ls, &nsrow, x + k1, &kOne);
  }
}

}  // namespace modalbench::rfem::detail
