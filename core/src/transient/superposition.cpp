// The transient response of `[request.transient]` by modal superposition: the back-end's modes
// sampled at the probes and the load points, their modal forces, each mode integrated exactly
// (modal_response.cpp), the static correction, the peaks, and the truncation estimate; the modes
// doubled until the estimate meets the tolerance.
#include "../solve_internal.hpp"
#include "load_quadrature.hpp"

#include "modalbench/transient.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace modalbench::detail {

namespace {

/// The modes of one solve reduced to what the superposition needs.
struct ModalBasis {
  std::vector<double> omega;
  std::vector<int> components;
  /// a[mode][component][probe] = phi(probe) P: the mode's share of the response per unit q.
  std::vector<std::vector<std::vector<double>>> a;
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

/// What one round (one modal solve) gives.
struct Round {
  ModalBasis basis;
  Transient out;
  double estimate = 0;
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

/// The histories on the output grid.
void histories(const Context& cx, const ModalBasis& b, const std::vector<std::vector<double>>& corr, Transient& out) {
  const auto K = static_cast<std::size_t>(std::floor(cx.rq.duration / cx.rq.step * (1 + 1e-12))) + 1;
  out.time_s.resize(K);
  for (std::size_t k = 0; k < K; ++k) out.time_s[k] = static_cast<double>(k) * cx.rq.step;
  out.values.assign(cx.probes, std::vector<std::vector<double>>(b.components.size(), std::vector<double>(K, 0.0)));
  for (int n = 0; n < b.used; ++n) {
    const ModalResponse r(b.w(n), damping_coefficient(cx.rq, b.w(n)), cx.g);
    const std::vector<double> q = r.sample(cx.rq.step, K);
    for (std::size_t j = 0; j < cx.probes; ++j)
      for (std::size_t c = 0; c < b.components.size(); ++c) {
        const double a = b.share(n, c, j);
        if (a != 0)
          for (std::size_t k = 0; k < K; ++k) out.values[j][c][k] += a * q[k];
      }
  }
  for (std::size_t k = 0; k < K; ++k) {
    const double gk = cx.g.value(out.time_s[k]);
    for (std::size_t j = 0; j < cx.probes; ++j)
      for (std::size_t c = 0; c < b.components.size(); ++c) out.values[j][c][k] += corr[c][j] * gk;
  }
}

/// w at probe j and time t from the closed forms.
double w_at(const Context& cx, const ModalBasis& b, const std::vector<std::vector<double>>& corr, std::size_t j,
            double t) {
  double w = corr[static_cast<std::size_t>(cx.w_index)][j] * cx.g.value(t);
  for (int n = 0; n < b.used; ++n) {
    const double a = b.share(n, static_cast<std::size_t>(cx.w_index), j);
    if (a != 0) w += a * ModalResponse(b.w(n), damping_coefficient(cx.rq, b.w(n)), cx.g).q(t);
  }
  return w;
}

/// The extreme of s w(t) on [lo, hi] by golden section (the bracket from the fine grid).
TransientPeak refine_peak(const Context& cx, const ModalBasis& b, const std::vector<std::vector<double>>& corr,
                          std::size_t j, double lo, double hi, TransientPeak best) {
  const double s = best.w >= 0 ? 1.0 : -1.0, r = 0.5 * (std::sqrt(5.0) - 1);
  double a = lo, d = hi, x1 = d - r * (d - a), x2 = a + r * (d - a);
  double f1 = s * w_at(cx, b, corr, j, x1), f2 = s * w_at(cx, b, corr, j, x2);
  for (int it = 0; it < 80 && d - a > 1e-14 * std::max(1.0, hi); ++it)
    if (f1 > f2) {
      d = x2, x2 = x1, f2 = f1, x1 = d - r * (d - a), f1 = s * w_at(cx, b, corr, j, x1);
    } else {
      a = x1, x1 = x2, f1 = f2, x2 = a + r * (d - a), f2 = s * w_at(cx, b, corr, j, x2);
    }
  const double t = f1 > f2 ? x1 : x2, f = std::max(f1, f2);
  if (f > std::abs(best.w)) best = {s * f, t};
  return best;
}

/// Peaks and the truncation estimate on the fine grid.
void peaks_and_estimate(const Context& cx, Round& rd, const std::vector<std::vector<double>>& corr) {
  const ModalBasis& b = rd.basis;
  const auto [dt, N] = fine_grid(cx, b, rd.resolution_note);
  const int half = unsplit(b, std::max(1, b.used / 2));
  const std::vector<std::vector<double>> corr_half = correction(b, half, cx.statics);
  const auto wi = static_cast<std::size_t>(cx.w_index);
  std::vector<std::vector<double>> full(cx.probes, std::vector<double>(N, 0.0)), diff = full, next = full;
  for (int n = 0; n < std::min(b.used + 1, b.computed); ++n) {
    const double om = b.w(n);
    const std::vector<double> q = ModalResponse(om, damping_coefficient(cx.rq, om), cx.g).sample(dt, N);
    for (std::size_t j = 0; j < cx.probes; ++j) {
      const double a = b.share(n, wi, j);
      if (a == 0) continue;
      for (std::size_t i = 0; i < N; ++i) {
        if (n < b.used) full[j][i] += a * q[i];
        if (n >= half && n < b.used) diff[j][i] += a * q[i];
        // The first neglected mode, less its static share where the correction carries it.
        if (n == b.used)
          next[j][i] = a * (q[i] - (cx.statics && om > 0 ? cx.g.value(static_cast<double>(i) * dt) / (om * om) : 0.0));
      }
    }
  }
  double worst = 0, peak = 0;
  rd.out.peaks.clear();
  for (std::size_t j = 0; j < cx.probes; ++j) {
    TransientPeak best;
    std::size_t at = 0;
    for (std::size_t i = 0; i < N; ++i) {
      const double gi = cx.g.value(static_cast<double>(i) * dt);
      const double w = full[j][i] + corr[wi][j] * gi;
      // The halved sum's own correction: the difference of the two corrections is quasi-static.
      const double d = diff[j][i] + (corr[wi][j] - corr_half[wi][j]) * gi;
      worst = std::max({worst, std::abs(d), std::abs(next[j][i])});
      if (std::abs(w) > std::abs(best.w)) best = {w, static_cast<double>(i) * dt}, at = i;
    }
    best = refine_peak(cx, b, corr, j, at > 0 ? static_cast<double>(at - 1) * dt : 0.0,
                       std::min(cx.rq.duration, static_cast<double>(at + 1) * dt), best);
    rd.out.peaks.push_back(best);
    peak = std::max(peak, std::abs(best.w));
  }
  rd.estimate = peak > 0 ? worst / peak : (worst > 0 ? kNotMeasured : 0.0);
}

/// The modal solve of `modes` + 1 modes with the shapes at the probes and at `loads`.
Scene modal_scene(const Scene& scene, int modes, const std::vector<LoadPoint>& loads) {
  Scene sub = scene;
  ShapeRequest sr;
  sr.points = scene.request.probes;
  for (const LoadPoint& p : loads) sr.points.push_back(p.at);
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
  for (int round = 0;; ++round) {
    const auto tr = std::chrono::steady_clock::now();
    if (round > 0) planned += estimate(transient_modal_scene(scene, modes));
    rd = one_round(cx, solve, modes, result);
    if (rd.basis.rigid > 0 && cx.statics) {
      cx.statics = nullptr;
      sc_note = "no static correction: the structure has rigid-body modes (no statics)";
    }
    const std::vector<std::vector<double>> corr = correction(rd.basis, rd.basis.used, cx.statics);
    peaks_and_estimate(cx, rd, corr);
    const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - tr).count();
    const bool complete = rd.basis.used == rd.basis.computed;
    if (!(rd.estimate > scene.request.tolerance) || complete || round == 4 || 3.0 * took > time_left_s) {
      histories(cx, rd.basis, corr, rd.out);
      break;
    }
    modes *= 2;
  }
  Transient& out = rd.out;
  out.modes_used = rd.basis.used;
  out.rigid_modes = rd.basis.rigid;
  out.static_correction = cx.statics != nullptr;
  out.error_estimate = rd.estimate;
  out.load = cx.g.describe();
  out.note = fmt::format(
      "modal superposition of {} modes ({} rigid), each integrated exactly for the load's time function; {}; "
      "truncation estimate: the larger of the change when the modes are halved and the first neglected mode's "
      "response{}",
      out.modes_used, out.rigid_modes,
      out.static_correction ? "static correction (mode acceleration) from the statics at the probes" : sc_note,
      rd.resolution_note);
  if (rd.basis.used == rd.basis.computed) out.note += fmt::format("; all {} modes of the model", rd.basis.computed);
  if (rd.estimate > scene.request.tolerance)
    sum.raise(Status::NotConverged,
              fmt::format("transient: truncation error estimate {:.2g} with {} modes exceeds the tolerance {:.2g}",
                          rd.estimate, out.modes_used, scene.request.tolerance));
  result.transient = std::move(out);
  sum.timings_s.transient = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return planned;
}

}  // namespace modalbench::detail
