// rfem natural modes: dense or shift-invert Lanczos with a Sturm check, family labels, residuals.
#include "modalbench/rfem/analysis.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <random>
#include <stdexcept>

#include "modalbench/rfem/factor.hpp"
#include "analysis_detail.hpp"

namespace modalbench::rfem {

namespace {

using detail::Clock;
using detail::ConstraintProjector;
using detail::dense_flexible;
using detail::Flexible;
using detail::seconds_since;

/// y = P_R (K - sigma M)^{-1} x, P_R = I - R R' M (rigid modes deflated), with G z = 0 enforced.
class ShiftInvertOp {
 public:
  using Scalar = double;
  ShiftInvertOp(const System& sys, const Eigen::MatrixXd& R) : sys_(sys), R_(R), MR_(sys.M * R) {
    pattern_ = sys.K + sys.M;
  }
  Eigen::Index rows() const { return sys_.K.rows(); }
  Eigen::Index cols() const { return sys_.K.rows(); }
  void set_shift(double sigma) {
    if (factored_ && sigma == sigma_) return;  // the retries of one solve reuse the factor
    const auto t0 = Clock::now();
    const SpMat A = sys_.K - sigma * sys_.M;
    if (!analysed_) {
      // The supernodal LDL' where the analysis finds dense fronts (plates): it factors this
      // matrix in half the time CHOLMOD's supernodal LL' took (Mindlin plate, 168 x 120
      // fragments: 0.15 s against 0.33 s, on one thread). CHOLMOD's LL' otherwise (beams).
      kkt_.analyze(pattern_, sys_.G, sys_.groups);
      use_pd_ = sys_.m() == 0 && !kkt_.supernodal();
      if (use_pd_) pd_.analyze(pattern_, sys_.groups);
      analysed_ = true;
    }
    if (use_pd_) {
      if (!pd_.factorize(A))
        throw std::runtime_error(fmt::format(
            "K - sigma M is not positive definite at sigma = {:.6g} (below every eigenvalue it must be): the stiffness "
            "matrix is indefinite",
            sigma));
      solver_name_ = pd_.name();
    } else {
      if (!kkt_.factorize(A) || kkt_.negative_count() != 0)
        throw std::runtime_error(fmt::format(
            "K - sigma M is not positive definite{} at sigma = {:.6g} (below every eigenvalue it must be): the "
            "stiffness matrix is indefinite",
            sys_.m() == 0 ? "" : " on the constraints", sigma));
      const char* threads = kkt_.two_thread_solves() ? ", two threads" : "";
      solver_name_ = sys_.m() == 0 ? fmt::format("supernodal sparse LDL' (grouped AMD{})", threads)
                                   : fmt::format("saddle-point {} sparse LDL' (multipliers after their unknowns, AMD{})",
                                                 kkt_.supernodal() ? "supernodal" : "simplicial", threads);
    }
    factor_seconds_ += seconds_since(t0);
    factored_ = true;
    sigma_ = sigma;
  }
  void perform_op(const double* x_in, double* y_out) const {
    if (use_pd_) pd_.solve_into(x_in, y_out);
    else kkt_.solve_into(x_in, y_out);
    if (R_.cols() > 0) {
      Eigen::Map<Eigen::VectorXd> y(y_out, rows());
      y -= R_ * (MR_.transpose() * y);
    }
    ++operations_;
  }
  long operations() const { return operations_; }
  double factor_seconds() const { return factor_seconds_; }
  const std::string& solver_name() const { return solver_name_; }

