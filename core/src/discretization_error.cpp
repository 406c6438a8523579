// The discretization error of a meshed result from the same request on coarser meshes of its
// family: Roache's grid convergence index, with the observed order where the meshes are not yet
// asymptotic, judged against the scene's tolerance.
#include "solve_internal.hpp"

#include "modalbench/frame.hpp"
#include "modalbench/extrapolation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace modalbench {

// Roache's factors of safety (extrapolation.hpp): kRoacheSafetyFactor for a two-mesh estimate with
// the formal order, kRoacheGuardFactor for the guard from the next coarser pair (a coarse pair
// converges faster than its formal order as a rule, so carrying it to h with that order over-states
// the error rather than under-states it).

namespace {

/// The grid convergence index of one quantity on the judged mesh: max(3 e1, 1.25 e2) from q
/// (judged), qc (coarse) and qcc (coarser, where there is one); 1.25 e1 where a fourth mesh
/// confirms the order (confirmed_order).
class Gci {
 public:
  Gci(double order, const detail::MeshSolve& coarse, const std::optional<detail::MeshSolve>& coarser,
      bool other_is_finer, const Result& fine, const std::optional<detail::MeshSolve>& coarsest)
      : order_(order), lowest_order_(order), r_(coarse.ratio), third_(coarser && coarser->result && !other_is_finer) {
    const double rp = std::pow(r_, order);
    // `fine` is the result judged; when the other mesh is the finer one, the error of the coarser
    // result is |q_H - q_h| r^p / (r^p - 1).
    denom_ = other_is_finer ? (rp - 1.0) / rp : rp - 1.0;
    if (third_) {
      r2_ = coarser->ratio;
      denom2_ = (std::pow(r2_, order) - 1.0) * rp;
    }
    // The fourth mesh counts only where it passed the back-end's checks and all four are successive
    // uniform coarsenings: an observed order means nothing otherwise.
    fourth_ = third_ && coarsest && coarsest->result && coarsest->ratio > 1 &&
              severity(coarsest->result->summary.status) < severity(Status::NumericalIssue) &&
              uniform_coarsening(fine, *coarse.result, r_) && uniform_coarsening(*coarse.result, *coarser->result, r2_) &&
              uniform_coarsening(*coarser->result, *coarsest->result, coarsest->ratio);
    if (fourth_) r3_ = coarsest->ratio;
  }

  /// How close to the formal order both observed orders must be (as the extrapolation's check of
  /// its next order, extrapolation.hpp).
  static constexpr double kConfirmWithin = 0.2;

  bool third() const { return third_; }
  bool fourth() const { return fourth_; }
  /// The lowest observed order used so far (frequencies), the formal order if none.
  double lowest_order() const { return lowest_order_; }
  /// How many quantities took the factor of safety 1.25 of a confirmed order, and how many were judged.
  int confirmed() const { return confirmed_; }
  int judged() const { return judged_; }

  /// Relative error estimate of q (scale: the quantity's size). Where the three meshes show an
  /// order below first (the pair differences resolved, above `noise` relative to the scale, and
  /// shrinking by less than r), the meshes are not yet in the asymptotic range: the observed
  /// order is used instead (floored at 1/4), which widens the estimate. A dtfm plate whose
  /// Kirchhoff penalty was set to 1e-3 converged at first order between 7, 15 and 30 strips; the
  /// formal order gave 0.21 for an error of 0.55. Frequencies only (a NaN noise skips it): a
  /// point load's deflection converges like h^2 log h, below its formal order on every mesh, and
  /// its two-mesh estimate already holds (rfem's paper plate: 2e-4 off, estimate 6e-4).
  /// `qccc` is the quantity on the fourth mesh (NaN: none), for confirmed_order.
  double operator()(double q, double qc, double qcc, double scale, double noise = kNotMeasured,
                    double qccc = kNotMeasured) {
    if (std::isfinite(noise)) ++judged_;
    const double d1 = std::abs(q - qc), d2 = third_ && std::isfinite(qcc) ? std::abs(qc - qcc) : kNotMeasured;
    if (const double p = confirmed_order(q, qc, qcc, qccc, scale, noise); std::isfinite(p)) {
      ++confirmed_;
      const double rp = std::pow(r_, p);
      const double err = std::max(d1 / (rp - 1.0), d2 / ((std::pow(r2_, p) - 1.0) * rp));
      return kRoacheGuardFactor * err / scale;
    }
    double dn = denom_, dn2 = denom2_;
    if (std::isfinite(noise) && std::isfinite(d2) && d1 > noise * scale && d2 > noise * scale) {
      // Only below first order: between that and the formal order (a point load's h^2 log h, a
      // Mindlin plate's mixed terms) the factor of safety 3 covers it, and widening there sent
      // the default meshes' refinement of dtfm plates past minutes.
      const double cap = std::min(order_, 1.0);
      const double p = observed_order(d1, d2, r_, r2_, 0.25, cap);
      if (p < cap) {
        lowest_order_ = std::min(lowest_order_, p);
        const double rpo = std::pow(r_, p);
        dn = rpo - 1.0;
        dn2 = (std::pow(r2_, p) - 1.0) * rpo;
      }
    }
    double err = kRoacheSafetyFactor * d1 / dn / scale;
    if (std::isfinite(d2)) err = std::max(err, kRoacheGuardFactor * d2 / dn2 / scale);
    return std::isfinite(err) ? err : std::numeric_limits<double>::infinity();
  }

