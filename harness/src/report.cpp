#include "modalbench/harness/report.hpp"

#include <Eigen/Core>
#include <fmt/format.h>
#include <sys/utsname.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "modalbench/harness/files.hpp"
#include "report_document.hpp"

namespace modalbench {

namespace fs = std::filesystem;
using namespace report_detail;

namespace report_detail {

namespace {

/// What a limit is, briefly: "exact solution", "Richardson, 4 meshes", "none (2 meshes)".
std::string limit_str(const ModelLimit& lim) {
  if (lim.source == "exact") return "exact solution";
  if (lim.source.rfind("richardson", 0) == 0) {
    const auto comma = lim.source.find(", ");
    return "Richardson, " + lim.source.substr(comma + 2, lim.source.size() - comma - 3);
  }
  return "none (" + lim.source.substr(6, lim.source.find(" successful") - 6) + " meshes)";
}

}  // namespace

namespace {

/// The time-to-accuracy rows of the scene's other quantities, where any method measured them:
/// static deflections at the probes (relative, as the frequencies) and the FRF (median |error| in
/// dB; 0.1 dB is about 1 % in amplitude), each against the same model limits.
void write_other_quantities(Doc& doc, const SceneComparison& c) {
  struct Other {
    Quantity q;
    const char* what;
    double targets[4];
    std::vector<std::string> head;
  };
  const Other others[] = {
      {Quantity::Deflections,
       "Static deflections at the probes (largest relative error): time to each accuracy, the statics alone with "
       "the model build, against the same limits.",
       {1e-2, 1e-3, 1e-4, 1e-5},
       {"method", "1 % [s]", "0.1 % [s]", "0.01 % [s]", "0.001 % [s]"}},
      {Quantity::Frf,
       "FRF (median |error| over the samples, in dB; 0.1 dB is about 1 % in amplitude): time to each accuracy, the "
       "FRF alone with the model build, against the same limits.",
       {0.1, 1e-2, 1e-3, 1e-4},
       {"method", "0.1 dB [s]", "0.01 dB [s]", "0.001 dB [s]", "0.0001 dB [s]"}},
  };
  for (const Other& o : others) {
    std::vector<std::vector<std::string>> rows;
    for (const auto& lim : c.limits) {
      // Measured at all: some run of it reaches an unbounded target.
      if (!std::isfinite(time_to_accuracy(c, lim.label, std::numeric_limits<double>::infinity(), o.q))) continue;
      std::vector<std::string> row = {lim.label};
      for (double t : o.targets) row.push_back(time_str(time_to_accuracy(c, lim.label, t, o.q)));
      rows.push_back(row);
    }
    if (rows.empty()) continue;
    doc.para(o.what);
    doc.table(o.head, rows, 1);
  }
}

}  // namespace

void write_summary(Doc& doc, const std::vector<SceneComparison>& all) {
  doc.heading(2, "Summary: how fast each method converges to its own model, and how far that model is from the best reference",
              "summary");
  doc.para("Each table below has one row per method of a scene. Read it with these definitions:");
  doc.list({"Converges to: the method's own limit. It is the exact solution where the method's model tends to the "
            "scene's theory, else the Richardson limit of its ladder of meshes.",
            "1 % … 0.001 % [s]: the time to that discretization error on the first 6 frequencies. It is the time of "
            "the modes alone (model build and eigen solve) on the cheapest mesh that reaches it.",
            "Observed order: how fast the frequencies converge as the mesh is refined.",
            "Model error [%]: how far the method's limit lies from the best reference of the scene. Its ± is the sum "
            "of both grid convergence indices; where that exceeds the value, the model error is not determined.",
            "Cheapest at: the accuracies at which this method is the fastest of those whose model error is within "
            "the target."});
  constexpr int kTargets = 4;
  const double targets[kTargets] = {1e-2, 1e-3, 1e-4, 1e-5};
  for (const auto& c : all) {
    double best_t[kTargets] = {kNaN, kNaN, kNaN, kNaN};
    std::string best_m[kTargets];
    for (const auto& lim : c.limits)
      for (int k = 0; k < kTargets; ++k) {
        // A method whose model is further from the best reference than the target buys no such accuracy.
        if (!(lim.model_error <= targets[k])) continue;
        const double t = time_to_accuracy(c, lim.label, targets[k]);
        if (std::isfinite(t) && !(t >= best_t[k])) {
          best_t[k] = t;
          best_m[k] = lim.label;
        }
      }
    std::vector<std::vector<std::string>> rows;
    for (const auto& lim : c.limits) {
      std::vector<std::string> row = {lim.label, limit_str(lim)};
      std::string cheapest;
      for (int k = 0; k < kTargets; ++k) {
        row.push_back(time_str(time_to_accuracy(c, lim.label, targets[k])));
        if (best_m[k] == lim.label) cheapest += (cheapest.empty() ? "" : ", ") + fmt::format("{:g} %", targets[k] * 100);
      }
      row.push_back(std::isfinite(lim.order[0]) ? fmt::format("{:.2f}", lim.order[0]) : "—");
      row.push_back(model_error_str(lim));
      row.push_back(cheapest);
      rows.push_back(row);
    }
    doc.heading(3, c.scene.name);
    doc.para("Best reference: " + c.best_label + ".");
    doc.table({"method", "converges to", "1 % [s]", "0.1 % [s]", "0.01 % [s]", "0.001 % [s]", "observed order",
               "model error [%]", "cheapest at"},
              rows, 2);
    write_other_quantities(doc, c);
  }
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
      "font-variant-numeric:tabular-nums}th{background:#eee}td.l,th.l{text-align:left}figure{margin:0.5em 0}figure img{width:100%;max-width:760px}"
      "figcaption{font-size:90%;color:#555}h2{border-top:2px solid #888;padding-top:0.5em;margin-top:2em}"
      "table.mac td{min-width:2.6em;text-align:center;font-size:85%}</style>"
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
  e.emplace_back("instruction set", std::string(MODALBENCH_ARCH_FLAGS_STRING).empty() ? "compiler default"
                                                                                    : MODALBENCH_ARCH_FLAGS_STRING);
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
  doc.para("Frequencies in rad/s, times in seconds: the median of repeated solves of each quantity alone (modes, "
           "statics, FRF), each charged with the model build and any factorization it needs. Errors are relative, "
           "over the first min(6, requested) frequencies (a run that misses one has none: —); rigid-body modes are "
           "not compared. Two errors are never mixed: the discretization error of a run is measured against its own "
           "model's converged limit, the model error of that limit against the best reference of the scene. Modes are "
           "paired by MAC on sampled shapes within their family (bending-xz, bending-xy, axial, torsion, plate).");
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
