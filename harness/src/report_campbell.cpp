// The report's Campbell section (rotor scenes, [rotor]): every back-end's whirl frequencies against
// the spin overlaid, forward and backward whirl by marker, the 1x line, the critical speeds, and a
// table of the criticals, the unstable spins and each back-end's distance to exact.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "modalbench/rotor_scene.hpp"
#include "report_document.hpp"

namespace modalbench::report_detail {

namespace {

std::string speeds(const std::vector<double>& v) {
  if (v.empty()) return "—";
  std::string out;
  for (std::size_t i = 0; i < v.size() && i < 4; ++i) out += (out.empty() ? "" : ", ") + fmt::format("{:.6g}", v[i]);
  return v.size() > 4 ? out + ", …" : out;
}

/// Data file of one run: spin, frequency, sense (1 forward, -1 backward, 0 otherwise), one row per root.
std::string campbell_data(const Campbell& c) {
  std::string out;
  for (const CampbellPoint& p : c.points)
    for (std::size_t i = 0; i < p.frequencies_rad_s.size(); ++i)
      out += fmt::format("{:.10g} {:.10g} {}\n", p.spin_rad_s, p.frequencies_rad_s[i],
                         p.whirl[i] == Whirl::Forward ? 1 : p.whirl[i] == Whirl::Backward ? -1 : 0);
  return out;
}

void write_plot(Doc& doc, const SceneComparison& c, Context& ctx, const std::string& sid) {
  static const char* colours[] = {"#000000", "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728"};
  // Where a critical speed shows: seen from the ground on whirl = spin; in the rotating frame a
  // forward one where a frequency reaches 0, a backward one where it reaches twice the spin.
  const bool rotating = c.rotor->frame == Rotor::Frame::Rotating;
  std::vector<std::pair<std::string, std::string>> data;
  std::string plots;
  double top = 0;
  for (std::size_t k = 0; k < c.rotor_runs.size(); ++k) {
    const RotorRun& r = c.rotor_runs[k];
    const Campbell& cb = r.result.campbell;
    if (cb.empty()) continue;
    for (const CampbellPoint& p : cb.points)
      for (double f : p.frequencies_rad_s) top = std::max(top, f);
    const std::string file = fmt::format("{}_campbell_{}.dat", sid, k), col = colours[k % 5];
    std::string who = r.backend;
    std::replace(who.begin(), who.end(), '_', '-');  // gnuplot's enhanced text reads _ as a subscript
    data.emplace_back(file, campbell_data(cb));
    const std::string path = data_path(ctx, file);
    plots += fmt::format("{}'{}' using 1:($3 > 0 ? $2 : 1/0) with points pt {} ps 0.7 lc rgb '{}' title '{} forward', "
                         "'{}' using 1:($3 < 0 ? $2 : 1/0) with points pt {} ps 0.7 lc rgb '{}' title '{} backward', "
                         "'{}' using 1:($3 == 0 ? $2 : 1/0) with points pt 2 ps 0.7 lc rgb '{}' notitle",
                         plots.empty() ? "" : ", ", path, 7 + 2 * static_cast<int>(k), col, who, path,
                         6 + 2 * static_cast<int>(k), col, who, path, col);
    std::string crit;
    for (double w : cb.forward_criticals) crit += fmt::format("{:.10g} {:.10g}\n", w, rotating ? 0.0 : w);
    for (double w : cb.backward_criticals) crit += fmt::format("{:.10g} {:.10g}\n", w, rotating ? 2 * w : w);
    if (!crit.empty()) {
      const std::string cf = fmt::format("{}_campbell_{}_crit.dat", sid, k);
      data.emplace_back(cf, crit);
      plots += fmt::format(", '{}' using 1:2 with points pt 3 ps 1.6 lc rgb '{}' title '{} critical speeds'",
                           data_path(ctx, cf), col, who);
    }
  }
  if (plots.empty()) return;
  const double spin_top = c.rotor->spin.back();
  const std::string body = fmt::format(
      "set key outside right top\nset grid\nset xlabel 'spin [rad/s]'\nset ylabel 'whirl frequency [rad/s]'\n"
      "set title 'Campbell diagram ({} frame)'\nset xrange [0:{:.10g}]\nset yrange [0:{:.10g}]\n"
      "plot {}, {}",
      to_string(c.rotor->frame), std::max(spin_top, 1e-9) * 1.02, top * 1.05, plots,
      rotating ? "2 * x with lines dt 2 lc rgb '#888888' title '2x (backward critical)'"
               : "x with lines dt 2 lc rgb '#888888' title '1x (whirl = spin)'");
  const std::string name = sid + "_campbell";
  if (auto svg = plot_script(ctx, name, body, data, "860,520"); !svg.empty())
    doc.figure("plots/" + name + ".svg", svg,
               rotating ? "Whirl frequencies seen from the shaft against spin, every back-end's default solve: filled "
                          "markers forward whirl, open ones backward, crosses neither (a root that grows or a planar "
                          "orbit); the large markers are the critical speeds each back-end solved for: forward ones "
                          "where a frequency reaches 0, backward ones on the dashed line, twice the spin"
                        : "Whirl frequencies against spin, every back-end's default solve: filled markers forward "
                          "whirl, open ones backward, crosses neither; the dashed line is whirl = spin, and the large "
                          "markers on it the critical speeds each back-end solved for");
}

}  // namespace

void write_campbell(Doc& doc, const SceneComparison& c, Context& ctx, const std::string& sid) {
  if (!c.rotor || c.rotor_runs.empty()) return;
  doc.heading(3, "Campbell diagram");
  doc.para(fmt::format("The shaft spinning about its axis at {} speeds from {:g} to {:g} rad/s, its whirl seen from the "
                       "{} frame; each back-end's default solve (its mesh refined to the tolerance {:g}), each by its "
                       "own method (see its note below). Critical speeds are solved for (a whirl frequency, seen from "
                       "the ground, equal to the spin), not read off the samples.",
                       c.rotor->spin.size(), c.rotor->spin.front(), c.rotor->spin.back(), to_string(c.rotor->frame),
                       c.scene.request.tolerance));
  const RotorRun* exact = nullptr;
  for (const RotorRun& r : c.rotor_runs)
    if (r.backend == "exact" && r.result.ok()) exact = &r;
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> notes;
  for (const RotorRun& r : c.rotor_runs) {
    const Result& x = r.result;
    const Campbell& cb = x.campbell;
    rows.push_back({r.backend, x.summary.mesh, to_string(x.summary.status), speeds(cb.forward_criticals),
                    speeds(cb.backward_criticals), cb.unstable_spins.empty() ? "none" : speeds(cb.unstable_spins),
                    err_str(x.summary.error_estimate.campbell),
                    exact && &r != exact ? err_str(campbell_difference(cb, exact->result.campbell)) : "—",
                    err_str(cb.max_backward_error), secs_str(x.summary.total_time_s)});
    notes.push_back(fmt::format("{}: {}{}", r.backend, cb.empty() ? x.summary.message : cb.note,
                                cb.criticals_note.empty() ? "" : "; critical speeds: " + cb.criticals_note));
  }
  doc.table({"back-end", "mesh", "status", "forward critical speeds [rad/s]", "backward critical speeds [rad/s]",
             "unstable at spins [rad/s]", "estimate", "vs exact", "backward error", "time [s]"},
            rows, 6);
  doc.para("estimate: the back-end's own discretization error estimate of its whirl frequencies (relative to the "
           "frequency plus the spin); vs exact: the largest difference from exact's, paired by rank at each spin, on "
           "the same scale.");
  doc.list(notes);
  write_plot(doc, c, ctx, sid);
}

}  // namespace modalbench::report_detail
