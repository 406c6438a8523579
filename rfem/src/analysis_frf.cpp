// rfem receptance FRFs: direct sparse solves per frequency, or modal superposition.
#include "modalbench/rfem/analysis.hpp"

#include <fmt/format.h>

#include <Eigen/UmfPackSupport>

#include <new>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <optional>
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

namespace {

/// The projected model the samples are evaluated from: Ritz pairs and their residuals' measure.
struct Projection {
  long p;                         ///< basis size
  Eigen::VectorXd theta, pf, pg;  ///< Ritz values; the load's and the probe's components
  Eigen::MatrixXd Gram, GramAbs;  ///< the residual pieces in the flexibility
  double g_out;                   ///< the probe's part on the modes left out
};

/// The modes below sigma and up to four load-dependent Ritz vectors (ldlt: K - s M); none if empty.
std::optional<Eigen::MatrixXd> ritz_basis(const System& sys, const KktLdlt& ldlt, const Eigen::VectorXd& f,
                                          const Modes& modes, long below) {
  const long n = sys.n();
  constexpr int kRitz = 4;
  Eigen::MatrixXd V(n, below + kRitz);
  if (below > 0) V.leftCols(below) = modes.Z;
  long p = below;
  Eigen::VectorXd u = f;
  for (int j = 0; j < kRitz; ++j) {
    u = ldlt.solve(j == 0 ? f : Eigen::VectorXd(sys.M * u));
    Eigen::VectorXd v = u;
    const double before = std::sqrt(std::max(0.0, v.dot(sys.M * v)));
    if (!(before > 0) || !std::isfinite(before)) break;
    for (int pass = 0; pass < 2; ++pass)  // M-orthogonal to the basis, twice (Gram-Schmidt)
      if (p > 0) v -= V.leftCols(p) * (V.leftCols(p).transpose() * (sys.M * v));
    const double after = std::sqrt(std::max(0.0, v.dot(sys.M * v)));
    if (!(after > 1e-10 * before)) break;  // the span holds it already
    V.col(p++) = v / after;
  }
  V.conservativeResize(n, p);
  if (p == 0 || !V.allFinite()) return std::nullopt;
  return V;
}

/// The Ritz pairs of the pencil projected onto V and their residuals' measure; none where they fail.
std::optional<Projection> project(const System& sys, const KktLdlt& ldlt, const Eigen::MatrixXd& V,
                                  const Eigen::VectorXd& f, const Eigen::VectorXd& g, const Modes& modes, long below,
                                  double shift) {
  const long n = sys.n(), p = V.cols();
  // Ritz pairs of the projected pencil (V' M V = I up to rounding: taken as a pencil anyway).
  const Eigen::MatrixXd KV = sys.K * V, MV = sys.M * V;
  Eigen::MatrixXd Kr = V.transpose() * KV, Mr = V.transpose() * MV;
  Kr = 0.5 * (Kr + Kr.transpose()).eval();
  Mr = 0.5 * (Mr + Mr.transpose()).eval();
  if (!Kr.allFinite() || !Mr.allFinite() || Eigen::LLT<Eigen::MatrixXd>(Mr).info() != Eigen::Success) return std::nullopt;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kr, Mr);
  if (es.info() != Eigen::Success || !es.eigenvalues().allFinite()) return std::nullopt;
  const Eigen::VectorXd theta = es.eigenvalues();
  const Eigen::MatrixXd& Q = es.eigenvectors();  // Mr-orthonormal
  const Eigen::MatrixXd Y = V * Q;
  const Eigen::VectorXd pf = Y.transpose() * f, pg = Y.transpose() * g;
  // Residual pieces: S = K Y - M Y Theta and f_perp = f - M Y pf (r = (1 + i eta) S y - f_perp).
  Eigen::MatrixXd A(n, p + 1);
  const Eigen::MatrixXd MY = MV * Q;
  A.leftCols(p) = KV * Q - MY * theta.asDiagonal();
  A.col(p) = f - MY * pf;
  // Their energy in the flexibility (K - s M)^-1 of the constrained model (the KKT solve: the
  // constraint forces drop out), and the part of g on the modes left out in the same measure.
  Eigen::MatrixXd FA(n, p + 1);
  for (long i = 0; i <= p; ++i) FA.col(i) = ldlt.solve(A.col(i));
  const Eigen::MatrixXd Gram = A.transpose() * FA;  // (p+1) x (p+1), real symmetric
  const Eigen::MatrixXd GramAbs = Gram.cwiseAbs();
  double g_in = 0;
  for (long i = 0; i < below; ++i) {
    const double c = modes.Z.col(i).dot(g);
    g_in += c * c / (modes.lambda[i] - shift);
  }
  const double g_all = std::max(0.0, g.dot(ldlt.solve(g)));
  const double g_out = std::sqrt(std::max(g_all - g_in, 1e-14 * g_all));
  return Projection{p, theta, pf, pg, Gram, GramAbs, g_out};
}

