// The transient response of `[request.transient]` by modal superposition: the back-end's modes
// sampled at the probes and the load points, their modal forces, each mode integrated exactly
// (modal_response.cpp), the static correction, the peaks, and the truncation estimate, for w and,
// where the modes carry them, for the bending moment My; the modes doubled until the estimates meet
// the tolerance.
#include "../solve_internal.hpp"
#include "load_quadrature.hpp"

#include "modalbench/transient.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>

namespace modalbench::detail {

namespace {

/// The modes of one solve reduced to what the superposition needs.
struct ModalBasis {
  std::vector<double> omega;
  std::vector<int> components;
  /// a[mode][component][probe] = phi(probe) P: the mode's share of the response per unit q.
  std::vector<std::vector<std::vector<double>>> a;
  /// m[mode][probe] = My_n(probe) P (empty: the modes carry no moments).
  std::vector<std::vector<double>> m;
  int computed = 0;  ///< modes the back-end gave
  int used = 0;      ///< modes superposed (no cluster of repeated frequencies split)
  int rigid = 0;
  double w(int n) const { return omega[static_cast<std::size_t>(n)]; }
  double share(int n, std::size_t c, std::size_t j) const { return a[static_cast<std::size_t>(n)][c][j]; }
};

/// A modes count no larger than m that splits no repeated frequency.
int unsplit(const ModalBasis& b, int m) {
  auto same = [&](int i) {
    const double hi = b.omega[static_cast<std::size_t>(i)], lo = b.omega[static_cast<std::size_t>(i) - 1];
    return std::abs(hi - lo) <= 1e-8 * hi;
  };
  while (m > 1 && m < b.computed && same(m)) --m;
  return m;
}

ModalBasis basis_of(const Result& r, std::size_t probes, const std::vector<LoadPoint>& loads, int asked) {
  ModalBasis b;
  const ModeShapes& ms = r.mode_shapes;
  b.components = ms.components;
  b.computed = static_cast<int>(std::min(r.frequencies_rad_s.size(), ms.values.size()));
  for (int n = 0; n < b.computed; ++n) {
    const auto& phi = ms.values[static_cast<std::size_t>(n)];
    double P = 0;
    for (std::size_t c = 0; c < ms.components.size(); ++c)
      for (std::size_t i = 0; i < loads.size(); ++i)
        P += loads[i].weight[static_cast<std::size_t>(ms.components[c])] * phi[c][probes + i];
    std::vector<std::vector<double>> an(ms.components.size(), std::vector<double>(probes));
    for (std::size_t c = 0; c < ms.components.size(); ++c)
      for (std::size_t j = 0; j < probes; ++j) an[c][j] = phi[c][j] * P;
    b.a.push_back(std::move(an));
    if (ms.moments.size() == ms.values.size()) {
      std::vector<double> mn(probes);
      for (std::size_t j = 0; j < probes; ++j) mn[j] = ms.moments[static_cast<std::size_t>(n)][j] * P;
      b.m.push_back(std::move(mn));
    }
    b.omega.push_back(r.frequencies_rad_s[static_cast<std::size_t>(n)]);
    if (b.omega.back() == 0) ++b.rigid;
  }
  // One mode is kept back as the first neglected, unless the back-end gave fewer than asked (then
  // the model has no more); never between two modes of one repeated frequency.
  b.used = unsplit(b, b.computed < asked ? b.computed : b.computed - 1);
  return b;
}

double component_of(const Deflection& d, int dof) {
  const double v[6] = {d.u, d.v, d.w, d.theta_x, d.theta_y, d.theta_z};
  return v[dof];
}

/// The static correction of the first m modes: the statics minus their static part, per
/// [component][probe] (zeros without a correction).
std::vector<std::vector<double>> correction(const ModalBasis& b, int m, const std::vector<Deflection>* statics) {
  std::vector<std::vector<double>> c(b.components.size(), std::vector<double>(b.a.empty() ? 0 : b.a[0][0].size(), 0.0));
  if (!statics) return c;
  for (std::size_t k = 0; k < b.components.size(); ++k)
    for (std::size_t j = 0; j < c[k].size(); ++j) {
      double s = component_of((*statics)[j], b.components[k]);
      for (int n = 0; n < m; ++n) s -= b.share(n, k, j) / (b.w(n) * b.w(n));
      c[k][j] = s;
    }
  return c;
}

/// The same for the bending moment My, per probe (zeros without a correction or without moments).
std::vector<double> moment_correction(const ModalBasis& b, int m, const std::vector<Deflection>* statics,
                                      std::size_t probes) {
  std::vector<double> c(probes, 0.0);
  if (!statics || b.m.empty()) return c;
  for (std::size_t j = 0; j < probes; ++j) {
    double s = (*statics)[j].forces.My;
    for (int n = 0; n < m; ++n) s -= b.m[static_cast<std::size_t>(n)][j] / (b.w(n) * b.w(n));
    c[j] = s;
  }
  return c;
}

/// One response at the probes, w or My: each mode's share per unit modal coordinate, the static
/// correction of the modes used and that of half of them (for the truncation estimate).
struct Channel {
  std::function<double(int, std::size_t)> share;
  std::vector<double> corr, corr_half;
  double scale = 0;  ///< a floor for the peak the estimate is relative to (0: the peak alone)
  /// The estimate's factor over the halving difference: 1 where the tail falls faster than 1 / modes
  /// (w: the difference is then several times the tail); 1.25 (Roache's safety factor) where the tail
  /// may fall like 1 / modes, so that the difference only equals it (a moment after a point load is
  /// suddenly applied).
  double factor = 1;
};

/// A channel's peaks per probe and its truncation estimate.
struct ChannelResult {
  std::vector<TransientPeak> peaks;
  double estimate = 0;
};

/// What one round (one modal solve) gives.
struct Round {
  ModalBasis basis;
  Transient out;
  double estimate = 0;         ///< of w
  double moment_estimate = 0;  ///< of My (where the modes carry it)
  double moment_scale = 0;     ///< moment_scale() of the solve
  std::string resolution_note;
};

struct Context {
  const Scene& scene;
  const TransientRequest& rq;
  LoadFunction g;
  const std::vector<Deflection>* statics;  ///< null: no static correction
  std::size_t probes;
  int w_index;  ///< w among the components
};

/// The fine grid of the peak search and the estimate: 8 samples per period of the highest mode
/// used, at most 2e5 samples.
std::pair<double, std::size_t> fine_grid(const Context& cx, const ModalBasis& b, std::string& note) {
  const double T = cx.rq.duration;
  double wmax = 0;
  for (int n = 0; n < std::min(b.used + 1, b.computed); ++n) wmax = std::max(wmax, b.w(n));
  double dt = std::min(cx.rq.step, wmax > 0 ? 2 * M_PI / wmax / 8 : cx.rq.step);
  constexpr double kMaxSamples = 2e5;
  if (T / dt > kMaxSamples) {
    dt = T / kMaxSamples;
    note = fmt::format("; the peak search samples every {:.3g} s (periods below {:.3g} s are under 8 samples)", dt,
                       8 * dt);
  }
  const auto n = static_cast<std::size_t>(std::ceil(T / dt - 1e-9)) + 1;
  return {T / static_cast<double>(n - 1), n};
}

/// The histories on the output grid (and the moments' where `moment_corr` is given).
void histories(const Context& cx, const ModalBasis& b, const std::vector<std::vector<double>>& corr,
               const std::vector<double>* moment_corr, Transient& out) {
  const auto K = static_cast<std::size_t>(std::floor(cx.rq.duration / cx.rq.step * (1 + 1e-12))) + 1;
  out.time_s.resize(K);
  for (std::size_t k = 0; k < K; ++k) out.time_s[k] = static_cast<double>(k) * cx.rq.step;
  out.values.assign(cx.probes, std::vector<std::vector<double>>(b.components.size(), std::vector<double>(K, 0.0)));
  if (moment_corr) out.moments.assign(cx.probes, std::vector<double>(K, 0.0));
  auto add = [K](std::vector<double>& to, double a, const std::vector<double>& q) {
    if (a != 0)
      for (std::size_t k = 0; k < K; ++k) to[k] += a * q[k];
  };
  for (int n = 0; n < b.used; ++n) {
    const ModalResponse r(b.w(n), damping_coefficient(cx.rq, b.w(n)), cx.g);
    const std::vector<double> q = r.sample(cx.rq.step, K);
    for (std::size_t j = 0; j < cx.probes; ++j) {
      for (std::size_t c = 0; c < b.components.size(); ++c) add(out.values[j][c], b.share(n, c, j), q);
      if (moment_corr) add(out.moments[j], b.m[static_cast<std::size_t>(n)][j], q);
    }
  }
  for (std::size_t k = 0; k < K; ++k) {
    const double gk = cx.g.value(out.time_s[k]);
    for (std::size_t j = 0; j < cx.probes; ++j) {
      for (std::size_t c = 0; c < b.components.size(); ++c) out.values[j][c][k] += corr[c][j] * gk;
      if (moment_corr) out.moments[j][k] += (*moment_corr)[j] * gk;
    }
  }
}

/// A channel's value at probe j and time t from the closed forms.
double value_at(const Context& cx, const ModalBasis& b, const Channel& ch, std::size_t j, double t) {
  double v = ch.corr[j] * cx.g.value(t);
  for (int n = 0; n < b.used; ++n) {
    const double a = ch.share(n, j);
    if (a != 0) v += a * ModalResponse(b.w(n), damping_coefficient(cx.rq, b.w(n)), cx.g).q(t);
  }
  return v;
}

/// The extreme of s v(t) on [lo, hi] by golden section (the bracket from the fine grid).
TransientPeak refine_peak(const Context& cx, const ModalBasis& b, const Channel& ch, std::size_t j, double lo,
                          double hi, TransientPeak best) {
  const double s = best.w >= 0 ? 1.0 : -1.0, r = 0.5 * (std::sqrt(5.0) - 1);
  double a = lo, d = hi, x1 = d - r * (d - a), x2 = a + r * (d - a);
  double f1 = s * value_at(cx, b, ch, j, x1), f2 = s * value_at(cx, b, ch, j, x2);
  for (int it = 0; it < 80 && d - a > 1e-14 * std::max(1.0, hi); ++it)
    if (f1 > f2) {
      d = x2, x2 = x1, f2 = f1, x1 = d - r * (d - a), f1 = s * value_at(cx, b, ch, j, x1);
    } else {
      a = x1, x1 = x2, f1 = f2, x2 = a + r * (d - a), f2 = s * value_at(cx, b, ch, j, x2);
    }
  const double t = f1 > f2 ? x1 : x2, f = std::max(f1, f2);
  if (f > std::abs(best.w)) best = {s * f, t};
  return best;
}

/// Peaks and truncation estimates of the channels on the fine grid: the estimate is the larger of
/// the change when the modes used are halved and the first neglected mode's response, relative to
/// the largest peak (or the channel's scale, where larger).
std::vector<ChannelResult> peaks_and_estimates(const Context& cx, Round& rd, const std::vector<Channel>& chs,
                                               int half) {
  const ModalBasis& b = rd.basis;
  const auto [dt, N] = fine_grid(cx, b, rd.resolution_note);
  using Grid = std::vector<std::vector<double>>;
  std::vector<Grid> full(chs.size(), Grid(cx.probes, std::vector<double>(N, 0.0))), diff = full, next = full;
  for (int n = 0; n < std::min(b.used + 1, b.computed); ++n) {
    const double om = b.w(n);
    const std::vector<double> q = ModalResponse(om, damping_coefficient(cx.rq, om), cx.g).sample(dt, N);
    for (std::size_t c = 0; c < chs.size(); ++c)
      for (std::size_t j = 0; j < cx.probes; ++j) {
        const double a = chs[c].share(n, j);
        if (a == 0) continue;
        for (std::size_t i = 0; i < N; ++i) {
          if (n < b.used) full[c][j][i] += a * q[i];
          if (n >= half && n < b.used) diff[c][j][i] += a * q[i];
          // The first neglected mode, less its static share where the correction carries it.
          if (n == b.used)
            next[c][j][i] =
                a * (q[i] - (cx.statics && om > 0 ? cx.g.value(static_cast<double>(i) * dt) / (om * om) : 0.0));
        }
      }
  }
  std::vector<ChannelResult> out(chs.size());
  for (std::size_t c = 0; c < chs.size(); ++c) {
    const Channel& ch = chs[c];
    double worst = 0, peak = 0;
    for (std::size_t j = 0; j < cx.probes; ++j) {
      TransientPeak best;
      std::size_t at = 0;
      for (std::size_t i = 0; i < N; ++i) {
        const double gi = cx.g.value(static_cast<double>(i) * dt);
        const double v = full[c][j][i] + ch.corr[j] * gi;
        // The halved sum's own correction: the difference of the two corrections is quasi-static.
        const double d = diff[c][j][i] + (ch.corr[j] - ch.corr_half[j]) * gi;
        worst = std::max({worst, std::abs(d), std::abs(next[c][j][i])});
        if (std::abs(v) > std::abs(best.w)) best = {v, static_cast<double>(i) * dt}, at = i;
      }
      best = refine_peak(cx, b, ch, j, at > 0 ? static_cast<double>(at - 1) * dt : 0.0,
                         std::min(cx.rq.duration, static_cast<double>(at + 1) * dt), best);
      out[c].peaks.push_back(best);
      peak = std::max(peak, std::abs(best.w));
    }
    const double size = std::max(peak, ch.scale);
    out[c].estimate = size > 0 ? ch.factor * worst / size : (worst > 0 ? kNotMeasured : 0.0);
  }
  return out;
}

/// The largest static moment share of one mode at any sampled point (probes and load points):
/// the size below which a probe's moments are rounding (a probe at a pinned end).
double moment_scale(const Result& r, const std::vector<LoadPoint>& loads, std::size_t probes) {
  const ModeShapes& ms = r.mode_shapes;
  double scale = 0;
  for (std::size_t n = 0; n < ms.moments.size() && n < r.frequencies_rad_s.size(); ++n) {
    const double om = r.frequencies_rad_s[n];
    if (!(om > 0)) continue;
    double P = 0;
    for (std::size_t c = 0; c < ms.components.size(); ++c)
      for (std::size_t i = 0; i < loads.size(); ++i)
        P += loads[i].weight[static_cast<std::size_t>(ms.components[c])] * ms.values[n][c][probes + i];
    for (double v : ms.moments[n]) scale = std::max(scale, std::abs(v * P) / (om * om));
  }
  return scale;
}

/// Peaks and estimates of w and (where the basis has them) My into the round.
void peaks_and_estimate(const Context& cx, Round& rd, const std::vector<std::vector<double>>& corr,
                        const std::vector<double>& moment_corr, double m_scale) {
  const ModalBasis& b = rd.basis;
  const int half = unsplit(b, std::max(1, b.used / 2));
  const auto wi = static_cast<std::size_t>(cx.w_index);
  std::vector<Channel> chs;
  chs.push_back({[&b, wi](int n, std::size_t j) { return b.share(n, wi, j); }, corr[wi],
                 correction(b, half, cx.statics)[wi], 0.0, 1.0});
  if (!b.m.empty())
    chs.push_back({[&b](int n, std::size_t j) { return b.m[static_cast<std::size_t>(n)][j]; }, moment_corr,
                   moment_correction(b, half, cx.statics, cx.probes), m_scale, 1.25});
  const std::vector<ChannelResult> res = peaks_and_estimates(cx, rd, chs, half);
  rd.out.peaks = res[0].peaks;
  rd.estimate = res[0].estimate;
  if (res.size() > 1) {
    rd.out.moment_peaks = res[1].peaks;
    rd.moment_estimate = res[1].estimate;
  }
}

/// The modal solve of `modes` + 1 modes with the shapes at the probes and at `loads`.
Scene modal_scene(const Scene& scene, int modes, const std::vector<LoadPoint>& loads) {
  Scene sub = scene;
  ShapeRequest sr;
  sr.points = scene.request.probes;
  for (const LoadPoint& p : loads) sr.points.push_back(p.at);
  sr.moments = scene.is_beam() && scene.request.transient &&
               scene.request.transient->moments != TransientRequest::Moments::Off;
  sub.request.modes = modes + 1;
  sub.request.shapes = sr;
  sub.request.probes.clear();
  sub.request.frf.reset();
  sub.request.transient.reset();
  return sub;
}

/// One round: the modal solve with `modes` + 1 modes, and everything from it.
Round one_round(const Context& cx, const ModalSolve& solve, int modes, Result& result) {
  const std::vector<LoadPoint> loads = load_points(cx.scene, modes + 1);
  const Result r = solve(modal_scene(cx.scene, modes, loads));
  if (severity(r.summary.status) > severity(Status::NotConverged) || r.mode_shapes.empty())
    throw std::runtime_error(fmt::format("the modal solve with {} modes was {}: {}", modes + 1,
                                         to_string(r.summary.status),
                                         r.summary.message.empty() ? "no mode shapes" : r.summary.message));
  if (r.summary.status == Status::NotConverged)
    result.summary.raise(Status::NotConverged, "transient: its modal solve: " + r.summary.message);
  Round rd;
  rd.basis = basis_of(r, cx.probes, loads, modes + 1);
  rd.moment_scale = moment_scale(r, loads, cx.probes);
  rd.out.components = rd.basis.components;
  return rd;
}

}  // namespace

Scene transient_modal_scene(const Scene& scene, int modes) {
  return modal_scene(scene, modes, load_points(scene, modes + 1));
}

int transient_first_modes(const Scene& scene) { return std::max(12, scene.request.modes); }

double solve_transient(const Scene& scene, const ModalSolve& solve, const ModalEstimate& estimate, double time_left_s,
                       Result& result) {
  const auto t0 = std::chrono::steady_clock::now();
  const TransientRequest& rq = *scene.request.transient;
  auto& sum = result.summary;
  // The statics of the same mesh carry the static correction, where there are statics to carry.
  std::string sc_note = "no static correction (switched off)";
  const std::vector<Deflection>* statics = nullptr;
  if (rq.static_correction) {
    if (rq.load == TransientRequest::Load::Impulse)
      sc_note = "no static correction (an impulse leaves no static load)";
    else if (result.deflections.size() != scene.request.probes.size() ||
             severity(sum.status) >= severity(Status::NumericalIssue))
      sc_note = "no static correction: the statics at the probes failed or were not computed (" + sum.message + ")";
    else
      statics = &result.deflections;
  }
  const std::vector<int> comps = scene.shape_components();
  Context cx{scene,
             rq,
             LoadFunction::of(rq),
             statics,
             scene.request.probes.size(),
             static_cast<int>(std::find(comps.begin(), comps.end(), 2) - comps.begin())};
  int modes = transient_first_modes(scene);
  double planned = 0;
  Round rd;
  std::string moment_note;
  for (int round = 0;; ++round) {
    const auto tr = std::chrono::steady_clock::now();
    if (round > 0) planned += estimate(transient_modal_scene(scene, modes));
    rd = one_round(cx, solve, modes, result);
    if (rd.basis.rigid > 0 && cx.statics) {
      cx.statics = nullptr;
      sc_note = "no static correction: the structure has rigid-body modes (no statics)";
    }
    if (!rd.basis.m.empty() && cx.statics &&
        !std::all_of(cx.statics->begin(), cx.statics->end(), [](const Deflection& d) { return d.has_forces; })) {
      rd.basis.m.clear();
      moment_note = "; no moment histories: the statics at the probes carry no internal forces for their correction";
    }
    const std::vector<std::vector<double>> corr = correction(rd.basis, rd.basis.used, cx.statics);
    const std::vector<double> mcorr = moment_correction(rd.basis, rd.basis.used, cx.statics, cx.probes);
    peaks_and_estimate(cx, rd, corr, mcorr, rd.moment_scale);
    const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - tr).count();
    const bool complete = rd.basis.used == rd.basis.computed;
    // The moments drive the modes only where they were asked for (TransientRequest::Moments).
    const bool moments_judged = rq.moments == TransientRequest::Moments::Asked;
    const bool met = !(rd.estimate > scene.request.tolerance) &&
                     !(moments_judged && rd.moment_estimate > scene.request.tolerance);
    if (met || complete || round == 4 || 3.0 * took > time_left_s) {
      histories(cx, rd.basis, corr, rd.basis.m.empty() ? nullptr : &mcorr, rd.out);
      break;
    }
    modes *= 2;
  }
  Transient& out = rd.out;
  out.modes_used = rd.basis.used;
  out.rigid_modes = rd.basis.rigid;
  out.static_correction = cx.statics != nullptr;
  out.error_estimate = rd.estimate;
  if (!rd.basis.m.empty()) out.moment_error_estimate = rd.moment_estimate;
  out.load = cx.g.describe();
  out.note = fmt::format(
      "modal superposition of {} modes ({} rigid), each integrated exactly for the load's time function; {}; "
      "truncation estimate: the larger of the change when the modes are halved and the first neglected mode's "
      "response{}{}",
      out.modes_used, out.rigid_modes,
      out.static_correction ? "static correction (mode acceleration) from the statics at the probes" : sc_note,
      rd.resolution_note, moment_note);
  if (!rd.basis.m.empty())
    out.note += fmt::format("; moment histories My from the modes' own moments{}, estimate {:.2g}",
                            out.static_correction ? " and the statics' (the same correction)" : "",
                            out.moment_error_estimate);
  if (rd.basis.used == rd.basis.computed) out.note += fmt::format("; all {} modes of the model", rd.basis.computed);
  if (rd.estimate > scene.request.tolerance)
    sum.raise(Status::NotConverged,
              fmt::format("transient: truncation error estimate {:.2g} with {} modes exceeds the tolerance {:.2g}",
                          rd.estimate, out.modes_used, scene.request.tolerance));
  if (!rd.basis.m.empty() && rd.moment_estimate > scene.request.tolerance) {
    // Asked for, they are judged; added by default, their estimate is said, not held against w.
    const std::string what = fmt::format(
        "transient: the moment histories' truncation estimate {:.2g} with {} modes exceeds the tolerance {:.2g} (after a "
        "suddenly applied point load a moment series converges only like 1 / modes)",
        rd.moment_estimate, out.modes_used, scene.request.tolerance);
    if (rq.moments == TransientRequest::Moments::Asked)
      sum.raise(Status::NotConverged, what + "; request.transient.moments = false keeps w and the rotations");
    else
      sum.warnings.push_back(what + ": they were added by default and do not set the status (request.transient."
                                    "moments = true judges them, false leaves them out)");
  }
  result.transient = std::move(out);
  sum.timings_s.transient = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return planned;
}

}  // namespace modalbench::detail
