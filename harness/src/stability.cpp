#include "modalbench/harness/stability.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
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

/// A steel Kirchhoff plate (E = 200 GPa, nu = 0.3, rho = 8000) of geometry {a, b, h} with its
/// edge supports {x0, xL, y0, yB}, modes only.
Scene base_plate(const std::string& name, const Geometry& g, const std::array<Support, 4>& edges) {
  Scene pl = base_beam(name, g.length, g.height, Theory::Kirchhoff);
  pl.kind = SceneKind::Plate;
  pl.geometry = g;
  pl.material.E = 2e11;
  pl.material.nu = 0.3;
  pl.material.G = pl.material.E / 2.6;
  pl.material.rho = 8000;
  pl.x0 = edges[0];
  pl.xL = edges[1];
  pl.y0 = edges[2];
  pl.yB = edges[3];
  pl.loads.clear();
  pl.request.probes.clear();
  return pl;
}

}  // namespace

std::vector<StabilityCase> stability_cases(bool quick) {
  std::vector<StabilityCase> cases;
  const std::vector<double> slender = {0.5, 1, 3, 10, 30, 100, 1e3, 1e4, 1e5};
  for (Theory th : {Theory::Timoshenko, Theory::EulerBernoulli})
    for (double s : pick(slender, quick)) {
      const double L = 1.0, h = L / s;
      const std::string theory = th == Theory::Timoshenko ? "Timoshenko" : "Euler-Bernoulli";
      cases.push_back({"slenderness", fmt::format("L/h = {:g}, {}, clamped-pinned", s, theory),
                       base_beam(fmt::format("slender-{:g}", s), L, h, th), false});
    }
  // Each end spring alone across 27 orders of magnitude, the other three at K = 1 (so that each
  // one matters), then all four together. K = k L^3 / EI (translational), k L / EI (rotational).
  const std::vector<double> stiff = {1e-12, 1e-9, 1e-6, 1e-3, 1, 1e3, 1e6, 1e9, 1e12, 1e15};
  auto spring_beam = [](const std::string& name, const std::array<double, 4>& K) {
    Scene sc = base_beam(name, 1.0, 0.01, Theory::EulerBernoulli);
    const double EI = sc.material.E * sc.section().Iy, L = sc.geometry.length;
    Support a, b;
    a.kind = b.kind = "springs";
    a.translational = K[0] * EI / (L * L * L);
    a.rotational = K[1] * EI / L;
    b.translational = K[2] * EI / (L * L * L);
    b.rotational = K[3] * EI / L;
    sc.x0 = a;
    sc.xL = b;
    sc.loads[0].x = 0.3 * L;
    sc.request.modes = 6;
    return sc;
  };
  const char* spring_name[4] = {"x0 translational", "x0 rotational", "xL translational", "xL rotational"};
  for (int which = 0; which < 4; ++which)
    for (double K : pick(stiff, quick)) {
      std::array<double, 4> k = {1, 1, 1, 1};
      k[static_cast<std::size_t>(which)] = K;
      cases.push_back({"springs", fmt::format("{} K = {:g}, the other three K = 1", spring_name[which], K),
                       spring_beam(fmt::format("spring-{}-{:g}", which, K), k), false});
    }
  for (double K : pick({1e-12, 1e-6, 1, 1e6, 1e15}, quick))
    cases.push_back({"springs", fmt::format("all four K = {:g}", K),
                     spring_beam(fmt::format("springs-{:g}", K), {K, K, K, K}), false});
  {
    Scene sc = base_beam("high-modes-beam", 1.0, 1e-3, Theory::EulerBernoulli);
    sc.x0 = sc.xL = Support::named("pinned");
    sc.request.modes = quick ? 30 : 1000;
    cases.push_back({"high-modes", fmt::format("L/h = 1000, pinned-pinned, {} modes", sc.request.modes), sc, false});
    const Support pinned = Support::named("pinned");
    Scene pl = base_plate("high-modes-plate", {1.0, 0.6, 0.03}, {pinned, pinned, pinned, pinned});
    pl.request.modes = quick ? 30 : 100;
    cases.push_back({"high-modes", fmt::format("paper plate, {} modes", pl.request.modes), pl, false});
  }
  // Plates without a support on some edges: free (three rigid-body modes) and cantilever
  // (NAFEMS FV12 and FV16 geometry, 10 x 10 x 0.05 m steel).
  for (bool free : {true, false}) {
    const Support none = Support::named("free");
    Scene pl = base_plate(free ? "free-plate" : "cantilever-plate", {10.0, 10.0, 0.05},
                          {free ? none : Support::named("clamped"), none, none, none});
    pl.request.modes = free ? 9 : 6;
    cases.push_back({"plates", free ? "free plate 10 x 10 x 0.05 m, 9 modes (3 rigid)"
                                    : "cantilever plate 10 x 10 x 0.05 m, 6 modes",
                     pl, false});
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
  if (!r.summary.mesh.empty() && r.summary.mesh != row.mesh) row.mesh += " → " + r.summary.mesh;  // refined
  row.status = r.summary.status;
  row.requested = c.scene.request.modes;
  row.returned = static_cast<int>(r.frequencies_rad_s.size());
  row.time_s = r.summary.total_time_s;
  row.max_error_vs_exact = kNaN;
  bool finite = true;
  for (double w : r.frequencies_rad_s) finite = finite && std::isfinite(w);
  for (const auto& d : r.deflections) finite = finite && std::isfinite(d.w) && std::isfinite(d.theta_y);
  const bool ordered = std::is_sorted(r.frequencies_rad_s.begin(), r.frequencies_rad_s.end());
  if (r.summary.status == Status::Unsupported || r.summary.status == Status::InvalidInput ||
      r.summary.status == Status::ResourceLimit) {
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
  // A success claims its numbers to its own error estimate (or, without one, to the tolerance):
  // beyond that, and beyond the exact reference's own accuracy, it is wrong without a flag.
  if (r.summary.status == Status::Success && r.summary.converges_to_scene_theory && std::isfinite(row.max_error_vs_exact)) {
    const double est = r.frequency_estimate();  // of the values reported (mesh or extrapolated)
    const double claimed = std::isfinite(est) ? est : c.scene.request.tolerance;
    if (row.max_error_vs_exact > claimed + 1e-9)
      bad.push_back(fmt::format("error {:.2g} against exact beyond its own {} {:.2g}", row.max_error_vs_exact,
                                std::isfinite(est) ? "estimate" : "tolerance", claimed));
  }
  if (r.summary.status != Status::Success) {
    row.verdict = Verdict::Flagged;
    row.detail = to_string(r.summary.status) + ": " + r.summary.message;
  } else if (!bad.empty()) {
    row.verdict = Verdict::UnflaggedBad;
    for (const auto& b : bad) row.detail += (row.detail.empty() ? "" : "; ") + b;
  } else if (const auto w = std::find_if(r.summary.warnings.begin(), r.summary.warnings.end(),
                                         [](const std::string& x) { return x.rfind("plausibility:", 0) != 0; });
             w != r.summary.warnings.end()) {
    // A plausibility warning says where the model stops describing the physics (a 1e5 slender
    // beam's rotations), not that a number is untrustworthy: it does not flag the run.
    row.verdict = Verdict::Flagged;
    row.detail = "warning: " + *w;
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
      // Only where the back-end's model is the scene's theory: elsewhere the difference from
      // exact is model error (the comparison report's business), not stability.
      const MeshFamily family = s->meshes(c.scene, Options{});
      if (!family.theory) continue;
      std::vector<Discretization> meshes = {*family.theory};
      if (c.stress_meshes) meshes = family.stress;
      for (const auto& m : meshes) {
        if (progress) *progress << fmt::format("[stability] {} | {} --mesh {} ...", c.label, s->name(), m.spec()) << std::flush;
        // With the back-end's own error estimate (a success must hold to it), except on the
        // largest meshes, where it would double the cost and robustness is what is asked.
        Options opts;
        opts.estimate_error = !c.stress_meshes;
        // On the back-end's default mesh, as a user without --mesh gets it: refined while its
        // estimate exceeds the tolerance (within five minutes a run: the free plate's dtfm strips
        // need 180 s to reach 1e-3).
        opts.refine_to_tolerance = !c.stress_meshes && m.spec() == family.default_mesh.spec();
        opts.max_time_s = 300;
        const Result r = s->solve(c.scene, m, opts);
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
  md += "A run is *ok* when it succeeded with the requested number of finite, ascending frequencies and no warning "
        "(plausibility warnings, on the model's physical range, aside); "
        "*flagged* when its status or warnings say it is not to be trusted; *refused* when the back-end declined the "
        "scene or mesh with a reason; *UNFLAGGED-BAD* when it claimed success but a number is non-finite, missing or "
        "out of order, or farther from the exact back-end than its own error estimate (this must never happen). The error "
        "column is against the exact back-end (all modes compared). Each back-end runs on the mesh where its model is the "
        "scene's theory (dtfm: one prism per beam); an Euler-Bernoulli back-end on a Timoshenko scene is model error, "
        "not stability, and is not run. Where that is the back-end's default mesh, the run is refined while its error "
        "estimate exceeds the tolerance, as `modalbench solve` without --mesh does (mesh column: default → kept).\n\n";
  std::string html = "<!doctype html><html><head><meta charset=\"utf-8\"><title>modalbench stability sweep</title><style>"
                     "body{font-family:Helvetica,Arial,sans-serif;max-width:80em;margin:1em auto}table{border-collapse:collapse}"
                     "td,th{border:1px solid #bbb;padding:2px 6px}td.n{text-align:right}.bad{background:#fbb}.flagged{background:#ffd}"
                     "</style></head><body><h1>modalbench stability sweep</h1>";
  html += fmt::format("<p>{} runs: {} ok, {} refused with a reason, {} flagged by their own diagnostics, <b>{} unflagged bad</b>.</p>",
                      rows.size(), tally[Verdict::Ok], tally[Verdict::Refused], tally[Verdict::Flagged], bad);
  // Per back-end: what a user of each can expect.
  std::map<std::string, std::map<Verdict, int>> per;
  for (const auto& r : rows) ++per[r.backend][r.verdict];
  md += "| back-end | runs | ok | flagged | refused | unflagged bad | flagged share |\n|---|---:|---:|---:|---:|---:|---:|\n";
  html += "<table><tr><th>back-end</th><th>runs</th><th>ok</th><th>flagged</th><th>refused</th><th>unflagged bad</th>"
          "<th>flagged share</th></tr>";
  for (const auto& [name, t] : per) {
    const int n = t.count(Verdict::Ok) ? t.at(Verdict::Ok) : 0, f = t.count(Verdict::Flagged) ? t.at(Verdict::Flagged) : 0,
              x = t.count(Verdict::Refused) ? t.at(Verdict::Refused) : 0,
              u = t.count(Verdict::UnflaggedBad) ? t.at(Verdict::UnflaggedBad) : 0;
    const int all = n + f + x + u;
    md += fmt::format("| {} | {} | {} | {} | {} | {} | {:.1f} % |\n", name, all, n, f, x, u, 100.0 * f / std::max(all, 1));
    html += fmt::format("<tr><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td>"
                        "<td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{:.1f} %</td></tr>",
                        name, all, n, f, x, u, 100.0 * f / std::max(all, 1));
  }
  html += "</table>";
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