 private:
  /// The order to take with Roache's factor of safety 1.25 (his three-mesh study), where the four
  /// meshes confirm it: the three differences resolved (above `noise`) and of one sign (monotone
  /// convergence), and the orders observed on the finer three and on the coarser three both
  /// within kConfirmWithin of the formal order; then the least of the two and the formal one. NaN
  /// otherwise (the factor of safety 3 stays). Frequencies only, as the observed order above.
  double confirmed_order(double q, double qc, double qcc, double qccc, double scale, double noise) const {
    if (!fourth_ || !std::isfinite(noise) || !std::isfinite(qcc) || !std::isfinite(qccc)) return kNotMeasured;
    const double e1 = q - qc, e2 = qc - qcc, e3 = qcc - qccc;
    for (double e : {e1, e2, e3})
      if (!(std::abs(e) > noise * scale)) return kNotMeasured;
    if (!(e1 * e2 > 0 && e2 * e3 > 0)) return kNotMeasured;
    const double p1 = observed_order(std::abs(e1), std::abs(e2), r_, r2_, 0.25, 4.0 * order_);
    const double p2 = observed_order(std::abs(e2), std::abs(e3), r2_, r3_, 0.25, 4.0 * order_);
    auto near_formal = [&](double p) { return std::isfinite(p) && std::abs(p - order_) <= kConfirmWithin * order_; };
    if (!near_formal(p1) || !near_formal(p2)) return kNotMeasured;
    return std::min({p1, p2, order_});
  }