/// The samples whose bound meets the target into out; returns the frequencies to solve directly.
std::vector<double> projected_samples(const Projection& pr, double eta, double sigma, double shift,
                                      const std::vector<double>& omegas, double target, FrfResult& out) {
  using Cplx = std::complex<double>;
  const long p = pr.p;
  const Eigen::VectorXd &theta = pr.theta, &pf = pr.pf, &pg = pr.pg;
  const Eigen::MatrixXd &Gram = pr.Gram, &GramAbs = pr.GramAbs;
  const double g_out = pr.g_out;
  const Cplx one_eta(1.0, eta);
  Eigen::VectorXcd c(p + 1);
  std::vector<double> redo;
  double worst = 0;
  for (double w : omegas) {
    Cplx h = 0;
    bool singular = false;
    for (long i = 0; i < p; ++i) {
      const Cplx den = one_eta * theta[i] - w * w;
      if (std::abs(den) == 0) {
        singular = true;
        break;
      }
      const Cplx y = pf[i] / den;
      h += pg[i] * y;
      c[i] = one_eta * y;
    }
    if (singular) {
      ++out.skipped;
      continue;
    }
    c[p] = -1.0;
    // The quadratic form cancels (the residual is far smaller than its pieces): its rounding,
    // eps (p + 1) |c|' |Gram| |c|, is added rather than left to make it zero or negative.
    const Eigen::VectorXd ca = c.cwiseAbs();
    const double r2 = std::max(0.0, (c.adjoint() * Gram * c).real()(0, 0)) +
                      std::numeric_limits<double>::epsilon() * static_cast<double>(p + 1) * ca.dot(GramAbs * ca);
    // For a mode left out (lambda >= sigma > w^2, shift s < 0): 1 / |(1 + i eta) lambda - w^2|
    // <= (1 - s / sigma) / ((1 - w^2 / sigma) (lambda - s)); Cauchy-Schwarz in the weights 1 / (lambda - s).
    const double bound = (1.0 - shift / sigma) / (1.0 - w * w / sigma) * g_out * std::sqrt(r2);
    const double rel = bound / std::abs(h);
    if (!(rel <= target) || !std::isfinite(std::abs(h))) {
      redo.push_back(w);
      continue;
    }
    worst = std::max(worst, rel);
    out.omega.push_back(w);
    out.receptance.push_back(h);
    out.error_bounds.push_back(rel);
  }
  out.max_error_bound = out.omega.empty() ? std::numeric_limits<double>::quiet_NaN() : worst;
  return redo;
}

/// The samples at `redo` solved directly, merged with those in out in frequency order.
void add_direct_samples(const Model& model, const System& sys, const Eigen::VectorXd& f, const Eigen::VectorXd& g,
                        const std::vector<double>& redo, FrfResult& out) {
  using Cplx = std::complex<double>;
  const FrfResult d = frf_direct(model, sys, f, g, redo);
  out.factor_seconds += d.factor_seconds;
  out.skipped += d.skipped;
  out.direct_samples = static_cast<long>(d.omega.size());
  // Merge in frequency order.
  struct Sample {
    double w;
    Cplx h;
    double bound;
  };
  std::vector<Sample> all;
  for (std::size_t i = 0; i < out.omega.size(); ++i) all.push_back({out.omega[i], out.receptance[i], out.error_bounds[i]});
  for (std::size_t i = 0; i < d.omega.size(); ++i)
    all.push_back({d.omega[i], d.receptance[i], std::numeric_limits<double>::quiet_NaN()});
  std::stable_sort(all.begin(), all.end(), [](const Sample& a, const Sample& b) { return a.w < b.w; });
  out.omega.clear();
  out.receptance.clear();
  out.error_bounds.clear();
  for (const Sample& x : all) {
    out.omega.push_back(x.w);
    out.receptance.push_back(x.h);
    out.error_bounds.push_back(x.bound);
  }
}

}  // namespace

bool frf_projected(const Model& model, const System& sys, const Eigen::VectorXd& f, const Eigen::VectorXd& g,
                   const std::vector<double>& omegas, const ProjectedFrfOptions& options, FrfResult& out) {
  if (sys.C.nonZeros() > 0 || omegas.empty()) return false;
  const double w_max = *std::max_element(omegas.begin(), omegas.end());
  if (!(w_max > 0) || !std::isfinite(w_max)) return false;
  const auto t0 = Clock::now();
  const double eta = model.loss_factor;
  // How many modes lie below sigma = (2 w_max)^2: the inertia of K - sigma M (Sylvester).
  const double sigma = 4.0 * w_max * w_max;
  KktLdlt ldlt;
  ldlt.analyze(SpMat(sys.K + sys.M), sys.G, sys.groups);
  if (!ldlt.factorize(SpMat(sys.K - sigma * sys.M))) return false;
  const long below = ldlt.negative_count();
  if (below < 0 || below > options.max_modes || below >= sys.n() - sys.m() - 4) return false;
  Modes modes;
  if (below > 0) {
    ModeOptions mo = options.modes;
    mo.modes = static_cast<int>(below);
    modes = solve_modes(model, sys, mo);
    if (!modes.converged || modes.lambda.size() != below) return false;
    // Every mode kept must lie below sigma, or the count and the solve disagree.
    if (modes.lambda[below - 1] >= sigma) return false;
  }
  // Load-dependent Ritz vectors: the quasi-static response of what the modes leave out.
  const double shift = -0.25 * w_max * w_max;
  if (!ldlt.factorize(SpMat(sys.K - shift * sys.M))) return false;
  const std::optional<Eigen::MatrixXd> V = ritz_basis(sys, ldlt, f, modes, below);
  if (!V) return false;
  const std::optional<Projection> pr = project(sys, ldlt, *V, f, g, modes, below, shift);
  if (!pr) return false;
  out.factor_seconds += seconds_since(t0);

  const std::vector<double> redo = projected_samples(*pr, eta, sigma, shift, omegas, options.target, out);
  if (!redo.empty()) add_direct_samples(model, sys, f, g, redo, out);
  out.method = fmt::format(
      "projected (Galerkin) onto the {} modes below 2 w_max = {:.6g} rad/s (Sturm count) and {} load-dependent Ritz "
      "vectors, eta = {}; each sample's error bounded from its residual (largest bound {:.2g} of |H|, target {:.2g}); "
      "{} sample(s) solved directly where the bound missed the target",
      below, 2.0 * w_max, pr->p - below, eta, out.max_error_bound, options.target, out.direct_samples);
  return true;
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
