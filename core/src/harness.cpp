#include "modalbench/harness.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "modalbench/json_output.hpp"

namespace modalbench {

std::vector<std::filesystem::path> scene_files(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  if (!std::filesystem::is_directory(dir)) throw InputError(dir.string(), "", "scene directory not found");
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == ".toml") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

namespace {

std::string html_escape(const std::string& s) {
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

const RunRecord* find_exact(const SceneReport& rep) {
  for (const auto& r : rep.runs)
    if (r.backend == "exact" && r.result.ok()) return &r;
  return nullptr;
}

}  // namespace

std::vector<SceneReport> compare(const std::vector<Scene>& scenes, const Registry& registry,
                                 const CompareOptions& opt) {
  std::vector<SceneReport> reports;
  for (const Scene& scene : scenes) {
    SceneReport rep{scene, {}};
    for (const Solver* s : registry.all()) {
      const Capability cap = s->supports(scene);
      if (!cap.any()) {
        if (opt.progress) *opt.progress << fmt::format("[{}] {}: skipped ({})\n", scene.name, s->name(), cap.reason);
        continue;
      }
      const Discretization mesh = s->default_mesh(scene);
      if (opt.progress) *opt.progress << fmt::format("[{}] {} --mesh {} ...\n", scene.name, s->name(), mesh.spec());
      rep.runs.push_back({s->name(), mesh, s->solve(scene, mesh, Options{})});
    }
    reports.push_back(std::move(rep));
  }

  std::filesystem::create_directories(opt.out_dir);
  nlohmann::json all = nlohmann::json::array();
  std::string md = "# modalbench report\n\nFrequencies in rad/s; relative error against the `exact` back-end.\n\n";
  std::string html =
      "<!doctype html><html><head><meta charset=\"utf-8\"><title>modalbench report</title>"
      "<style>body{font-family:sans-serif;max-width:70em;margin:auto}table{border-collapse:collapse}"
      "td,th{border:1px solid #999;padding:2px 8px;text-align:right}</style></head><body>"
      "<h1>modalbench report</h1><p>Frequencies in rad/s; relative error against the <code>exact</code> back-end.</p>";
  for (const auto& rep : reports) {
    const RunRecord* ex = find_exact(rep);
    md += fmt::format("## {} (`{}`)\n\n", rep.scene.name, rep.scene.source);
    html += fmt::format("<h2>{} (<code>{}</code>)</h2>", html_escape(rep.scene.name), html_escape(rep.scene.source));
    for (const auto& n : rep.scene.notes) {
      md += "- note: " + n + "\n";
      html += "<p>note: " + html_escape(n) + "</p>";
    }
    for (const auto& run : rep.runs) {
      const auto& r = run.result;
      all.push_back(to_json(rep.scene, run.backend, run.mesh, r));
      md += fmt::format("\n### {} (mesh {}): {}{}\n\n", run.backend, run.mesh.spec(), to_string(r.summary.status),
                        r.summary.message.empty() ? "" : " — " + r.summary.message);
      html += fmt::format("<h3>{} (mesh {}): {}</h3>", html_escape(run.backend), html_escape(run.mesh.spec()),
                          html_escape(to_string(r.summary.status) +
                                      (r.summary.message.empty() ? "" : " — " + r.summary.message)));
      if (!r.frequencies_rad_s.empty()) {
        md += "| mode | family | omega [rad/s] | rel. error vs exact |\n|---:|---|---:|---:|\n";
        html += "<table><tr><th>mode</th><th>family</th><th>omega [rad/s]</th><th>rel. error vs exact</th></tr>";
        for (std::size_t i = 0; i < r.frequencies_rad_s.size(); ++i) {
          std::string err = "—";
          if (ex && &run != ex && i < ex->result.frequencies_rad_s.size() && ex->result.frequencies_rad_s[i] > 0)
            err = fmt::format("{:.3e}", std::abs(r.frequencies_rad_s[i] / ex->result.frequencies_rad_s[i] - 1.0));
          md += fmt::format("| {} | {} | {:.6g} | {} |\n", i + 1, to_string(r.mode_families[i]),
                            r.frequencies_rad_s[i], err);
          html += fmt::format("<tr><td>{}</td><td>{}</td><td>{:.6g}</td><td>{}</td></tr>", i + 1,
                              to_string(r.mode_families[i]), r.frequencies_rad_s[i], err);
        }
        html += "</table>";
      }
      if (!r.deflections.empty()) {
        md += "\n| probe x [m] | w [m] | rotation theta_y [rad] |\n|---:|---:|---:|\n";
        html += "<table><tr><th>probe x [m]</th><th>w [m]</th><th>rotation theta_y [rad]</th></tr>";
        for (const auto& d : r.deflections) {
          md += fmt::format("| {:.4g} | {:.6e} | {:.6e} |\n", d.position[0], d.w, d.theta_y);
          html += fmt::format("<tr><td>{:.4g}</td><td>{:.6e}</td><td>{:.6e}</td></tr>", d.position[0], d.w, d.theta_y);
        }
        html += "</table>";
      }
      for (const auto& w : r.summary.warnings) {
        md += "- warning: " + w + "\n";
        html += "<p>warning: " + html_escape(w) + "</p>";
      }
      md += fmt::format("\nrun time {:.3g} s\n", r.summary.total_time_s);
    }
    md += "\n";
  }
  html += "</body></html>\n";
  std::ofstream(opt.out_dir / "report.md") << md;
  std::ofstream(opt.out_dir / "index.html") << html;
  std::ofstream(opt.out_dir / "results.json") << all.dump(2) << "\n";
  return reports;
}

}  // namespace modalbench
