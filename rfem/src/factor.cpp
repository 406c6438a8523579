#include "modalbench/rfem/factor.hpp"

#include <amd.h>

#include <Eigen/CholmodSupport>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace modalbench::rfem {

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

Eigen::VectorXi amd_order(const SpMat& pattern) {
  const int n = static_cast<int>(pattern.rows());
  Eigen::VectorXi order(n);
  if (n == 0) return order;
  SpMat A = pattern;
  A.makeCompressed();
  double control[AMD_CONTROL], info[AMD_INFO];
  amd_defaults(control);
  const int status = ::amd_order(n, A.outerIndexPtr(), A.innerIndexPtr(), order.data(), control, info);
  if (status != AMD_OK && status != AMD_OK_BUT_JUMBLED) throw std::runtime_error("AMD ordering failed");
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

void KktLdlt::analyze(const SpMat& pattern, const SpMat& G) {
  n_ = static_cast<long>(pattern.rows());
  m_ = static_cast<long>(G.rows());
  if (pattern.cols() != n_ || (m_ > 0 && G.cols() != n_))
    throw std::invalid_argument("KktLdlt: inconsistent matrix sizes");
  G_ = G;
  G_.makeCompressed();
  // Primal graph: A's pattern plus the couplings through the constraint rows.
  SpMat P = pattern;
  if (m_ > 0) {
    const SpMat Ga = G_.cwiseAbs();
    P = SpMat(pattern.cwiseAbs()) + SpMat(Ga.transpose() * Ga);
  }
  const Eigen::VectorXi order = amd_order(P);
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
  double mean = 0;
  for (long i = 0; i < n_; ++i) mean += std::abs(pattern.coeff(i, i));
  s_ = n_ > 0 && mean > 0 ? mean / static_cast<double>(n_) : 1.0;
  // Augmented Lagrangian: A + rho G'G has the same solution on G x = 0 and is definite there
  // even where A alone is not (a Kirchhoff plate's w carries no stiffness of its own).
  if (m_ > 0) GtG_ = SpMat(G_.transpose() * G_);
  SpMat Ac = augmented(pattern);
  a_nnz_ = Ac.nonZeros();
  // The permuted matrix with each nonzero tagged by its source (A's value index + 1, or -(G's + 1)).
  SpMat At = Ac;
  for (long p = 0; p < a_nnz_; ++p) At.valuePtr()[p] = static_cast<double>(p) + 1.0;
  if (m_ == 0) {
    Perm Pm(n_);
    for (long i = 0; i < n_; ++i) Pm.indices()[i] = pos_[i];
    K_ = At.selfadjointView<Eigen::Lower>().twistedBy(Pm);
  } else {
    std::vector<Triplet> t;
    t.reserve(static_cast<std::size_t>(a_nnz_ + 2 * G_.nonZeros()));
    for (int j = 0; j < At.outerSize(); ++j)
      for (int p = At.outerIndexPtr()[j]; p < At.outerIndexPtr()[j + 1]; ++p)
        t.emplace_back(pos_[At.innerIndexPtr()[p]], pos_[j], At.valuePtr()[p]);
    for (int j = 0; j < G_.outerSize(); ++j)
      for (int p = G_.outerIndexPtr()[j]; p < G_.outerIndexPtr()[j + 1]; ++p) {
        const int r = pos_[n_ + G_.innerIndexPtr()[p]], c = pos_[j];
        t.emplace_back(r, c, -(static_cast<double>(p) + 1.0));
        t.emplace_back(c, r, -(static_cast<double>(p) + 1.0));
      }
    K_.resize(n_ + m_, n_ + m_);
    K_.setFromTriplets(t.begin(), t.end());
  }
  K_.makeCompressed();
  source_.resize(static_cast<std::size_t>(K_.nonZeros()));
  for (long p = 0; p < K_.nonZeros(); ++p) {
    const double v = K_.valuePtr()[p];
    source_[static_cast<std::size_t>(p)] = v > 0 ? static_cast<long>(v) - 1 : -static_cast<long>(-v);
  }
  ldlt_.analyzePattern(K_);
  analysed_ = true;

}

SpMat KktLdlt::augmented(const SpMat& A) const {
  SpMat Au = m_ > 0 ? SpMat(A + s_ * GtG_) : A;
  Au.makeCompressed();
  return Au;
}

void KktLdlt::fill(const SpMat& A) {
  if (!(A.isCompressed() && A.nonZeros() == a_nnz_))
    throw std::invalid_argument("KktLdlt: matrix pattern differs from the analysed one");
  const double* av = A.valuePtr();
  const double* gv = G_.valuePtr();
  for (std::size_t p = 0; p < source_.size(); ++p) {
    const long s = source_[p];
    K_.valuePtr()[p] = s >= 0 ? av[s] : s_ * gv[-s - 1];
  }
}

bool KktLdlt::factorize(const SpMat& A) {
  if (!analysed_) throw std::logic_error("KktLdlt::factorize before analyze");
  if (m_ > 0) {
    fill(augmented(A));
  } else if (A.isCompressed()) {
    fill(A);
  } else {
    SpMat Ac = A;
    Ac.makeCompressed();
    fill(Ac);
  }
  diag_ = K_.diagonal();
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
  ldlt_.matrixL().solveInPlace(work_);
  work_.array() /= ldlt_.vectorD().array();
  ldlt_.matrixU().solveInPlace(work_);
  for (long i = 0; i < n_; ++i) x[i] = work_[pos_[i]];
}

long KktLdlt::negative_count() const {
  const Eigen::VectorXd& D = ldlt_.vectorD();
  long neg = 0;
  for (long k = 0; k < D.size(); ++k) neg += D[k] < 0;
  return neg - m_;
}

double KktLdlt::smallest_primal_pivot_ratio(long* where) const {
  const Eigen::VectorXd& D = ldlt_.vectorD();
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
  bool is_super() const { return this->m_cholmodFactor != nullptr && this->m_cholmodFactor->is_super; }
  cholmod_factor* factor() const { return this->m_cholmodFactor; }
  cholmod_dense *X = nullptr, *Y = nullptr, *E = nullptr;  // reused by cholmod_solve2
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

void PdFactor::analyze(const SpMat& pattern) {
  impl_->analyzePattern(pattern);
  if (impl_->info() != Eigen::Success) throw std::runtime_error("CHOLMOD analysis failed");
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
