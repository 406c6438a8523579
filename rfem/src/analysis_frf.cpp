// rfem receptance FRFs: direct sparse solves per frequency, or modal superposition.
#include "modalbench/rfem/analysis.hpp"

#include <fmt/format.h>

#include <Eigen/UmfPackSupport>

#include <new>
#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "modalbench/rfem/factor.hpp"
#include "analysis_detail.hpp"

namespace modalbench::rfem {

namespace {
using detail::Clock;
using detail::ConstraintProjector;
using detail::seconds_since;
}  // namespace

FrfResult frf_direct(const Model& model, const System& sys, const Eigen::VectorXd& f, const Eigen::VectorXd& g,
                     const std::vector<double>& omegas) {
  using Cplx = std::complex<double>;
  using CSp = Eigen::SparseMatrix<Cplx>;
  FrfResult out;
  const long n = sys.n(), m = sys.m();
  const double eta = model.loss_factor;
  const bool real = eta == 0 && sys.C.nonZeros() == 0;
  const double fn = std::max(f.norm(), 1e-300);
  // Undamped: the real symmetric dynamic stiffness K - w^2 M by the saddle-point LDL' (its
  // symbolic analysis done once); a sample whose residual is poor falls back to the LU below.
  KktLdlt ldlt;
  if (real) ldlt.analyze(SpMat(sys.K + sys.M), sys.G, sys.groups);
  long fallbacks = 0;
  double s = 0;
  for (long i = 0; i < n; ++i) s += std::abs(sys.K.coeff(i, i));
  s = n > 0 && s > 0 ? s / static_cast<double>(n) : 1.0;
  std::vector<Eigen::Triplet<Cplx>> base;
  auto add = [&](const SpMat& A, Cplx factor) {
    for (int j = 0; j < A.outerSize(); ++j)
      for (SpMat::InnerIterator it(A, j); it; ++it) base.emplace_back(it.row(), j, factor * it.value());
  };
  for (int j = 0; j < sys.G.outerSize(); ++j)
    for (SpMat::InnerIterator it(sys.G, j); it; ++it) {
      base.emplace_back(n + it.row(), j, s * it.value());
      base.emplace_back(j, n + it.row(), s * it.value());
    }
  const std::size_t nborder = base.size();
  Eigen::UmfPackLU<CSp> lu;
  bool analysed = false;
  Eigen::VectorXcd rhs = Eigen::VectorXcd::Zero(n + m);
  rhs.head(n) = f.cast<Cplx>();
  const ConstraintProjector P(sys.G);
  for (double w : omegas) {
    const auto t0 = Clock::now();
    if (real) {
      const SpMat A = sys.K - (w * w) * sys.M;
      if (ldlt.factorize(A)) {
        const Eigen::VectorXd x = ldlt.solve(f);
        const double res = P(A * x - f).norm() / fn;
        out.factor_seconds += seconds_since(t0);
        if (res < 1e-8 && x.allFinite()) {
          out.omega.push_back(w);
          out.receptance.push_back(Cplx(g.dot(x), 0.0));
          continue;
        }
      }
      ++fallbacks;
    }
    base.resize(nborder);
    add(sys.K, Cplx(1.0, eta));
    add(sys.C, Cplx(0.0, w));
    add(sys.M, Cplx(-w * w, 0.0));
    CSp A(n + m, n + m);
    A.setFromTriplets(base.begin(), base.end());
    A.makeCompressed();
    if (!analysed) {
      lu.analyzePattern(A);
      analysed = true;
    }
    lu.factorize(A);
    out.factor_seconds += seconds_since(t0);
    if (lu.umfpackFactorizeReturncode() == UMFPACK_ERROR_out_of_memory) throw std::bad_alloc();
    if (lu.info() != Eigen::Success) {
      ++out.skipped;
      continue;
    }
    const Eigen::VectorXcd x = lu.solve(rhs);
    const Cplx h = g.cast<Cplx>().dot(x.head(n));  // dot conjugates g, which is real
    if (!std::isfinite(std::abs(h))) {
      ++out.skipped;
      continue;
    }
    out.omega.push_back(w);
    out.receptance.push_back(h);
  }
  if (real)
    out.method = fmt::format(
        "direct, undamped: sparse LDL' of K - w^2 M{} per frequency (residual-checked; {} sample(s) by sparse LU)",
        m > 0 ? " with the constraint border" : "", fallbacks);
  else
    out.method = fmt::format(
        "direct: sparse LU (UMFPACK) of K(1 + i eta) + i w C - w^2 M{} per frequency, eta = {}",
        m > 0 ? " with the constraint border" : "", eta);
  return out;
}

FrfResult frf_modal(const Model& model, const System& sys, const Modes& modes, const Eigen::VectorXd& f,
                    const Eigen::VectorXd& g, const std::vector<double>& omegas) {
  using Cplx = std::complex<double>;
  FrfResult out;
  const double eta = model.loss_factor;
  const long k = modes.lambda.size();
  Eigen::VectorXd pf(k), pg(k), c(k);
  for (long i = 0; i < k; ++i) {
    const Eigen::VectorXd z = modes.Z.col(i);
    pf[i] = z.dot(f);
    pg[i] = z.dot(g);
    c[i] = z.dot(sys.C * z);
  }
  for (double w : omegas) {
    Cplx h = 0;
    bool singular = false;
    for (long i = 0; i < k; ++i) {
      const Cplx den = Cplx(modes.lambda[i] - w * w, eta * modes.lambda[i] + w * c[i]);
      if (std::abs(den) == 0) {
        singular = true;
        break;
      }
      h += pg[i] * pf[i] / den;
    }
    if (singular || !std::isfinite(std::abs(h))) {
      ++out.skipped;
      continue;
    }
    out.omega.push_back(w);
    out.receptance.push_back(h);
  }
  out.method = fmt::format("modal superposition over {} modes (diagonal modal damping z' C z, eta = {})", k, eta);
  return out;
}

}  // namespace modalbench::rfem
