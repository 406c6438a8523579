// The stationary frame's Campbell sweep by projection (rotor.hpp: GyroscopicSweep, whirl_count).
//
// M x'' + Omega G x' + K x = 0, x = x e^{i w t}: P(w) x = (K - w^2 M + i w Omega G) x = 0, P(w)
// Hermitian for real w. Its 1 / lambda form (mu = 1 / (i w)) is the pencil
//   A u = mu B u,  A = [[0, M], [-M, -Omega G]] (skew),  B = diag(M, K) (positive definite),
// u = [x; mu x], whose residual is [0; -mu^2 P(w) x]. A Hermitian definite pencil has an eigenvalue
// within |r|_{B^-1} / |u|_B of any trial value; in w this is
//   |w - w_true| / w_true <= |P(w) x|_{K^-1} / sqrt(w^2 x*Mx + x*Kx),
// the bound each reported root must meet (K^-1 through the sweep's one factorization, whose solve
// also gives the direction that enriches the basis: Voss's nonlinear Arnoldi).
#include "rotor.hpp"

#include <Eigen/Dense>
#include <Eigen/SparseLU>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <random>

#include "modalbench/rfem/factor.hpp"
#include "analysis_detail.hpp"

namespace modalbench::rfem::detail {

namespace {

using Cd = std::complex<double>;

constexpr int kMaxSteps = 30;

/// The projected problem's positive frequencies, ascending, with their coefficient vectors (the x
/// part of u): the real skew pencil (A_V, B_V) reduced by B_V = L L' to S = L^-1 A_V L^-T (real skew,
/// eigenvalues +-i w), whose S'S has each w^2 twice; a vector v of S'S gives u = v - i S v / w.
struct Ritz {
  std::vector<double> w;
  Eigen::MatrixXcd a;  ///< m x count
};
Ritz projected_roots(const Eigen::MatrixXd& Mr, const Eigen::MatrixXd& Gr, const Eigen::MatrixXd& Kr, double spin,
                     int want) {
  const Eigen::Index m = Mr.rows();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * m, 2 * m), B = Eigen::MatrixXd::Zero(2 * m, 2 * m);
  // The i w form: [[0, K], [-K, -Omega G]] u = i w diag(K, M) u with u = [x; i w x].
  A.topRightCorner(m, m) = Kr;
  A.bottomLeftCorner(m, m) = -Kr;
  A.bottomRightCorner(m, m) = -spin * Gr;
  B.topLeftCorner(m, m) = Kr;
  B.bottomRightCorner(m, m) = Mr;
  Ritz out;
  const Eigen::LLT<Eigen::MatrixXd> llt(B);
  if (llt.info() != Eigen::Success) return out;
  const Eigen::MatrixXd L = llt.matrixL();
  Eigen::MatrixXd S = L.triangularView<Eigen::Lower>().solve(A);
  S = L.triangularView<Eigen::Lower>().solve(S.transpose()).transpose();
  S = 0.5 * (S - S.transpose()).eval();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(S.transpose() * S);
  if (es.info() != Eigen::Success) return out;
  // Each w^2 twice, its vectors spanning {v, S v / w} for each root (a repeated root's several such
  // planes mixed): a vector is taken where its part outside the planes already taken is at least
  // half of it, and its plane is taken with it.
  const Eigen::VectorXd& ev = es.eigenvalues();
  Eigen::MatrixXd Q(2 * m, 2 * std::min<Eigen::Index>(want, m));
  Eigen::Index q = 0;
  std::vector<std::pair<double, Eigen::VectorXcd>> roots;
  for (Eigen::Index i = 0; i < 2 * m && static_cast<int>(roots.size()) < want; ++i) {
    const double w = std::sqrt(std::max(0.0, ev[i]));
    if (!(w > 0)) continue;
    Eigen::VectorXd v = es.eigenvectors().col(i);
    for (int pass = 0; pass < 2; ++pass) v -= Q.leftCols(q) * (Q.leftCols(q).transpose() * v);
    if (!(v.norm() >= 0.5)) continue;
    v.normalize();
    const Eigen::VectorXd Sv = S * v;
    Q.col(q++) = v;
    Q.col(q++) = Sv / Sv.norm();
    // y = v - i S v / w; u = L^-T y is an eigenvector of A u = i w B u; its x part is the first m entries.
    const auto Lt = L.transpose().triangularView<Eigen::Upper>();
    const Eigen::VectorXd ur = Lt.solve(v), ui = Lt.solve(Eigen::VectorXd(-Sv / w));
    roots.emplace_back(w, ur.head(m).cast<Cd>() + Cd(0, 1) * ui.head(m).cast<Cd>());
  }
  out.a.resize(m, static_cast<Eigen::Index>(roots.size()));
  for (std::size_t j = 0; j < roots.size(); ++j) {
    out.w.push_back(roots[j].first);
    out.a.col(static_cast<Eigen::Index>(j)) = roots[j].second;
  }
  return out;
}

}  // namespace