  double order_, lowest_order_, r_, r2_ = kNotMeasured, r3_ = kNotMeasured, denom_ = 0, denom2_ = 0;
  bool third_, fourth_ = false;
  int confirmed_ = 0, judged_ = 0;
};

/// The factors of safety the frequencies took, in words.
std::string safety_words(const Gci& gci) {
  const std::string usual = fmt::format("{:g} and {:g}", kRoacheSafetyFactor, kRoacheGuardFactor);
  if (gci.confirmed() == 0) return usual;
  if (gci.confirmed() == gci.judged()) return fmt::format("{:g} (the order confirmed by the fourth mesh)", kRoacheGuardFactor);
  return fmt::format("{:g} on {} of {} modes (the order confirmed by the fourth mesh), else {}", kRoacheGuardFactor,
                     gci.confirmed(), gci.judged(), usual);
}

/// The frequencies' estimate (worst mode, plus the solve's own bound) into `e`; what exceeds
/// the tolerance into `problems`.
void judge_frequencies(const Result& fine, const detail::MeshSolve& coarse, const std::optional<detail::MeshSolve>& coarser,
                       const std::optional<detail::MeshSolve>& coarsest, double order, Gci& gci, ErrorEstimate& e,
                       std::vector<std::string>& problems) {
  const auto& f = fine.frequencies_rad_s;
  const auto& c = coarse.result->frequencies_rad_s;
  const std::vector<double> none;
  const auto& cc = gci.third() ? coarser->result->frequencies_rad_s : none;
  const auto& ccc = gci.fourth() ? coarsest->result->frequencies_rad_s : none;
  const std::size_t n = std::min(f.size(), c.size());
  double noise = 1e-10;
  for (const Result* x : {&fine, coarse.result, gci.third() ? coarser->result : nullptr,
                          gci.fourth() ? coarsest->result : nullptr})
    if (x && std::isfinite(x->summary.diagnostic("frequency_solve_error_bound")))
      noise = std::max(noise, 10.0 * x->summary.diagnostic("frequency_solve_error_bound"));
  double worst = 0;
  std::size_t worst_mode = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (f[i] == 0 && c[i] == 0) continue;  // rigid-body modes on both meshes
    const double qcc = i < cc.size() && !(cc[i] == 0 && c[i] != 0) ? cc[i] : kNotMeasured;
    const double qccc = std::isfinite(qcc) && i < ccc.size() && !(ccc[i] == 0 && c[i] != 0) ? ccc[i] : kNotMeasured;
    const double rel = gci(f[i], c[i], qcc, std::max(std::abs(f[i]), std::abs(c[i])), noise, qccc);
    if (!(rel <= worst)) {
      worst = rel;
      worst_mode = i + 1;
    }
  }
  // The solve's own bound (rounding): refinement does not reduce it, Richardson does not see it.
  const double solve = fine.summary.diagnostic("frequency_solve_error_bound");
  e.frequencies_solve = solve;
  e.frequencies = worst + (std::isfinite(solve) ? solve : 0.0);
  if (n < f.size())
    problems.push_back(fmt::format("frequencies: modes {}..{} have no counterpart on the coarser mesh {}, so their "
                                   "discretization error is not estimated", n + 1, f.size(), coarse.spec));
  // A solve bound past the tolerance is the back-end's own numerical issue (it says so); a finer
  // mesh is advised only where the discretization part is what exceeds it.
  if (!(e.frequencies <= e.tolerance) && !(std::isfinite(solve) && solve > e.tolerance))
    problems.push_back(fmt::format("frequencies: estimated discretization error {:.2g} (mode {}; mesh {} against {}{}, "
                                   "Richardson of order {}, factors of safety {}{}) exceeds the tolerance "
                                   "{:.2g} ([request] tolerance): use a finer mesh",
                                   e.frequencies, worst_mode, fine.summary.mesh, coarse.spec,
                                   gci.third() ? " and " + coarser->spec : std::string(),
                                   gci.lowest_order() < order
                                       ? fmt::format("{:g}, down to the observed {:.2g}: not yet in the asymptotic range",
                                                     order, gci.lowest_order())
                                       : fmt::format("{:g}", order),
                                   safety_words(gci),
                                   std::isfinite(solve) ? fmt::format(", plus the solve's own bound {:.2g}", solve)
                                                        : std::string(),
                                   e.tolerance));
}

/// The deflections' estimate (worst component of every probe, relative to the largest
/// deflection) into `e`; what exceeds the tolerance into `problems`.
/// The stress resultants at the probes where every mesh gives them: the largest estimate, each
/// component relative to the size of its kind in the structure (moments, forces; a plate's
/// moments per length): the largest at the probes or in the support reactions (a moment: also a
/// reaction force times the length), so a resultant that is zero at its probe (a free end) is not
/// judged by its rounding. 0 where there are none.
double judge_forces(const Result& fine, const Result& coarse, const Result* coarser, double length, Gci& gci) {
  auto all = [](const Result* r) {
    return r && std::all_of(r->deflections.begin(), r->deflections.end(), [](const Deflection& d) { return d.has_forces; });
  };
  if (!all(&fine) || !all(&coarse) || (coarser && !all(coarser))) return 0.0;
  using F = double InternalForces::*;
  const std::vector<std::vector<F>> kinds = {{&InternalForces::My, &InternalForces::Mz, &InternalForces::T},
                                             {&InternalForces::N, &InternalForces::Qy, &InternalForces::Qz},
                                             {&InternalForces::mx, &InternalForces::my, &InternalForces::mxy}};
  double force = 0, moment = 0;  // of the reactions
  for (const Reaction& r : fine.reactions)
    for (int k = 0; k < 3; ++k) {
      force = std::max(force, std::abs(r.force[k]));
      moment = std::max(moment, std::abs(r.moment[k]));
    }
  double worst = 0;
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    const auto& kind = kinds[k];
    double scale = k == 0 ? std::max(moment, force * length) : k == 1 ? force : 0.0;
    for (const auto& d : fine.deflections)
      for (F c : kind) scale = std::max(scale, std::abs(d.forces.*c));
    if (!(scale > 0)) continue;
    for (std::size_t i = 0; i < fine.deflections.size(); ++i)
      for (F c : kind)
        worst = std::max(worst, gci(fine.deflections[i].forces.*c, coarse.deflections[i].forces.*c,
                                    coarser ? coarser->deflections[i].forces.*c : kNotMeasured, scale));
  }
  return worst;
}