 private:
  const System& sys_;
  const Eigen::MatrixXd& R_;
  Eigen::MatrixXd MR_;
  SpMat pattern_;
  PdFactor pd_;
  KktLdlt kkt_;
  bool analysed_ = false, use_pd_ = false;
  mutable long operations_ = 0;
  double factor_seconds_ = 0;
  bool factored_ = false;
  double sigma_ = 0;
  std::string solver_name_;
};

double choose_shift(const Model& model, const System& sys) {
  double w = model.omega_hint;
  if (!(w > 0)) {
    std::vector<double> ratio;
    for (long i = 0; i < sys.n(); ++i)
      if (sys.M.coeff(i, i) > 0) ratio.push_back(std::abs(sys.K.coeff(i, i)) / sys.M.coeff(i, i));
    std::nth_element(ratio.begin(), ratio.begin() + static_cast<long>(ratio.size() / 2), ratio.end());
    w = ratio.empty() ? 1.0 : 1e-3 * std::sqrt(ratio[ratio.size() / 2]);
  }
  return -std::pow(0.2 * w, 2);
}

}  // namespace

std::vector<double> family_shares(const Model& model, const Eigen::VectorXd& q) {
  std::vector<double> share(7, 0.0);
  const int na = model.dofs_per_element();
  double total = 0;
  for (std::size_t e = 0; e < model.elements.size(); ++e)
    for (int k = 0; k < na; ++k) {
      const int d = model.active[static_cast<std::size_t>(k)];
      const double mass = d < 3 ? model.elements[e].mass : model.elements[e].inertia[d - 3];
      const double v = q[static_cast<long>(e) * na + k];
      const double en = mass * v * v;
      share[static_cast<std::size_t>(model.dof_family[static_cast<std::size_t>(k)])] += en;
      total += en;
    }
  if (total > 0)
    for (double& s : share) s /= total;
  return share;
}

namespace {

/// Two steps of subspace iteration with the sparse shift-invert operator (factorized at sigma) on
/// the full coordinates, each closed by Rayleigh-Ritz: W' (K - sigma M) W = W' M Z needs no
/// product with K, so the refined pairs do not inherit the rounding of a reduced K formed through
/// the constraint basis (dense path: a beam on 1e12 EI/L^3 springs, 128 segments, backward error
/// 1e-7 -> 5e-9) nor the Lanczos tolerance on the operator's small eigenvalues (a deep beam,
/// L/h = 0.5, 512 segments: 1.5e-7). Returns the steps completed (a failed Rayleigh-Ritz step
/// keeps the pairs it had).
int refine_pairs(ShiftInvertOp& op, const System& sys, double sigma, Flexible& flex) {
  const long n = sys.n(), k = flex.lambda.size();
  int steps = 0;
  for (bool ok = true; steps < 2 && ok;) {
    const Eigen::MatrixXd MZ = sys.M * flex.Z;
    Eigen::MatrixXd W(n, k);
    Eigen::VectorXd s(k);
    for (long j = 0; j < k; ++j) {
      op.perform_op(MZ.col(j).data(), W.col(j).data());
      s[j] = 1.0 / std::sqrt(W.col(j).dot(sys.M * W.col(j)));
      W.col(j) *= s[j];
    }
    Eigen::MatrixXd A = W.transpose() * MZ * s.asDiagonal();  // W' (K - sigma M) W
    A = 0.5 * (A + A.transpose()).eval();
    Eigen::MatrixXd B = W.transpose() * (sys.M * W);
    B = 0.5 * (B + B.transpose()).eval();
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> rr(A, B);
    ok = rr.info() == Eigen::Success && rr.eigenvalues().minCoeff() > 0;
    if (ok) {
      flex.lambda = (rr.eigenvalues().array() + sigma).matrix();
      flex.Z = W * rr.eigenvectors();
      ++steps;
    }
  }
  return steps;
}

/// Largest componentwise backward error of the pairs, as the final check measures it (constraint
/// forces projected out, against |K| |z| + lambda |M| |z|, and the constraint violation): only to
/// decide whether refine_pairs runs after Lanczos.
double pair_backward_error(const System& sys, const Flexible& flex) {
  const ConstraintProjector P(sys.G);
  const SpMat Ka = sys.K.cwiseAbs(), Ma = sys.M.cwiseAbs();
  double worst = 0;
  for (long j = 0; j < flex.lambda.size(); ++j) {
    const Eigen::VectorXd z = flex.Z.col(j);
    Eigen::VectorXd res = sys.K * z - flex.lambda[j] * (sys.M * z);
    if (sys.m() > 0) res = P(res);
    const Eigen::VectorXd za = z.cwiseAbs();
    const double scale = (Ka * za + std::abs(flex.lambda[j]) * (Ma * za)).norm();
    const double viol = sys.m() > 0 ? (sys.G * z).norm() / z.norm() : 0.0;
    worst = std::max({worst, res.norm() / std::max(scale, 1e-300), viol});
  }
  return worst;
}

/// What the phases of one eigensolve share: the problem, its rigid modes, the counts and the result.
struct ModeSolve {
  const Model& model;
  const System& sys;
  const ModeOptions& opt;
  const Eigen::MatrixXd& R;  ///< the free rigid modes
  long n_eff, kf;            ///< the flexible space's dimension; the flexible pairs wanted
  Modes& out;
  std::string how;  ///< the method so far (out.method at the end)
};

/// The dense path: the flexible pairs, refined on the full coordinates when few are wanted.
Flexible dense_modes(ModeSolve& ms) {
  const System& sys = ms.sys;
  Modes& out = ms.out;
  const long kf = ms.kf;
  const double sigma = choose_shift(ms.model, sys);
  Flexible flex = dense_flexible(sys, ms.R, kf, sigma, ms.how);
  // Two steps of subspace iteration with the sparse operator on the full coordinates, each
  // closed by Rayleigh-Ritz: the reduced matrices of the dense path are formed through the
  // constraint basis, which spreads the rounding of stiff supports over every coordinate;
  // W' (K - sigma M) W = W' M Z needs no product with K, so the refined pairs do not inherit it
  // (beam on 1e12 EI/L^3 springs, 128 segments: backward error 1e-7 -> 5e-9). Only when a
  // small part of the spectrum is wanted: the complete spectral decomposition of the FRF would
  // pay O(n^3) again for nothing.
  if (3 * kf < ms.n_eff) {
    try {
      ShiftInvertOp op(sys, ms.R);
      op.set_shift(sigma);
      const int steps = refine_pairs(op, sys, sigma, flex);
      out.factor_seconds += op.factor_seconds();
      if (steps > 0)
        ms.how += fmt::format("; refined by {} shift-invert subspace step(s) on the full coordinates ({})", steps,
                              op.solver_name());
      if (steps < 2)
        out.warnings.push_back(fmt::format("dense eigenpairs refined by {} of 2 steps: a Rayleigh-Ritz step failed", steps));
    } catch (const std::exception& e) {
      out.warnings.push_back(fmt::format("dense eigenpairs not refined: {}", e.what()));
    }
  }
  return flex;
}

/// What the Lanczos attempts share (the generator's draws go on from one attempt to the next).
struct Lanczos {
  ShiftInvertOp op;
  Spectra::SparseSymMatProd<double> bop;
  std::mt19937 rng;
  std::uniform_real_distribution<double> uni;
  double sigma;
};

/// The Sturm check's LDL', its symbolic analysis run on a second core while Lanczos iterates.
struct SturmCheck {
  KktLdlt ldlt;
  bool analysed = false;
  std::future<void> analysis;  ///< last: its destructor waits for the analysis before ldlt goes
};

/// One Lanczos run for nev pairs (subspace ncv) into flex; false, with a warning, where it fails.
bool lanczos_attempt(ModeSolve& ms, Lanczos& lz, long nev, long ncv, Flexible& flex) {
  const long n = ms.sys.n();
  Modes& out = ms.out;
  Spectra::SymGEigsShiftSolver<ShiftInvertOp, Spectra::SparseSymMatProd<double>, Spectra::GEigsMode::ShiftInvert>
      eigs(lz.op, lz.bop, nev, ncv, lz.sigma);
  // Start in the flexible space: the operator maps onto {G z = 0, R' M z = 0}.
  Eigen::VectorXd v0(n), s0(n);
  for (long i = 0; i < n; ++i) v0[i] = lz.uni(lz.rng);
  lz.op.perform_op(v0.data(), s0.data());
  eigs.init(s0.data());
  const long nconv = eigs.compute(Spectra::SortRule::LargestMagn, 1000, ms.opt.tolerance, Spectra::SortRule::SmallestAlge);
  out.iterations += eigs.num_iterations();
  flex.lambda = eigs.eigenvalues();
  flex.Z = eigs.eigenvectors();
  const bool ok = eigs.info() == Spectra::CompInfo::Successful && nconv >= nev;
  ms.how = fmt::format(
      "shift-invert Lanczos (Spectra SymGEigsShiftSolver, sigma = {:.6g} rad^2/s^2, nev = {}, ncv = {}, {}), {} of {} "
      "converged in {} restarts, {} solves",
      lz.sigma, nev, ncv, lz.op.solver_name(), nconv, nev, eigs.num_iterations(), lz.op.operations());
  if (!ok) {
    out.converged = false;
    out.warnings.push_back(fmt::format("Lanczos did not converge: {} of {} eigenpairs (tolerance {:g})", nconv, nev,
                                       ms.opt.tolerance));
  }
  return ok;
}

/// The Sturm check of the pairs found: true where Lanczos must rerun, with the larger nev it sets.
bool sturm_asks_rerun(ModeSolve& ms, SturmCheck& sturm, const Flexible& flex, double sigma, int attempt, long& nev) {
  const System& sys = ms.sys;
  Modes& out = ms.out;
  const long kf = ms.kf;
  // Sturm count just above the kf-th eigenvalue.
  const double mu = flex.lambda[kf - 1] * (1 + 1e-6) + 1e-12 * std::abs(sigma);
  const auto t0 = Clock::now();
  if (!sturm.analysed) {
    sturm.analysis.get();  // rethrows what the analysis threw
    sturm.analysed = true;
  }
  const bool fact = sturm.ldlt.factorize(SpMat(sys.K - mu * sys.M));
  out.factor_seconds += seconds_since(t0);
  if (!fact) {
    out.warnings.push_back("Sturm count skipped: zero pivot at the check point");
    return false;
  }
  const long count = sturm.ldlt.negative_count();
  long found = ms.R.cols();
  for (long i = 0; i < flex.lambda.size(); ++i) found += flex.lambda[i] < mu;
  out.sturm_count = count;
  if (count == found) {
    ms.how += fmt::format("; Sturm count {} below {:.8g} rad/s agrees", count, std::sqrt(mu));
    return false;
  }
  if (count < found) {
    out.converged = false;
    out.warnings.push_back(fmt::format("Sturm count {} below {:.8g} rad/s is less than the {} modes found", count,
                                       std::sqrt(mu), found));
    return false;
  }
  if (attempt == 2) {
    out.converged = false;
    out.warnings.push_back(fmt::format("Sturm count {} below {:.8g} rad/s exceeds the {} modes found: modes missed",
                                       count, std::sqrt(mu), found));
    return false;
  }
  // A recovery, not a doubt: the rerun's modes face the same count (a fall-back on record).
  out.fallbacks.push_back(fmt::format("eigen: the Sturm count found {} mode(s) missed by Lanczos; rerun with nev = {}",
                                      count - found, nev + (count - found) + 2));
  nev += (count - found) + 2;
  nev = std::min(nev, ms.n_eff - 1);
  return true;
}

/// The sparse path: shift-invert Lanczos checked by a Sturm count, refined where the pairs are poor.
Flexible lanczos_modes(ModeSolve& ms) {
  const System& sys = ms.sys;
  const ModeOptions& opt = ms.opt;
  Modes& out = ms.out;
  const long kf = ms.kf, n_eff = ms.n_eff;
  if (kf >= n_eff) throw std::runtime_error("shift-invert Lanczos needs fewer modes than unknowns; use the dense solver");
  const double sigma = choose_shift(ms.model, sys);
  out.shift = sigma;
  Lanczos lz{ShiftInvertOp(sys, ms.R), Spectra::SparseSymMatProd<double>(sys.M), std::mt19937(opt.seed),
             std::uniform_real_distribution<double>(-1.0, 1.0), sigma};
  SturmCheck sturm;
  // The Sturm check's ordering and symbolic analysis need only the pattern: on a second core
  // they overlap the Lanczos iteration (read-only access to sys on both threads).
  if (opt.sturm_check)
    sturm.analysis = std::async(std::launch::async, [&ldlt = sturm.ldlt, &sys] {
      detail::reserve_blas_workspace();
      ldlt.analyze(SpMat(sys.K + sys.M), sys.G, sys.groups);
    });
  Flexible flex;
  long nev = kf;
  for (int attempt = 0; attempt < 3; ++attempt) {
    const long ncv = std::min<long>(n_eff, std::max<long>(2 * nev + 1, nev + 16));
    if (nev >= ncv) throw std::runtime_error("too many modes requested for the Lanczos subspace; use the dense solver");
    if (!lanczos_attempt(ms, lz, nev, ncv, flex)) break;
    if (!opt.sturm_check || flex.lambda.size() < kf) break;
    if (!sturm_asks_rerun(ms, sturm, flex, sigma, attempt, nev)) break;
  }
  if (flex.lambda.size() > kf) {
    flex.lambda.conservativeResize(kf);
    flex.Z.conservativeResize(Eigen::NoChange, kf);
  }
  if (const double back = out.converged && kf > 0 && 3 * kf < n_eff ? pair_backward_error(sys, flex) : 0.0;
      back > opt.backward_error_warning) {
    // The operator is factorized at sigma already: two more solves per pair.
    const Flexible before = flex;
    const int steps = refine_pairs(lz.op, sys, sigma, flex);
    if (steps > 0 && pair_backward_error(sys, flex) < back)
      ms.how += fmt::format("; refined by {} shift-invert subspace step(s)", steps);
    else
      flex = before;
  }
  out.operations = lz.op.operations();
  out.factor_seconds += lz.op.factor_seconds();
  return flex;
}

/// The first nr rigid modes (exact zeros), then the flexible pairs M-normalized, into out.
void store_pairs(const System& sys, const Eigen::MatrixXd& R, long nr, const Flexible& flex, Modes& out) {
  const long n = sys.n();
  const long nf = flex.lambda.size();
  out.rigid = static_cast<int>(nr);
  out.lambda.resize(nr + nf);
  out.Z.resize(n, nr + nf);
  for (long i = 0; i < nr; ++i) {
    out.lambda[i] = 0;
    out.Z.col(i) = R.col(i);
  }
  for (long i = 0; i < nf; ++i) {
    out.lambda[nr + i] = flex.lambda[i];
    Eigen::VectorXd z = flex.Z.col(i);
    const double mn = std::sqrt(z.dot(sys.M * z));
    out.Z.col(nr + i) = z / mn;
  }
}

Modes solve_modes_once(const Model& model, const System& sys, const ModeOptions& opt) {
  Modes out;
  const long n = sys.n(), m = sys.m();
  if (opt.modes <= 0) {
    out.lambda.resize(0);
    out.Z.resize(n, 0);
    return out;
  }
  auto t_eigen = Clock::now();
  const RigidModes rigid = free_rigid_modes(model, sys);
  const Eigen::MatrixXd& R = rigid.Z;
  const long r = R.cols();
  const long n_eff = n - m - r;  // dimension of the flexible space
  const long want = opt.modes;
  long kf = std::max<long>(0, want - r);
  if (kf > n_eff) {
    out.warnings.push_back(fmt::format("only {} flexible modes exist in this model ({} requested)", n_eff, kf));
    kf = n_eff;
  }
  // Dense when small; also when most of a moderate spectrum is wanted (Lanczos would need a
  // subspace close to the whole space). Its cost grows like n (m + r)^2, hence the bounds on n.
  // Every flexible mode (a time history's doubling ran past the mesh's unknowns) is the dense
  // solver's whatever the size: shift-invert Lanczos needs fewer modes than unknowns.
  const bool all_flexible = kf > 0 && kf >= n_eff;
  const bool dense = opt.method == EigenMethod::Dense || all_flexible ||
                     (opt.method == EigenMethod::Auto &&
                      (n <= opt.dense_limit || (3 * kf >= n_eff && n <= 4 * opt.dense_limit) || n_eff < 40));
  if (all_flexible && opt.method == EigenMethod::ShiftInvert)
    out.fallbacks.push_back(fmt::format("eigen: shift-invert asked, but all {} flexible modes are wanted (Lanczos needs "
                                        "fewer modes than unknowns): the dense solver instead",
                                        n_eff));
  ModeSolve ms{model, sys, opt, R, n_eff, kf, out, {}};
  Flexible flex;
  if (kf > 0 && dense) flex = dense_modes(ms);
  else if (kf > 0) flex = lanczos_modes(ms);
  if (kf == 0) ms.how = "no flexible modes requested";

  // Rigid modes (exact zeros) then the flexible ones.
  const long nr = std::min<long>(r, want);
  store_pairs(sys, R, nr, flex, out);
  std::string rigid_text;
  if (r > 0) {
    rigid_text = fmt::format("; {} free rigid-body mode(s) ({}) found structurally and reported as 0", r,
                             fmt::join(rigid.motions, "; "));
  }
  const std::vector<char> near_rigid = detail::take_near_rigid_pairs(model, sys, nr, out, rigid_text);
  out.method = ms.how + rigid_text;

  detail::label_families(model, sys, nr, out);
  detail::measure_residuals(sys, nr, near_rigid, out);
  out.eigen_seconds = seconds_since(t_eigen) - out.factor_seconds;
  return out;
}

}  // namespace

Modes solve_modes(const Model& model, const System& sys, const ModeOptions& opt) {
  Modes out = solve_modes_once(model, sys, opt);
  // Near-mechanism supports leave Lanczos pairs of near-rigid modes at a backward error of 1e-9
  // (beam on K = 1e-6 springs, 128 segments); the dense path's refinement reaches 1e-11.
  const bool lanczos = out.method.find("Lanczos") != std::string::npos;
  if (opt.method != EigenMethod::Auto || !lanczos || out.max_backward_error <= opt.backward_error_warning ||
      sys.n() > kDenseFallbackLimit)
    return out;
  ModeOptions dense = opt;
  dense.method = EigenMethod::Dense;
  Modes second = solve_modes_once(model, sys, dense);
  if (!(second.max_backward_error < out.max_backward_error) || second.lambda.size() != out.lambda.size()) return out;
  second.fallbacks.push_back(fmt::format("eigen: Lanczos pairs had backward error {:.2g} > {:.1g}; the dense path "
                                         "(refined) gives {:.2g}",
                                         out.max_backward_error, opt.backward_error_warning, second.max_backward_error));
  second.factor_seconds += out.factor_seconds;
  second.eigen_seconds += out.eigen_seconds;
  return second;
}

}  // namespace modalbench::rfem
