#include "modalbench/rfem/factor.hpp"

#include "analysis_detail.hpp"
#include "supernodal_ldlt.hpp"

#include <amd.h>

#include <Eigen/CholmodSupport>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

extern "C" void dtrsv_(const char* uplo, const char* trans, const char* diag, const int* n, const double* a,
                       const int* lda, double* x, const int* incx);

namespace modalbench::rfem {

namespace detail {
void reserve_blas_workspace() {
  static thread_local bool done = false;
  if (done) return;
  done = true;
  // A triangular solve takes the buffer whatever its size (level 3 has a buffer-free small path).
  const int n = 1, inc = 1;
  const double a = 1;
  double x = 1;
  dtrsv_("U", "N", "N", &n, &a, &n, &x, &inc);
}
}  // namespace detail

namespace {
using Triplet = Eigen::Triplet<double>;
using Perm = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;

/// Permutation P with P.indices()[old] = new for an elimination order.
Perm permutation_of(const Eigen::VectorXi& order) {
  Perm P(order.size());
  for (int k = 0; k < order.size(); ++k) P.indices()[order[k]] = k;
  return P;
}
}  // namespace

Eigen::VectorXi amd_order(const SpMat& pattern, const std::vector<int>& groups) {
  const int n = static_cast<int>(pattern.rows());
  Eigen::VectorXi order(n);
  if (n == 0) return order;
  if (!groups.empty() && static_cast<int>(groups.size()) != n) throw std::invalid_argument("amd_order: one group per unknown");
  const int ng = groups.empty() ? n : *std::max_element(groups.begin(), groups.end()) + 1;
  SpMat Q;
  if (groups.empty()) {
    Q = pattern;
  } else {
    std::vector<Triplet> t;
    t.reserve(static_cast<std::size_t>(pattern.nonZeros()));
    for (int j = 0; j < pattern.outerSize(); ++j)
      for (SpMat::InnerIterator it(pattern, j); it; ++it)
        t.emplace_back(groups[static_cast<std::size_t>(it.row())], groups[static_cast<std::size_t>(j)], 1.0);
    Q.resize(ng, ng);
    Q.setFromTriplets(t.begin(), t.end());
  }
  Q.makeCompressed();
  Eigen::VectorXi qorder(ng);
  double control[AMD_CONTROL], info[AMD_INFO];
  amd_defaults(control);
  const int status = ::amd_order(ng, Q.outerIndexPtr(), Q.innerIndexPtr(), qorder.data(), control, info);
  if (status != AMD_OK && status != AMD_OK_BUT_JUMBLED) throw std::runtime_error("AMD ordering failed");
  if (groups.empty()) return qorder;
  // Expand: the groups in AMD's order, each group's unknowns in their own order.
  std::vector<int> start(static_cast<std::size_t>(ng) + 1, 0), members(static_cast<std::size_t>(n));
  for (int g : groups) ++start[static_cast<std::size_t>(g) + 1];
  for (int g = 0; g < ng; ++g) start[static_cast<std::size_t>(g) + 1] += start[static_cast<std::size_t>(g)];
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int i = 0; i < n; ++i) members[static_cast<std::size_t>(fill[static_cast<std::size_t>(groups[static_cast<std::size_t>(i)])]++)] = i;
  int k = 0;
  for (int q = 0; q < ng; ++q) {
    const auto g = static_cast<std::size_t>(qorder[q]);
    for (int p = start[g]; p < start[g + 1]; ++p) order[k++] = members[static_cast<std::size_t>(p)];
  }
  return order;
}

std::vector<long> dependent_rows(const SpMat& G) {
  std::vector<long> dep;
  const long m = static_cast<long>(G.rows());
  if (m == 0) return dep;
  SpMat GGt = G * G.transpose();
  const double delta = 1e-14;
  for (long i = 0; i < m; ++i) GGt.coeffRef(i, i) += delta;
  const Eigen::VectorXi order = amd_order(GGt);
  const Perm P = permutation_of(order);
  SpMat Gp;
  Gp = GGt.selfadjointView<Eigen::Lower>().twistedBy(P);
  Eigen::SimplicialLDLT<SpMat, Eigen::Lower, Eigen::NaturalOrdering<int>> ldlt(Gp);
  if (ldlt.info() != Eigen::Success) throw std::runtime_error("rfem: Gram matrix of the constraints not factorable");
  const Eigen::VectorXd& D = ldlt.vectorD();
  for (long k = 0; k < m; ++k)
    if (D[k] < 1e-10) dep.push_back(order[k]);
  std::sort(dep.begin(), dep.end());
  return dep;
}