void judge_deflections(const Result& fine, const detail::MeshSolve& coarse, const std::optional<detail::MeshSolve>& coarser,
                       double length, Gci& gci, ErrorEstimate& e, std::vector<std::string>& problems) {
  const Result& cr = *coarse.result;
  if (fine.deflections.size() != cr.deflections.size() || fine.deflections.empty()) return;
  double scale = 0, worst = 0;
  for (const auto& d : fine.deflections) scale = std::max({scale, std::abs(d.u), std::abs(d.v), std::abs(d.w)});
  const bool third_defl = gci.third() && coarser->result->deflections.size() == fine.deflections.size();
  if (!(scale > 0)) return;
  for (std::size_t i = 0; i < fine.deflections.size(); ++i) {
    const auto& x = fine.deflections[i];
    const auto& y = cr.deflections[i];
    const double nan = kNotMeasured;
    const auto* z = third_defl ? &coarser->result->deflections[i] : nullptr;
    worst = std::max({worst, gci(x.u, y.u, z ? z->u : nan, scale), gci(x.v, y.v, z ? z->v : nan, scale),
                      gci(x.w, y.w, z ? z->w : nan, scale)});
  }
  worst = std::max(worst, judge_forces(fine, cr, third_defl ? coarser->result : nullptr, length, gci));
  e.deflections = worst;
  if (!(worst <= e.tolerance))
    problems.push_back(fmt::format("deflections: estimated discretization error {:.2g} of the largest deflection "
                                   "(or stress resultant of its kind; mesh {} against {}{}) exceeds the tolerance {:.2g} ([request] tolerance): use a "
                                   "finer mesh",
                                   worst, fine.summary.mesh, coarse.spec,
                                   third_defl ? " and " + coarser->spec : std::string(), e.tolerance));
}

/// The Campbell frequencies' estimate (worst over spins and ranks, relative to |f| + spin) into
/// `e`; what exceeds the tolerance into `problems`. Ranks pair only where both meshes give as many
/// frequencies at a spin.
void judge_campbell(const Result& fine, const detail::MeshSolve& coarse, const std::optional<detail::MeshSolve>& coarser,
                    Gci& gci, ErrorEstimate& e, std::vector<std::string>& problems) {
  const Campbell& f = fine.campbell;
  const Campbell& c = coarse.result->campbell;
  const Campbell* cc = gci.third() ? &coarser->result->campbell : nullptr;
  if (f.points.size() != c.points.size()) return;
  double worst = 0, at_spin = 0;
  for (std::size_t p = 0; p < f.points.size(); ++p) {
    const CampbellPoint& a = f.points[p];
    const CampbellPoint& b = c.points[p];
    const CampbellPoint* d = cc && cc->points.size() == f.points.size() ? &cc->points[p] : nullptr;
    if (a.frequencies_rad_s.size() != b.frequencies_rad_s.size()) continue;
    for (std::size_t i = 0; i < a.frequencies_rad_s.size(); ++i) {
      const double qcc = d && d->frequencies_rad_s.size() == a.frequencies_rad_s.size() ? d->frequencies_rad_s[i] : kNotMeasured;
      const double scale = std::max(std::abs(a.frequencies_rad_s[i]), std::abs(b.frequencies_rad_s[i])) + a.spin_rad_s;
      if (!(scale > 0)) continue;
      const double rel = gci(a.frequencies_rad_s[i], b.frequencies_rad_s[i], qcc, scale);
      if (!(rel <= worst)) {
        worst = rel;
        at_spin = a.spin_rad_s;
      }
    }
  }
  // The solve's own bound where the back-end gives one (rfem's projected sweep): refinement does
  // not reduce it, Richardson does not see it.
  const double solve = fine.summary.diagnostic("campbell_solve_error_bound");
  if (std::isfinite(solve)) worst += solve;
  e.campbell = worst;
  if (!(worst <= e.tolerance))
    problems.push_back(fmt::format("Campbell: estimated discretization error {:.2g} of the whirl frequencies (at spin "
                                   "{:g} rad/s; mesh {} against {}) exceeds the tolerance {:.2g} ([request] tolerance): "
                                   "use a finer mesh",
                                   worst, at_spin, fine.summary.mesh, coarse.spec, e.tolerance));
}

