// The whirl roots of a spinning shaft at one spin (rotor.hpp): the quadratic eigenproblem
// (lambda^2 M + lambda C + K) x = 0 by shift-invert Arnoldi on its first companion form
//   lambda [I 0; 0 M] [x; y] = [0 I; -K -C] [x; y],
// whose inverse applied to [x; y] is [-K^-1 (M y + C x); x] (one solve with K), eigenvalue 1 / lambda:
// the largest ones are the lowest whirl frequencies.
#include "rotor.hpp"

#include <Eigen/Dense>
#include <Eigen/SparseLU>
#include <Spectra/GenEigsSolver.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>

#include "analysis_detail.hpp"

namespace modalbench::rfem::detail {

namespace {

using Cd = std::complex<double>;

/// x -> (A - 0 B)^-1 B x of the companion pencil (Spectra's user operator).
class CompanionOp {
 public:
  using Scalar = double;
  CompanionOp(const SpMat& M, const SpMat& C, const Eigen::SparseLU<SpMat>& lu) : M_(M), C_(C), lu_(lu), n_(M.rows()) {}
  Eigen::Index rows() const { return 2 * n_; }
  Eigen::Index cols() const { return 2 * n_; }
  void perform_op(const double* in, double* out) const {
    Eigen::Map<const Eigen::VectorXd> x(in, n_), y(in + n_, n_);
    Eigen::Map<Eigen::VectorXd> p(out, n_), q(out + n_, n_);
    const Eigen::VectorXd rhs = M_ * y + C_ * x;
    p = -lu_.solve(rhs);
    q = x;
  }

