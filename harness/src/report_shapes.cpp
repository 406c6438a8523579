// The mode-shape section of a scene: the MAC matrix of each back-end's finest run against the
// reference (a heat map), and the first modes' shapes of every back-end overlaid on the
// reference's (beams: lines along x; plates: contour lines of w).

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "report_document.hpp"

namespace modalbench::report_detail {

namespace {

constexpr std::size_t kShownModes = 4;

/// The component that carries a mode (largest sampled norm; translations first, then the twist).
int main_component(const ModeShapes& s, std::size_t mode) {
  int best = -1;
  double big = 0;
  for (bool translations : {true, false}) {
    for (std::size_t c = 0; c < s.components.size(); ++c) {
      if ((s.components[c] < 3) != translations) continue;
      double n = 0;
      for (double v : s.values[mode][c]) n += v * v;
      if (n > big) {
        big = n;
        best = static_cast<int>(c);
      }
    }
    if (best >= 0) return best;
  }
  return 0;
}

std::vector<const RunRecord*> shaped_runs(const SceneComparison& c) {
  std::vector<const RunRecord*> out;
  for (const auto& b : backends_of(c)) {
    if (b == c.reference.source) continue;
    const RunRecord* f = finest(c, b);
    if (f && f->paired_by_mac && !f->result.mode_shapes.empty()) out.push_back(f);
  }
  return out;
}

void mac_heat_maps(Doc& doc, const SceneComparison& c, Context& ctx, const std::string& sid,
                   const std::vector<const RunRecord*>& runs) {
  const Section sec = c.scene.section();
  const double twist = c.scene.is_beam() ? std::sqrt(sec.Ip / sec.A) : 0.0;
  for (const RunRecord* r : runs) {
    const auto m = mac_matrix(c.reference.shapes, r->result.mode_shapes, twist);
    std::string data;
    for (std::size_t i = 0; i < m.size(); ++i) {
      for (std::size_t j = 0; j < m[i].size(); ++j)
        data += fmt::format("{} {} {:.6f}\n", j + 1, i + 1, std::isfinite(m[i][j]) ? m[i][j] : 0.0);
      data += "\n";
    }
    const std::string name = sid + "_mac_" + slug(run_label(*r));
    const std::string body = fmt::format(
        "set title 'MAC: {} against the reference ({})' noenhanced\nset xlabel '{} mode'\nset ylabel 'reference mode'\n"
        "set cbrange [0:1]\nset palette defined (0 'white', 0.5 '#9ecae1', 0.9 '#3182bd', 1 '#08306b')\n"
        "set xtics 1\nset ytics 1\nset size ratio -1\nunset key\nset xrange [0.5:{}]\nset yrange [0.5:{}]\n"
        "plot '{}' using 1:2:3 with image pixels, '' using 1:2:(sprintf('%.2f', $3)) with labels font ',9'\n",
        run_label(*r), c.reference.source, r->backend, m.empty() ? 1.5 : static_cast<double>(m[0].size()) + 0.5,
        static_cast<double>(m.size()) + 0.5, data_path(ctx, name + ".dat"));
    // The Markdown links the SVG; the page shows the matrix as a shaded table (about 2 % of its size).
    if (auto svg = plot_script(ctx, name, body, {{name + ".dat", data}}, "560,480"); !svg.empty())
      doc.figure_html("plots/" + name + ".svg",
                      mac_table_html(m, "reference (" + c.reference.source + ") mode", run_label(*r) + " mode"),
                      fmt::format("MAC matrix of {} against the reference ({}): the diagonal pairs the modes; off-diagonal "
                                  "weight means shapes mix",
                                  run_label(*r), c.reference.source));
  }
}

void beam_overlays(Doc& doc, const SceneComparison& c, Context& ctx, const std::string& sid,
                   const std::vector<const RunRecord*>& runs) {
  const ModeShapes& ref = c.reference.shapes;
  for (std::size_t i = 0; i < std::min(kShownModes, ref.values.size()); ++i) {
    const int comp = main_component(ref, i);
    const std::string cname = component_name(ref.components[static_cast<std::size_t>(comp)]);
    std::vector<Series> series;
    Series rs{"reference (" + c.reference.source + ")", {}, "lines"};
    for (std::size_t p = 0; p < ref.points.size(); ++p)
      rs.points.emplace_back(ref.points[p][0], ref.values[i][static_cast<std::size_t>(comp)][p]);
    series.push_back(rs);
    for (const RunRecord* r : runs) {
      const int j = i < r->match.size() ? r->match[i] : -1;
      if (j < 0) continue;
      const auto& ms = r->result.mode_shapes;
      // Shapes are mass-normalized with the largest translation positive; a pair may still differ
      // in sign when two samples tie: align with the reference for the overlay.
      double dot = 0;
      for (std::size_t p = 0; p < ms.points.size(); ++p)
        dot += ms.values[static_cast<std::size_t>(j)][static_cast<std::size_t>(comp)][p] *
               ref.values[i][static_cast<std::size_t>(comp)][p];
      const double sign = dot < 0 ? -1.0 : 1.0;
      // A line with a marker every fourth sample: each marker is an SVG element of its own, and all
      // of them made three quarters of the figure.
      Series s{fmt::format("{} (MAC {:.4f})", run_label(*r), r->pair_mac[i]), {}, "linespoints pi 4"};
      for (std::size_t p = 0; p < ms.points.size(); ++p)
        s.points.emplace_back(ms.points[p][0], sign * ms.values[static_cast<std::size_t>(j)][static_cast<std::size_t>(comp)][p]);
      series.push_back(s);
    }
    const std::string name = fmt::format("{}_shape_{}", sid, i + 1);
    if (auto svg = plot(ctx, name,
                        fmt::format("set title 'Mode {} ({}, {:.6g} rad/s): {}'\nset xlabel 'x [m]'\nset ylabel '{} "
                                    "[per sqrt(kg)]'\nset grid\n",
                                    i + 1, to_string(c.reference.families[i]), c.reference.frequencies_rad_s[i], cname,
                                    cname),
                        series);
        !svg.empty())
      doc.figure("plots/" + name + ".svg", svg,
                 fmt::format("Mode {} of every back-end (finest run, paired by MAC) over the reference: {} along the "
                             "beam, unit modal mass",
                             i + 1, cname));
  }
}

void plate_overlays(Doc& doc, const SceneComparison& c, Context& ctx, const std::string& sid,
                    const std::vector<const RunRecord*>& runs) {
  const ModeShapes& ref = c.reference.shapes;
  const int nx = c.scene.request.shapes ? c.scene.request.shapes->nx : ShapeRequest::kPlateDefaultNx;
  auto grid = [&](const ModeShapes& s, std::size_t mode, double sign) {
    std::string d;
    for (std::size_t p = 0; p < s.points.size(); ++p) {
      d += fmt::format("{} {} {:.8g}\n", s.points[p][0], s.points[p][1], sign * s.values[mode][0][p]);
      if ((p + 1) % static_cast<std::size_t>(nx) == 0) d += "\n";
    }
    return d;
  };
  for (std::size_t i = 0; i < std::min(kShownModes, ref.values.size()); ++i) {
    const std::string name = fmt::format("{}_shape_{}", sid, i + 1);
    std::vector<std::pair<std::string, std::string>> data = {{name + "_ref.dat", grid(ref, i, 1.0)}};
    std::string plots = fmt::format("'{}' using 1:2:3 with lines lw 3 lc rgb '#222222' title 'reference ({})'",
                                    data_path(ctx, name + "_ref.dat"), c.reference.source);
    const char* colors[] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e"};
    std::size_t k = 0;
    for (const RunRecord* r : runs) {
      const int j = i < r->match.size() ? r->match[i] : -1;
      if (j < 0) continue;
      const auto& ms = r->result.mode_shapes;
      double dot = 0;
      for (std::size_t p = 0; p < ms.points.size(); ++p)
        dot += ms.values[static_cast<std::size_t>(j)][0][p] * ref.values[i][0][p];
      const std::string file = fmt::format("{}_{}.dat", name, slug(run_label(*r)));
      data.emplace_back(file, grid(ms, static_cast<std::size_t>(j), dot < 0 ? -1.0 : 1.0));
      plots += fmt::format(", '{}' using 1:2:3 with lines lw 1.5 dt 2 lc rgb '{}' title '{} (MAC {:.4f})'",
                           data_path(ctx, file), colors[k++ % 5], run_label(*r), r->pair_mac[i]);
    }
    // Contours at +-20, 40, 60, 80 % of the reference's largest |w| (not at 0: the edges are 0).
    double big = 0;
    for (double v : ref.values[i][0]) big = std::max(big, std::abs(v));
    std::string levels;
    for (double f : {-0.8, -0.6, -0.4, -0.2, 0.2, 0.4, 0.6, 0.8}) levels += fmt::format("{}{:.6g}", levels.empty() ? "" : ",", f * big);
    const std::string body = fmt::format(
        "set title 'Mode {} ({:.6g} rad/s): contour lines of w' noenhanced\nset xlabel 'x [m]'\nset ylabel 'y [m]'\n"
        "set view map\nset contour base\nunset surface\nset cntrparam levels discrete {}\nset size ratio -1\n"
        "set key outside right top noenhanced\nunset clabel\nsplot {}\n",
        i + 1, c.reference.frequencies_rad_s[i], levels, plots);
    if (auto svg = plot_script(ctx, name, body, data); !svg.empty())
      doc.figure("plots/" + name + ".svg", svg,
                 fmt::format("Mode {}: contour lines of w of every back-end (dashed, finest run, paired by MAC) over "
                             "the reference's (solid)",
                             i + 1));
  }
}

}  // namespace

void write_shapes(Doc& doc, const SceneComparison& c, Context& ctx, const std::string& sid) {
  if (c.reference.shapes.empty()) return;
  const auto runs = shaped_runs(c);
  doc.heading(3, "Mode shapes: MAC against the reference and the first modes overlaid");
  if (runs.empty()) {
    doc.para("No back-end run with shapes to compare.");
    return;
  }
  std::vector<std::vector<std::string>> rows;
  for (const RunRecord* r : runs) {
    std::vector<std::string> row = {run_label(*r)};
    for (std::size_t i = 0; i < std::min<std::size_t>(8, r->pair_mac.size()); ++i)
      row.push_back(std::isfinite(r->pair_mac[i]) ? fmt::format("{:.5f}{}", r->pair_mac[i], r->pair_mac[i] < kLowMac ? " LOW" : "")
                                                  : "—");
    rows.push_back(row);
  }
  std::vector<std::string> head = {"finest run"};
  for (std::size_t i = 0; i < std::min<std::size_t>(8, c.reference.frequencies_rad_s.size()); ++i)
    head.push_back(fmt::format("mode {}", i + 1));
  doc.table(head, rows);
  doc.para(fmt::format("MAC of each reference mode with the mode paired to it (pairs below {} are flagged LOW). "
                       "Shapes sampled at the same points by every back-end and mass-normalized in each back-end's "
                       "own model.",
                       kLowMac));
  mac_heat_maps(doc, c, ctx, sid, runs);
  if (c.scene.is_beam()) beam_overlays(doc, c, ctx, sid, runs);
  else plate_overlays(doc, c, ctx, sid, runs);
}

}  // namespace modalbench::report_detail
