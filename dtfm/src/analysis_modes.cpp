// LineAnalysis natural frequencies: count-driven slicing per class, family labels, reproducibility check.
#include "modalbench/dtfm/analysis.hpp"

#include <fmt/format.h>

#include <Eigen/SVD>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "analysis_detail.hpp"
#include "modalbench/numerics/line_system.hpp"
#include "modalbench/numerics/quadrature.hpp"
#include "modalbench/numerics/segment_dynamic_stiffness.hpp"
#include "modalbench/numerics/symmetric_factor.hpp"

namespace modalbench::dtfm {

namespace {
using detail::to_fields;
}  // namespace

double LineAnalysis::family_share(ClassLine& c, double lambda) {
  if (c.family_motions.cols() == 0) return 1.0;
  // The mode shape by one inverse-iteration solve just off the eigenvalue, on 32 segments.
  const Mesh mesh = mesh_for(c, lambda, {}, 32);
  const int nn = static_cast<int>(mesh.x.size());
  Eigen::VectorXd f(static_cast<Eigen::Index>(nn) * c.mc);
  for (Eigen::Index i = 0; i < f.size(); ++i) f[i] = std::sin(1.0 + 2.3 * static_cast<double>(i));  // deterministic
  // Just off the eigenvalue; further off if the solve meets the rounding floor (a very stiff
  // support makes the largest pivot huge): the contamination by other modes stays ~ shift / gap.
  Eigen::VectorXd d;
  for (double shift : {1e-7, 1e-5, 1e-3}) {
    try {
      d = assemble(c, lambda * (1.0 + shift) + 1e-12 * model_.lambda_scale, mesh).K.solve(f);
      break;
    } catch (const std::runtime_error&) {
      d.resize(0);
    }
  }
  if (d.size() == 0) return std::numeric_limits<double>::quiet_NaN();
  const auto q = to_fields(c, d, mesh.x);
  const Eigen::MatrixXd& T = c.family_motions;
  const Eigen::MatrixXd TM = T.transpose() * model_.M;
  const Eigen::MatrixXd H = TM * T;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(H);
  double rigid = 0, total = 0;
  for (int i = 0; i < nn; ++i) {
    const double w = (i > 0 ? mesh.x[i] - mesh.x[i - 1] : 0.0) + (i + 1 < nn ? mesh.x[i + 1] - mesh.x[i] : 0.0);
    const Eigen::VectorXd r = cod.solve(Eigen::VectorXd(TM * q[i]));
    rigid += w * r.dot(H * r);
    total += w * q[i].dot(model_.M * q[i]);
  }
  return total > 0 ? rigid / total : 0.0;
}

/// The lowest eigenvalues of a class with rigid motions of its own: its rigid-body modes (the
/// motions no support reaches: exactly 0) and its near-rigid modes (a beam on springs of 1e-6
/// N/m, or rocking on 1.9 N/m about a support of 8e18 N/m), which the count cannot resolve: K's
/// rounding is eps of its largest stiffness. They come from the split at lambda = 0
/// (detail::condense_rigid): the rigid amplitudes' condensed springs S (graded, the elastic
/// compliance included) against their mass Mr = int Phi^T M Phi dx. With S = L D L^T and
/// Mr = R^T R, 1/lambda are the squared singular values of Z = D^-1/2 L^-1 R^T, whose rows are
/// graded: one-sided Jacobi on them (rows sorted, full-pivot QR first) keeps the small lambda to
/// relative accuracy however stiff the other springs.
///
/// What the split leaves out is second order: the exact condition is S(lambda) a = 0 with
/// S(lambda) = S - lambda Mg - lambda^2 R(lambda), 0 <= lambda R <= lambda / (lambda_E - lambda) Mg
/// (lambda_E: the anchored line's lowest eigenvalue, bounded below by its inertia), and Mg, the
/// mass of the static shapes Psi - E^-1 B, differs from Mr by at most 2 sqrt(g) + g relative,
/// g = a^T B^T E^-1 B a / lambda_E. Their sum is each value's bound.
///
/// Every value below the count's threshold is taken with its bound (the solver flags a loose one).
/// Above it, the lowest ones whose bound is tight and which lie far below lambda_E (the count at a
/// point between them and the next must agree) become enclosures [l_RR / (1 + b), l_RR] of the
/// sliced values: l_RR is a Rayleigh-Ritz value of the static shapes, an upper bound. A sliced
/// value inside its enclosure stays (it is at least as accurate); one outside it is moved to the
/// enclosure's nearer end, with its bound (a rocking on 1.9 N/m beside 8e18 N/m was sliced 6.8e-7
/// off).
LineAnalysis::NearRigid LineAnalysis::near_rigid(ClassLine& c0, int below) {
  NearRigid out;
  out.rigid = below;
  const double delta = kRigidThreshold * model_.lambda_scale;
  out.lo = delta;
  out.below_lo = below;
  const std::optional<detail::RigidLine> rl = detail::rigid_line(c0, model_.length);
  if (!rl) return out;  // no rigid motions of its own (plates): below the threshold is rigid
  const int n_near = below - rl->unrestrained;  // near-rigid ones below the threshold
  const Eigen::Index rf = static_cast<Eigen::Index>(rl->free_a.size());
  auto fail = [&](const std::string& why) {
    if (n_near > 0)
      out.problem = fmt::format("{} mode(s) of the {} family below {:g} of the stiffness scale are not rigid-body "
                                "modes (supports reach them) but could not be resolved, reported as 0: {}",
                                n_near, to_string(c0.family), kRigidThreshold, why);
    return out;
  };
  if (rf == 0 && n_near <= 0) return out;
  if (n_near < 0 || n_near > rf)
    return fail(fmt::format("the count finds {} below the threshold, the supports leave {} rigid motion(s) free and "
                            "restrain {}", below, rl->unrestrained, rf));
  const Mesh mesh0 = mesh_for(c0, 0.0, {});
  Assembled a0 = assemble(rl->line, 0.0, mesh0);
  detail::RigidCondensed cd;
  try {
    cd = detail::condense_rigid(*rl, a0.K, mesh0.x);
  } catch (const std::runtime_error& e) {
    return fail(e.what());
  }
  // The rigid amplitudes' mass (class units: the kinetic energy is int d^T M d dx and the point
  // masses'), over the free amplitudes and then the unrestrained ones (true rigid modes). A
  // near-rigid mode is M-orthogonal to those: with K zero on them, its equations over them give
  // M_uf a_f + M_uu a_u = 0, so its mass is the Schur complement M_ff - M_fu M_uu^-1 M_uf (a rigid
  // bar on one end spring rocks about its centre of percussion: omega = 2 sqrt(k / m), not
  // sqrt(k / m)).
  const Eigen::MatrixXd Mall = rl->mass();
  std::vector<int> amp(rl->free_a.begin(), rl->free_a.end());
  for (int a = 0; a < static_cast<int>(rl->anchors.size()); ++a)
    if (!std::isinf(rl->anchors[static_cast<std::size_t>(a)].k) &&
        std::find(rl->free_a.begin(), rl->free_a.end(), a) == rl->free_a.end())
      amp.push_back(a);
  const Eigen::Index ra = static_cast<Eigen::Index>(amp.size());
  auto schur = [rf, ra](const Eigen::MatrixXd& M) -> Eigen::MatrixXd {
    if (ra == rf) return M;
    const Eigen::MatrixXd Muu = M.bottomRightCorner(ra - rf, ra - rf);
    return M.topLeftCorner(rf, rf) - M.topRightCorner(rf, ra - rf) * Muu.ldlt().solve(M.bottomLeftCorner(ra - rf, rf));
  };
  Eigen::MatrixXd Mfull(ra, ra);
  for (Eigen::Index p = 0; p < ra; ++p)
    for (Eigen::Index q = 0; q < ra; ++q) Mfull(p, q) = Mall(amp[static_cast<std::size_t>(p)], amp[static_cast<std::size_t>(q)]);
  Eigen::MatrixXd Mr = schur(Mfull);
  // The mass of the static shapes Psi - E^-1 B (the rigid motions with the line's elastic response
  // to the non-anchor springs), exactly: a segment's divided difference (K(l) - K(0)) / l at a tiny
  // l is minus the consistent mass of the static fields between its nodes. With it the Ritz values
  // leave out only the second-order term (bound l / (l_E - l)). Checked against the rigid motions'
  // mass by quadrature; where a segment is longer than its base piece (no divided difference by
  // doubling) or the check fails, Mr and the first-order bound stay.
  std::optional<Eigen::MatrixXd> Mg;
  {
    const auto& x = mesh0.x;
    const int nn = static_cast<int>(x.size()), mc = c0.mc;
    bool short_segments = true;
    for (int i = 0; i + 1 < nn; ++i) short_segments = short_segments && x[i + 1] - x[i] <= mesh0.h_base * (1 + 1e-9);
    if (short_segments) {
      const double ls = 1e-12 * model_.lambda_scale;
      // Over the free amplitudes, then the unrestrained ones (no spring acts on them: their
      // static shapes are their rigid motions).
      Eigen::MatrixXd P(static_cast<Eigen::Index>(nn) * mc, ra);
      for (int i = 0; i < nn; ++i)
        for (Eigen::Index q = 0; q < ra; ++q)
          P.block(static_cast<Eigen::Index>(i) * mc, q, mc, 1) =
              cd.psi[static_cast<std::size_t>(i)].col(amp[static_cast<std::size_t>(q)]);
      Eigen::MatrixXd V = P;
      V.leftCols(rf) -= cd.Y;
      Eigen::MatrixXd mg = Eigen::MatrixXd::Zero(ra, ra), mr = Eigen::MatrixXd::Zero(ra, ra);
      for (int i = 0; i + 1 < nn; ++i) {
        const int piece = rl->line.piece_of(x[i], x[i + 1]);
        const Eigen::MatrixXd A1 = rl->line.state(ls, piece), A0 = rl->line.state(0.0, piece);
        Eigen::MatrixXd dK = segment_dynamic_stiffness_divided(A1, A0, ls, x[i + 1] - x[i]).dK;
        Eigen::MatrixXd T = Eigen::MatrixXd::Identity(2 * mc, 2 * mc);
        if (const auto* e = rl->line.condition_at(x, static_cast<std::size_t>(i))) T.topLeftCorner(mc, mc) = e->B;
        if (const auto* e = rl->line.condition_at(x, static_cast<std::size_t>(i) + 1)) T.bottomRightCorner(mc, mc) = e->B;
        dK = (T.transpose() * dK * T).eval();
        const Eigen::MatrixXd Vs = V.middleRows(static_cast<Eigen::Index>(i) * mc, 2 * mc);
        const Eigen::MatrixXd Ps = P.middleRows(static_cast<Eigen::Index>(i) * mc, 2 * mc);
        mg -= Vs.transpose() * dK * Vs;
        mr -= Ps.transpose() * dK * Ps;
      }
      for (int i = 0; i < nn; ++i)  // the point masses: K's term -lambda mass at their nodes
        if (const auto* e = rl->line.condition_at(x, static_cast<std::size_t>(i)); e && e->mass_scaled.size() > 0) {
          const Eigen::MatrixXd Vn = V.middleRows(static_cast<Eigen::Index>(i) * mc, e->n_free);
          const Eigen::MatrixXd Pn = P.middleRows(static_cast<Eigen::Index>(i) * mc, e->n_free);
          mg += Vn.transpose() * e->mass_scaled * Vn;
          mr += Pn.transpose() * e->mass_scaled * Pn;
        }
      if (mg.allFinite() && (mr - Mfull).norm() <= 1e-9 * Mfull.norm()) Mg = schur(0.5 * (mg + mg.transpose()));
    }
  }
  if (Mg) Mr = *Mg;
  Eigen::MatrixXd L = cd.S;
  const Eigen::VectorXd piv = graded_ldlt(L);
  for (Eigen::Index i = 0; i < rf; ++i)
    if (!(piv[i] > 0) || !std::isfinite(piv[i]))
      return fail(fmt::format("condensed spring pivot {} of {} is {:.3g}", i + 1, rf, piv[i]));
  const Eigen::LLT<Eigen::MatrixXd> llt(Mr);
  if (llt.info() != Eigen::Success) return fail("the rigid motions' mass is not positive definite");
  const Eigen::MatrixXd R = llt.matrixU();
  Eigen::MatrixXd Z = L.triangularView<Eigen::UnitLower>().solve(Eigen::MatrixXd(R.transpose()));
  for (Eigen::Index i = 0; i < rf; ++i) Z.row(i) /= std::sqrt(piv[i]);
  std::vector<Eigen::Index> order(static_cast<std::size_t>(rf));
  for (Eigen::Index i = 0; i < rf; ++i) order[static_cast<std::size_t>(i)] = i;
  std::stable_sort(order.begin(), order.end(), [&](Eigen::Index x, Eigen::Index y) { return Z.row(x).norm() > Z.row(y).norm(); });
  Eigen::MatrixXd Zs(rf, rf);
  for (Eigen::Index i = 0; i < rf; ++i) Zs.row(i) = Z.row(order[static_cast<std::size_t>(i)]);
  const Eigen::JacobiSVD<Eigen::MatrixXd, Eigen::FullPivHouseholderQRPreconditioner> svd(Zs, Eigen::ComputeFullV);
  const Eigen::VectorXd sig = svd.singularValues();  // descending: lambda ascending
  if (!sig.allFinite() || !(sig[rf - 1] > 0)) return fail("the rigid-body Rayleigh-Ritz breaks down");
  std::vector<double> ritz(static_cast<std::size_t>(rf));
  for (Eigen::Index i = 0; i < rf; ++i) ritz[static_cast<std::size_t>(i)] = 1.0 / (sig[i] * sig[i]);
  // The count and the Ritz values must split the spectrum at the threshold alike.
  if ((n_near > 0 && ritz[static_cast<std::size_t>(n_near - 1)] > 10.0 * delta) ||
      (n_near < rf && ritz[static_cast<std::size_t>(n_near)] < 0.1 * delta))
    return fail(fmt::format("the count below the threshold ({}) and the rigid-body Rayleigh-Ritz values disagree", n_near));
  // A lower bound on the anchored line's lowest eigenvalue: the largest of scale * 10^-j at which
  // it is still positive definite.
  auto anchored_pd = [&](double t) {
    const Mesh mt = mesh_for(c0, t, {});
    Assembled at = assemble(rl->line, t, mt);
    for (const auto& an : rl->anchors) at.K.hold(rl->node_of(an.end, mt.x), an.coord);
    const auto in = at.K.inertia();
    return in.negative == 0 && in.zero == 0 && at.info.clamped_below == 0;
  };
  // Up by decades where it is positive definite at the scale itself: a class far stiffer than
  // the model's scale (torsion with nu near -1: G = 1e17 Pa) had no lambda_E, so no bound, and its
  // near-rigid mode was left to the count, 1.5e-8 off with a bound of 2.7e-9 (fuzz seed 7).
  double lambda_e = 0;
  bool bracketed = false;  // anchored_pd fails at 10 lambda_e
  if (anchored_pd(model_.lambda_scale)) {
    lambda_e = model_.lambda_scale;
    for (int up = 0; up < 12 && !bracketed; ++up) {
      if (anchored_pd(10.0 * lambda_e)) lambda_e *= 10.0;
      else bracketed = true;
    }
  } else {
    for (double t = 0.1 * model_.lambda_scale; t > 100.0 * ritz[0]; t *= 0.1)
      if (anchored_pd(t)) {
        lambda_e = t;
        bracketed = true;
        break;
      }
  }
  // Closer (to 4 %) where a value above the threshold may be taken.
  if (lambda_e > 0 && bracketed && n_near < rf &&
      ritz[static_cast<std::size_t>(n_near)] < 1e-4 * lambda_e)
    for (int step = 0; step < 6; ++step) {
      const double up = lambda_e * std::pow(10.0, std::ldexp(1.0, -step - 1));
      if (anchored_pd(up)) lambda_e = up;
    }
  Eigen::MatrixXd Bf(cd.B.rows(), rf);
  for (Eigen::Index q = 0; q < rf; ++q) Bf.col(q) = cd.B.col(rl->free_a[static_cast<std::size_t>(q)]);
  const Eigen::MatrixXd Rinv_v = R.triangularView<Eigen::Upper>().solve(svd.matrixV());
  std::vector<double> bound(static_cast<std::size_t>(rf), std::numeric_limits<double>::infinity());
  if (lambda_e > 0)
    for (Eigen::Index i = 0; i < rf; ++i) {
      const double lam = ritz[static_cast<std::size_t>(i)];
      if (!(lam < lambda_e)) break;
      const Eigen::VectorXd av = Rinv_v.col(i);  // a^T Mr a = 1
      const double g = Mg ? 0.0 : std::max(0.0, (Bf * av).dot(cd.Y * av)) / lambda_e;
      bound[static_cast<std::size_t>(i)] = lam / (lambda_e - lam) + 2.0 * std::sqrt(g) + g + 1e-14;
    }
  // Those below the threshold, with their bound whatever it is.
  for (int i = 0; i < n_near; ++i) {
    out.lambdas.push_back(ritz[static_cast<std::size_t>(i)]);
    out.bound = std::max(out.bound, bound[static_cast<std::size_t>(i)]);
  }
  out.rigid = rl->unrestrained;
  // Above it: those whose bound is tight (1e-5) and which lie far below lambda_E become enclosures
  // of the sliced values (the count's own resolution there is not known: a rocking on 1.9 N/m
  // beside 8e18 N/m was sliced 6.8e-7 off, a heave beside springs of 4e-5 EI / L^3 1.05e-5 off,
  // a torsion on 1.5 N m / rad 2.4e-7 off).
  int n_acc = n_near;
  for (; n_acc < rf; ++n_acc) {
    const double lam = ritz[static_cast<std::size_t>(n_acc)], b = bound[static_cast<std::size_t>(n_acc)];
    if (!(b <= 1e-5 && lam <= 1e-4 * lambda_e)) break;
  }
  if (n_acc > n_near) {
    // Between the last one taken and the next Ritz value (or lambda_E).
    const double next = n_acc < rf ? std::min(lambda_e, ritz[static_cast<std::size_t>(n_acc)]) : lambda_e;
    const double sep = std::sqrt(ritz[static_cast<std::size_t>(n_acc - 1)] * next);
    if (count_det(c0, sep, mesh_for(c0, sep, {})).count == rl->unrestrained + n_acc)
      for (int i = n_near; i < n_acc; ++i)
        out.enclosures.push_back({ritz[static_cast<std::size_t>(i)], bound[static_cast<std::size_t>(i)]});
  }
  return out;
}

/// Where a line is cut into two incommensurate segments (a second discretization): the golden
/// section, 0.618... of the way along.
const double kGoldenCut = 0.5 * (std::sqrt(5.0) - 1.0);

/// A beam's line is one segment: its poles (the segment's clamped-clamped frequencies) are the
/// zeros of a free-free Euler-Bernoulli span exactly, and nearly those of a span on very soft or
/// very stiff springs. At such a root K(lambda) is rounded relative to the pole's size, and the
/// count placed it 1e-8 off (a beam on springs of 1e-12 EI/L^3: mode 4 3.8e-9 off in omega with
/// a bound of 1.5e-12). Each value with a segment pole within kPoleGap of it (the segments' J0
/// differs across that interval) is sliced again there on the line cut at its golden section: two
/// segments of incommensurate lengths, whose poles lie elsewhere (halves would not do: a pinned
/// span's odd modes approach their clamped-clamped ones exponentially). The cut is not used
/// throughout: its shorter segments are stiffer, and a near-rigid mode's count resolves it less
/// well (a rocking on springs of 4e-5 EI/L^3 came out 9e-6 off instead of within 1.4e-6).
void LineAnalysis::repolish_near_poles(ClassLine& c, const Mesh& mesh, double lambda_max, std::vector<double>& vals,
                                       ModeList& out, SliceStats* st) {
  constexpr double kPoleGap = 1e-4;
  Mesh cut;
  for (std::size_t j = 0; j < vals.size(); ++j) {
    const double lo = vals[j] * (1 - kPoleGap), hi = vals[j] * (1 + kPoleGap);
    if (!(lo > 0) || assemble(c, lo, mesh).info.clamped_below == assemble(c, hi, mesh).info.clamped_below) continue;
    if (cut.x.empty()) cut = mesh_for(c, lambda_max, {kGoldenCut * model_.length});
    const auto again = slice_interval_polished([&](double lam) { return count_det(c, lam, cut); }, lo, hi,
                                               ctl_.rel_tol, 0.0, st);
    std::size_t here = 0;
    for (double v : vals) here += v >= lo && v < hi;
    if (again.size() == 1 && here == 1) {
      vals[j] = again[0];
    } else {
      out.count_consistent = false;
      out.count_message += fmt::format(
          "{}mode at {:.6g} rad/s lies within {:g} of a segment's pole and the cut line counts {} value(s) there, "
          "not {}",
          out.count_message.empty() ? "" : "; ", std::sqrt(vals[j]), kPoleGap, again.size(), here);
    }
  }
}

/// A free plate's rigid threshold (modes(), where the count does not place its rigid motions within
/// +-delta): the least decade t = 10^j delta up to 1e-4 of the scale where the count finds exactly
/// the rigid motions below t, none below -t, and no other below 100 t. Once t is past the rounding
/// of the rigid motions' places, the first two hold up to the elastic modes: the least such decade
/// is found by bisection (NAFEMS FV12 on 180 strips: 9 counts instead of 15), then checked whole;
/// where the top decade does not hold them, or the check fails, the decades are tried in turn.
double LineAnalysis::plate_rigid_threshold(double delta, double scale, const std::function<int(double)>& total) const {
  const int rbm = model_.rigid_body_motions;
  std::vector<double> t;
  for (double x = 10.0 * delta; x <= 1e-4 * scale; x *= 10.0) t.push_back(x);
  auto clean = [&](double x) { return total(x) == rbm && total(-x) == 0; };
  auto whole = [&](double x) { return clean(x) && total(100.0 * x) == rbm; };
  std::size_t from = 0;
  if (!t.empty() && clean(t.back())) {
    std::size_t lo = 0, hi = t.size() - 1;  // clean at hi; the least clean decade lies in [lo, hi]
    while (lo < hi) {
      const std::size_t mid = lo + (hi - lo) / 2;
      if (clean(t[mid]))
        hi = mid;
      else
        lo = mid + 1;
    }
    if (total(100.0 * t[hi]) == rbm) return t[hi];
    from = hi + 1;
  }
  for (std::size_t j = from; j < t.size(); ++j)
    if (whole(t[j])) return t[j];
  return delta;
}

ModeList LineAnalysis::modes(int k, const std::vector<ModeFamily>& families) {
  ModeList out;
  if (k <= 0) return out;
  const long evals0 = evaluations_;
  const std::vector<int> cls = pick(families);
  if (cls.empty()) return out;
  const double scale = model_.lambda_scale;
  const double delta = kRigidThreshold * scale;
  std::vector<Mesh> mesh(lines_.size());
  // The classes are independent line problems: each step below runs them side by side.
  auto refresh = [&](double lam) {
    side_by_side(cls.size(), [&](std::size_t i) { mesh[cls[i]] = mesh_for(*lines_[cls[i]], lam, {}); });
  };
  auto total = [&](double lam) {
    std::vector<int> n(cls.size(), 0);
    side_by_side(cls.size(), [&](std::size_t i) { n[i] = count_det(*lines_[cls[i]], lam, mesh[cls[i]]).count; });
    int sum = 0;
    for (int v : n) sum += v;
    return sum;
  };
  refresh(scale);
  // A plate's rigid-body motions that no edge reaches are exact zeros of the model, but its count
  // places them only within the rounding of K, which can exceed kRigidThreshold (a free plate of
  // 30 strips: three at |omega| ~ 2e-3 rad/s against 10 rad/s for the first elastic mode, some of
  // them negative on coarser strips). The threshold then moves up by decades to where the count
  // finds exactly those, none below minus it, and no other within a further factor of 100 (a gap
  // of two decades to the elastic modes); otherwise it stays, and what the count finds is judged
  // as before.
  double rigid_below = delta;
  if (model_.kind == SceneKind::Plate && model_.rigid_body_motions > 0 &&
      (total(delta) != model_.rigid_body_motions || total(-delta) != 0))
    rigid_below = plate_rigid_threshold(delta, scale, total);
  rigid_shift_ = rigid_below;
  if (const int neg = total(-rigid_below); neg > 0)
    throw std::runtime_error(fmt::format("the prism model has {} negative eigenvalue(s) omega^2 < 0: unstable", neg));
  // Each class's count below the threshold and the lowest eigenvalues of classes with rigid
  // motions of their own, rigid (0) and near-rigid, side by side.
  std::vector<int> rigid_c(lines_.size(), 0);
  std::vector<NearRigid> near(lines_.size());
  side_by_side(cls.size(), [&](std::size_t i) {
    const int c = cls[i];
    rigid_c[c] = count_det(*lines_[c], rigid_below, mesh[c]).count;
    near[c] = near_rigid(*lines_[c], rigid_c[c]);
  });
  int rigid = 0;
  for (int c : cls) {
    rigid += rigid_c[c];
    if (rigid_below > delta) {  // a plate's (no rigid split of its own): its rigid modes lie below
      near[c].lo = rigid_below;
      near[c].below_lo = near[c].rigid = rigid_c[c];
    }
    if (!near[c].problem.empty()) {
      out.count_consistent = false;
      out.count_message += (out.count_message.empty() ? "" : "; ") + near[c].problem;
    }
  }
  // A plate's bracket starts where its k-th eigenvalue is expected, over-estimated: by Weyl's law
  // (N ~ a b sqrt(lambda rho h / D) / (4 pi), which under-counts a bounded plate's lowest modes)
  // times 4. One count then usually brackets the k lowest: doubling from lambda_scale took 11
  // counts and 11 meshes per class on a 40-strip plate. The growth below still covers an
  // under-estimate, the trimming an over-estimate; the counts decide. A beam's classes (axial,
  // torsion, bending in two planes) spread its spectrum too unevenly for one estimate (the simply
  // supported beam's (k+1)-th cost a 2x2 section 545 counts for 25 modes instead of 453): it
  // doubles from lambda_scale, its first bending mode's order.
  double expected = scale;
  if (model_.kind == SceneKind::Plate) {
    double b = 0;
    for (const auto& p : model_.prisms) b += p.width;
    const double a = model_.length, D_over_mass = scale * std::pow(std::max(a, b) / std::numbers::pi, 4);
    if (b > 0) expected = 4.0 * std::pow(4.0 * std::numbers::pi * k / (a * b), 2) * D_over_mass;
  }
  // Off the grid of dyadic multiples of the scale: the bracket's top and the bands below it (a factor
  // kBand apart) would otherwise fall on the eigenvalues of symmetric structures (a beam pinned at
  // its middle: mode 1 at exactly 16 times the scale), where the two bands' counts disagree by
  // rounding.
  const double off_grid = 1.0 + 1.0 / (10.0 * std::numbers::sqrt2);
  double lo = delta, hi = (std::isfinite(expected) ? std::max(scale, expected) : scale) * off_grid;
  int n_hi = rigid;
  if (rigid < k) {
    refresh(hi);
    double meshed_at = hi;
    n_hi = total(hi);
    for (int grow = 0; n_hi < k; ++grow) {
      if (grow > 200) throw std::runtime_error("dtfm: could not bracket the requested modes");
      lo = hi;
      hi *= 2.0;
      refresh(hi);
      meshed_at = hi;
      n_hi = total(hi);
    }
    for (int it = 0; it < 8 && n_hi > k + 1; ++it) {  // fewer modes to polish above the k-th
      const double mid = 0.5 * (lo + hi);
      const int n = total(mid);
      if (n >= k) {
        hi = mid;
        n_hi = n;
      } else {
        lo = mid;
      }
    }
    // The mesh for the bracket's top, not for an over-estimate far above it.
    if (hi < 0.5 * meshed_at) refresh(hi);
  }
  struct Found {
    double lambda;
    int cls;
    bool near = false;            // a near-rigid mode (below the count's resolution)
    const Mesh* mesh = nullptr;   // the mesh its band was sliced on
  };
  std::vector<Found> all;
  int true_rigid = 0;
  for (int c : cls) {
    for (int j = 0; j < near[c].rigid; ++j) all.push_back({0.0, c});
    true_rigid += near[c].rigid;
    for (double v : near[c].lambdas) {
      all.push_back({v, c, true});
      ++out.near_rigid;
      out.near_rigid_bound = std::max(out.near_rigid_bound, near[c].bound);
    }
  }
  // Each class is sliced in bands of a factor kBand in lambda, each on the mesh its top needs:
  // one mesh for the whole range would cut the low modes into base pieces set by the highest
  // one, whose K(lambda) keeps lambda only to eps / (lambda m h^4 / EI) (mode 1 of a 1000-mode
  // slicing was 9.5e-4 off). Adjacent bands' counts at their common end must agree.
  constexpr double kBand = 16.0;
  // Whether two meshes discretize alike: the same nodes, every segment halved as often.
  auto same_pieces = [](const Mesh& a, const Mesh& b) {
    if (a.x != b.x) return false;
    for (std::size_t i = 0; i + 1 < a.x.size(); ++i) {
      const double h = a.x[i + 1] - a.x[i];
      if (detail::doubling_levels(h, a.h_base) != detail::doubling_levels(h, b.h_base)) return false;
    }
    return true;
  };
  std::vector<std::vector<Band>> bands(lines_.size());
  if (rigid < k) {
    // Each class banded and sliced on its own (side by side), its findings merged in class order
    // after.
    struct Sliced {
      SliceStats st;
      std::vector<double> vals;
      std::vector<const Band*> band_of;
      ModeList notes;  // count_consistent, count_message of the class's bands and re-polish
    };
    std::vector<Sliced> sliced(cls.size());
    side_by_side(cls.size(), [&](std::size_t i) {
      const int c = cls[i];
      Sliced& sl = sliced[i];
      auto& bc = bands[c];
      double top = hi, bot = hi;
      Mesh m = mesh[c];
      for (;;) {
        const double next = bot / kBand;
        Mesh mb;
        if (next > near[c].lo) mb = mesh_for(*lines_[c], next, {});
        if (!(next > near[c].lo) || !(mb.h_base > m.h_base)) {
          bc.push_back({near[c].lo, top, m});
          break;
        }
        bot = next;
        // A mesh that cuts every segment into as many base pieces is the same discretization: the
        // band goes on down (a 6x6 spatial beam's bound moved by 1e-4 relative per decade and
        // gave ten bands of one discretization per class, each with its own counts).
        if (same_pieces(mb, m)) continue;
        bc.push_back({bot, top, m});
        top = bot;
        m = mb;
      }
      std::reverse(bc.begin(), bc.end());
      for (std::size_t b = 0; b + 1 < bc.size(); ++b) {
        const int below = count_det(*lines_[c], bc[b].hi, bc[b].mesh).count;
        const int above = count_det(*lines_[c], bc[b].hi, bc[b + 1].mesh).count;
        if (below != above) {
          sl.notes.count_consistent = false;
          sl.notes.count_message += fmt::format("{}the counts at {:.6g} rad/s on two meshes differ ({} and {})",
                                                sl.notes.count_message.empty() ? "" : "; ", std::sqrt(bc[b].hi),
                                                below, above);
        }
      }
      for (const Band& band : bands[c]) {
        auto v = slice_interval_polished([&](double lam) { return count_det(*lines_[c], lam, band.mesh); }, band.lo,
                                         band.hi, ctl_.rel_tol, 1e-14 * scale, &sl.st);
        if (model_.kind == SceneKind::Beam) repolish_near_poles(*lines_[c], band.mesh, band.hi, v, sl.notes, &sl.st);
        sl.vals.insert(sl.vals.end(), v.begin(), v.end());
        sl.band_of.insert(sl.band_of.end(), v.size(), &band);
      }
    });
    for (std::size_t ci = 0; ci < cls.size(); ++ci) {
      const int c = cls[ci];
      const SliceStats& st = sliced[ci].st;
      const std::vector<double>& vals = sliced[ci].vals;
      const std::vector<const Band*>& band_of = sliced[ci].band_of;
      if (!sliced[ci].notes.count_consistent) {
        out.count_consistent = false;
        out.count_message += (out.count_message.empty() ? "" : "; ") + sliced[ci].notes.count_message;
      }
      out.polish_floor_width = std::max(out.polish_floor_width, st.polish_floor_width);
      for (std::size_t j = 0; j < vals.size(); ++j) {
        if (j < near[c].enclosures.size()) {
          // Inside its enclosure a sliced value is known to b as well (the count that placed it is
          // the one in doubt here), so b is its bound either way. One outside it is moved to the
          // enclosure's nearer end: a torsion on one spring beside G = 1e17 Pa was sliced 3e-8
          // below the lower end, the Ritz value (the upper end) 1.3e-7 above the truth.
          const auto [ritz, b] = near[c].enclosures[j];
          out.near_rigid_bound = std::max(out.near_rigid_bound, b);
          ++out.near_rigid;
          if (vals[j] < ritz / (1.0 + b) || vals[j] > ritz * (1.0 + 1e-12)) {
            all.push_back({std::clamp(vals[j], ritz / (1.0 + b), ritz), c, true});
            continue;
          }
        }
        all.push_back({vals[j], c, false, &band_of[j]->mesh});
      }
    }
  }
  std::stable_sort(all.begin(), all.end(), [](const Found& a, const Found& b) { return a.lambda < b.lambda; });
  if (static_cast<int>(all.size()) > k) all.resize(k);
  out.rigid = std::min(true_rigid, k);
  // One prism cannot deform in its section: every mode of a class is of its family (the share's
  // inverse iteration loses its digits next to springs of 1e12 EI / L^3 and mislabelled them).
  // Otherwise each mode's share from its own inverse iteration, side by side.
  const bool one_prism = model_.kind == SceneKind::Beam && model_.prisms.size() == 1;
  std::vector<double> shares(all.size(), 1.0);
  side_by_side(all.size(), [&](std::size_t i) {
    if (static_cast<int>(i) < out.rigid || all[i].near || one_prism) return;
    shares[i] = family_share(*lines_[all[i].cls], all[i].lambda);
  });
  for (std::size_t i = 0; i < all.size(); ++i) {
    const auto& f = all[i];
    out.omega_rad_s.push_back(std::sqrt(std::max(f.lambda, 0.0)));
    out.cls.push_back(f.cls);
    auto& line = *lines_[f.cls];
    if (static_cast<int>(i) < out.rigid) {
      out.family.push_back(ModeFamily::Rigid);
      out.family_share.push_back(1.0);
      continue;
    }
    if (f.near) {  // a rigid motion of its class on soft springs, by construction
      out.family.push_back(line.family);
      out.family_share.push_back(1.0);
      continue;
    }
    const double share = shares[i];
    out.family_share.push_back(share);
    out.family.push_back(share >= ctl_.family_threshold ? line.family : ModeFamily::Unknown);
  }
  // Reproducibility: each mode's class is counted just below and above it (lambda (1 -+ tau))
  // on a second discretization: each segment cut in three equal pieces, base pieces within the
  // same bounds (other J0, other pivots, other rounding, the same accuracy; 2/3 of the first's
  // length, not a power of two of it). Equal pieces share one long-segment matrix: the golden
  // section used before gave two of different lengths, twice the work. A mode whose count
  // does not come out as expected is below the model's rounding floor (stiff layers or very
  // slender spans against soft supports). Base pieces longer or shorter than the bounds would
  // test a worse discretization instead: twice the evanescent bound loses digits in exp(A h), half
  // of it one more doubling (a free plate of 180 strips and a cantilever of 64 were flagged so).
  constexpr double tau = 1e-4;
  auto alt_of = [&](const Mesh& m) {
    Mesh a = m;
    a.x = {m.x.front()};
    for (std::size_t i = 0; i + 1 < m.x.size(); ++i) {
      const double d = m.x[i + 1] - m.x[i];
      a.x.push_back(m.x[i] + d / 3.0);
      a.x.push_back(m.x[i] + 2.0 * d / 3.0);
      a.x.push_back(m.x[i + 1]);
    }
    return a;
  };
  std::deque<std::pair<const Mesh*, Mesh>> alt;  // per band's mesh
  auto alt_for = [&](const Mesh* m) -> const Mesh& {
    for (const auto& [key, a] : alt)
      if (key == m) return a;
    alt.emplace_back(m, alt_of(*m));
    return alt.back().second;
  };
  // The second discretizations first (one per band, shared by its modes), then every mode's two
  // counts side by side (count_det reads its class and mesh only), then the verdicts in order.
  const std::size_t first = static_cast<std::size_t>(out.rigid);
  std::vector<const Mesh*> alt_mesh(all.size(), nullptr);
  for (std::size_t i = first; i < all.size(); ++i)
    if (!all[i].near) alt_mesh[i] = &alt_for(all[i].mesh ? all[i].mesh : &mesh[all[i].cls]);
  std::vector<std::array<int, 2>> got(all.size(), {0, 0});
  side_by_side(all.size() - first, [&](std::size_t j) {
    const std::size_t i = first + j;
    if (!alt_mesh[i]) return;
    got[i][0] = count_det(*lines_[all[i].cls], all[i].lambda * (1 - tau), *alt_mesh[i]).count;
    got[i][1] = count_det(*lines_[all[i].cls], all[i].lambda * (1 + tau), *alt_mesh[i]).count;
  });
  int failures = 0;
  for (std::size_t i = first; i < all.size(); ++i) {
    if (all[i].near) {  // below the count's resolution: checked by its own bound instead
      out.reproducible.push_back(true);
      continue;
    }
    const int c = all[i].cls;
    const double lam = all[i].lambda;
    int below = near[c].below_lo, upto = near[c].below_lo;
    for (const auto& f : all)
      if (f.cls == c && f.lambda >= delta) {  // those below it are in below_lo
        below += f.lambda < lam * (1 - tau);
        upto += f.lambda <= lam * (1 + tau);
      }
    const int got_lo = got[i][0], got_hi = got[i][1];
    const bool ok = got_lo == below && got_hi >= upto;
    out.reproducible.push_back(ok);
    if (!ok) {
      out.count_consistent = false;
      if (++failures > 4) continue;
      out.count_message += fmt::format(
          "{}mode {} ({:.6g} rad/s) not reproduced to {:g} on a second discretization (counts {} / {} around it, "
          "expected {} / {})",
          out.count_message.empty() ? "" : "; ", i + 1, std::sqrt(lam), tau / 2, got_lo, got_hi, below, upto);
    }
  }
  if (failures > 4) out.count_message += fmt::format("; {} more", failures - 4);
  out.evaluations = evaluations_ - evals0;
  return out;
}

}  // namespace modalbench::dtfm
