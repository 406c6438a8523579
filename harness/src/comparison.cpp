#include "modalbench/harness/comparison.hpp"

#include "modalbench/extrapolation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>

namespace modalbench {

namespace {

using clock_type = std::chrono::steady_clock;

/// The scene as the warm-up run solves it: with mode shapes (default sampling) for MAC pairing.
Scene with_shapes(const Scene& scene, const CompareOptions& opt) {
  Scene s = scene;
  // Frames: no mode shapes yet (modes are paired by order).
  if (opt.shapes && s.request.modes > 0 && !s.request.shapes && !s.is_frame()) {
    ShapeRequest sr;
    sr.nx = s.is_beam() ? ShapeRequest::kBeamDefaultNx : ShapeRequest::kPlateDefaultNx;
    sr.ny = s.is_beam() ? 1 : ShapeRequest::kPlateDefaultNy;
    s.request.shapes = sr;
  }
  return s;
}

/// The scene with only one quantity requested: what that quantity costs alone (shapes the scene
/// asks for belong to its modes; those the comparison adds for MAC pairing are not timed).
Scene only(const Scene& scene, Quantity q) {
  Scene s = scene;
  if (q != Quantity::Frequencies) s.request.shapes.reset();
  if (q != Quantity::Frequencies) s.request.modes = 0;
  if (q != Quantity::Deflections) s.request.probes.clear();
  if (q != Quantity::Frf) s.request.frf.reset();
  return s;
}

bool requested(const Scene& s, Quantity q) {
  return q == Quantity::Frequencies ? s.request.modes > 0 : q == Quantity::Deflections ? !s.request.probes.empty()
                                                                                       : s.request.frf.has_value();
}

/// Whether a result carries the quantity (a back-end may not compute one it was asked for).
bool produced(const Result& r, Quantity q) {
  return q == Quantity::Frequencies ? !r.frequencies_rad_s.empty() : q == Quantity::Deflections ? !r.deflections.empty()
                                                                                                : !r.frf.empty();
}

RunRecord timed_run(const Solver& s, const Scene& scene, const Discretization& mesh, const CompareOptions& opt) {
  RunRecord rec;
  rec.backend = s.name();
  rec.mesh = mesh;
  const auto now = [&] {
    return opt.clock ? opt.clock() : std::chrono::duration<double>(clock_type::now().time_since_epoch()).count();
  };
  const double start = now();
  // The ladder is the convergence study (Richardson over it, or the exact limit): each rung is one
  // solve on its mesh, without the solver's own coarse-mesh estimate.
  Options one_mesh;
  one_mesh.estimate_error = false;
  // The untimed warm-up solves the whole scene (with shapes when the comparison adds them); its
  // result is the one kept.
  rec.result = s.solve(with_shapes(scene, opt), mesh, one_mesh);
  rec.median_s = 0;
  for (Quantity q : kQuantities) {
    if (!requested(scene, q) || !produced(rec.result, q)) continue;
    const Scene alone = only(scene, q);
    std::vector<double> times;
    double spent = 0;
    while (true) {
      const double t0 = now();
      s.solve(alone, mesh, one_mesh);
      times.push_back(now() - t0);
      spent += times.back();
      const int n = static_cast<int>(times.size());
      if (opt.quick || rec.failed() || times.front() >= 1.0 || n >= opt.max_repeats || (n >= 3 && spent >= opt.min_timing_s))
        break;
    }
    std::sort(times.begin(), times.end());
    const double median = times[times.size() / 2];
    (q == Quantity::Frequencies ? rec.time_s.modes : q == Quantity::Deflections ? rec.time_s.statics : rec.time_s.frf) = median;
    rec.median_s += median;
    rec.repeats = std::max(rec.repeats, static_cast<int>(times.size()));
  }
  rec.spent_s = now() - start;
  return rec;
}

/// Richardson-extrapolated runs of one back-end's ladder (extrapolation.hpp), as a peer of its own:
/// "<back-end>+richardson", one per rung whose two predecessors are its coarser meshes (and the
/// third, where it is the next again), timed as those solves together (what `modalbench solve
/// --mesh` pays for the extrapolated values and their estimate). Made only
/// where the runs tend to the scene's theory (their error is then measured against the exact
/// solution, not against a limit of their own) and the back-end states the next order of its
/// expansion for the family.
std::vector<RunRecord> richardson_runs(const Solver& s, const Scene& scene, const std::vector<const RunRecord*>& runs) {
  std::vector<RunRecord> out;
  for (std::size_t k = 2; k < runs.size(); ++k) {
    const RunRecord &f = *runs[k], &c = *runs[k - 1], &cc = *runs[k - 2];
    if (f.failed() || c.failed() || cc.failed() || !f.result.summary.converges_to_scene_theory) continue;
    const MeshFamily family = s.meshes(scene, Options{});
    const std::optional<CoarserMesh> h = family.coarser_than(f.mesh);
    const std::optional<CoarserMesh> hh = family.coarser_than(c.mesh);
    if (!h || !hh || h->mesh.counts != c.mesh.counts || hh->mesh.counts != cc.mesh.counts) continue;
    // The rung below, where it is the next coarsening again, checks the extrapolated values' order.
    const std::optional<CoarserMesh> hhh = family.coarser_than(cc.mesh);
    const RunRecord* ccc =
        k >= 3 && hhh && hhh->mesh.counts == runs[k - 3]->mesh.counts && !runs[k - 3]->failed() ? runs[k - 3] : nullptr;
    const ExtrapolationMesh fourth{ccc ? &ccc->result : nullptr, hhh ? hhh->ratio : kNaN};
    const Extrapolation x = richardson_extrapolate(f.result, {&c.result, h->ratio}, {&cc.result, hh->ratio}, h->order,
                                                   h->next_order, f.result.summary.diagnostic("frequency_solve_error_bound"),
                                                   ccc ? &fourth : nullptr);
    if (x.frequencies_rad_s.empty() && x.deflections.empty()) continue;
    RunRecord rec = f;
    rec.backend = s.name() + "+richardson";
    rec.result.extrapolated = x;
    if (!x.frequencies_rad_s.empty()) {
      rec.result.frequencies_rad_s = x.frequencies_rad_s;
    } else {
      rec.result.frequencies_rad_s.clear();
      rec.result.mode_families.clear();
      rec.result.mode_shapes = ModeShapes{};
    }
    rec.result.deflections = x.deflections;  // none where they were not extrapolated
    // No FRF is extrapolated: the record carries none, so its FRF is neither timed nor compared.
    rec.result.frf.clear();
    rec.result.summary.method = x.note;
    rec.time_s = QuantityTimes{};
    rec.median_s = 0;
    for (Quantity q : {Quantity::Frequencies, Quantity::Deflections}) {
      const bool made = q == Quantity::Frequencies ? !x.frequencies_rad_s.empty() : !x.deflections.empty();
      if (!made) continue;
      const double t = f.time_s.of(q) + c.time_s.of(q) + cc.time_s.of(q) + (ccc ? ccc->time_s.of(q) : 0.0);
      (q == Quantity::Frequencies ? rec.time_s.modes : rec.time_s.statics) = t;
      if (std::isfinite(t)) rec.median_s += t;
    }
    rec.spent_s = 0;
    out.push_back(std::move(rec));
  }
  return out;
}

/// A Richardson reference from the finest three successful runs of one back-end.
std::optional<Reference> richardson_reference(const std::vector<RunRecord>& runs, const std::string& backend) {
  std::vector<const RunRecord*> ok;
  for (const auto& r : runs)
    if (r.backend == backend && !r.failed() && !r.result.frequencies_rad_s.empty() && !r.mesh.counts.empty())
      ok.push_back(&r);
  if (ok.size() < 3) return std::nullopt;
  const RunRecord& fine = *ok.back();
  Reference ref;
  ref.source = "richardson(" + backend + ")";
  ref.families = fine.result.mode_families;
  ref.shapes = fine.result.mode_shapes;
  const auto m1 = match_modes(ref.families, ok[ok.size() - 3]->result.mode_families);
  const auto m2 = match_modes(ref.families, ok[ok.size() - 2]->result.mode_families);
  const std::vector<double> h = {mesh_h(ok[ok.size() - 3]->mesh), mesh_h(ok[ok.size() - 2]->mesh), mesh_h(fine.mesh)};
  for (std::size_t i = 0; i < ref.families.size(); ++i) {
    const double f3 = fine.result.frequencies_rad_s[i];
    if (ref.families[i] == ModeFamily::Rigid || m1[i] < 0 || m2[i] < 0) {
      ref.frequencies_rad_s.push_back(f3);
      ref.frequency_uncertainty.push_back(ref.families[i] == ModeFamily::Rigid ? 0.0 : kNaN);
      continue;
    }
    const Richardson rr = richardson(h, {ok[ok.size() - 3]->result.frequencies_rad_s[m1[i]],
                                         ok[ok.size() - 2]->result.frequencies_rad_s[m2[i]], f3});
    ref.frequencies_rad_s.push_back(rr.value);
    ref.frequency_uncertainty.push_back(rr.ok ? rr.uncertainty : kNaN);
  }
  return ref;
}

}  // namespace

std::string to_string(Quantity q) {
  return q == Quantity::Frequencies ? "frequencies" : q == Quantity::Deflections ? "deflections" : "frf";
}

double mesh_h(const Discretization& d) {
  double prod = 1;
  for (int c : d.counts) prod *= c;
  return d.counts.empty() ? kNaN : std::pow(prod, -1.0 / static_cast<double>(d.counts.size()));
}

void measure_errors(const Scene& scene, const Reference& ref, RunRecord& run) {
  const Result& r = run.result;
  run.frequency_errors.assign(ref.frequencies_rad_s.size(), kNaN);
  run.max_frequency_error = kNaN;
  run.matched_by_order = std::none_of(r.mode_families.begin(), r.mode_families.end(), [](ModeFamily f) {
    return f != ModeFamily::Unknown && f != ModeFamily::Rigid;
  }) && !r.mode_families.empty();
  run.match.assign(ref.frequencies_rad_s.size(), -1);
  run.pair_mac.assign(ref.frequencies_rad_s.size(), kNaN);
  run.paired_by_mac = false;
  run.low_mac_pairs = 0;
  if (!ref.frequencies_rad_s.empty() && !r.frequencies_rad_s.empty()) {
    // Pair by MAC on the common sample points when both have shapes, else by family order.
    const bool shapes = !ref.shapes.empty() && !r.mode_shapes.empty() && ref.shapes.points == r.mode_shapes.points &&
                        ref.shapes.values.size() == ref.frequencies_rad_s.size() &&
                        r.mode_shapes.values.size() == r.frequencies_rad_s.size();
    std::vector<std::vector<double>> mac_m;
    if (shapes) {
      const Section sec = scene.section();
      mac_m = mac_matrix(ref.shapes, r.mode_shapes, scene.is_beam() ? std::sqrt(sec.Ip / sec.A) : 0.0);
    }
    run.paired_by_mac = shapes;
    run.match = shapes ? match_modes_by_mac(ref.families, r.mode_families, mac_m) : match_modes(ref.families, r.mode_families);
    const auto& match = run.match;
    if (shapes)
      for (std::size_t i = 0; i < match.size(); ++i)
        if (match[i] >= 0) run.pair_mac[i] = mac_m[i][static_cast<std::size_t>(match[i])];
    const int first = std::min<int>(6, std::max(scene.request.modes, 1));
    double worst = 0;
    int counted = 0;
    bool complete = true;
    for (std::size_t i = 0; i < ref.frequencies_rad_s.size(); ++i) {
      if (match[i] >= 0) run.frequency_errors[i] = relative_error(r.frequencies_rad_s[match[i]], ref.frequencies_rad_s[i]);
      if (ref.families[i] == ModeFamily::Rigid || counted >= first) continue;
      ++counted;
      if (run.pair_mac[i] < kLowMac) ++run.low_mac_pairs;
      if (std::isnan(run.frequency_errors[i])) complete = false;
      else worst = std::max(worst, run.frequency_errors[i]);
    }
    run.max_frequency_error = (complete && counted > 0) ? worst : kNaN;
  }
  run.deflection_error = kNaN;
  if (!ref.deflections.empty() && r.deflections.size() == ref.deflections.size()) {
    double scale = 0, worst = 0;
    // A frame sways: every translation counts (a beam's and a plate's errors are in w).
    const auto size = [&](const Deflection& d) {
      return scene.is_frame() ? std::max({std::abs(d.u), std::abs(d.v), std::abs(d.w)}) : std::abs(d.w);
    };
    const auto diff = [&](const Deflection& a, const Deflection& b) {
      return scene.is_frame() ? std::max({std::abs(a.u - b.u), std::abs(a.v - b.v), std::abs(a.w - b.w)}) : std::abs(a.w - b.w);
    };
    for (const auto& d : ref.deflections) scale = std::max(scale, size(d));
    for (std::size_t i = 0; i < ref.deflections.size(); ++i) worst = std::max(worst, diff(r.deflections[i], ref.deflections[i]));
    if (scale > 0) run.deflection_error = worst / scale;
  }
  run.frf_error_db = kNaN;
  if (!ref.frf.empty() && !r.frf.empty()) {
    std::vector<double> db;
    std::size_t j = 0;
    for (const auto& s : r.frf) {
      while (j < ref.frf.size() && ref.frf[j].omega_rad_s < s.omega_rad_s - 1e-9 * (1 + s.omega_rad_s)) ++j;
      if (j >= ref.frf.size()) break;
      if (std::abs(ref.frf[j].omega_rad_s - s.omega_rad_s) > 1e-9 * (1 + s.omega_rad_s)) continue;
      const double a = std::abs(s.receptance), b = std::abs(ref.frf[j].receptance);
      if (a > 0 && b > 0 && std::isfinite(a) && std::isfinite(b)) db.push_back(std::abs(20 * std::log10(a / b)));
    }
    if (!db.empty()) {
      std::nth_element(db.begin(), db.begin() + static_cast<long>(db.size() / 2), db.end());
      run.frf_error_db = db[db.size() / 2];
    }
  }
}

double time_to_accuracy(const SceneComparison& c, const std::string& label, double target, Quantity q) {
  double best = kNaN;
  for (const auto& r : c.runs)
    if ((r.limit == label || (r.limit.empty() && r.backend == label)) && !r.failed() && r.disc_error(q) <= target &&
        !(r.time_s.of(q) >= best))
      best = r.time_s.of(q);
  return best;
}

namespace {

/// The scene of the timed runs: the time history and the Campbell diagram are each back-end's
/// default solves of their own (transient_runs, rotor_runs), not part of the ladder's timings.
Scene timed_scene(const Scene& input, const Registry& registry, const CompareOptions& opt, SceneComparison& c) {
  // The time history is not compared (yet): its timed runs would charge it to the modes.
  Scene scene = input;
  c.transients = transient_runs(input, registry, opt);
  c.transient = input.request.transient;
  if (scene.request.transient) {
    scene.request.transient.reset();
    c.notes.push_back("the scene's time history ([request.transient]) is not in the timed runs: each back-end's "
                      "default solve of it is shown in its own section");
  }
  c.rotor_runs = rotor_runs(input, registry, opt);
  c.rotor = input.rotor;
  if (scene.rotor) {
    scene.rotor.reset();
    c.notes.push_back("the scene's Campbell diagram ([rotor]) is not in the timed runs (they time the shaft at "
                      "rest): each back-end's default solve of it is shown in its own section");
  }
  return scene;
}

/// One back-end over its mesh ladder, within the time budget (each rung predicted from the last),
/// and its extrapolated peers.
void ladder_runs(const Solver& s, const Scene& scene, const CompareOptions& opt, SceneComparison& c) {
  std::vector<Discretization> ladder = s.meshes(scene, Options{}).ladder;
  if (opt.quick && ladder.size() > 3) ladder.resize(3);
  double spent = 0, last_time = 0, last_spent = 0, growth = 2.0;
  for (std::size_t k = 0; k < ladder.size(); ++k) {
    if (k > 0 && spent + last_spent * growth > opt.budget_s) {
      c.notes.push_back(fmt::format("{}: ladder stopped before mesh {} (time budget {:.0f} s per back-end)", s.name(),
                                    ladder[k].spec(), opt.budget_s));
      if (opt.progress)
        *opt.progress << fmt::format("[{}] {}: ladder stopped before mesh {} (time budget {:.0f} s)\n", scene.name,
                                     s.name(), ladder[k].spec(), opt.budget_s);
      break;
    }
    if (opt.progress) *opt.progress << fmt::format("[{}] {} --mesh {} ...", scene.name, s.name(), ladder[k].spec()) << std::flush;
    RunRecord rec = timed_run(s, scene, ladder[k], opt);
    spent += rec.spent_s;
    if (last_time > 0 && rec.median_s > 0) growth = std::clamp(rec.median_s / last_time, 1.5, 16.0);
    last_time = rec.median_s;
    last_spent = rec.spent_s;
    if (opt.progress)
      *opt.progress << fmt::format(" {} in {:.3g} s (x{})\n", to_string(rec.result.summary.status), rec.median_s,
                                   rec.repeats);
    c.runs.push_back(std::move(rec));
  }
  std::vector<const RunRecord*> own;
  for (const auto& r : c.runs)
    if (r.backend == s.name()) own.push_back(&r);
  for (auto& rec : richardson_runs(s, scene, own)) c.runs.push_back(std::move(rec));
}

/// The exact back-end's results as the reference, where it succeeded, with its deflection line
/// on a fine grid for the plots.
void exact_reference(const Scene& scene, const Registry& registry, SceneComparison& c) {
  for (const auto& r : c.runs) {
    if (r.backend != "exact") continue;
    const Result& x = r.result;
    if (!x.frequencies_rad_s.empty() && x.summary.status == Status::Success) {
      c.reference.source = "exact";
      c.reference.frequencies_rad_s = x.frequencies_rad_s;
      c.reference.families = x.mode_families;
      c.reference.frequency_uncertainty.assign(x.frequencies_rad_s.size(), 0.0);
      c.reference.shapes = x.mode_shapes;
    }
    if (x.summary.status == Status::Success) {
      c.reference.deflections = x.deflections;
      c.reference.frf = x.frf;
    }
  }
  if (c.reference.source == "exact" && scene.is_beam() && !scene.loads.empty() && !c.reference.deflections.empty()) {
    Scene fine = scene;
    fine.request.modes = 0;
    fine.request.frf.reset();
    fine.request.probes.clear();
    for (int i = 0; i <= 100; ++i) fine.request.probes.push_back({scene.geometry.length * i / 100.0, 0.0});
    const Result line = registry.get("exact").solve(fine, {}, Options{});
    if (line.ok()) c.reference.deflection_line = line.deflections;
  }
}

/// Without an exact solution: the back-end whose Richardson limit is the most certain, or none.
void best_richardson_reference(const Registry& registry, SceneComparison& c) {
  std::optional<Reference> best;
  double best_unc = std::numeric_limits<double>::infinity();
  for (const Solver* s : registry.all()) {
    auto ref = richardson_reference(c.runs, s->name());
    if (!ref) continue;
    double worst = 0;
    for (std::size_t i = 0; i < ref->frequencies_rad_s.size() && i < 6; ++i)
      worst = std::max(worst, ref->frequency_uncertainty[i] / ref->frequencies_rad_s[i]);
    if (std::isfinite(worst) && worst < best_unc) {
      best_unc = worst;
      best = std::move(ref);
    }
  }
  if (best) {
    c.notes.push_back(fmt::format("no exact solution: errors are against {} (relative uncertainty up to {:.1e})",
                                  best->source, best_unc));
    best->deflections = c.reference.deflections;
    best->frf = c.reference.frf;
    c.reference = std::move(*best);
  } else {
    c.reference.source = "none";
    c.notes.push_back("no exact solution and no back-end converged well enough for a Richardson estimate: errors not measured");
  }
}

}  // namespace

std::vector<SceneComparison> run_comparison(const std::vector<Scene>& scenes, const Registry& registry,
                                            const CompareOptions& opt) {
  std::vector<SceneComparison> out;
  for (const Scene& input : scenes) {
    SceneComparison c;
    const Scene scene = timed_scene(input, registry, opt, c);
    c.scene = scene;
    for (const Solver* s : registry.all()) {
      const Capability cap = s->supports(scene);
      if (!cap.any()) {
        c.notes.push_back(fmt::format("{}: not run ({})", s->name(), cap.reason));
        if (opt.progress) *opt.progress << fmt::format("[{}] {}: skipped ({})\n", scene.name, s->name(), cap.reason);
        continue;
      }
      ladder_runs(*s, scene, opt, c);
    }
    for (const auto& extra : opt.extra_references)
      for (auto& rec : extra(scene, opt.progress)) c.runs.push_back(std::move(rec));
    // The reference: the exact back-end where it succeeded, else Richardson.
    exact_reference(scene, registry, c);
    if (c.reference.frequencies_rad_s.empty()) best_richardson_reference(registry, c);
    // The extrapolated peers are judged against the exact solution only: without one (a free plate)
    // their limit would be a Richardson limit of their own, of two or three rungs.
    if (c.reference.source != "exact") {
      const auto is_peer = [](const RunRecord& r) { return r.backend.ends_with("+richardson"); };
      if (std::any_of(c.runs.begin(), c.runs.end(), is_peer)) {
        c.runs.erase(std::remove_if(c.runs.begin(), c.runs.end(), is_peer), c.runs.end());
        c.notes.push_back("no exact solution: the extrapolated (+richardson) peers are not shown");
      }
    }
    for (auto& r : c.runs) measure_errors(scene, c.reference, r);
    analyse_limits(c);
    out.push_back(std::move(c));
  }
  return out;
}

std::vector<std::string> scene_files(const std::string& dir) {
  std::vector<std::string> files;
  if (!std::filesystem::is_directory(dir)) throw InputError(dir, "", "scene directory not found");
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == ".toml") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace modalbench