namespace {
/// For every stored entry of `super` (CSC, sorted), the index of the same entry in `sub` (whose
/// pattern is contained in super's), or -1.
std::vector<int> entry_map(const SpMat& super, const SpMat& sub) {
  std::vector<int> map(static_cast<std::size_t>(super.nonZeros()), -1);
  for (int j = 0; j < super.outerSize(); ++j) {
    int q = sub.outerIndexPtr()[j];
    const int qend = sub.outerIndexPtr()[j + 1];
    for (int p = super.outerIndexPtr()[j]; p < super.outerIndexPtr()[j + 1]; ++p) {
      while (q < qend && sub.innerIndexPtr()[q] < super.innerIndexPtr()[p]) ++q;
      if (q < qend && sub.innerIndexPtr()[q] == super.innerIndexPtr()[p]) map[static_cast<std::size_t>(p)] = q;
    }
  }
  return map;
}
}  // namespace

KktLdlt::KktLdlt() : super_(std::make_unique<detail::SupernodalLdlt>()) {}
KktLdlt::~KktLdlt() = default;

bool KktLdlt::two_thread_solves() const { return use_super_ && super_->two_threads(); }

Eigen::VectorXd KktLdlt::pivots() const { return use_super_ ? super_->vectorD() : ldlt_.vectorD(); }

void KktLdlt::analyze(const SpMat& pattern_in, const SpMat& G, const std::vector<int>& groups) {
  SpMat compressed;
  if (!pattern_in.isCompressed()) {
    compressed = pattern_in;
    compressed.makeCompressed();
  }
  const SpMat& pattern = pattern_in.isCompressed() ? pattern_in : compressed;
  n_ = static_cast<long>(pattern.rows());
  m_ = static_cast<long>(G.rows());
  if (pattern.cols() != n_ || (m_ > 0 && G.cols() != n_))
    throw std::invalid_argument("KktLdlt: inconsistent matrix sizes");
  G_ = G;
  G_.makeCompressed();
  // Primal block: A's pattern plus the couplings through the constraint rows. Augmented
  // Lagrangian: A + s G'G has the same solution on G x = 0 and is definite there even where A
  // alone is not (a Kirchhoff plate's w carries no stiffness of its own).
  SpMat P;
  if (m_ > 0) {
    GtG_ = SpMat(G_.transpose() * G_);
    GtG_.makeCompressed();
    P = pattern + GtG_;
  } else {
    GtG_.resize(0, 0);
    P = pattern;
  }
  P.makeCompressed();
  a_nnz_ = pattern.nonZeros();
  const Eigen::VectorXi order = amd_order(P, groups);
  std::vector<long> rank(static_cast<std::size_t>(n_));
  for (long k = 0; k < n_; ++k) rank[static_cast<std::size_t>(order[k])] = k;
  // Each multiplier right after the last (in elimination order) primal unknown of its row.
  std::vector<std::vector<long>> after(static_cast<std::size_t>(n_));
  if (m_ > 0) {
    const Eigen::SparseMatrix<double, Eigen::RowMajor> Gr = G_;
    for (long r = 0; r < m_; ++r) {
      long last = -1;
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(Gr, r); it; ++it)
        last = std::max(last, rank[static_cast<std::size_t>(it.col())]);
      if (last < 0) throw std::invalid_argument("KktLdlt: empty constraint row");
      after[static_cast<std::size_t>(last)].push_back(r);
    }
  }
  pos_.resize(n_ + m_);
  int next = 0;
  for (long k = 0; k < n_; ++k) {
    pos_[order[k]] = next++;
    for (long r : after[static_cast<std::size_t>(k)]) pos_[n_ + r] = next++;
  }
  // The augmentation's scale: the median diagonal magnitude, not the mean. A few stiff support
  // springs (a finite k = 1e17 N/m on a beam whose elements have 1e10) would make the mean a
  // thousand times the typical entry, and s G'G would then swamp the elastic stiffness in the
  // rounding (the first mode of such a beam was 6.5e-4 off at every mesh).
  std::vector<double> diagonal;
  diagonal.reserve(static_cast<std::size_t>(n_));
  for (int j = 0; j < pattern.outerSize(); ++j)
    for (SpMat::InnerIterator it(pattern, j); it; ++it)
      if (it.row() == j && it.value() != 0.0) diagonal.push_back(std::abs(it.value()));
  s_ = 1.0;
  if (!diagonal.empty()) {
    auto mid = diagonal.begin() + static_cast<std::ptrdiff_t>(diagonal.size() / 2);
    std::nth_element(diagonal.begin(), mid, diagonal.end());
    s_ = *mid;
  }

  // The permuted upper triangle, each entry tagged by its number; the sources per number.
  const std::vector<int> in_a = entry_map(P, pattern);
  const std::vector<int> in_gtg = m_ > 0 ? entry_map(P, GtG_) : std::vector<int>();
  std::vector<Triplet> t;
  t.reserve(static_cast<std::size_t>(P.nonZeros() / 2 + n_ + G_.nonZeros()));
  std::vector<int> a_of, gtg_of, g_of;
  for (int j = 0; j < P.outerSize(); ++j)
    for (int p = P.outerIndexPtr()[j]; p < P.outerIndexPtr()[j + 1]; ++p) {
      const int r = pos_[P.innerIndexPtr()[p]], c = pos_[j];
      if (r > c) continue;
      t.emplace_back(r, c, static_cast<double>(t.size()));
      a_of.push_back(in_a[static_cast<std::size_t>(p)]);
      gtg_of.push_back(m_ > 0 ? in_gtg[static_cast<std::size_t>(p)] : -1);
      g_of.push_back(-1);
    }
  for (int j = 0; j < G_.outerSize(); ++j)
    for (int p = G_.outerIndexPtr()[j]; p < G_.outerIndexPtr()[j + 1]; ++p) {
      const int r = pos_[n_ + G_.innerIndexPtr()[p]], c = pos_[j];
      t.emplace_back(std::min(r, c), std::max(r, c), static_cast<double>(t.size()));
      a_of.push_back(-1);
      gtg_of.push_back(-1);
      g_of.push_back(p);
    }
  K_.resize(n_ + m_, n_ + m_);
  K_.setFromTriplets(t.begin(), t.end());
  K_.makeCompressed();
  const std::size_t nnz = static_cast<std::size_t>(K_.nonZeros());
  from_a_.resize(nnz);
  from_gtg_.resize(nnz);
  from_g_.resize(nnz);
  for (std::size_t p = 0; p < nnz; ++p) {
    const auto k = static_cast<std::size_t>(K_.valuePtr()[p]);
    from_a_[p] = a_of[k];
    from_gtg_[p] = gtg_of[k];
    from_g_[p] = g_of[k];
  }
  // Supernodal where CHOLMOD's analysis of this order finds it pays (plates), else simplicial.
  use_super_ = super_->analyze(K_);
  if (!use_super_) ldlt_.analyzePattern(K_);
  analysed_ = true;
}

