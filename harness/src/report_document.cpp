#include "report_document.hpp"

#include <fmt/format.h>

#include <filesystem>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>

namespace modalbench::report_detail {

std::string display_path(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path rel = fs::relative(fs::path(path), fs::current_path(ec), ec);
  if (!ec && !rel.empty() && *rel.begin() != "..") return rel.generic_string();
  return fs::path(path).filename().string();
}

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
std::string secs_str(double t) { return std::isfinite(t) ? fmt::format("{:.3g}", t) : "—"; }

std::string model_error_str(const ModelLimit& lim) {
  if (!std::isfinite(lim.model_error)) return "—";
  const double u = lim.model_error_uncertainty;
  // An uncertainty beyond the value leaves no information in the value: said, not printed.
  if (std::isfinite(u) && u > lim.model_error) return fmt::format("not determined (± {:.2g} %)", 100 * u);
  std::string v = lim.model_error == 0 ? "0 %" : fmt::format("{:.2g} %", 100 * lim.model_error);
  if (std::isfinite(u) && u > 0) v += fmt::format(" ± {:.2g} %", 100 * u);
  return v;
}



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

std::string slug(const std::string& s) {
  std::string o;
  for (char c : s) o += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return o;
}

void Doc::heading(int level, const std::string& text, const std::string& id) {
  md += std::string(level, '#') + " " + text + "\n\n";
  html += fmt::format("<h{}{}>{}</h{}>\n", level, id.empty() ? "" : " id=\"" + id + "\"", esc(text), level);
}

void Doc::para(const std::string& text) {
  md += text + "\n\n";
  html += fmt::format("<p>{}</p>\n", esc(text));
}

void Doc::list(const std::vector<std::string>& items) {
  if (items.empty()) return;
  html += "<ul>";
  for (const auto& i : items) {
    md += "- " + i + "\n";
    html += fmt::format("<li>{}</li>", esc(i));
  }
  md += "\n";
  html += "</ul>\n";
}

void Doc::table(const std::vector<std::string>& head, const std::vector<std::vector<std::string>>& rows, std::size_t left) {
  if (rows.empty()) return;
  md += "|";
  html += "<table><tr>";
  for (std::size_t i = 0; i < head.size(); ++i) {
    md += fmt::format(" {} |", md_cell(head[i]));
    html += fmt::format("{}{}</th>", i < left ? "<th class=\"l\">" : "<th>", esc(head[i]));
  }
  md += "\n|";
  for (std::size_t i = 0; i < head.size(); ++i) md += i < left ? "---|" : "---:|";
  md += "\n";
  html += "</tr>\n";
  for (const auto& r : rows) {
    md += "|";
    html += "<tr>";
    for (std::size_t i = 0; i < r.size(); ++i) {
      md += fmt::format(" {} |", md_cell(r[i]));
      html += fmt::format("{}{}</td>", i < left ? "<td class=\"l\">" : "<td>", esc(r[i]));
    }
    md += "\n";
    html += "</tr>\n";
  }
  md += "\n";
  html += "</table>\n";
}

void Doc::figure(const std::string& svg_file, const std::string& svg, const std::string& caption) {
  md += fmt::format("![{}]({})\n\n", caption, svg_file);
  html += fmt::format(
      "<figure><img alt=\"{}\" src=\"data:image/svg+xml;base64,{}\"><figcaption>{}</figcaption></figure>\n",
      esc(caption), base64(svg), esc(caption));
}

void Doc::figure_html(const std::string& svg_file, const std::string& html_body, const std::string& caption) {
  md += fmt::format("![{}]({})\n\n", caption, svg_file);
  html += fmt::format("<figure>{}<figcaption>{}</figcaption></figure>\n", html_body, esc(caption));
}

std::string mac_table_html(const std::vector<std::vector<double>>& mac, const std::string& row_label,
                           const std::string& column_label) {
  // The palette of the SVG heat maps: white, #9ecae1 at 0.5, #3182bd at 0.9, #08306b at 1.
  const auto shade = [](double v) {
    struct Stop {
      double at, r, g, b;
    };
    static const Stop stops[] = {{0, 255, 255, 255}, {0.5, 158, 202, 225}, {0.9, 49, 130, 189}, {1, 8, 48, 107}};
    v = std::isfinite(v) ? std::clamp(v, 0.0, 1.0) : 0.0;
    std::size_t k = 1;
    while (k < 3 && v > stops[k].at) ++k;
    const Stop &a = stops[k - 1], &b = stops[k];
    const double t = (v - a.at) / (b.at - a.at);
    return fmt::format("#{:02x}{:02x}{:02x}", static_cast<int>(std::lround(a.r + t * (b.r - a.r))),
                       static_cast<int>(std::lround(a.g + t * (b.g - a.g))),
                       static_cast<int>(std::lround(a.b + t * (b.b - a.b))));
  };
  std::string h = fmt::format("<table class=\"mac\"><tr><th class=\"l\">{} \\ {}</th>", esc(row_label), esc(column_label));
  for (std::size_t j = 0; j < (mac.empty() ? 0 : mac[0].size()); ++j) h += fmt::format("<th>{}</th>", j + 1);
  h += "</tr>";
  for (std::size_t i = 0; i < mac.size(); ++i) {
    h += fmt::format("<tr><th>{}</th>", i + 1);
    for (double v : mac[i])
      h += fmt::format("<td style=\"background:{};color:{}\">{}</td>", shade(v), std::isfinite(v) && v > 0.6 ? "#fff" : "#000",
                       std::isfinite(v) ? fmt::format("{:.2f}", v) : "—");
    h += "</tr>";
  }
  return h + "</table>";
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

}  // namespace modalbench::report_detail