/// How the estimate was formed, in words (ErrorEstimate::note).
std::string estimate_note(const ErrorEstimate& e, const Result& fine, const detail::MeshSolve& coarse,
                          const std::optional<detail::MeshSolve>& coarser, const std::optional<detail::MeshSolve>& coarsest,
                          const Gci& gci, bool other_is_finer) {
  const bool third = gci.third();
  const double order = e.order;
  std::string note;
  if (other_is_finer)
    note = fmt::format("grid convergence index against the finer mesh {}: {:g} |q(mesh {}) - q(mesh {})| {:.3g}^{:g} "
                       "/ ({:.3g}^{:g} - 1), relative (no coarser mesh of the family)",
                       coarse.spec, kRoacheSafetyFactor, fine.summary.mesh, coarse.spec, coarse.ratio, order, coarse.ratio,
                       order);
  else if (third)
    note = fmt::format("grid convergence index: max({:g} |q(mesh {}) - q(mesh {})| / ({:.3g}^{:g} - 1), {:g} |q(mesh {}) - "
                       "q(mesh {})| / ({:.3g}^{:g} - 1) / {:.3g}^{:g}), relative; p the observed order per quantity "
                       "where the three meshes show a lower one (at least 1/4)",
                       kRoacheSafetyFactor, fine.summary.mesh, coarse.spec, coarse.ratio, order, kRoacheGuardFactor,
                       coarse.spec, coarser->spec, coarser->ratio, order, coarse.ratio, order);
  else
    note = fmt::format("grid convergence index: {:g} |q(mesh {}) - q(mesh {})| / ({:.3g}^{:g} - 1), relative",
                       kRoacheSafetyFactor, fine.summary.mesh, coarse.spec, coarse.ratio, order);
  if (gci.confirmed() > 0)
    note += fmt::format("; {} of {} frequencies with factor of safety {:g} and the observed order (at most p) instead, "
                        "where the fourth mesh {} confirms it (monotone, both observed orders within {:g} % of p)",
                        gci.confirmed(), gci.judged(), kRoacheGuardFactor, coarsest->spec, 100 * Gci::kConfirmWithin);
  if (std::isfinite(e.frequencies_solve))
    note += fmt::format("; frequencies plus the solve's own error bound {:.2g}", e.frequencies_solve);
  return note;
}

}  // namespace

detail::Verdict detail::judge_discretization(const Scene& scene, double order, const Result& fine, const MeshSolve& coarse,
                                             const std::optional<MeshSolve>& coarser, bool other_is_finer,
                                             const std::optional<MeshSolve>& coarsest) {
  ErrorEstimate e;
  e.tolerance = scene.request.tolerance;
  e.coarse_mesh = coarse.spec;
  e.ratio = coarse.ratio;
  e.order = order;
  e.safety_factor = kRoacheSafetyFactor;
  Gci gci(order, coarse, coarser, other_is_finer, fine, coarsest);
  if (gci.third()) e.coarser_mesh = coarser->spec;
  std::vector<std::string> problems;
  if (scene.request.modes > 0 && !fine.frequencies_rad_s.empty())
    judge_frequencies(fine, coarse, coarser, coarsest, order, gci, e, problems);
  // A frame's length scale: its longest member.
  double length = scene.geometry.length;
  if (scene.is_frame())
    for (const FrameMember& m : scene.frame->members) length = std::max(length, m.length);
  if (!scene.request.probes.empty()) judge_deflections(fine, coarse, coarser, length, gci, e, problems);
  if (scene.rotor && !fine.campbell.empty()) judge_campbell(fine, coarse, coarser, gci, e, problems);
  // Every judged quantity with a confirmed order: the factor of the whole estimate is 1.25.
  if (gci.judged() > 0 && gci.confirmed() == gci.judged() && scene.request.probes.empty() && !scene.rotor)
    e.safety_factor = kRoacheGuardFactor;
  e.note = estimate_note(e, fine, coarse, coarser, coarsest, gci, other_is_finer);
  return {e, problems};
}

}  // namespace modalbench