bool KktLdlt::factorize(const SpMat& A_in) {
  if (!analysed_) throw std::logic_error("KktLdlt::factorize before analyze");
  SpMat compressed;
  if (!A_in.isCompressed()) {
    compressed = A_in;
    compressed.makeCompressed();
  }
  const SpMat& A = A_in.isCompressed() ? A_in : compressed;
  if (A.nonZeros() != a_nnz_ || A.rows() != n_)
    throw std::invalid_argument("KktLdlt: matrix pattern differs from the analysed one");
  const double* av = A.valuePtr();
  const double* gtg = GtG_.valuePtr();
  const double* gv = G_.valuePtr();
  double* kv = K_.valuePtr();
  for (std::size_t p = 0; p < from_a_.size(); ++p) {
    double v = 0;
    if (from_a_[p] >= 0) v += av[from_a_[p]];
    if (from_gtg_[p] >= 0) v += s_ * gtg[from_gtg_[p]];
    if (from_g_[p] >= 0) v += s_ * gv[from_g_[p]];
    kv[p] = v;
  }
  diag_ = K_.diagonal();
  if (use_super_) return super_->factorize(K_);
  ldlt_.factorize(K_);
  return ldlt_.info() == Eigen::Success;
}

Eigen::VectorXd KktLdlt::solve(const Eigen::VectorXd& b) const {
  Eigen::VectorXd out(n_);
  solve_into(b.data(), out.data());
  return out;
}

void KktLdlt::solve_into(const double* b, double* x) const {
  work_.setZero(n_ + m_);
  for (long i = 0; i < n_; ++i) work_[pos_[i]] = b[i];
  // In place: L, D, L' (natural ordering: the permutation is ours, applied above).
  if (use_super_) {
    super_->solve_in_place(work_.data());
  } else {
    ldlt_.matrixL().solveInPlace(work_);
    work_.array() /= ldlt_.vectorD().array();
    ldlt_.matrixU().solveInPlace(work_);
  }
  for (long i = 0; i < n_; ++i) x[i] = work_[pos_[i]];
}

