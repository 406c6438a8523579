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
  auto apply = [&](const SpMat& A) -> Eigen::VectorXcd {
    return (A * x.real()).cast<Cd>() + Cd(0, 1) * (A * x.imag()).cast<Cd>();
  };
  const Eigen::VectorXcd r = lambda * lambda * apply(M) + lambda * apply(C) + apply(K);
  const double a = std::abs(lambda);
  return r.lpNorm<1>() / ((a * a * norms[0] + a * norms[1] + norms[2]) * x.lpNorm<1>());
}

}  // namespace

WhirlRoots whirl_roots(const Model& model, const System& sys, const SpMat& K, const Eigen::SparseLU<SpMat>& lu,
                       const SpMat& C, int k, const Eigen::VectorXd& start) {
  const SpMat& M = sys.M;
  const Eigen::Index n = sys.n();
  const CompanionOp op(M, C, lu);
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
  const std::array<double, 3> norms = {norm1(M), norm1(C), norm1(K)};
  WhirlRoots out;
  out.iterations = ep.iterations;
  out.start = Eigen::VectorXd::Zero(2 * n);
  for (std::size_t i = 0; i < keep.size() && i < static_cast<std::size_t>(k); ++i) {  // the k nearest
    const Eigen::VectorXcd v = ep.V.col(keep[i]) / ep.V.col(keep[i]).norm();
    out.start += v.real() + v.imag();
  }
  for (std::size_t i = 0; i < keep.size() && static_cast<int>(out.omega.size()) < k;) {
    // A repeated root (its copies within 1e-8): one basis, turned to the orbits' senses.
    std::size_t j = i + 1;
    const Cd li = ep.lambda[keep[i]];
    while (j < keep.size() && std::abs(ep.lambda[keep[j]] - li) <= 1e-8 * std::abs(li)) ++j;
    Eigen::MatrixXcd X(n, static_cast<Eigen::Index>(j - i));
    for (std::size_t m = i; m < j; ++m) X.col(static_cast<Eigen::Index>(m - i)) = ep.V.col(keep[m]).head(n);
    if (j - i > 1) diagonalize_sense(model, sys, X);
    for (std::size_t m = i; m < j && static_cast<int>(out.omega.size()) < k; ++m) {
      const Cd l = ep.lambda[keep[m]];
      const Eigen::VectorXcd x = X.col(static_cast<Eigen::Index>(m - i));
      const double be = backward_error(M, C, K, l, ep.V.col(keep[m]).head(n), norms);
      // Rounding leaves |Re lambda| of about sqrt(backward error) |lambda| where roots meet (a
      // defective pair at the edge of an unstable range); below that it is not a growth rate.
      const double noise = std::max(1e-8, 10.0 * std::sqrt(be)) * std::abs(l);
      out.omega.push_back(std::abs(l.imag()) <= 1e-10 * std::abs(l) ? 0.0 : std::abs(l.imag()));
      out.growth.push_back(std::abs(l.real()) <= noise ? 0.0 : std::abs(l.real()));
      out.backward_error.push_back(be);
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
  sorted.start = std::move(out.start);
  sorted.iterations = out.iterations;
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

}  // namespace modalbench::rfem::detail
