#include "modalbench/harness/stability.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "modalbench/harness/comparison.hpp"
#include "modalbench/harness/files.hpp"

namespace modalbench {

std::string to_string(Verdict v) {
  switch (v) {
    case Verdict::Ok: return "ok";
    case Verdict::Refused: return "refused";
    case Verdict::Flagged: return "flagged";
    case Verdict::UnflaggedBad: return "UNFLAGGED-BAD";
  }
  return "?";
}

namespace {

Scene base_beam(const std::string& name, double L, double h, Theory theory) {
  Scene s;
  s.name = name;
  s.source = "stability sweep";
  s.kind = SceneKind::Beam;
  s.physics = Physics::Bending;
  s.theory = theory;
  s.geometry = {L, h, h};
  s.material.E = 2e11;
  s.material.nu = 0.3;
  s.material.G = s.material.E / (2 * 1.3);
  s.material.rho = 7850;
  s.material.kappa = 5.0 / 6.0;
  s.x0 = Support::named("clamped");
  s.xL = Support::named("pinned");
  PointLoad p;
  p.x = 0.5 * L;
  p.Fz = -1.0;
  s.loads = {p};
  s.request.modes = 10;
  s.request.probes = {{0.25 * L, 0}, {0.5 * L, 0}, {0.75 * L, 0}};
  return s;
}

std::vector<double> pick(const std::vector<double>& all, bool quick) {
  if (!quick) return all;
  return {all.front(), all[all.size() / 2], all.back()};
}

}  // namespace

std::vector<StabilityCase> stability_cases(bool quick) {
  std::vector<StabilityCase> cases;
  for (double s : pick({1, 3, 10, 30, 100, 1e3, 1e4}, quick)) {
    const double L = 1.0, h = L / s;
    cases.push_back({"slenderness", fmt::format("L/h = {:g}, Timoshenko, clamped-pinned", s),
                     base_beam(fmt::format("slender-{:g}", s), L, h, Theory::Timoshenko), false});
  }
  for (double K : pick({1e-6, 1e-3, 1, 1e3, 1e6, 1e9, 1e12}, quick)) {
    Scene sc = base_beam(fmt::format("springs-{:g}", K), 1.0, 0.01, Theory::EulerBernoulli);
    const double EI = sc.material.E * sc.section().Iy, L = sc.geometry.length;
    Support sp;
    sp.kind = "springs";
    sp.translational = K * EI / (L * L * L);
    sp.rotational = K * EI / L;
    sc.x0 = sc.xL = sp;
    sc.loads[0].x = 0.3 * L;
    sc.request.modes = 6;
    cases.push_back({"springs", fmt::format("K = kL^3/EI = Kr = krL/EI = {:g} at both ends", K), sc, false});
  }
  {
    Scene sc = base_beam("high-modes-beam", 1.0, 1e-3, Theory::EulerBernoulli);
    sc.x0 = sc.xL = Support::named("pinned");
    sc.request.modes = quick ? 30 : 100;
    cases.push_back({"high-modes", fmt::format("L/h = 1000, pinned-pinned, {} modes", sc.request.modes), sc, false});
    Scene pl = base_beam("high-modes-plate", 1.0, 0.03, Theory::Kirchhoff);
    pl.kind = SceneKind::Plate;
    pl.geometry = {1.0, 0.6, 0.03};
    pl.material.E = 2e11;
    pl.material.nu = 0.3;
    pl.material.G = pl.material.E / 2.6;
    pl.material.rho = 8000;
    pl.x0 = pl.xL = pl.y0 = pl.yB = Support::named("pinned");
    pl.loads.clear();
    pl.request.probes.clear();
    pl.request.modes = quick ? 30 : 100;
    cases.push_back({"high-modes", fmt::format("paper plate, {} modes", pl.request.modes), pl, false});
  }
  {
    Scene sc = base_beam("size-beam", 1.0, 0.01, Theory::EulerBernoulli);
    sc.request.modes = 10;
    cases.push_back({"size", "slender beam, each back-end's largest meshes", sc, true});
  }
  return cases;
}

StabilityRow judge(const StabilityCase& c, const std::string& backend, const Discretization& mesh, const Result& r,
                   const Result* exact) {
  StabilityRow row;
  row.group = c.group;
  row.label = c.label;
  row.backend = backend;
  row.mesh = mesh.spec();
  row.status = r.summary.status;
  row.requested = c.scene.request.modes;
  row.returned = static_cast<int>(r.frequencies_rad_s.size());
  row.time_s = r.summary.total_time_s;
  row.max_error_vs_exact = kNaN;
  bool finite = true;
  for (double w : r.frequencies_rad_s) finite = finite && std::isfinite(w);
  for (const auto& d : r.deflections) finite = finite && std::isfinite(d.w) && std::isfinite(d.theta_y);
  const bool ordered = std::is_sorted(r.frequencies_rad_s.begin(), r.frequencies_rad_s.end());
  if (r.summary.status == Status::Unsupported || r.summary.status == Status::InvalidInput) {
    row.verdict = Verdict::Refused;
    row.detail = r.summary.message;
    return row;
  }
  std::vector<std::string> bad;
  if (!finite) bad.push_back("non-finite value");
  if (!ordered) bad.push_back("frequencies not ascending");
  if (row.returned != row.requested) bad.push_back(fmt::format("{} of {} frequencies", row.returned, row.requested));
  if (exact && exact->ok() && !exact->frequencies_rad_s.empty()) {
    RunRecord rec;
    rec.result = r;
    Reference ref;
    ref.source = "exact";
    ref.frequencies_rad_s = exact->frequencies_rad_s;
    ref.families = exact->mode_families;
    ref.frequency_uncertainty.assign(ref.frequencies_rad_s.size(), 0.0);
    measure_errors(c.scene, ref, rec);
    double worst = 0;
    bool any = false;
    for (double e : rec.frequency_errors)
      if (std::isfinite(e)) {
        worst = std::max(worst, e);
        any = true;
      }
    if (any) row.max_error_vs_exact = worst;
  }
  if (r.summary.status != Status::Success) {
    row.verdict = Verdict::Flagged;
    row.detail = to_string(r.summary.status) + ": " + r.summary.message;
  } else if (!bad.empty()) {
    row.verdict = Verdict::UnflaggedBad;
    for (const auto& b : bad) row.detail += (row.detail.empty() ? "" : "; ") + b;
  } else if (!r.summary.warnings.empty()) {
    row.verdict = Verdict::Flagged;
    row.detail = "warning: " + r.summary.warnings.front();
  } else {
    row.verdict = Verdict::Ok;
  }
  return row;
}

std::vector<StabilityRow> run_stability(const std::vector<StabilityCase>& cases, const Registry& registry,
                                        std::ostream* progress) {
  std::vector<StabilityRow> rows;
  const Solver* exact = nullptr;
  for (const Solver* s : registry.all())
    if (s->name() == "exact") exact = s;
  for (const auto& c : cases) {
    std::optional<Result> ex;
    if (exact) {
      ex = exact->solve(c.scene, {}, Options{});
      StabilityRow row = judge(c, "exact", {}, *ex, nullptr);
      rows.push_back(row);
    }
    for (const Solver* s : registry.all()) {
      if (s == exact) continue;
      std::vector<Discretization> meshes = {s->default_mesh(c.scene)};
      if (c.stress_meshes) meshes = s->stress_meshes(c.scene);
      for (const auto& m : meshes) {
        if (progress) *progress << fmt::format("[stability] {} | {} --mesh {} ...", c.label, s->name(), m.spec()) << std::flush;
        // Robustness, not the tolerance: each run is judged against exact below, so the solver's
        // own coarse-mesh estimate is not made (it would double the largest meshes' cost).
        Options one_mesh;
        one_mesh.estimate_error = false;
        const Result r = s->solve(c.scene, m, one_mesh);
        StabilityRow row = judge(c, s->name(), m, r, ex ? &*ex : nullptr);
        if (progress) *progress << fmt::format(" {} ({:.3g} s)\n", to_string(row.verdict), row.time_s);
        rows.push_back(std::move(row));
      }
    }
  }
  return rows;
}

int write_stability_report(const std::vector<StabilityRow>& rows, const std::string& dir) {
  make_output_dir(dir);
  std::map<Verdict, int> tally;
  for (const auto& r : rows) ++tally[r.verdict];
  const int bad = tally[Verdict::UnflaggedBad];
  std::string md = "# modalbench stability sweep\n\n";
  md += fmt::format("{} runs: {} ok, {} refused with a reason, {} flagged by their own diagnostics, {} unflagged bad.\n\n",
                    rows.size(), tally[Verdict::Ok], tally[Verdict::Refused], tally[Verdict::Flagged], bad);
  md += "A run is *ok* when it succeeded with the requested number of finite, ascending frequencies and no warning; "
        "*flagged* when its status or warnings say it is not to be trusted; *refused* when the back-end declined the "
        "scene or mesh with a reason; *UNFLAGGED-BAD* when it claimed success but a number is non-finite, missing or "
        "out of order (this must never happen). The error column is against the exact back-end (all modes compared).\n\n";
  std::string html = "<!doctype html><html><head><meta charset=\"utf-8\"><title>modalbench stability sweep</title><style>"
                     "body{font-family:Helvetica,Arial,sans-serif;max-width:80em;margin:1em auto}table{border-collapse:collapse}"
                     "td,th{border:1px solid #bbb;padding:2px 6px}td.n{text-align:right}.bad{background:#fbb}.flagged{background:#ffd}"
                     "</style></head><body><h1>modalbench stability sweep</h1>";
  html += fmt::format("<p>{} runs: {} ok, {} refused with a reason, {} flagged by their own diagnostics, <b>{} unflagged bad</b>.</p>",
                      rows.size(), tally[Verdict::Ok], tally[Verdict::Refused], tally[Verdict::Flagged], bad);
  std::string csv = "group,case,backend,mesh,verdict,status,requested,returned,max_error_vs_exact,time_s,detail\n";
  std::string group;
  for (const auto& r : rows) {
    if (r.group != group) {
      if (!group.empty()) html += "</table>";
      group = r.group;
      md += fmt::format("\n## {}\n\n| case | back-end | mesh | verdict | modes | error vs exact | time [s] | detail |\n|---|---|---|---|---:|---:|---:|---|\n", group);
      html += fmt::format("<h2>{}</h2><table><tr><th>case</th><th>back-end</th><th>mesh</th><th>verdict</th><th>modes</th>"
                          "<th>error vs exact</th><th>time [s]</th><th>detail</th></tr>", group);
    }
    const std::string err = std::isfinite(r.max_error_vs_exact) ? fmt::format("{:.2e}", r.max_error_vs_exact) : "—";
    std::string detail = r.detail.substr(0, 200);
    std::replace(detail.begin(), detail.end(), '|', '/');
    std::replace(detail.begin(), detail.end(), '\n', ' ');
    md += fmt::format("| {} | {} | {} | {} | {}/{} | {} | {:.3g} | {} |\n", r.label, r.backend, r.mesh, to_string(r.verdict),
                      r.returned, r.requested, err, r.time_s, detail);
    const char* cls = r.verdict == Verdict::UnflaggedBad ? " class=\"bad\"" : r.verdict == Verdict::Flagged ? " class=\"flagged\"" : "";
    html += fmt::format("<tr{}><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td class=\"n\">{}/{}</td><td class=\"n\">{}</td>"
                        "<td class=\"n\">{:.3g}</td><td>{}</td></tr>",
                        cls, r.label, r.backend, r.mesh, to_string(r.verdict), r.returned, r.requested, err, r.time_s, detail);
    std::string cdetail = detail;
    std::replace(cdetail.begin(), cdetail.end(), ',', ';');
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", r.group, r.label, r.backend, r.mesh, to_string(r.verdict),
                       to_string(r.status), r.requested, r.returned, r.max_error_vs_exact, r.time_s, cdetail);
  }
  html += "</table></body></html>\n";
  const std::filesystem::path d(dir);
  write_text_file((d / "stability.csv").string(), csv);
  write_text_file((d / "stability.md").string(), md);
  write_text_file((d / "stability.html").string(), html);
  return bad;
}

}  // namespace modalbench
