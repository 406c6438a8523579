// One scene's section of the report: notes, error charts, the run ladder, frequencies,
// the published table beside ours, the FRF overlay and the static deflections.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "modalbench/frame.hpp"
#include "modalbench/harness/paper_tables.hpp"
#include "report_document.hpp"

namespace modalbench::report_detail {

namespace {

void write_notes(Doc& doc, const SceneComparison& c) {
  std::vector<std::string> notes = {fmt::format("scene file: {}", display_path(c.scene.source)),
                                    fmt::format("reference: {}", c.reference.source)};
  for (const auto& n : c.scene.notes) notes.push_back("scene: " + n);
  for (const auto& n : c.notes) notes.push_back(n);
  doc.list(notes);
}

/// Discretization error of each quantity against that quantity's own time, and the frequency
/// error against the number of unknowns: one curve per model limit.
void write_error_charts(Doc& doc, const SceneComparison& c, Context& ctx, const std::string& sid) {
  struct Chart {
    Quantity q;
    const char* what;
    const char* time;
    const char* ylabel;
  };
  const Chart charts[] = {
      {Quantity::Frequencies, "frequencies", "modes", "max relative error, first frequencies"},
      {Quantity::Deflections, "deflections", "statics", "max relative error at the probes"},
      {Quantity::Frf, "frf", "FRF", "median |error| [dB]"},
  };
  for (const auto& ch : charts) {
    std::vector<Series> vs_time;
    for (const auto& lim : c.limits) {
      Series st{lim.label, {}};
      for (const auto& r : c.runs)
        if (r.limit == lim.label && !r.failed() && r.disc_error(ch.q) > 0 && std::isfinite(r.disc_error(ch.q)))
          st.points.emplace_back(r.time_s.of(ch.q), r.disc_error(ch.q));
      vs_time.push_back(st);
    }
    const std::string name = fmt::format("{}_{}_error_vs_time", sid, ch.what);
    if (auto svg = plot(ctx, name,
                        fmt::format("set title 'Discretization error of the {} against their own run time'\n"
                                    "set xlabel '{} time alone [s]'\nset format x '10^{{%T}}'\nset ylabel '{}'\n"
                                    "set logscale xy\nset format y '10^{{%T}}'\nset grid\n",
                                    ch.what, ch.time, ch.ylabel),
                        vs_time);
        !svg.empty())
      doc.figure("plots/" + name + ".svg", svg,
                 fmt::format("Discretization error of the {} (against each model's own limit) against the median time "
                             "of the {} alone, model build included: which method buys that accuracy cheapest",
                             ch.what, ch.time));
  }
  std::vector<Series> vs_dofs;
  for (const auto& lim : c.limits) {
    Series sd{lim.label, {}};
    for (const auto& r : c.runs)
      if (r.limit == lim.label && !r.failed() && r.disc_frequency_error > 0 && std::isfinite(r.disc_frequency_error) &&
          r.result.summary.unknowns > 0)
        sd.points.emplace_back(static_cast<double>(r.result.summary.unknowns), r.disc_frequency_error);
    vs_dofs.push_back(sd);
  }
  if (auto svg = plot(ctx, sid + "_error_vs_dofs",
                      "set title 'Discretization error against model size'\nset xlabel 'unknowns'\n"
                      "set ylabel 'max relative error, first frequencies'\nset logscale xy\nset format y '10^{%T}'\nset grid\n",
                      vs_dofs);
      !svg.empty())
    doc.figure("plots/" + sid + "_error_vs_dofs.svg", svg,
               "Discretization error of the frequencies against the number of unknowns solved");
}

/// Each model limit: what it is, its observed orders and GCI, and its model error.
void write_limits_table(Doc& doc, const SceneComparison& c) {
  std::vector<std::vector<std::string>> rows;
  auto order = [](double p) { return std::isfinite(p) ? fmt::format("{:.2f}", p) : "—"; };
  for (const auto& lim : c.limits)
    rows.push_back({lim.label, lim.source, order(lim.order[0]), order(lim.order[1]), order(lim.order[2]),
                    lim.source == "exact"  ? "0 (exact)"
                    : std::isfinite(lim.gci) ? fmt::format("{:.2g} % (Fs {:g})", 100 * lim.gci, lim.safety_factor)
                                             : "—",
                    model_error_str(lim), lim.convergence_note});
  doc.heading(3, "Converged models: observed order, GCI and model error");
  doc.para("Best reference: " + c.best_label + ". Observed orders per quantity (frequencies: median over the first "
           "modes); GCI: Roache's grid convergence index of the finest frequency, relative, safety factor Fs = 1.25 when a "
           "fourth mesh confirms the order, else 3.");
  doc.table({"method", "converges to", "order (freq.)", "order (defl.)", "order (FRF)", "GCI [%]", "model error [%]", "note"},
            rows, 2);
}

void write_runs_table(Doc& doc, const SceneComparison& c) {
  std::vector<std::vector<std::string>> rows;
  // Messages and warnings as numbered notes below the table (a long one in a cell made every row
  // of the table hundreds of pixels tall); a run's notes are numbered once, equal texts share one.
  std::vector<std::string> notes;
  auto note = [&](const std::string& text) {
    const auto it = std::find(notes.begin(), notes.end(), text);
    if (it != notes.end()) return static_cast<int>(it - notes.begin()) + 1;
    notes.push_back(text);
    return static_cast<int>(notes.size());
  };
  for (const auto& r : c.runs) {
    const auto& s = r.result.summary;
    std::vector<std::string> texts;
    if (r.low_mac_pairs > 0) texts.push_back(fmt::format("{} mode pair(s) with MAC < {}", r.low_mac_pairs, kLowMac));
    if (r.matched_by_order && !r.paired_by_mac) texts.push_back("modes matched by order (no family labels)");
    if (!s.message.empty()) texts.push_back(s.message);
    for (const auto& w : s.warnings) texts.push_back(w);
    std::string refs;
    for (const auto& t : texts) refs += fmt::format("{}[{}]", refs.empty() ? "" : " ", note(t));
    rows.push_back({r.limit.empty() ? r.backend : r.limit, r.mesh.spec(), std::to_string(s.unknowns), to_string(s.status),
                    secs_str(r.time_s.modes), secs_str(r.time_s.statics), secs_str(r.time_s.frf), std::to_string(r.repeats),
                    err_str(r.disc_frequency_error), err_str(r.disc_deflection_error),
                    std::isfinite(r.disc_frf_error_db) ? fmt::format("{:.2g}", r.disc_frf_error_db) : "—",
                    err_str(r.max_frequency_error), refs});
  }
  doc.heading(3, "Runs");
  doc.para("Times are medians of each quantity solved alone (modes, statics, FRF).");
  doc.para("Discretization errors are relative, against the run's own converged model.");
  doc.para("The last error column compares the frequencies with the scene's reference (" + c.reference.source +
           "): it adds the model error where the run's model is another.");
  doc.table({"method", "mesh", "unknowns", "status", "modes [s]", "statics [s]", "FRF [s]", "repeats", "freq. disc. error",
             "defl. disc. error", "FRF disc. error [dB]", "freq. vs reference", "notes"},
            rows);
  std::vector<std::string> numbered;
  for (std::size_t i = 0; i < notes.size(); ++i) numbered.push_back(fmt::format("[{}] {}", i + 1, notes[i]));
  doc.list(numbered);
}

/// The reference beside the finest run of each back-end.
void write_frequency_table(Doc& doc, const SceneComparison& c) {
  if (c.reference.frequencies_rad_s.empty()) return;
  std::vector<std::string> head = {"mode", "family", "reference [rad/s]"};
  std::vector<const RunRecord*> cols;
  for (const auto& b : backends_of(c))
    if (b != c.reference.source)
      if (const RunRecord* f = finest(c, b)) {
        cols.push_back(f);
        head.push_back(run_label(*f) + " (rel. error)");
      }
  std::vector<std::vector<std::string>> rows;
  for (std::size_t i = 0; i < c.reference.frequencies_rad_s.size(); ++i) {
    std::string refcell = num_str(c.reference.frequencies_rad_s[i]);
    if (c.reference.frequency_uncertainty[i] > 0) refcell += fmt::format(" ± {:.2g}", c.reference.frequency_uncertainty[i]);
    std::vector<std::string> row = {std::to_string(i + 1), to_string(c.reference.families[i]), refcell};
    for (const RunRecord* f : cols) {
      const auto& m = f->match;
      std::string cell = "—";
      if (i < m.size() && m[i] >= 0) {
        cell = fmt::format("{} ({})", num_str(f->result.frequencies_rad_s[static_cast<std::size_t>(m[i])]),
                           err_str(f->frequency_errors[i]));
        if (std::isfinite(f->pair_mac[i]))
          cell += fmt::format(" MAC {:.4f}{}", f->pair_mac[i], f->pair_mac[i] < kLowMac ? " (LOW)" : "");
      }
      row.push_back(cell);
    }
    rows.push_back(row);
  }
  doc.heading(3, "Frequencies (finest run of each back-end; relative error and the MAC of the pair)");
  doc.table(head, rows);
}

/// A run's frequencies beside the rows of a published table: the k-th row of a family beside the
/// run's k-th mode of that family (rows without families: bending modes of a beam, plate modes of a
/// plate); a run without labels gives its elastic modes in order. NaN: no such mode.
std::vector<double> published_family(const SceneComparison& c, const PublishedTable& pub, const RunRecord& r) {
  const auto& fams = r.result.mode_families;
  const bool labelled = std::any_of(fams.begin(), fams.end(), [](ModeFamily f) {
    return f != ModeFamily::Unknown && f != ModeFamily::Rigid;
  });
  const std::size_t rows = pub.columns.front().values.size();
  std::vector<double> out(rows, kNaN);
  std::map<ModeFamily, std::size_t> seen;
  std::size_t elastic = 0;
  for (std::size_t i = 0; i < rows; ++i) {
    const ModeFamily want = !pub.families.empty() ? pub.families[i]
                            : c.scene.is_beam()   ? ModeFamily::BendingXZ
                                                  : ModeFamily::Plate;
    if (want == ModeFamily::Unknown) continue;
    std::size_t k = labelled ? seen[want]++ : elastic++, n = 0;
    for (std::size_t m = 0; m < fams.size(); ++m)
      if (labelled ? fams[m] == want : fams[m] != ModeFamily::Rigid) {
        if (n++ == k) {
          out[i] = r.result.frequencies_rad_s[m];
          break;
        }
      }
  }
  return out;
}

void write_published_table(Doc& doc, const SceneComparison& c) {
  const PublishedTable pub = published_table(c.scene.name);
  if (pub.columns.empty()) return;
  std::vector<std::string> head = {"mode"};
  for (const auto& col : pub.columns) head.push_back(col.label);
  // The finest run of each back-end and at most two coarser rungs (the full ladder is in the CSV).
  std::vector<std::vector<double>> ours;
  for (const auto& b : backends_of(c)) {
    std::vector<const RunRecord*> ok;
    for (const auto& r : c.runs)
      if (r.backend == b && !r.failed() && !r.result.frequencies_rad_s.empty()) ok.push_back(&r);
    for (std::size_t k = ok.size() > 3 ? ok.size() - 3 : 0; k < ok.size(); ++k) {
      head.push_back(fmt::format("ours: {}", run_label(*ok[k])));
      ours.push_back(published_family(c, pub, *ok[k]));
    }
  }
  std::vector<std::vector<std::string>> rows;
  const std::size_t n = pub.columns.front().values.size();
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<std::string> row = {pub.families.empty() ? std::to_string(i + 1)
                                                         : fmt::format("{} ({})", i + 1, to_string(pub.families[i]))};
    for (const auto& col : pub.columns) row.push_back(i < col.values.size() ? num_str(col.values[i]) : "—");
    for (const auto& fam : ours) row.push_back(num_str(fam[i]));
    rows.push_back(row);
  }
  doc.heading(3, pub.title + ", side by side with ours");
  doc.table(head, rows);
  std::vector<std::string> notes;
  for (const auto& col : pub.columns)
    if (!col.note.empty()) notes.push_back(col.label + ": " + col.note);
  doc.list(notes);
}

void write_frf(Doc& doc, const SceneComparison& c, Context& ctx, const std::string& sid) {
  std::vector<Series> frf;
  if (!c.reference.frf.empty()) {
    Series s{"reference (" + c.reference.source + ")", {}, "lines"};
    for (const auto& p : c.reference.frf) s.points.emplace_back(p.omega_rad_s, std::abs(p.receptance));
    frf.push_back(s);
  }
  for (const auto& b : backends_of(c)) {
    const RunRecord* f = finest(c, b);
    if (!f || f->result.frf.empty() || b == c.reference.source) continue;
    Series s{run_label(*f), {}, "lines"};
    for (const auto& p : f->result.frf) s.points.emplace_back(p.omega_rad_s, std::abs(p.receptance));
    frf.push_back(s);
  }
  if (!c.scene.request.frf) return;
  const auto& fr = *c.scene.request.frf;
  const std::string where =
      c.scene.is_beam() ? fmt::format("force at x = {} m, response at x = {} m", fr.excite[0], fr.observe[0])
                        : fmt::format("force at ({}, {}) m, response at ({}, {}) m", fr.excite[0], fr.excite[1],
                                      fr.observe[0], fr.observe[1]);
  if (auto svg = plot(ctx, sid + "_frf",
                      "set title 'Receptance |w/F|'\nset xlabel 'omega [rad/s]'\nset ylabel '|w/F| [m/N]'\nset logscale "
                      "y\nset format y '10^{%T}'\nset grid\n",
                      frf);
      !svg.empty())
    doc.figure("plots/" + sid + "_frf.svg", svg, "Frequency response (finest run of each back-end), " + where);
}

/// Deflection w at the probes of a run as plot points (beam: against x; plate: probe number).
Series deflection_series(const SceneComparison& c, const std::string& title, const std::vector<Deflection>& d,
                         const std::string& style) {
  Series s{title, {}, style};
  for (std::size_t i = 0; i < d.size(); ++i)
    s.points.emplace_back(c.scene.is_beam() ? d[i].position[0] : static_cast<double>(i + 1), d[i].w);
  return s;
}

void write_deflections(Doc& doc, const SceneComparison& c, Context& ctx, const std::string& sid) {
  if (c.scene.request.probes.empty()) return;
  // A frame's probes are named (a node, a member at s) and sway: (u, w) per probe, (u, v, w) in space.
  const bool frame = c.scene.is_frame(), spatial = frame && c.scene.physics == Physics::Spatial;
  const std::string comps = !frame ? "w" : spatial ? "(u, v, w)" : "(u, w)";
  const auto value = [&](const Deflection& d) {
    return !frame   ? fmt::format("{:.6e}", d.w)
           : spatial ? fmt::format("({:.6e}, {:.6e}, {:.6e})", d.u, d.v, d.w)
                     : fmt::format("({:.6e}, {:.6e})", d.u, d.w);
  };
  std::vector<std::string> head = {c.scene.is_beam() ? "probe x [m]" : frame ? "probe" : "probe (x, y) [m]",
                                   "reference " + comps + " [m]"};
  std::vector<const RunRecord*> cols;
  std::vector<Series> series;
  const std::string ref_title = "reference (" + c.reference.source + ")";
  if (!c.reference.deflection_line.empty()) {
    Series s{ref_title, {}, "lines"};
    for (const auto& d : c.reference.deflection_line) s.points.emplace_back(d.position[0], d.w);
    series.push_back(s);
  } else if (!c.reference.deflections.empty()) {
    series.push_back(deflection_series(c, ref_title, c.reference.deflections, "points"));
  }
  for (const auto& b : backends_of(c))
    if (b != c.reference.source)
      if (const RunRecord* f = finest(c, b); f && f->result.deflections.size() == c.scene.request.probes.size()) {
        cols.push_back(f);
        head.push_back(run_label(*f) + " " + comps + " [m]");
        series.push_back(deflection_series(c, run_label(*f), f->result.deflections, "points"));
      }
  std::vector<std::vector<std::string>> rows;
  for (std::size_t i = 0; i < c.scene.request.probes.size(); ++i) {
    const auto& p = c.scene.request.probes[i];
    std::vector<std::string> row = {
        c.scene.is_beam() ? num_str(p[0])
        : frame           ? (i < c.scene.frame->probes.size() ? c.scene.frame->probes[i].label : "?")
                          : fmt::format("({}, {})", p[0], p[1]),
        i < c.reference.deflections.size() ? value(c.reference.deflections[i]) : "—"};
    for (const RunRecord* f : cols) row.push_back(value(f->result.deflections[i]));
    rows.push_back(row);
  }
  if (cols.empty() && c.reference.deflections.empty()) return;
  doc.heading(3, "Static deflection at the probes");
  doc.table(head, rows);
  if (auto svg = plot(ctx, sid + "_deflection",
                      std::string("set title 'Static deflection w at the probes'\nset xlabel '") +
                          (c.scene.is_beam() ? "x [m]" : "probe number") + "'\nset ylabel 'w [m]'\nset grid\n",
                      series);
      !svg.empty())
    doc.figure("plots/" + sid + "_deflection.svg", svg, "Static deflection under the scene's loads");
}

}  // namespace

void write_scene(Doc& doc, const SceneComparison& c, Context& ctx) {
  const std::string sid = slug(c.scene.name);
  doc.heading(2,
              fmt::format("{} — {} {} ({})", c.scene.name, to_string(c.scene.kind), to_string(c.scene.physics),
                          to_string(c.scene.theory)),
              sid);
  write_notes(doc, c);
  write_error_charts(doc, c, ctx, sid);
  write_limits_table(doc, c);
  write_runs_table(doc, c);
  write_frequency_table(doc, c);
  write_published_table(doc, c);
  write_shapes(doc, c, ctx, sid);
  write_frf(doc, c, ctx, sid);
  write_deflections(doc, c, ctx, sid);
  write_transient(doc, c, ctx, sid);
  write_campbell(doc, c, ctx, sid);
}

}  // namespace modalbench::report_detail