GyroscopicSweep::GyroscopicSweep(const SpMat& M, const SpMat& G, const SpMat& K, int k)
    : M_(M), G_(G), K_(K), normM_(norm1(M)), normG_(norm1(G)), normK_(norm1(K)), llt_(K), k_(k),
      cap_(std::min<long>(K.rows(), std::max(6L * k + 8, 32L))) {
  V_.resize(K.rows(), cap_);
  Mr_ = Gr_ = Kr_ = Eigen::MatrixXd::Zero(cap_, cap_);
}

bool GyroscopicSweep::add(const Eigen::VectorXd& v0) {
  if (m_ >= cap_) return false;
  const double before = v0.norm();
  if (!(before > 0) || !std::isfinite(before)) return false;
  Eigen::VectorXd v = v0 / before;
  for (int pass = 0; pass < 2; ++pass) v -= V_.leftCols(m_) * (V_.leftCols(m_).transpose() * v);
  const double after = v.norm();
  if (!(after > 1e-8)) return false;  // within 1e-8 of the span already
  v /= after;
  V_.col(m_) = v;
  const Eigen::Index n1 = m_ + 1;
  const Eigen::VectorXd Mv = M_ * v, Kv = K_ * v, Gv = G_ * v;
  Mr_.col(m_).head(n1) = V_.leftCols(n1).transpose() * Mv;
  Kr_.col(m_).head(n1) = V_.leftCols(n1).transpose() * Kv;
  Gr_.col(m_).head(n1) = V_.leftCols(n1).transpose() * Gv;  // Gr(i, m) = V_i' G v
  Mr_.row(m_).head(n1) = Mr_.col(m_).head(n1).transpose();
  Kr_.row(m_).head(n1) = Kr_.col(m_).head(n1).transpose();
  Gr_.row(m_).head(n1) = -Gr_.col(m_).head(n1).transpose();  // v' G V_i = -V_i' G v
  Gr_(m_, m_) = 0;
  ++m_;
  largest_ = std::max(largest_, m_);
  return true;
}

void GyroscopicSweep::restart(const Eigen::MatrixXcd& keep) {
  m_ = 0;
  for (Eigen::Index j = 0; j < keep.cols(); ++j) {
    add(keep.col(j).real());
    add(keep.col(j).imag());
  }
}

