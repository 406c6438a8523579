#include "modalbench/harness/report.hpp"

#include <Eigen/Core>
#include <fmt/format.h>
#include <sys/utsname.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "modalbench/harness/files.hpp"
#include "report_document.hpp"

namespace modalbench {

namespace fs = std::filesystem;
using namespace report_detail;

namespace report_detail {

void write_summary(Doc& doc, const std::vector<SceneComparison>& all) {
  doc.heading(2, "Summary: run time to reach 1 % and 0.1 % on the first 6 frequencies", "summary");
  std::vector<std::vector<std::string>> rows;
  for (const auto& c : all)
    for (const auto& b : backends_of(c)) {
      if (b == c.reference.source) continue;
      const RunRecord* f = finest(c, b);
      rows.push_back({c.scene.name, b, time_str(time_to_accuracy(c, b, 1e-2)), time_str(time_to_accuracy(c, b, 1e-3)),
                      f ? err_str(f->max_frequency_error) : "failed", f ? f->mesh.spec() : "—", c.reference.source});
    }
  doc.table({"scene", "back-end", "time to 1 % [s]", "time to 0.1 % [s]", "finest error", "finest mesh", "reference"},
            rows);
}

void write_environment(Doc& doc, const std::vector<std::pair<std::string, std::string>>& env) {
  doc.heading(2, "Environment", "environment");
  std::vector<std::vector<std::string>> rows;
  for (auto& [k, v] : env) rows.push_back({k, v});
  doc.table({"what", "value"}, rows);
}

}  // namespace report_detail

namespace {

void open_html(Doc& doc, const std::string& title) {
  doc.html =
      fmt::format("<!doctype html><html><head><meta charset=\"utf-8\"><title>{}", esc(title)) +
      "</title><style>body{font-family:Helvetica,Arial,sans-serif;max-width:78em;margin:1em auto;padding:0 1em;color:#222}"
      "table{border-collapse:collapse;margin:0.5em 0 1.2em}td,th{border:1px solid #bbb;padding:2px 8px;text-align:right;"
      "font-variant-numeric:tabular-nums}th{background:#eee}td.l{text-align:left}figure{margin:0.5em 0}figure img{width:100%;max-width:760px}"
      "figcaption{font-size:90%;color:#555}h2{border-top:2px solid #888;padding-top:0.5em;margin-top:2em}</style>"
      "</head><body>\n";
}

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
  make_output_dir(dir);
  Context ctx{dir, opt, {}};
  Doc doc;
  const auto env = environment_info(opt.gnuplot);
  open_html(doc, opt.title);
  doc.heading(1, opt.title);
  doc.para("Frequencies in rad/s, times in seconds (median of repeated runs after a warm-up), errors relative. "
           "Modes are matched to the reference within their family (bending-xz, bending-xy, axial, torsion, plate); "
           "rigid-body modes are not compared. The error of a run is the largest relative error over the first "
           "min(6, requested) frequencies; a run that misses one of them has no error (—).");
  for (const auto& p : opt.preface) doc.para(p);
  write_summary(doc, all);
  for (const auto& c : all) write_scene(doc, c, ctx);
  write_environment(doc, env);
  if (!ctx.problems.empty()) {
    doc.heading(2, "Problems while writing this report");
    doc.list(ctx.problems);
  }
  doc.html += "</body></html>\n";

  write_runs_csv((fs::path(dir) / "runs.csv").string(), all);
  write_frequencies_csv((fs::path(dir) / "frequencies.csv").string(), all);
  write_results_json((fs::path(dir) / "results.json").string(), all, env, ctx.problems);
  write_text_file((fs::path(dir) / "report.md").string(), doc.md);
  write_text_file((fs::path(dir) / "index.html").string(), doc.html);
  return (fs::path(dir) / "index.html").string();
}

}  // namespace modalbench