long KktLdlt::negative_count() const {
  const Eigen::VectorXd D = pivots();
  long neg = 0;
  for (long k = 0; k < D.size(); ++k) neg += D[k] < 0;
  return neg - m_;
}

double KktLdlt::smallest_primal_pivot_ratio(long* where) const {
  const Eigen::VectorXd D = pivots();
  double worst = std::numeric_limits<double>::infinity();
  for (long i = 0; i < n_; ++i) {
    const long k = pos_[i];
    const double d = std::abs(diag_[k]);
    const double r = d > 0 ? std::abs(D[k]) / d : (D[k] == 0 ? 0.0 : std::numeric_limits<double>::infinity());
    if (r < worst) {
      worst = r;
      if (where) *where = i;
    }
  }
  return worst;
}

struct PdFactor::Impl : public Eigen::CholmodDecomposition<SpMat, Eigen::Lower> {
  // CHOLMOD prints its warnings ("not positive definite") on stdout, which would corrupt a JSON
  // answer; its status reaches us through info() and the factor's `minor` instead.
  Impl() { this->cholmod().print = 0; }
  bool is_super() const { return this->m_cholmodFactor != nullptr && this->m_cholmodFactor->is_super; }
  cholmod_factor* factor() const { return this->m_cholmodFactor; }
  cholmod_dense *X = nullptr, *Y = nullptr, *E = nullptr;  // reused by cholmod_solve2
  /// cholmod_analyze_p in the given elimination order (Eigen's wrapper lets CHOLMOD choose).
  void analyze_given(const SpMat& pattern, Eigen::VectorXi& order) {
    if (m_cholmodFactor) cholmod_free_factor(&m_cholmodFactor, &this->cholmod());
    cholmod_sparse A = Eigen::viewAsCholmod(pattern.selfadjointView<Eigen::Lower>());
    this->cholmod().nmethods = 1;
    this->cholmod().method[0].ordering = CHOLMOD_GIVEN;
    this->cholmod().postorder = 1;
    m_cholmodFactor = cholmod_analyze_p(&A, order.data(), nullptr, 0, &this->cholmod());
    if (!m_cholmodFactor) throw std::runtime_error("CHOLMOD analysis failed");
    m_isInitialized = true;
    m_info = Eigen::Success;
    m_analysisIsOk = true;
    m_factorizationIsOk = false;
  }
  ~Impl() {
    for (cholmod_dense** d : {&X, &Y, &E})
      if (*d) cholmod_free_dense(d, &this->cholmod());
  }
};

PdFactor::PdFactor() : impl_(std::make_unique<Impl>()) {}
PdFactor::~PdFactor() = default;

void PdFactor::solve_into(const double* b, double* x) const {
  cholmod_factor* L = impl_->factor();
  if (!L) throw std::logic_error("PdFactor::solve_into before factorize");
  const std::size_t n = L->n;
  cholmod_dense B{};
  B.nrow = n;
  B.ncol = 1;
  B.nzmax = n;
  B.d = n;
  B.x = const_cast<double*>(b);
  B.xtype = CHOLMOD_REAL;
  B.dtype = CHOLMOD_DOUBLE;
  if (!cholmod_solve2(CHOLMOD_A, L, &B, nullptr, &impl_->X, nullptr, &impl_->Y, &impl_->E, &impl_->cholmod()))
    throw std::runtime_error("CHOLMOD solve failed");
  std::copy_n(static_cast<const double*>(impl_->X->x), n, x);
}

void PdFactor::analyze(const SpMat& pattern, const std::vector<int>& groups) {
  if (groups.empty()) {
    impl_->analyzePattern(pattern);
    if (impl_->info() != Eigen::Success) throw std::runtime_error("CHOLMOD analysis failed");
    return;
  }
  Eigen::VectorXi order = amd_order(pattern, groups);
  impl_->analyze_given(pattern, order);
}

bool PdFactor::factorize(const SpMat& A) {
  impl_->factorize(A);
  return impl_->info() == Eigen::Success;
}

Eigen::VectorXd PdFactor::solve(const Eigen::VectorXd& b) const { return impl_->solve(b); }

bool PdFactor::supernodal() const { return impl_->is_super(); }

std::string PdFactor::name() const {
  return supernodal() ? "CHOLMOD supernodal LL'" : "CHOLMOD simplicial LL'";
}

}  // namespace modalbench::rfem
