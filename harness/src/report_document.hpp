#pragma once
// Private to the report writers: a Markdown and an HTML document written side by side,
// gnuplot plots, and the formatting helpers they share.

#include <string>
#include <utility>
#include <vector>

#include "modalbench/harness/report.hpp"

namespace modalbench::report_detail {

std::string esc(const std::string& s);      ///< HTML-escaped
/// A scene file as the report names it: relative to the working directory where it lies below it
/// (scenes/two_span_beam.toml), else its file name (no build machine's absolute paths).
std::string display_path(const std::string& path);
std::string md_cell(const std::string& s);  ///< '|' escaped for a Markdown table cell
std::string err_str(double e);              ///< relative error, or an em dash
std::string num_str(double v);              ///< 6 significant digits, or an em dash
std::string time_str(double t);             ///< seconds, or "not reached"
std::string secs_str(double t);             ///< seconds to 3 digits, or an em dash
/// A limit's model error with its uncertainty: "4.2e-02 ± 1.9e-03", "0" for an exact zero, "—" unknown.
std::string model_error_str(const ModelLimit& lim);
std::string base64(const std::string& in);
/// Standard output and error of a shell command (trailing newlines removed).
std::string command_output(const std::string& cmd);
std::string slug(const std::string& s);  ///< a file-name-safe version of s

/// Markdown and HTML written side by side.
struct Doc {
  std::string md, html;
  void heading(int level, const std::string& text, const std::string& id = "");
  void para(const std::string& text);
  void list(const std::vector<std::string>& items);
  /// The first `left` columns are text (left-aligned), the others numbers.
  void table(const std::vector<std::string>& head, const std::vector<std::vector<std::string>>& rows, std::size_t left = 1);
  void figure(const std::string& svg_file, const std::string& svg, const std::string& caption);
  /// A figure whose HTML is the caller's (a heat map as a table: a few KB where the SVG took 100);
  /// the Markdown links the SVG file.
  void figure_html(const std::string& svg_file, const std::string& html_body, const std::string& caption);
};

/// A MAC matrix (rows: the reference's modes; columns: the run's) as an HTML table, each cell
/// shaded by its value (white 0, dark blue 1) with the value printed.
std::string mac_table_html(const std::vector<std::vector<double>>& mac, const std::string& row_label,
                           const std::string& column_label);

struct Series {
  std::string title;
  std::vector<std::pair<double, double>> points;
  std::string style = "linespoints";
};

/// What every section writer needs: the output folder, the options, and a list of problems
/// met on the way (shown at the end of the report).
struct Context {
  std::string dir;
  const ReportOptions& options;
  std::vector<std::string> problems;
};

/// Runs gnuplot on one plot (files under dir/plots); returns the SVG text, or "" (and
/// records why in ctx.problems) on failure.
std::string plot(Context& ctx, const std::string& name, const std::string& setup, const std::vector<Series>& series);

/// A gnuplot script of the caller's: `data` files (name, content) are written into dir/plots
/// first, then `body` runs after the SVG terminal and output are set; `body` refers to a data file
/// by the path data_path(ctx, name). Returns the SVG text or "" (reason in ctx.problems).
std::string plot_script(Context& ctx, const std::string& name, const std::string& body,
                        const std::vector<std::pair<std::string, std::string>>& data, const std::string& size = "760,460");
std::string data_path(const Context& ctx, const std::string& file);

/// The time-history section of a scene with [request.transient] (report_transient.cpp).
void write_transient(Doc& doc, const SceneComparison& c, Context& ctx, const std::string& sid);

/// The Campbell section of a rotor scene ([rotor]) (report_campbell.cpp).
void write_campbell(Doc& doc, const SceneComparison& c, Context& ctx, const std::string& sid);

/// The mode-shape section: MAC matrices and overlaid shapes (report_shapes.cpp).
void write_shapes(Doc& doc, const SceneComparison& c, Context& ctx, const std::string& sid);

/// Back-end names in the order of their first run.
std::vector<std::string> backends_of(const SceneComparison& c);
/// The finest successful run of a back-end, or nullptr.
const RunRecord* finest(const SceneComparison& c, const std::string& backend);
std::string run_label(const RunRecord& r);  ///< "rfem 64", or "exact"

// Sections (report_sections.cpp, report_scene.cpp).
void write_summary(Doc& doc, const std::vector<SceneComparison>& all);
void write_scene(Doc& doc, const SceneComparison& c, Context& ctx);
void write_environment(Doc& doc, const std::vector<std::pair<std::string, std::string>>& env);

// Machine-readable files (report_data.cpp).
void write_runs_csv(const std::string& path, const std::vector<SceneComparison>& all);
void write_frequencies_csv(const std::string& path, const std::vector<SceneComparison>& all);
void write_results_json(const std::string& path, const std::vector<SceneComparison>& all,
                        const std::vector<std::pair<std::string, std::string>>& env,
                        const std::vector<std::string>& problems);

}  // namespace modalbench::report_detail