GyroscopicSweep::Roots GyroscopicSweep::solve(double spin) {
  const Eigen::Index n = K_.rows();
  Roots out;
  if (llt_.info() != Eigen::Success) return out;  // not positive definite: the caller's Arnoldi says why
  if (m_ == 0) {  // a start: two steps of inverse iteration, K^-1 M, on fixed pseudo-random vectors
    std::mt19937 gen(20240917);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const long b = std::min<long>(2L * k_ + 2, cap_);
    Eigen::MatrixXd R(n, b);
    for (Eigen::Index j = 0; j < R.size(); ++j) R.data()[j] = u(gen);
    for (int step = 0; step < 2; ++step) R = llt_.solve(Eigen::MatrixXd(M_ * R));
    solves_ += 2 * b;
    for (long j = 0; j < b; ++j) add(R.col(j));
  }
  std::vector<double> last(static_cast<std::size_t>(k_), std::numeric_limits<double>::infinity());
  for (int step = 0; step < kMaxSteps; ++step) {
    const Ritz z = projected_roots(Mr_.topLeftCorner(m_, m_), Gr_.topLeftCorner(m_, m_), Kr_.topLeftCorner(m_, m_),
                                   spin, k_ + 1);
    if (static_cast<int>(z.w.size()) < k_) return out;
    out.lambda.clear();
    out.backward_error.clear();
    out.X.resize(n, k_);
    out.bound = 0;
    out.next = static_cast<int>(z.w.size()) > k_ ? z.w[static_cast<std::size_t>(k_)]
                                                 : std::numeric_limits<double>::infinity();
    // The residuals P(w) x of the k roots (real and imaginary parts as columns), their K^-1 norms by
    // the forward half of the Cholesky solve (r' K^-1 r = |L^-1 P r|^2, K = P' L L' P).
    Eigen::MatrixXd Rs(n, 2 * k_);
    std::vector<double> energy(static_cast<std::size_t>(k_));
    const Eigen::MatrixXd Xr = V_.leftCols(m_) * z.a.leftCols(k_).real();
    const Eigen::MatrixXd Xi = V_.leftCols(m_) * z.a.leftCols(k_).imag();
    for (int j = 0; j < k_; ++j) {
      const double w = z.w[static_cast<std::size_t>(j)];
      Eigen::VectorXd xr = Xr.col(j), xi = Xi.col(j);
      const double scale = std::sqrt(xr.squaredNorm() + xi.squaredNorm());
      xr /= scale;
      xi /= scale;
      const Eigen::VectorXd Mxr = M_ * xr, Mxi = M_ * xi, Kxr = K_ * xr, Kxi = K_ * xi;
      Rs.col(2 * j) = Kxr - w * w * Mxr - w * spin * (G_ * xi);
      Rs.col(2 * j + 1) = Kxi - w * w * Mxi + w * spin * (G_ * xr);
      energy[static_cast<std::size_t>(j)] = w * w * (xr.dot(Mxr) + xi.dot(Mxi)) + xr.dot(Kxr) + xi.dot(Kxi);
      out.lambda.emplace_back(0.0, w);
      out.X.col(j) = xr.cast<Cd>() + Cd(0, 1) * xi.cast<Cd>();
      // The backward error |r|_1 / ((w^2 |M| + w |Omega G| + |K|) |x|_1), 1-norms (collect_roots's).
      const double r1 = (Rs.col(2 * j).array().square() + Rs.col(2 * j + 1).array().square()).sqrt().sum();
      const double x1 = (xr.array().square() + xi.array().square()).sqrt().sum();
      out.backward_error.push_back(r1 / ((w * w * normM_ + w * std::abs(spin) * normG_ + normK_) * x1));
    }
    const Eigen::MatrixXd Ys = llt_.matrixL().solve(llt_.permutationP() * Rs);
    solves_ += k_;  // two half solves per root
    std::vector<Eigen::Index> open;
    for (int j = 0; j < k_; ++j) {
      const double eta = std::sqrt((Ys.col(2 * j).squaredNorm() + Ys.col(2 * j + 1).squaredNorm()) /
                                   energy[static_cast<std::size_t>(j)]);
      out.bound = std::max(out.bound, std::isfinite(eta) ? eta : std::numeric_limits<double>::infinity());
      double& before = last[static_cast<std::size_t>(j)];
      const bool floor = eta <= kFloorBound && eta > 0.5 * before;  // no longer falling: rounding
      before = eta;
      if (!(eta <= kBound) && !floor) {
        open.push_back(2 * j);
        open.push_back(2 * j + 1);
      }
    }
    std::vector<Eigen::VectorXd> fresh;
    if (!open.empty()) {  // K^-1 r: the back half of the solve, for the roots over the bound
      Eigen::MatrixXd Yo(n, static_cast<Eigen::Index>(open.size()));
      for (std::size_t i = 0; i < open.size(); ++i) Yo.col(static_cast<Eigen::Index>(i)) = Ys.col(open[i]);
      const Eigen::MatrixXd S = llt_.permutationPinv() * Eigen::MatrixXd(llt_.matrixU().solve(Yo));
      solves_ += static_cast<long>(open.size()) / 2;
      for (Eigen::Index i = 0; i < S.cols(); ++i) fresh.push_back(S.col(i));
    }
    if (fresh.empty()) {
      out.converged = true;
      return out;
    }
    if (m_ + static_cast<long>(fresh.size()) > cap_) {
      Eigen::MatrixXcd keep(n, z.a.cols());
      for (Eigen::Index j = 0; j < z.a.cols(); ++j)
        keep.col(j) = (V_.leftCols(m_) * z.a.col(j).real()).cast<Cd>() +
                      Cd(0, 1) * (V_.leftCols(m_) * z.a.col(j).imag()).cast<Cd>();
      restart(keep);
    }
    long added = 0;
    for (const Eigen::VectorXd& v : fresh) added += add(v);
    if (added == 0) return out;
  }
  return out;
}

