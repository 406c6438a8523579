// What each back-end's runs converge to (its model's limit), the runs' discretization errors
// against it, and each limit's model error against the best reference of the scene.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "modalbench/harness/comparison.hpp"

namespace modalbench {

namespace {

int first_modes(const Scene& s) { return std::min(6, std::max(s.request.modes, 1)); }

double median(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

/// The finest two runs with a mesh and an error of `q` above the rounding level: their observed
/// order (errors at rounding, e.g. the exact nodal statics of difference_eq, have none).
double order_from_errors(const std::vector<RunRecord*>& runs, Quantity q) {
  const double rounding = q == Quantity::Frf ? 1e-9 : 1e-11;  // dB for the FRF, relative otherwise
  const RunRecord* fine = nullptr;
  const RunRecord* coarse = nullptr;
  for (auto it = runs.rbegin(); it != runs.rend(); ++it) {
    const double e = (*it)->disc_error(q);
    if ((*it)->mesh.counts.empty() || !(e > rounding) || !std::isfinite(e)) continue;
    if (!fine) fine = *it;
    else if (!coarse) coarse = *it;
  }
  if (!fine || !coarse) return kNaN;
  return observed_order(mesh_h(coarse->mesh), coarse->disc_error(q), mesh_h(fine->mesh), fine->disc_error(q));
}

/// The deflections' limit of a ladder: each probe's w extrapolated by its grid convergence (the
/// finest run's value where it does not converge); returns the order of the largest w.
double deflection_limit(const std::vector<RunRecord*>& ok, std::vector<Deflection>& out) {
  const RunRecord& fine = *ok.back();
  out = fine.result.deflections;
  std::vector<double> h;
  for (const RunRecord* r : ok) h.push_back(mesh_h(r->mesh));
  double largest = -1, order = kNaN;
  for (std::size_t p = 0; p < out.size(); ++p) {
    std::vector<double> w;
    for (const RunRecord* r : ok)
      if (r->result.deflections.size() == out.size()) w.push_back(r->result.deflections[p].w);
    if (w.size() != ok.size()) continue;
    const GridConvergence g = grid_convergence(h, w);
    if (g.ok) out[p].w = g.value;
    if (std::abs(w.back()) > largest) {
      largest = std::abs(w.back());
      order = g.order;
    }
  }
  return order;
}

/// The limit of a back-end's own ladder: per mode (paired with the finest run's by family
/// order) and per probe, the grid convergence of the finest meshes.
void own_limit(const Scene& scene, const std::vector<RunRecord*>& ok, ModelLimit& lim) {
  const RunRecord& fine = *ok.back();
  std::vector<double> h;
  for (const RunRecord* r : ok) h.push_back(mesh_h(r->mesh));
  Reference& v = lim.values;
  v.source = lim.source = fmt::format("richardson({}, {} meshes)", lim.backend, ok.size());
  v.families = fine.result.mode_families;
  v.shapes = fine.result.mode_shapes;
  std::vector<std::vector<int>> match;
  for (const RunRecord* r : ok) match.push_back(match_modes(v.families, r->result.mode_families));
  std::vector<double> orders;
  double worst_gci = 0, factor = 1.25;
  bool complete = true;
  int counted = 0;
  for (std::size_t i = 0; i < v.families.size(); ++i) {
    const double f_fine = fine.result.frequencies_rad_s[i];
    if (v.families[i] == ModeFamily::Rigid) {
      v.frequencies_rad_s.push_back(0.0);
      v.frequency_uncertainty.push_back(0.0);
      continue;
    }
    std::vector<double> f;
    for (std::size_t k = 0; k < ok.size(); ++k)
      if (match[k][i] >= 0) f.push_back(ok[k]->result.frequencies_rad_s[static_cast<std::size_t>(match[k][i])]);
    const GridConvergence g = f.size() == ok.size() ? grid_convergence(h, f) : GridConvergence{};
    v.frequencies_rad_s.push_back(g.ok ? g.value : f_fine);
    v.frequency_uncertainty.push_back(g.ok ? g.gci * std::abs(f_fine) : kNaN);
    if (counted++ >= first_modes(scene)) continue;
    orders.push_back(g.order);
    if (!g.ok) {
      complete = false;
      if (lim.convergence_note.empty()) lim.convergence_note = fmt::format("mode {}: {}", i + 1, g.note.empty() ? "not paired on every mesh" : g.note);
      continue;
    }
    if (g.safety_factor > factor || lim.convergence_note.empty()) lim.convergence_note = g.note;
    factor = std::max(factor, g.safety_factor);
    worst_gci = std::max(worst_gci, g.gci);
  }
  lim.order[0] = median(orders);
  lim.gci = complete ? worst_gci : kNaN;
  lim.safety_factor = complete ? factor : kNaN;
  if (!fine.result.deflections.empty()) lim.order[1] = deflection_limit(ok, v.deflections);
}

/// Max relative difference of the limit from the best reference over the first modes of the
/// families the limit's model has (a bending-only model is not blamed for the torsion modes of a
/// 3D solid, nor any model for the solid's unlabelled in-plane modes).
void model_error(const Scene& scene, const Reference& best, double best_gci, ModelLimit& lim) {
  if (best.frequencies_rad_s.empty() || lim.values.frequencies_rad_s.empty()) return;
  const auto& fams = lim.values.families;
  const auto match = match_modes(best.families, fams);
  double worst = 0;
  int counted = 0;
  for (std::size_t i = 0; i < best.families.size() && counted < first_modes(scene); ++i) {
    const ModeFamily f = best.families[i];
    if (f == ModeFamily::Rigid || f == ModeFamily::Unknown || std::find(fams.begin(), fams.end(), f) == fams.end()) continue;
    if (match[i] < 0) break;  // the limit has fewer modes of this family than compared: stop there
    ++counted;
    worst = std::max(worst, relative_error(lim.values.frequencies_rad_s[static_cast<std::size_t>(match[i])],
                                           best.frequencies_rad_s[i]));
  }
  if (counted == 0) return;
  lim.model_error = worst;
  lim.model_error_uncertainty = lim.gci + best_gci;
}

}  // namespace

void analyse_limits(SceneComparison& c) {
  const Scene& scene = c.scene;
  // Group the runs by back-end and by whether they tend to the scene's theory.
  std::map<std::string, int> kinds;  // backend -> bit 1: scene theory, bit 2: own model
  for (const auto& r : c.runs) kinds[r.backend] |= r.result.summary.converges_to_scene_theory ? 1 : 2;
  c.limits.clear();
  std::map<std::string, std::vector<RunRecord*>> members;
  for (auto& r : c.runs) {
    const bool theory = r.result.summary.converges_to_scene_theory;
    std::string label = r.backend;
    if (kinds[r.backend] == 3) label += theory ? " (" + to_string(scene.theory) + ")" : " (own model)";
    r.limit = label;
    if (members.find(label) == members.end()) {
      ModelLimit lim;
      lim.label = label;
      lim.backend = r.backend;
      lim.scene_theory = theory;
      c.limits.push_back(lim);
    }
    members[label].push_back(&r);
  }
  const bool exact = c.reference.source == "exact";
  for (auto& lim : c.limits) {
    const auto& runs = members[lim.label];
    if (lim.scene_theory && exact) {
      lim.source = "exact";
      lim.values = c.reference;
      lim.gci = 0;
      for (RunRecord* r : runs) {
        r->disc_frequency_error = r->max_frequency_error;
        r->disc_deflection_error = r->deflection_error;
        r->disc_frf_error_db = r->frf_error_db;
      }
      // Statics the exact back-end does not give (e.g. a Levy plate): the ladder's own limit.
      std::vector<RunRecord*> ok;
      for (RunRecord* r : runs)
        if (!r->failed() && !r->mesh.counts.empty() && !r->result.deflections.empty()) ok.push_back(r);
      if (c.reference.deflections.empty() && ok.size() >= 3) {
        Reference defl;
        deflection_limit(ok, defl.deflections);
        for (RunRecord* r : runs) {
          RunRecord probe = *r;
          measure_errors(scene, defl, probe);
          r->disc_deflection_error = probe.deflection_error;
        }
      }
      for (Quantity q : kQuantities) lim.order[static_cast<int>(q)] = order_from_errors(runs, q);
      lim.convergence_note = c.reference.deflections.empty() && ok.size() >= 3
                                 ? "frequencies against the exact solution; deflections against the ladder's Richardson limit"
                                 : "limit known exactly: errors against the exact solution";
      continue;
    }
    std::vector<RunRecord*> ok;
    for (RunRecord* r : runs)
      if (!r->failed() && !r->mesh.counts.empty() && !r->result.frequencies_rad_s.empty()) ok.push_back(r);
    if (ok.size() < 3) {
      lim.source = fmt::format("none: {} successful mesh(es), three are needed for a Richardson limit", ok.size());
      continue;
    }
    own_limit(scene, ok, lim);
    for (RunRecord* r : runs) {
      RunRecord probe = *r;
      measure_errors(scene, lim.values, probe);
      r->disc_frequency_error = probe.max_frequency_error;
      r->disc_deflection_error = probe.deflection_error;
    }
  }
  // The best reference: 3D bricks extrapolated over their ladder when they converged, else the
  // scene's reference (the exact theory, or the best Richardson limit).
  c.best = c.reference;
  double best_gci = 0;
  c.best_label = c.reference.source == "exact" ? "exact " + to_string(scene.theory) + " theory" : c.reference.source;
  // A 3D limit only counts when it is itself known to better than 1 %.
  for (const auto& lim : c.limits)
    if (lim.backend == "calculix" && !std::isfinite(lim.gci))
      c.notes.push_back(fmt::format("the 3D bricks give no reference: {}", lim.source.rfind("none", 0) == 0 ? lim.source : lim.convergence_note));
    else if (lim.backend == "calculix" && lim.gci > 1e-2)
      c.notes.push_back(fmt::format("the 3D bricks give no reference: their Richardson limit is uncertain to {:.1e} "
                                    "(GCI; {}): model errors are against the exact theory",
                                    lim.gci, lim.convergence_note));
  for (const auto& lim : c.limits)
    if (lim.backend == "calculix" && std::isfinite(lim.gci) && lim.gci <= 1e-2) {
      c.best = lim.values;
      best_gci = lim.gci;
      c.best_label = fmt::format("3D elasticity: CalculiX C3D20R bricks, {} (GCI {:.1e}, safety factor {})", lim.source,
                                 lim.gci, lim.safety_factor);
    }
  if (c.reference.source != "exact" && c.best_label == c.reference.source)
    for (std::size_t i = 0; i < c.best.frequencies_rad_s.size() && i < 6; ++i)
      best_gci = std::max(best_gci, c.best.frequency_uncertainty[i] / std::abs(c.best.frequencies_rad_s[i]));
  for (auto& lim : c.limits) model_error(scene, c.best, best_gci, lim);
}

}  // namespace modalbench