 private:
  const SpMat& M_;
  const SpMat& C_;
  const Eigen::SparseLU<SpMat>& lu_;
  Eigen::Index n_;
};

struct Eigenpairs {
  Eigen::VectorXcd lambda;
  Eigen::MatrixXcd V;  ///< 2n x count: the companion form's vectors [x; lambda x]
  long iterations = 0;
};

/// The `nev` eigenvalues of the pencil nearest 0: Arnoldi, or on a small model the whole dense
/// spectrum of the operator.
Eigenpairs nearest_zero(const CompanionOp& op, Eigen::Index n, Eigen::Index nev, const Eigen::VectorXd& start) {
  Eigenpairs out;
  const Eigen::Index dim = 2 * n;
  if (dim <= std::max<Eigen::Index>(80, 2 * nev + 2)) {
    Eigen::MatrixXd A(dim, dim);
    Eigen::VectorXd e = Eigen::VectorXd::Zero(dim);
    for (Eigen::Index j = 0; j < dim; ++j) {
      e[j] = 1.0;
      op.perform_op(e.data(), A.col(j).data());
      e[j] = 0.0;
    }
    Eigen::EigenSolver<Eigen::MatrixXd> es(A);
    if (es.info() != Eigen::Success) throw std::runtime_error("rfem rotor: the dense companion eigensolve failed");
    out.lambda = es.eigenvalues().cwiseInverse();
    out.V = es.eigenvectors();
    return out;
  }
  const Eigen::Index ncv = std::min<Eigen::Index>(dim, std::max<Eigen::Index>(2 * nev + 1, 40));
  Spectra::GenEigsSolver<CompanionOp> eigs(const_cast<CompanionOp&>(op), nev, ncv);
  if (start.size() == dim && start.norm() > 0) eigs.init(start.data());
  else eigs.init();
  eigs.compute(Spectra::SortRule::LargestMagn, 10000, 1e-12);
  if (eigs.info() != Spectra::CompInfo::Successful)
    throw std::runtime_error(fmt::format("rfem rotor: shift-invert Arnoldi did not converge ({} of {} eigenvalues)",
                                         eigs.eigenvalues().size(), nev));
  out.lambda = eigs.eigenvalues().cwiseInverse();
  out.V = eigs.eigenvectors();
  out.iterations = eigs.num_iterations();
  return out;
}

/// v, w (or, where the translations vanish, the tilt axis theta_z, -theta_y) at each rigid element.
struct Orbits {
  std::vector<Cd> V, W;
};
Orbits orbits(const Model& model, const System& sys, const Eigen::VectorXcd& x) {
  const Eigen::VectorXcd q = (sys.T * x.real()).cast<Cd>() + Cd(0, 1) * (sys.T * x.imag()).cast<Cd>();
  const long na = model.dofs_per_element();
  const int iv = model.local_index(dofs::Uy), iw = model.local_index(dofs::Uz);
  const int iy = model.local_index(dofs::Ry), iz = model.local_index(dofs::Rz);
  Orbits o;
  double translation = 0;
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    const long b = static_cast<long>(e) * na;
    o.V.push_back(q[b + iv]);
    o.W.push_back(q[b + iw]);
    translation = std::max(translation, std::norm(q[b + iv]) + std::norm(q[b + iw]));
  }
  if (translation > 1e-24 * q.squaredNorm()) return o;
  for (std::size_t e = 0; e < model.elements.size(); ++e) {  // a pure tilt: the axis' orbit
    const long b = static_cast<long>(e) * na;
    o.V[e] = q[b + iz];
    o.W[e] = -q[b + iy];
  }
  return o;
}

/// The orbit sense of a root (lambda with Im lambda >= 0, time e^{lambda t}): per element
/// Im(V conj W) > 0 turns from +y towards +z, the spin's sense.
Whirl sense(const Orbits& o) {
  double top = 0;
  for (std::size_t e = 0; e < o.V.size(); ++e) top = std::max(top, std::norm(o.V[e]) + std::norm(o.W[e]));
  bool fwd = false, bwd = false;
  for (std::size_t e = 0; e < o.V.size(); ++e) {
    const double a = std::norm(o.V[e]) + std::norm(o.W[e]), s = (o.V[e] * std::conj(o.W[e])).imag();
    if (!(a > 1e-6 * top) || std::abs(s) <= 1e-6 * a) continue;
    (s > 0 ? fwd : bwd) = true;
  }
  return fwd && bwd ? Whirl::Mixed : fwd ? Whirl::Forward : bwd ? Whirl::Backward : Whirl::Planar;
}

/// A repeated root's basis (columns of X) turned so that the orbit-sense form sum_e Im(V conj W)
/// is diagonal relative to the orbits' size sum_e |V|^2 + |W|^2 (a generalized Hermitian
/// eigenproblem): the forward and backward circles of a pair at spin 0 (with the sense form alone,
/// two planar modes of unequal size came out as ellipses).
void diagonalize_sense(const Model& model, const System& sys, Eigen::MatrixXcd& X) {
  const Eigen::Index c = X.cols();
  std::vector<Orbits> o;
  for (Eigen::Index j = 0; j < c; ++j) o.push_back(orbits(model, sys, X.col(j)));
  Eigen::MatrixXcd H = Eigen::MatrixXcd::Zero(c, c), G = Eigen::MatrixXcd::Zero(c, c);
  for (Eigen::Index i = 0; i < c; ++i)
    for (Eigen::Index j = 0; j < c; ++j)
      for (std::size_t e = 0; e < o[0].V.size(); ++e) {
        H(i, j) += (o[j].V[e] * std::conj(o[i].W[e]) - std::conj(o[i].V[e]) * o[j].W[e]) / Cd(0, 2);
        G(i, j) += std::conj(o[i].V[e]) * o[j].V[e] + std::conj(o[i].W[e]) * o[j].W[e];
      }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXcd> es(H, G);
  if (es.info() == Eigen::Success) X = X * es.eigenvectors();
}

double backward_error(const SpMat& M, const SpMat& C, const SpMat& K, Cd lambda, const Eigen::VectorXcd& x,
                      const std::array<double, 3>& norms) {
  // r = (lambda^2 M + lambda C + K) x in real arithmetic (lambda = a + i b, x = p + i q).
  const Eigen::VectorXd p = x.real(), q = x.imag();
  const Cd l2 = lambda * lambda;
  const Eigen::VectorXd Mp = M * p, Mq = M * q, Cp = C * p, Cq = C * q;
  const Eigen::ArrayXd rr = (l2.real() * Mp - l2.imag() * Mq + lambda.real() * Cp - lambda.imag() * Cq + K * p).array();
  const Eigen::ArrayXd ri = (l2.real() * Mq + l2.imag() * Mp + lambda.real() * Cq + lambda.imag() * Cp + K * q).array();
  const double r1 = (rr.square() + ri.square()).sqrt().sum();
  const double x1 = (p.array().square() + q.array().square()).sqrt().sum();
  const double a = std::abs(lambda);
  return r1 / ((a * a * norms[0] + a * norms[1] + norms[2]) * x1);
}

/// The end of the repeated root starting at i: its copies within 1e-8 (lambda ascending by |lambda|).
std::size_t repeated_end(const std::vector<Cd>& lambda, std::size_t i) {
  std::size_t j = i + 1;
  while (j < lambda.size() && std::abs(lambda[j] - lambda[i]) <= 1e-8 * std::abs(lambda[i])) ++j;
  return j;
}

/// The copies of a repeated root (columns of X, eigenvalues lam) by Rayleigh-Ritz on their span:
/// the quadratic eigenproblem projected there (companion form, dense), its roots nearest the copies'
/// mean. Arnoldi's copies of a repeated root differ by up to 2e-9 (Timoshenko shaft at rest, 64
/// segments) where the span is right to its tolerance; left as they are where the projection has
/// no roots within 1e-6 of them.
void rayleigh_ritz(const SpMat& M, const SpMat& C, const SpMat& K, std::vector<Cd>& lam, Eigen::MatrixXcd& X) {
  const Eigen::Index c = X.cols();
  const Eigen::HouseholderQR<Eigen::MatrixXcd> qr(X);
  const Eigen::MatrixXcd Q = qr.householderQ() * Eigen::MatrixXcd::Identity(X.rows(), c);
  auto project = [&](const SpMat& A) -> Eigen::MatrixXcd {
    Eigen::MatrixXcd AQ(Q.rows(), c);
    AQ.real() = A * Q.real();
    AQ.imag() = A * Q.imag();
    return Q.adjoint() * AQ;
  };
  const Eigen::PartialPivLU<Eigen::MatrixXcd> mc(project(M));
  Eigen::MatrixXcd A = Eigen::MatrixXcd::Zero(2 * c, 2 * c);
  A.topRightCorner(c, c).setIdentity();
  A.bottomLeftCorner(c, c) = -mc.solve(project(K));
  A.bottomRightCorner(c, c) = -mc.solve(project(C));
  const Eigen::ComplexEigenSolver<Eigen::MatrixXcd> es(A);
  if (es.info() != Eigen::Success) return;
  Cd mean = 0;
  for (Cd l : lam) mean += l / static_cast<double>(c);
  std::vector<Eigen::Index> order(static_cast<std::size_t>(2 * c));
  for (Eigen::Index i = 0; i < 2 * c; ++i) order[static_cast<std::size_t>(i)] = i;
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
    return std::abs(es.eigenvalues()[a] - mean) < std::abs(es.eigenvalues()[b] - mean);
  });
  if (!(std::abs(es.eigenvalues()[order[static_cast<std::size_t>(c - 1)]] - mean) <= 1e-6 * std::abs(mean))) return;
  for (Eigen::Index i = 0; i < c; ++i) {
    const Eigen::Index e = order[static_cast<std::size_t>(i)];
    lam[static_cast<std::size_t>(i)] = es.eigenvalues()[e];
    X.col(i) = Q * es.eigenvectors().col(e).head(c);
  }
}

}  // namespace