double projected_seconds_per_spin(double coordinates, int k) {
  return 4.5e-4 * std::pow((6.0 * k + 8.0) / 44.0, 3) + 0.5e-6 * coordinates * k / 6.0;
}

double arnoldi_seconds_per_spin(double coordinates, int k) { return 2.5e-6 * coordinates * (1.0 + k / 12.0); }

bool projected_sweep(const std::string& method, double coordinates, int k) {
  if (method == "arnoldi" || !(2.0 * k + 2 < coordinates)) return false;
  return method == "projected" || projected_seconds_per_spin(coordinates, k) < arnoldi_seconds_per_spin(coordinates, k);
}

long whirl_count(const SpMat& M, const SpMat& G, const SpMat& K, double spin, double sigma) {
  const Eigen::Index n = K.rows();
  const SpMat A = K - sigma * sigma * M, B = sigma * spin * G;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(2 * A.nonZeros() + 2 * B.nonZeros()));
  for (Eigen::Index c = 0; c < n; ++c) {
    for (SpMat::InnerIterator it(A, c); it; ++it) {
      t.emplace_back(static_cast<int>(it.row()), static_cast<int>(c), it.value());
      t.emplace_back(static_cast<int>(it.row() + n), static_cast<int>(c + n), it.value());
    }
    for (SpMat::InnerIterator it(B, c); it; ++it) {
      t.emplace_back(static_cast<int>(it.row() + n), static_cast<int>(c), it.value());
      t.emplace_back(static_cast<int>(it.row()), static_cast<int>(c + n), -it.value());
    }
  }
  SpMat R(2 * n, 2 * n);
  R.setFromTriplets(t.begin(), t.end());
  // Each coordinate's real and imaginary parts eliminated together.
  std::vector<int> groups(static_cast<std::size_t>(2 * n));
  for (Eigen::Index i = 0; i < n; ++i)
    groups[static_cast<std::size_t>(i)] = groups[static_cast<std::size_t>(i + n)] = static_cast<int>(i);
  KktLdlt ldlt;
  ldlt.analyze(R, SpMat(0, 2 * n), groups);
  if (!ldlt.factorize(R)) return -1;
  const long negative = ldlt.negative_count();
  return negative % 2 == 0 ? negative / 2 : -1;
}

}  // namespace modalbench::rfem::detail
