#include "modalbench/report.hpp"

#include <Eigen/Core>
#include <fmt/format.h>
#include <sys/utsname.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "modalbench/json_output.hpp"
#include "modalbench/paper_tables.hpp"

namespace modalbench {

namespace fs = std::filesystem;

namespace {

std::string esc(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '&': o += "&amp;"; break;
      case '"': o += "&quot;"; break;
      default: o += c;
    }
  }
  return o;
}

std::string md_cell(const std::string& s) {
  std::string o;
  for (char c : s) o += (c == '|') ? std::string("\\|") : std::string(1, c);
  return o;
}

std::string err_str(double e) { return std::isfinite(e) ? fmt::format("{:.2e}", e) : "—"; }
std::string num_str(double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : "—"; }
std::string time_str(double t) { return std::isfinite(t) ? fmt::format("{:.3g}", t) : "not reached"; }

std::string command_output(const std::string& cmd) {
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return "";
  std::string out;
  std::array<char, 512> buf{};
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) out.append(buf.data(), n);
  pclose(p);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

std::string base64(const std::string& in) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(in[i]) << 16) | (static_cast<unsigned char>(in[i + 1]) << 8) |
                       static_cast<unsigned char>(in[i + 2]);
    out += t[(v >> 18) & 63];
    out += t[(v >> 12) & 63];
    out += t[(v >> 6) & 63];
    out += t[v & 63];
  }
  if (i < in.size()) {
    unsigned v = static_cast<unsigned char>(in[i]) << 16;
    if (i + 1 < in.size()) v |= static_cast<unsigned char>(in[i + 1]) << 8;
    out += t[(v >> 18) & 63];
    out += t[(v >> 12) & 63];
    out += (i + 1 < in.size()) ? t[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

/// Markdown and HTML written side by side.
struct Doc {
  std::string md, html;
  void heading(int level, const std::string& text, const std::string& id = "") {
    md += std::string(level, '#') + " " + text + "\n\n";
    html += fmt::format("<h{}{}>{}</h{}>\n", level, id.empty() ? "" : " id=\"" + id + "\"", esc(text), level);
  }
  void para(const std::string& text) {
    md += text + "\n\n";
    html += fmt::format("<p>{}</p>\n", esc(text));
  }
  void list(const std::vector<std::string>& items) {
    if (items.empty()) return;
    html += "<ul>";
    for (const auto& i : items) {
      md += "- " + i + "\n";
      html += fmt::format("<li>{}</li>", esc(i));
    }
    md += "\n";
    html += "</ul>\n";
  }
  void table(const std::vector<std::string>& head, const std::vector<std::vector<std::string>>& rows) {
    if (rows.empty()) return;
    md += "|";
    html += "<table><tr>";
    for (const auto& h : head) {
      md += fmt::format(" {} |", md_cell(h));
      html += fmt::format("<th>{}</th>", esc(h));
    }
    md += "\n|";
    for (std::size_t i = 0; i < head.size(); ++i) md += i == 0 ? "---|" : "---:|";
    md += "\n";
    html += "</tr>\n";
    for (const auto& r : rows) {
      md += "|";
      html += "<tr>";
      for (std::size_t i = 0; i < r.size(); ++i) {
        md += fmt::format(" {} |", md_cell(r[i]));
        html += fmt::format("{}{}</td>", i == 0 ? "<td class=\"l\">" : "<td>", esc(r[i]));
      }
      md += "\n";
      html += "</tr>\n";
    }
    md += "\n";
    html += "</table>\n";
  }
  void figure(const std::string& svg_file, const std::string& svg, const std::string& caption) {
    md += fmt::format("![{}]({})\n\n", caption, svg_file);
    html += fmt::format("<figure><img alt=\"{}\" src=\"data:image/svg+xml;base64,{}\"><figcaption>{}</figcaption></figure>\n",
                        esc(caption), base64(svg), esc(caption));
  }
};

struct Series {
  std::string title;
  std::vector<std::pair<double, double>> points;
  std::string style = "linespoints";
};

/// Runs gnuplot on one plot; returns the SVG text, or "" (and records why) on failure.
std::string plot(const std::string& dir, const std::string& name, const std::string& setup,
                 const std::vector<Series>& series, const std::string& gnuplot, std::vector<std::string>& problems) {
  std::vector<const Series*> used;
  for (const auto& s : series)
    if (!s.points.empty()) used.push_back(&s);
  if (used.empty()) return "";
  const fs::path pdir = fs::path(dir) / "plots";
  fs::create_directories(pdir);
  std::string cmd = "set terminal svg size 760,460 dynamic enhanced font 'Helvetica,12' background rgb 'white'\n";
  cmd += fmt::format("set output '{}'\n{}\nset key outside right top\n", (pdir / (name + ".svg")).string(), setup);
  cmd += "plot ";
  for (std::size_t i = 0; i < used.size(); ++i) {
    const fs::path dat = pdir / fmt::format("{}_{}.dat", name, i);
    std::ofstream d(dat);
    for (auto& [x, y] : used[i]->points)
      if (std::isfinite(x) && std::isfinite(y)) d << fmt::format("{:.10g} {:.10g}\n", x, y);
    std::string title = used[i]->title;
    std::replace(title.begin(), title.end(), '\'', ' ');
    std::replace(title.begin(), title.end(), '_', '-');
    cmd += fmt::format("{}'{}' using 1:2 with {} lw 2 title '{}'", i ? ", " : "", dat.string(), used[i]->style, title);
  }
  cmd += "\n";
  const fs::path gp = pdir / (name + ".gp");
  std::ofstream(gp) << cmd;
  const std::string out = command_output(gnuplot + " '" + gp.string() + "'");
  std::ifstream in(pdir / (name + ".svg"));
  std::stringstream ss;
  ss << in.rdbuf();
  if (ss.str().find("<svg") == std::string::npos) {
    problems.push_back(fmt::format("plot {} not made (gnuplot: {})", name, out.empty() ? "no output" : out.substr(0, 200)));
    return "";
  }
  return ss.str();
}

std::string slug(const std::string& s) {
  std::string o;
  for (char c : s) o += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return o;
}

std::vector<std::string> backends_of(const SceneComparison& c) {
  std::vector<std::string> names;
  for (const auto& r : c.runs)
    if (std::find(names.begin(), names.end(), r.backend) == names.end()) names.push_back(r.backend);
  return names;
}

const RunRecord* finest(const SceneComparison& c, const std::string& backend) {
  const RunRecord* f = nullptr;
  for (const auto& r : c.runs)
    if (r.backend == backend && !r.failed()) f = &r;
  return f;
}

std::string run_label(const RunRecord& r) { return r.mesh.counts.empty() ? r.backend : r.backend + " " + r.mesh.spec(); }

nlohmann::json num(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace

std::vector<std::pair<std::string, std::string>> environment_info(const std::string& gnuplot) {
  std::vector<std::pair<std::string, std::string>> e;
  utsname u{};
  if (uname(&u) == 0) e.emplace_back("machine", fmt::format("{} {} {} {}", u.sysname, u.release, u.machine, u.nodename));
  e.emplace_back("cores", std::to_string(sysconf(_SC_NPROCESSORS_ONLN)));
  const long pages = sysconf(_SC_PHYS_PAGES), psize = sysconf(_SC_PAGE_SIZE);
  e.emplace_back("memory", fmt::format("{:.1f} GiB", static_cast<double>(pages) * static_cast<double>(psize) / (1 << 30)));
  e.emplace_back("compiler", std::string("g++ ") + __VERSION__);
#ifdef NDEBUG
  e.emplace_back("build type", "Release (NDEBUG)");
#else
  e.emplace_back("build type", "Debug (assertions on)");
#endif
  e.emplace_back("Eigen", fmt::format("{}.{}.{}", EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION));
  e.emplace_back("nlohmann_json", fmt::format("{}.{}.{}", NLOHMANN_JSON_VERSION_MAJOR, NLOHMANN_JSON_VERSION_MINOR,
                                              NLOHMANN_JSON_VERSION_PATCH));
  e.emplace_back("fmt", std::to_string(FMT_VERSION));
  const std::string gp = command_output(gnuplot + " --version");
  e.emplace_back("gnuplot", gp.empty() ? "not found" : gp);
  return e;
}

std::string write_report(const std::vector<SceneComparison>& all, const std::string& dir, const ReportOptions& opt) {
  fs::create_directories(dir);
  std::vector<std::string> problems;
  Doc doc;
  const auto env = environment_info(opt.gnuplot);
  doc.html =
      fmt::format("<!doctype html><html><head><meta charset=\"utf-8\"><title>{}", esc(opt.title)) +
      "</title><style>body{font-family:Helvetica,Arial,sans-serif;max-width:78em;margin:1em auto;padding:0 1em;color:#222}"
      "table{border-collapse:collapse;margin:0.5em 0 1.2em}td,th{border:1px solid #bbb;padding:2px 8px;text-align:right;"
      "font-variant-numeric:tabular-nums}th{background:#eee}td.l{text-align:left}figure{margin:0.5em 0}figure img{width:100%;max-width:760px}"
      "figcaption{font-size:90%;color:#555}h2{border-top:2px solid #888;padding-top:0.5em;margin-top:2em}</style>"
      "</head><body>\n";
  doc.heading(1, opt.title);
  doc.para("Frequencies in rad/s, times in seconds (median of repeated runs after a warm-up), errors relative. "
           "Modes are matched to the reference within their family (bending-xz, bending-xy, axial, torsion, plate); "
           "rigid-body modes are not compared. The error of a run is the largest relative error over the first "
           "min(6, requested) frequencies; a run that misses one of them has no error (—).");
  for (const auto& p : opt.preface) doc.para(p);

  // Summary: the cost of 1 % and 0.1 %.
  doc.heading(2, "Summary: run time to reach 1 % and 0.1 % on the first 6 frequencies", "summary");
  std::vector<std::vector<std::string>> srows;
  for (const auto& c : all)
    for (const auto& b : backends_of(c)) {
      if (b == c.reference.source) continue;
      const RunRecord* f = finest(c, b);
      srows.push_back({c.scene.name, b, time_str(time_to_accuracy(c, b, 1e-2)), time_str(time_to_accuracy(c, b, 1e-3)),
                       f ? err_str(f->max_frequency_error) : "failed", f ? f->mesh.spec() : "—", c.reference.source});
    }
  doc.table({"scene", "back-end", "time to 1 % [s]", "time to 0.1 % [s]", "finest error", "finest mesh", "reference"}, srows);

  nlohmann::json jscenes = nlohmann::json::array();
  std::ofstream runs_csv(fs::path(dir) / "runs.csv"), freq_csv(fs::path(dir) / "frequencies.csv");
  runs_csv << "scene,backend,mesh,dofs,status,median_s,repeats,max_frequency_error,deflection_error,frf_error_db,reference\n";
  freq_csv << "scene,backend,mesh,mode,family,omega_rad_s,reference_rad_s,reference_uncertainty_rad_s,relative_error\n";

  for (const auto& c : all) {
    const std::string sid = slug(c.scene.name);
    doc.heading(2, fmt::format("{} — {} {} ({})", c.scene.name, to_string(c.scene.kind), to_string(c.scene.physics),
                               to_string(c.scene.theory)),
                sid);
    std::vector<std::string> notes = {fmt::format("scene file: {}", c.scene.source),
                                      fmt::format("reference: {}", c.reference.source)};
    for (const auto& n : c.scene.notes) notes.push_back("scene: " + n);
    for (const auto& n : c.notes) notes.push_back(n);
    doc.list(notes);

    // Error vs time and vs DOFs.
    std::vector<Series> vs_time, vs_dofs;
    for (const auto& b : backends_of(c)) {
      if (b == c.reference.source) continue;
      Series st{b, {}}, sd{b, {}};
      for (const auto& r : c.runs)
        if (r.backend == b && !r.failed() && std::isfinite(r.max_frequency_error) && r.max_frequency_error > 0) {
          st.points.emplace_back(r.median_s, r.max_frequency_error);
          if (r.result.summary.dofs > 0) sd.points.emplace_back(static_cast<double>(r.result.summary.dofs), r.max_frequency_error);
        }
      vs_time.push_back(st);
      vs_dofs.push_back(sd);
    }
    const std::string ylabel = "set ylabel 'max relative error, first frequencies'\nset logscale xy\nset format y '10^{%T}'\nset grid\n";
    if (auto svg = plot(dir, sid + "_error_vs_time", "set title 'Error against run time'\nset xlabel 'run time [s]'\nset format x '10^{%T}'\n" + ylabel,
                        vs_time, opt.gnuplot, problems);
        !svg.empty())
      doc.figure("plots/" + sid + "_error_vs_time.svg", svg,
                 "Error against run time (median): which method buys accuracy cheapest. Reference: " + c.reference.source);
    if (auto svg = plot(dir, sid + "_error_vs_dofs", "set title 'Error against model size'\nset xlabel 'degrees of freedom'\n" + ylabel,
                        vs_dofs, opt.gnuplot, problems);
        !svg.empty())
      doc.figure("plots/" + sid + "_error_vs_dofs.svg", svg, "Error against the number of unknowns");

    // Ladder table.
    std::vector<std::vector<std::string>> rows;
    for (const auto& r : c.runs) {
      const auto& s = r.result.summary;
      std::string msg = s.message;
      if (msg.empty() && !s.warnings.empty()) msg = fmt::format("{} warning(s): {}", s.warnings.size(), s.warnings.front());
      if (r.matched_by_order) msg = "modes matched by order (no family labels). " + msg;
      rows.push_back({r.backend, r.mesh.spec(), std::to_string(s.dofs), to_string(s.status),
                      fmt::format("{} (x{})", num_str(r.median_s), r.repeats), err_str(r.max_frequency_error),
                      err_str(r.deflection_error), std::isfinite(r.frf_error_db) ? fmt::format("{:.2f}", r.frf_error_db) : "—",
                      msg.substr(0, 160)});
      runs_csv << fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", c.scene.name, r.backend, r.mesh.spec(), s.dofs,
                              to_string(s.status), r.median_s, r.repeats, r.max_frequency_error, r.deflection_error,
                              r.frf_error_db, c.reference.source);
      for (std::size_t i = 0; i < r.result.frequencies_rad_s.size(); ++i) {
        // Report each run's modes with the reference mode they were matched to.
        double refv = kNaN, unc = kNaN, err = kNaN;
        const auto m = match_modes(c.reference.families, r.result.mode_families);
        for (std::size_t k = 0; k < m.size(); ++k)
          if (m[k] == static_cast<int>(i)) {
            refv = c.reference.frequencies_rad_s[k];
            unc = c.reference.frequency_uncertainty[k];
            err = r.frequency_errors[k];
          }
        freq_csv << fmt::format("{},{},{},{},{},{},{},{},{}\n", c.scene.name, r.backend, r.mesh.spec(), i + 1,
                                to_string(r.result.mode_families[i]), r.result.frequencies_rad_s[i], refv, unc, err);
      }
    }
    doc.heading(3, "Runs");
    doc.table({"back-end", "mesh", "DOFs", "status", "time [s] (repeats)", "freq. error", "deflection error",
               "FRF error [dB]", "message"},
              rows);

    // Frequencies: the reference beside the finest run of each back-end.
    if (!c.reference.frequencies_rad_s.empty()) {
      std::vector<std::string> head = {"mode", "family", "reference [rad/s]"};
      std::vector<const RunRecord*> cols;
      for (const auto& b : backends_of(c))
        if (b != c.reference.source)
          if (const RunRecord* f = finest(c, b)) {
            cols.push_back(f);
            head.push_back(run_label(*f) + " (rel. error)");
          }
      std::vector<std::vector<std::string>> frows;
      for (std::size_t i = 0; i < c.reference.frequencies_rad_s.size(); ++i) {
        std::string refcell = num_str(c.reference.frequencies_rad_s[i]);
        if (c.reference.frequency_uncertainty[i] > 0)
          refcell += fmt::format(" ± {:.2g}", c.reference.frequency_uncertainty[i]);
        std::vector<std::string> row = {std::to_string(i + 1), to_string(c.reference.families[i]), refcell};
        for (const RunRecord* f : cols) {
          const auto m = match_modes(c.reference.families, f->result.mode_families);
          row.push_back(m[i] >= 0 ? fmt::format("{} ({})", num_str(f->result.frequencies_rad_s[m[i]]), err_str(f->frequency_errors[i]))
                                  : "—");
        }
        frows.push_back(row);
      }
      doc.heading(3, "Frequencies (finest run of each back-end)");
      doc.table(head, frows);
    }

    // The paper's table, side by side with ours.
    const PublishedTable pub = published_table(c.scene.name);
    if (!pub.columns.empty()) {
      std::vector<std::string> head = {"mode"};
      for (const auto& col : pub.columns) head.push_back(col.label);
      std::vector<const RunRecord*> ours;
      for (const auto& r : c.runs)
        if (!r.failed() && !r.result.frequencies_rad_s.empty()) ours.push_back(&r);
      for (const RunRecord* r : ours) head.push_back(fmt::format("ours: {}", run_label(*r)));
      std::vector<std::vector<std::string>> prow;
      const std::size_t n = pub.columns.front().values.size();
      for (std::size_t i = 0; i < n; ++i) {
        std::vector<std::string> row = {std::to_string(i + 1)};
        for (const auto& col : pub.columns) row.push_back(i < col.values.size() ? num_str(col.values[i]) : "—");
        for (const RunRecord* r : ours) {
          // The paper lists bending (beam) or plate modes only: take ours in order within that
          // family; a run without labels in order of its elastic modes.
          const ModeFamily want = c.scene.is_beam() ? ModeFamily::BendingXZ : ModeFamily::Plate;
          const auto& fams = r->result.mode_families;
          const bool labelled = std::any_of(fams.begin(), fams.end(), [](ModeFamily f) {
            return f != ModeFamily::Unknown && f != ModeFamily::Rigid;
          });
          std::vector<double> fam;
          for (std::size_t k = 0; k < r->result.frequencies_rad_s.size(); ++k)
            if (labelled ? fams[k] == want : fams[k] != ModeFamily::Rigid) fam.push_back(r->result.frequencies_rad_s[k]);
          row.push_back(i < fam.size() ? num_str(fam[i]) : "—");
        }
        prow.push_back(row);
      }
      doc.heading(3, pub.title + ", side by side with ours");
      doc.table(head, prow);
      std::vector<std::string> pnotes;
      for (const auto& col : pub.columns)
        if (!col.note.empty()) pnotes.push_back(col.label + ": " + col.note);
      doc.list(pnotes);
    }

    // FRF overlay.
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
    if (c.scene.request.frf) {
      const auto& fr = *c.scene.request.frf;
      const std::string where = c.scene.is_beam() ? fmt::format("force at x = {} m, response at x = {} m", fr.excite[0], fr.observe[0])
                                                   : fmt::format("force at ({}, {}) m, response at ({}, {}) m", fr.excite[0],
                                                                 fr.excite[1], fr.observe[0], fr.observe[1]);
      if (auto svg = plot(dir, sid + "_frf", "set title 'Receptance |w/F|'\nset xlabel 'omega [rad/s]'\nset ylabel '|w/F| [m/N]'\nset logscale y\nset format y '10^{%T}'\nset grid\n",
                          frf, opt.gnuplot, problems);
          !svg.empty())
        doc.figure("plots/" + sid + "_frf.svg", svg, "Frequency response (finest run of each back-end), " + where);
    }

    // Deflections at the probes.
    if (!c.scene.request.probes.empty()) {
      std::vector<std::string> head = {c.scene.is_beam() ? "probe x [m]" : "probe (x, y) [m]", "reference w [m]"};
      std::vector<const RunRecord*> cols;
      std::vector<Series> dser;
      if (!c.reference.deflection_line.empty()) {
        Series s{"reference (" + c.reference.source + ")", {}, "lines"};
        for (const auto& d : c.reference.deflection_line) s.points.emplace_back(d.position[0], d.w);
        dser.push_back(s);
      } else if (!c.reference.deflections.empty()) {
        Series s{"reference (" + c.reference.source + ")", {}, "points"};
        for (std::size_t i = 0; i < c.reference.deflections.size(); ++i)
          s.points.emplace_back(c.scene.is_beam() ? c.reference.deflections[i].position[0] : static_cast<double>(i + 1),
                                c.reference.deflections[i].w);
        dser.push_back(s);
      }
      for (const auto& b : backends_of(c))
        if (b != c.reference.source)
          if (const RunRecord* f = finest(c, b); f && f->result.deflections.size() == c.scene.request.probes.size()) {
            cols.push_back(f);
            head.push_back(run_label(*f) + " w [m]");
            Series s{run_label(*f), {}, "points"};
            for (std::size_t i = 0; i < f->result.deflections.size(); ++i)
              s.points.emplace_back(c.scene.is_beam() ? f->result.deflections[i].position[0] : static_cast<double>(i + 1),
                                    f->result.deflections[i].w);
            dser.push_back(s);
          }
      std::vector<std::vector<std::string>> drows;
      for (std::size_t i = 0; i < c.scene.request.probes.size(); ++i) {
        const auto& p = c.scene.request.probes[i];
        std::vector<std::string> row = {c.scene.is_beam() ? num_str(p[0]) : fmt::format("({}, {})", p[0], p[1]),
                                        i < c.reference.deflections.size() ? fmt::format("{:.6e}", c.reference.deflections[i].w) : "—"};
        for (const RunRecord* f : cols) row.push_back(fmt::format("{:.6e}", f->result.deflections[i].w));
        drows.push_back(row);
      }
      if (!cols.empty() || !c.reference.deflections.empty()) {
        doc.heading(3, "Static deflection at the probes");
        doc.table(head, drows);
        if (auto svg = plot(dir, sid + "_deflection",
                            std::string("set title 'Static deflection w at the probes'\nset xlabel '") +
                                (c.scene.is_beam() ? "x [m]" : "probe number") + "'\nset ylabel 'w [m]'\nset grid\n",
                            dser, opt.gnuplot, problems);
            !svg.empty())
          doc.figure("plots/" + sid + "_deflection.svg", svg, "Static deflection under the scene's loads");
      }
    }

    // JSON of every number.
    nlohmann::json js;
    js["scene"] = c.scene.name;
    js["scene_file"] = c.scene.source;
    js["notes"] = c.notes;
    js["reference"] = {{"source", c.reference.source}, {"frequencies_rad_s", nlohmann::json::array()},
                       {"uncertainty_rad_s", nlohmann::json::array()}, {"families", nlohmann::json::array()}};
    for (std::size_t i = 0; i < c.reference.frequencies_rad_s.size(); ++i) {
      js["reference"]["frequencies_rad_s"].push_back(num(c.reference.frequencies_rad_s[i]));
      js["reference"]["uncertainty_rad_s"].push_back(num(c.reference.frequency_uncertainty[i]));
      js["reference"]["families"].push_back(to_string(c.reference.families[i]));
    }
    js["runs"] = nlohmann::json::array();
    for (const auto& r : c.runs) {
      auto jr = to_json(c.scene, r.backend, r.mesh, r.result);
      jr["median_s"] = num(r.median_s);
      jr["repeats"] = r.repeats;
      jr["max_frequency_error"] = num(r.max_frequency_error);
      jr["deflection_error"] = num(r.deflection_error);
      jr["frf_error_db"] = num(r.frf_error_db);
      jr["frequency_errors"] = nlohmann::json::array();
      for (double e : r.frequency_errors) jr["frequency_errors"].push_back(num(e));
      js["runs"].push_back(jr);
    }
    jscenes.push_back(js);
  }

  doc.heading(2, "Environment", "environment");
  std::vector<std::vector<std::string>> erows;
  for (auto& [k, v] : env) erows.push_back({k, v});
  doc.table({"what", "value"}, erows);
  if (!problems.empty()) {
    doc.heading(2, "Problems while writing this report");
    doc.list(problems);
  }
  doc.html += "</body></html>\n";

  nlohmann::json root;
  root["environment"] = nlohmann::json::object();
  for (auto& [k, v] : env) root["environment"][k] = v;
  root["scenes"] = jscenes;
  root["problems"] = problems;
  std::ofstream(fs::path(dir) / "results.json") << root.dump(2) << "\n";
  std::ofstream(fs::path(dir) / "report.md") << doc.md;
  std::ofstream(fs::path(dir) / "index.html") << doc.html;
  return (fs::path(dir) / "index.html").string();
}

}  // namespace modalbench
