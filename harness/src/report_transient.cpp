// The report's time-history section (scenes with [request.transient]): every back-end's default
// solve overlaid, its peaks, modes and truncation estimates, and the published target where one
// is on file.
#include <fmt/format.h>

#include <cmath>

#include "report_document.hpp"

namespace modalbench::report_detail {

namespace {

/// A published target of a transient benchmark: w at the first probe.
struct PublishedPeak {
  const char* scene;
  double w, time_s;
  const char* source;
};

// NAFEMS R0016's 5T target (quoted by vendors' verification manuals); it is a single-mode
// answer (the static deflection times the damped oscillator's overshoot, at half the first period).
constexpr PublishedPeak kPublished[] = {
    {"nafems-5t-deep-beam", -1.043e-3, 0.0117,
     "NAFEMS R0016 5T (a single-mode approximation; its sign here: downward)"},
};

std::string damping_str(const TransientRequest& t) {
  switch (t.damping) {
    case TransientRequest::Damping::None:
      return "undamped";
    case TransientRequest::Damping::Modal:
      return fmt::format("modal damping zeta = {:g}", t.zeta);
    case TransientRequest::Damping::Rayleigh:
      return fmt::format("Rayleigh damping alpha = {:g} 1/s, beta = {:g} s", t.alpha, t.beta);
  }
  return "";
}

std::vector<std::string> row_of(const TransientRun& r) {
  const Result& x = r.result;
  const Transient& t = x.transient;
  // A back-end whose model is not the scene's theory says so where its numbers are read.
  const std::string who =
      x.summary.converges_to_scene_theory || x.summary.model.empty() ? r.backend : r.backend + " (" + x.summary.model + ")";
  if (t.empty())
    return {r.backend,
            x.summary.mesh,
            "—",
            "—",
            "—",
            "—",
            "—",
            "—",
            "—",
            to_string(x.summary.status) + ": " + md_cell(x.summary.message),
            secs_str(x.summary.total_time_s)};
  return {who,
          x.summary.mesh,
          fmt::format("{}{}", t.modes_used, t.static_correction ? " + static" : ""),
          fmt::format("{:.7g}", t.peaks[0].w),
          fmt::format("{:.6g}", t.peaks[0].time_s),
          err_str(t.error_estimate),
          t.moment_peaks.empty() ? "—" : fmt::format("{:.6g}", t.moment_peaks[0].w),
          t.moments.empty() ? "—" : err_str(t.moment_error_estimate),
          err_str(x.summary.error_estimate.frequencies),
          to_string(x.summary.status),
          secs_str(x.summary.total_time_s)};
}

/// The error of the peak against the modes used and the run time, every back-end, against the
/// exact back-end's run with the most modes (its truncation the smallest).
void write_mode_convergence(Doc& doc, const SceneComparison& c, Context& ctx, const std::string& sid) {
  const TransientRun* ref = nullptr;
  for (const TransientRun& r : c.transients)
    if (r.backend == "exact" && !r.by_modes.empty()) ref = &r;
  if (!ref) return;
  const TransientRun::ByModes& best = ref->by_modes.back();
  std::vector<Series> vs_modes, vs_time;
  for (const TransientRun& r : c.transients) {
    Series m{r.backend + " " + r.result.summary.mesh, {}, "linespoints"}, t = m;
    for (const auto& p : r.by_modes) {
      const double e = std::abs(p.peak_w / best.peak_w - 1);
      if (&r == ref && &p == &best) continue;  // the reference itself
      if (!(e > 0)) continue;
      m.points.emplace_back(p.modes, e);
      t.points.emplace_back(p.run_s, e);
    }
    vs_modes.push_back(std::move(m));
    vs_time.push_back(std::move(t));
  }
  doc.para(fmt::format("The peak against the modes used (12, 24, 48, 96, each on the mesh the default solve kept), "
                       "relative to the exact back-end's with {} modes: a discretized back-end levels off at its "
                       "mesh's own error.",
                       best.modes));
  const std::string setup = "set logscale xy\nset format y '%.0e'\nset grid\nset ylabel 'relative error of the peak'\n";
  if (auto svg = plot(ctx, sid + "_transient_modes", setup + "set title 'Peak error against modes used'\nset xlabel 'modes'\n",
                      vs_modes);
      !svg.empty())
    doc.figure("plots/" + sid + "_transient_modes.svg", svg, "Relative error of the peak against the modes used");
  if (auto svg = plot(ctx, sid + "_transient_time", setup + "set title 'Peak error against run time'\nset xlabel 'run time [s]'\n",
                      vs_time);
      !svg.empty())
    doc.figure("plots/" + sid + "_transient_time.svg", svg, "Relative error of the peak against the run time of the whole solve");
}

}  // namespace

void write_transient(Doc& doc, const SceneComparison& c, Context& ctx, const std::string& sid) {
  if (c.transients.empty() || !c.transient) return;
  const TransientRequest& t = *c.transient;
  doc.heading(3, "Time history");
  const auto& p = c.scene.request.probes[0];
  const std::string at =
      c.scene.is_beam() ? fmt::format("x = {:g} m", p[0]) : fmt::format("(x, y) = ({:g}, {:g}) m", p[0], p[1]);
  doc.para(fmt::format(
      "Load: {}; {}; from rest. By modal superposition of each back-end's own modes on the mesh its "
      "default solve kept (refined to the tolerance {:g}): each modal coordinate integrated exactly, the truncated "
      "modes' static share added from the statics, and the modes doubled from 12 until the truncation estimate meets "
      "the tolerance (the moments' estimate too, where the back-end's modes carry moments). Peaks are located on the "
      "modes' closed forms. Peaks at {}; the frequency estimate is the mesh's own (its discretization error, which "
      "the truncation estimates do not include: the histories superpose the mesh's modes, also where the default "
      "solve reports extrapolated frequencies).",
      c.transients.front().result.transient.load.empty() ? to_string(t.load)
                                                         : c.transients.front().result.transient.load,
      damping_str(t), c.scene.request.tolerance, at));
  std::vector<std::vector<std::string>> rows;
  std::vector<Series> series, moments;
  for (const TransientRun& r : c.transients) {
    rows.push_back(row_of(r));
    const Transient& tr = r.result.transient;
    if (tr.empty()) continue;
    Series s{r.backend + " " + r.result.summary.mesh, {}, "lines"}, m = s;
    for (std::size_t k = 0; k < tr.time_s.size(); ++k) {
      s.points.emplace_back(tr.time_s[k], tr.values[0][0][k]);
      if (!tr.moments.empty()) m.points.emplace_back(tr.time_s[k], tr.moments[0][k]);
    }
    series.push_back(std::move(s));
    if (!m.points.empty()) moments.push_back(std::move(m));
  }
  for (const PublishedPeak& pp : kPublished)
    if (c.scene.name == pp.scene)
      rows.push_back({std::string("published: ") + pp.source, "—", "1", fmt::format("{:.7g}", pp.w),
                      fmt::format("{:.6g}", pp.time_s), "—", "—", "—", "—", "—", "—"});
  doc.table({"back-end", "mesh kept", "modes", "peak w [m]", "at t [s]", "truncation estimate", "peak My [N m]",
             "its estimate", "frequency estimate", "status", "time [s]"},
            rows, 3);
  if (auto svg = plot(
          ctx, sid + "_transient",
          fmt::format("set title 'w at {} under the time history'\nset xlabel 't [s]'\nset ylabel 'w [m]'\nset grid\n",
                      at),
          series);
      !svg.empty())
    doc.figure("plots/" + sid + "_transient.svg", svg, "Time history of w at the first probe, every back-end overlaid");
  if (!moments.empty()) {
    const std::string setup = fmt::format(
        "set title 'My at {} under the time history'\nset xlabel 't [s]'\nset ylabel 'My [N m]'\nset grid\n", at);
    if (auto svg = plot(ctx, sid + "_transient_moment", setup, moments); !svg.empty())
      doc.figure("plots/" + sid + "_transient_moment.svg", svg,
                 "Bending moment My (sagging positive) at the first probe, every back-end overlaid: the modes' own "
                 "moments with the statics' as the static correction");
  }
  write_mode_convergence(doc, c, ctx, sid);
}

}  // namespace modalbench::report_detail