WhirlRoots collect_roots(const Model& model, const System& sys, const SpMat& K, const SpMat& C, int k,
                         const std::vector<std::complex<double>>& lambda, const Eigen::MatrixXcd& X,
                         const std::vector<double>& backward_errors) {
  const SpMat& M = sys.M;
  const Eigen::Index n = sys.n();
  const std::array<double, 3> norms = {norm1(M), norm1(C), norm1(K)};
  WhirlRoots out;
  const std::size_t count = lambda.size();
  for (std::size_t i = 0; i < count && static_cast<int>(out.omega.size()) < k;) {
    // A repeated root (its copies within 1e-8): one basis, turned to the orbits' senses.
    const std::size_t j = repeated_end(lambda, i);
    Eigen::MatrixXcd Xr(n, static_cast<Eigen::Index>(j - i));
    for (std::size_t m = i; m < j; ++m) Xr.col(static_cast<Eigen::Index>(m - i)) = X.col(static_cast<Eigen::Index>(m));
    std::vector<double> be(j - i);
    for (std::size_t m = i; m < j; ++m)
      be[m - i] = m < backward_errors.size() ? backward_errors[m]
                                             : backward_error(M, C, K, lambda[m], X.col(static_cast<Eigen::Index>(m)), norms);
    if (j - i > 1) diagonalize_sense(model, sys, Xr);
    for (std::size_t m = i; m < j && static_cast<int>(out.omega.size()) < k; ++m) {
      const Cd l = lambda[m];
      const Eigen::VectorXcd x = Xr.col(static_cast<Eigen::Index>(m - i));
      // Rounding leaves |Re lambda| of about sqrt(backward error) |lambda| where roots meet (a
      // defective pair at the edge of an unstable range); below that it is not a growth rate.
      const double noise = std::max(1e-8, 10.0 * std::sqrt(be[m - i])) * std::abs(l);
      out.omega.push_back(std::abs(l.imag()) <= 1e-10 * std::abs(l) ? 0.0 : std::abs(l.imag()));
      out.growth.push_back(std::abs(l.real()) <= noise ? 0.0 : std::abs(l.real()));
      out.backward_error.push_back(be[m - i]);
      const Orbits o = orbits(model, sys, x);
      out.whirl.push_back(out.omega.back() == 0.0 ? Whirl::None : sense(o));
      out.orbit_v.push_back(o.V);
      out.orbit_w.push_back(o.W);
    }
    i = j;
  }
  std::vector<std::size_t> order(out.omega.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return out.omega[a] < out.omega[b]; });
  WhirlRoots sorted;
  for (std::size_t i : order) {
    sorted.omega.push_back(out.omega[i]);
    sorted.growth.push_back(out.growth[i]);
    sorted.backward_error.push_back(out.backward_error[i]);
    sorted.whirl.push_back(out.whirl[i]);
    sorted.orbit_v.push_back(std::move(out.orbit_v[i]));
    sorted.orbit_w.push_back(std::move(out.orbit_w[i]));
  }
  return sorted;
}

