#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "modalbench/harness/files.hpp"
#include "report_document.hpp"

namespace modalbench::report_detail {

namespace fs = std::filesystem;

namespace {

/// One colour and marker per method across the whole report, whatever the plot and its other
/// series: keyed by the series' method (its title's first word: a back-end, a CalculiX element
/// family, or "reference", drawn black and dashed).
std::string method_style(const std::string& title) {
  const std::string key = title.substr(0, title.find(' '));
  struct Style {
    const char* key;
    const char* colour;
    int marker;
  };
  static const Style fixed[] = {{"reference", "#000000", 0}, {"exact", "#000000", 6},     {"rfem", "#1f77b4", 7},
                                {"dtfm", "#ff7f0e", 5},      {"difference_eq", "#2ca02c", 9}};
  for (const Style& f : fixed)
    if (key == f.key) return fmt::format("lc rgb '{}' pt {}{}", f.colour, f.marker, key == "reference" ? " dt 2" : "");
  // Others (CalculiX elements, limits named by a back-end and a theory): a fixed hash of the name.
  static const char* colours[] = {"#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  static const int markers[] = {11, 13, 4, 8, 10, 12, 14};
  unsigned h = 2166136261u;
  for (char ch : key) h = (h ^ static_cast<unsigned char>(ch)) * 16777619u;
  return fmt::format("lc rgb '{}' pt {}", colours[h % 7], markers[(h / 7) % 7]);
}

/// gnuplot's SVG without what does not draw: comments, empty groups (gnuplot opens and closes one
/// per style change), attributes at their defaults and runs of white space (a quarter to a third of
/// the file).
std::string minified(const std::string& svg) {
  std::string out;
  out.reserve(svg.size());
  for (std::size_t i = 0; i < svg.size();) {
    if (svg.compare(i, 4, "<!--") == 0) {
      const std::size_t end = svg.find("-->", i + 4);
      i = end == std::string::npos ? svg.size() : end + 3;
    } else if (std::isspace(static_cast<unsigned char>(svg[i]))) {
      if (!out.empty() && out.back() != ' ') out += ' ';
      ++i;
    } else {
      out += svg[i++];
    }
  }
  // SVG's defaults, which gnuplot writes on every group.
  for (const char* dflt : {" stroke-linecap=\"butt\"", " stroke-linejoin=\"miter\""})
    for (std::size_t at = out.find(dflt); at != std::string::npos; at = out.find(dflt, at)) out.erase(at, std::strlen(dflt));
  const std::regex empty_group("<g [^<>]*> ?</g>");
  for (std::string before; before != out;) {
    before = out;
    out = std::regex_replace(out, empty_group, "");
  }
  return std::regex_replace(out, std::regex("> <(?!/?t)"), "><");
}

/// The SVG gnuplot wrote to `svg` (minified, and written back so), or "" with the reason recorded.
std::string read_plot(Context& ctx, const std::string& name, const fs::path& svg, const std::string& gnuplot_out) {
  std::ifstream in(svg);
  std::stringstream ss;
  ss << in.rdbuf();
  if (ss.str().find("<svg") == std::string::npos) {
    ctx.problems.push_back(fmt::format("plot {} not made (gnuplot: {})", name,
                                       gnuplot_out.empty() ? "no output" : gnuplot_out.substr(0, 200)));
    return "";
  }
  std::string text = minified(ss.str());
  write_text_file(svg.string(), text);
  return text;
}

}  // namespace

std::string plot(Context& ctx, const std::string& name, const std::string& setup, const std::vector<Series>& series) {
  std::vector<const Series*> used;
  for (const auto& s : series)
    if (!s.points.empty()) used.push_back(&s);
  if (used.empty()) return "";
  const fs::path pdir = fs::path(ctx.dir) / "plots";
  make_output_dir(pdir.string());
  std::string cmd = "set terminal svg size 760,460 dynamic enhanced font 'Helvetica,12' background rgb 'white'\n";
  cmd += fmt::format("set output '{}'\n{}\nset key outside right top\n", (pdir / (name + ".svg")).string(), setup);
  cmd += "plot ";
  for (std::size_t i = 0; i < used.size(); ++i) {
    const fs::path dat = pdir / fmt::format("{}_{}.dat", name, i);
    std::string data;
    for (auto& [x, y] : used[i]->points)
      if (std::isfinite(x) && std::isfinite(y)) data += fmt::format("{:.10g} {:.10g}\n", x, y);
    write_text_file(dat.string(), data);
    std::string title = used[i]->title;
    std::replace(title.begin(), title.end(), '\'', ' ');
    std::replace(title.begin(), title.end(), '_', '-');
    cmd += fmt::format("{}'{}' using 1:2 with {} lw 2 {} title '{}'", i ? ", " : "", dat.string(), used[i]->style,
                       method_style(used[i]->title), title);
  }
  cmd += "\n";
  const fs::path gp = pdir / (name + ".gp");
  write_text_file(gp.string(), cmd);
  const std::string out = command_output(ctx.options.gnuplot + " '" + gp.string() + "'");
  return read_plot(ctx, name, pdir / (name + ".svg"), out);
}

std::string data_path(const Context& ctx, const std::string& file) {
  return (fs::path(ctx.dir) / "plots" / file).string();
}

std::string plot_script(Context& ctx, const std::string& name, const std::string& body,
                        const std::vector<std::pair<std::string, std::string>>& data, const std::string& size) {
  const fs::path pdir = fs::path(ctx.dir) / "plots";
  make_output_dir(pdir.string());
  for (const auto& [file, content] : data) write_text_file(data_path(ctx, file), content);
  const fs::path svg = pdir / (name + ".svg"), gp = pdir / (name + ".gp");
  write_text_file(gp.string(), fmt::format("set terminal svg size {} dynamic enhanced font 'Helvetica,12' background rgb "
                                           "'white'\nset output '{}'\n{}\n",
                                           size, svg.string(), body));
  const std::string out = command_output(ctx.options.gnuplot + " '" + gp.string() + "'");
  return read_plot(ctx, name, svg, out);
}

}  // namespace modalbench::report_detail