WhirlRoots whirl_roots(const Model& model, const System& sys, const SpMat& K, const Eigen::SparseLU<SpMat>& lu,
                       const SpMat& C, int k, const Eigen::VectorXd& start) {
  const Eigen::Index n = sys.n();
  const CompanionOp op(sys.M, C, lu);
  const Eigen::Index nev = std::min<Eigen::Index>(2 * n - 2, 2 * k + 4);
  const Eigenpairs ep = nearest_zero(op, n, nev, start);
  // Each pair +-lambda once: Im lambda > 0, or a real root with Re >= 0.
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < ep.lambda.size(); ++i) {
    const Cd l = ep.lambda[i];
    if (l.imag() > 1e-10 * std::abs(l) || (std::abs(l.imag()) <= 1e-10 * std::abs(l) && l.real() >= 0)) keep.push_back(i);
  }
  // The k nearest 0 (a root with a large real part may have a small frequency, but is not among
  // the lowest), reported by frequency.
  std::sort(keep.begin(), keep.end(),
            [&](Eigen::Index a, Eigen::Index b) { return std::abs(ep.lambda[a]) < std::abs(ep.lambda[b]); });
  std::vector<Cd> lambda;
  Eigen::MatrixXcd X(n, static_cast<Eigen::Index>(keep.size()));
  Eigen::VectorXd start_next = Eigen::VectorXd::Zero(2 * n);
  for (std::size_t i = 0; i < keep.size(); ++i) {
    lambda.push_back(ep.lambda[keep[i]]);
    X.col(static_cast<Eigen::Index>(i)) = ep.V.col(keep[i]).head(n);
    if (i < static_cast<std::size_t>(k)) {  // the k nearest: the next spin's start
      const Eigen::VectorXcd v = ep.V.col(keep[i]) / ep.V.col(keep[i]).norm();
      start_next += v.real() + v.imag();
    }
  }
  // Arnoldi's copies of a repeated root refined on their span.
  for (std::size_t i = 0; i < lambda.size();) {
    const std::size_t j = repeated_end(lambda, i);
    if (j - i > 1) {
      std::vector<Cd> lr(lambda.begin() + static_cast<long>(i), lambda.begin() + static_cast<long>(j));
      Eigen::MatrixXcd Xr = X.middleCols(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j - i));
      rayleigh_ritz(sys.M, C, K, lr, Xr);
      std::copy(lr.begin(), lr.end(), lambda.begin() + static_cast<long>(i));
      X.middleCols(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j - i)) = Xr;
    }
    i = j;
  }
  WhirlRoots out = collect_roots(model, sys, K, C, k, lambda, X);
  out.start = std::move(start_next);
  out.iterations = ep.iterations;
  return out;
}

}  // namespace modalbench::rfem::detail
