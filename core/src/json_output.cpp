#include "modalbench/json_output.hpp"

#include <cmath>

namespace modalbench {

namespace {
// JSON has no Inf/NaN: such a value becomes null (and the summary already flags it).
nlohmann::json num(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

/// [rotor]'s Campbell diagram: per spin its whirl frequencies, senses and growth rates; the criticals.
nlohmann::json campbell_json(const Campbell& c) {
  using nlohmann::json;
  json points = json::array();
  for (const CampbellPoint& p : c.points) {
    json f = json::array(), w = json::array(), g = json::array();
    for (double v : p.frequencies_rad_s) f.push_back(num(v));
    for (Whirl x : p.whirl) w.push_back(to_string(x));
    for (double v : p.growth_rates_1_s) g.push_back(num(v));
    json point = {{"spin_rad_s", num(p.spin_rad_s)}, {"frequencies_rad_s", f}, {"whirl", w}, {"growth_rate_1_s", g}};
    if (!p.orbits.empty()) {
      json orbits = json::array();
      for (const Orbit& o : p.orbits) {
        json v = json::array(), wz = json::array();
        for (const auto& z : o.v) v.push_back({num(z.real()), num(z.imag())});
        for (const auto& z : o.w) wz.push_back({num(z.real()), num(z.imag())});
        orbits.push_back({{"v", v}, {"w", wz}});
      }
      point["orbits"] = orbits;
    }
    points.push_back(point);
  }
  json fw = json::array(), bw = json::array(), un = json::array();
  for (double v : c.forward_criticals) fw.push_back(num(v));
  for (double v : c.backward_criticals) bw.push_back(num(v));
  for (double v : c.unstable_spins) un.push_back(num(v));
  return {{"frame", c.frame},
          {"points", points},
          {"critical_speeds", {{"forward", fw}, {"backward", bw}, {"note", c.criticals_note}}},
          {"unstable_spins_rad_s", un},
          {"max_backward_error", num(c.max_backward_error)},
          {"orbit_points_m", c.orbit_points_m},
          {"orbit_note", c.orbit_note},
          {"units", "rad/s (spin, frequencies, critical speeds), 1/s (growth rates); orbits: [re, im] of v and w "
                    "at orbit_points_m, normalized"},
          {"note", c.note}};
}

/// request.transient's histories: per probe its position, each component's history, and the peak of w.
nlohmann::json transient_json(const Scene& scene, const Transient& tr) {
  using nlohmann::json;
  json probes = json::array();
  for (std::size_t p = 0; p < tr.values.size(); ++p) {
    const auto& at = scene.request.probes[p];
    json e;
    e["position"] = scene.is_beam() ? json::array({at[0]}) : json::array({at[0], at[1]});
    for (std::size_t c = 0; c < tr.components.size(); ++c) {
      json h = json::array();
      for (double v : tr.values[p][c]) h.push_back(num(v));
      e[component_name(tr.components[c])] = h;
    }
    e["peak"] = {{"w", num(tr.peaks[p].w)}, {"time_s", num(tr.peaks[p].time_s)}};
    if (p < tr.moments.size()) {
      json h = json::array();
      for (double v : tr.moments[p]) h.push_back(num(v));
      e["My"] = h;
      e["moment_peak"] = {{"My", num(tr.moment_peaks[p].w)}, {"time_s", num(tr.moment_peaks[p].time_s)}};
    }
    probes.push_back(e);
  }
  json out = {{"time_s", tr.time_s},
          {"probes", probes},
          {"units", "m (u, v, w), rad (theta_x, theta_y, theta_z), N m (My), s"},
          {"modes_used", tr.modes_used},
          {"rigid_modes", tr.rigid_modes},
          {"static_correction", tr.static_correction},
          {"error_estimate", num(tr.error_estimate)},
          {"load", tr.load},
          {"note", tr.note}};
  if (!tr.moments.empty()) out["moment_error_estimate"] = num(tr.moment_error_estimate);
  return out;
}

/// Stress resultants (result.hpp, InternalForces) in the components the scene carries.
nlohmann::json forces_json(const Scene& scene, const InternalForces& f) {
  nlohmann::json e;
  if (scene.is_plate()) {
    e["mx_N_m_per_m"] = num(f.mx);
    e["my_N_m_per_m"] = num(f.my);
    e["mxy_N_m_per_m"] = num(f.mxy);
    return e;
  }
  if (scene.is_frame()) e["axes"] = "member";  // a member's resultants, in its own axes
  e["My_N_m"] = num(f.My);
  e["Qz_N"] = num(f.Qz);
  if (carries_axial(scene.physics)) e["N_N"] = num(f.N);
  if (carries_xy(scene.physics)) {
    e["Mz_N_m"] = num(f.Mz);
    e["Qy_N"] = num(f.Qy);
  }
  if (carries_torsion(scene.physics)) e["T_N_m"] = num(f.T);
  return e;
}

/// One probe's deflection, in the components the scene carries (also for the extrapolated ones).
nlohmann::json deflection_json(const Scene& scene, const Deflection& d) {
  using nlohmann::json;
  json e;
  if (scene.is_frame()) {
    e["probe"] = d.probe;
    e["position"] = json::array({d.point[0], d.point[1], d.point[2]});
    e["u"] = num(d.u);
    e["w"] = num(d.w);
    e["theta_y"] = num(d.theta_y);
    if (carries_xy(scene.physics)) {
      e["v"] = num(d.v);
      e["theta_x"] = num(d.theta_x);
      e["theta_z"] = num(d.theta_z);
    }
  } else if (scene.is_beam()) {
    e["position"] = json::array({d.position[0]});
    e["w"] = num(d.w);
    e["rotation"] = num(d.theta_y);
    if (carries_axial(scene.physics)) e["u"] = num(d.u);
    if (carries_xy(scene.physics)) {
      e["v"] = num(d.v);
      e["theta_z"] = num(d.theta_z);
    }
    if (carries_torsion(scene.physics)) e["theta_x"] = num(d.theta_x);
  } else {
    e["position"] = json::array({d.position[0], d.position[1]});
    e["w"] = num(d.w);
    e["rotation"] = json::array({num(d.theta_x), num(d.theta_y)});
  }
  if (d.has_forces) e["forces"] = forces_json(scene, d.forces);
  return e;
}

nlohmann::json deflections_json(const Scene& scene, const std::vector<Deflection>& ds) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& d : ds) out.push_back(deflection_json(scene, d));
  return out;
}

nlohmann::json reactions_json(const Scene& scene, const std::vector<Reaction>& rs) {
  using nlohmann::json;
  json out = json::array();
  for (const Reaction& rc : rs)
    out.push_back({{"support", rc.support},
                   {"position", scene.is_frame()  ? json::array({rc.point[0], rc.point[1], rc.point[2]})
                                : scene.is_beam() ? json::array({rc.position[0]})
                                                  : json::array({rc.position[0], rc.position[1]})},
                   {"force_N", {num(rc.force[0]), num(rc.force[1]), num(rc.force[2])}},
                   {"moment_N_m", {num(rc.moment[0]), num(rc.moment[1]), num(rc.moment[2])}}});
  return out;
}

/// The modal quantities of the shapes: generalized masses, participations and effective masses
/// per direction the model carries.
nlohmann::json modal_json(const ModeShapes& ms) {
  using nlohmann::json;
  json modal;
  modal["generalized_mass_kg"] = ms.generalized_mass;
  json part = json::object(), eff = json::object(), sum = json::object();
  static const char* dir[] = {"x", "y", "z"};
  for (int d = 0; d < 3; ++d) {
    if (!ms.directions[d]) continue;
    json p = json::array(), e = json::array();
    double total = 0;
    for (std::size_t k = 0; k < ms.values.size(); ++k) {
      p.push_back(num(ms.participation[k][d]));
      e.push_back(num(ms.effective_mass[k][d]));
      total += ms.effective_mass[k][d];
    }
    part[dir[d]] = p;
    eff[dir[d]] = e;
    sum[dir[d]] = num(total);
  }
  modal["participation_sqrt_kg"] = part;
  modal["effective_mass_kg"] = eff;
  modal["effective_mass_sum_kg"] = sum;
  modal["total_mass_kg"] = num(ms.total_mass);
  return modal;
}

nlohmann::json mode_shapes_json(const Scene& scene, const ModeShapes& ms) {
  using nlohmann::json;
  json shapes;
  json pts = json::array();
  for (const auto& p : ms.points) pts.push_back(scene.is_beam() ? json::array({p[0]}) : json::array({p[0], p[1]}));
  shapes["points"] = pts;
  shapes["normalization"] = ms.normalization;
  shapes["note"] = ms.note;
  for (std::size_t c = 0; c < ms.components.size(); ++c) {
    json per_mode = json::array();
    for (const auto& mode : ms.values) {
      json v = json::array();
      for (double x : mode[c]) v.push_back(num(x));
      per_mode.push_back(v);
    }
    shapes[component_name(ms.components[c])] = per_mode;
  }
  shapes["modal"] = modal_json(ms);
  return shapes;
}

nlohmann::json error_estimate_json(const ErrorEstimate& ee) {
  return {{"frequencies", num(ee.frequencies)},
          {"deflections", num(ee.deflections)},
          {"frequencies_solve", num(ee.frequencies_solve)},
          {"campbell", num(ee.campbell)},
          {"tolerance", num(ee.tolerance)},
          {"coarse_mesh", ee.coarse_mesh},
          {"coarser_mesh", ee.coarser_mesh},
          {"ratio", num(ee.ratio)},
          {"order", num(ee.order)},
          {"safety_factor", num(ee.safety_factor)},
          {"note", ee.note}};
}

nlohmann::json numbers(const std::vector<double>& v) {
  nlohmann::json out = nlohmann::json::array();
  for (double x : v) out.push_back(num(x));
  return out;
}

nlohmann::json extrapolated_json(const Scene& scene, const Extrapolation& xp) {
  nlohmann::json x = {{"frequencies_rad_s", numbers(xp.frequencies_rad_s)},
                      {"frequency_errors", numbers(xp.frequency_errors)},
                      {"observed_orders", numbers(xp.observed_orders)},
                      {"frequency_error", num(xp.frequency_error)},
                      {"deflections", deflections_json(scene, xp.deflections)},
                      {"deflection_error", num(xp.deflection_error)},
                      {"meshes", xp.meshes},
                      {"order", num(xp.order)},
                      {"next_order", num(xp.next_order)},
                      {"deflection_next_order", num(xp.deflection_next_order)},
                      {"note", xp.note}};
  if (xp.frequencies_reported) x["mesh_frequencies_rad_s"] = numbers(xp.mesh_frequencies_rad_s);
  if (xp.deflections_reported) x["mesh_deflections"] = deflections_json(scene, xp.mesh_deflections);
  return x;
}

/// What was asked and used, the model solved, and the size of what was solved.
void summary_json(const Scene& scene, const Summary& sum, nlohmann::json& j) {
  j["status"] = to_string(sum.status);
  j["message"] = sum.message;
  j["method"] = {{"requested", sum.method_requested},
                 {"used", sum.method},
                 {"fallbacks", sum.fallbacks},
                 {"converges_to_scene_theory", sum.converges_to_scene_theory}};
  j["model"] = {{"solved", sum.model},
                {"scene_theory", to_string(scene.theory)},
                {"is_scene_theory", sum.converges_to_scene_theory}};
  j["unknowns"] = sum.unknowns;
  j["threads"] = sum.threads;
  j["max_backward_error"] = num(sum.max_backward_error);
  nlohmann::json steps = nlohmann::json::array();
  for (const StepOutcome& s : sum.steps)
    steps.push_back({{"step", s.step}, {"status", to_string(s.status)}, {"message", s.message}});
  j["steps"] = steps;
  const auto& t = sum.timings_s;
  j["timing_s"] = {{"build", t.build}, {"modes", t.modes}, {"statics", t.statics}, {"frf", t.frf},
                   {"error_estimate", t.error_estimate}, {"transient", t.transient}, {"campbell", t.campbell},
                   {"total", sum.total_time_s}};
  j["error_estimate"] = error_estimate_json(sum.error_estimate);
  nlohmann::json diag = nlohmann::json::object();
  for (const auto& [name, v] : sum.diagnostics) diag[name] = num(v);
  j["diagnostics"] = diag;
}

/// The quantities: frequencies, reactions, deflections, FRF, shapes, extrapolation, history, Campbell.
void quantities_json(const Scene& scene, const Result& r, nlohmann::json& j) {
  using nlohmann::json;
  json fams = json::array();
  for (std::size_t i = 0; i < r.frequencies_rad_s.size(); ++i) fams.push_back(to_string(r.mode_families[i]));
  j["frequencies_rad_s"] = numbers(r.frequencies_rad_s);
  j["mode_families"] = fams;
  j["reactions"] = reactions_json(scene, r.reactions);
  j["deflections"] = deflections_json(scene, r.deflections);
  if (!r.frf.empty() || scene.request.frf) {  // requested: present, even when no sample could be computed
    json f = json::array();
    for (const auto& s : r.frf)
      f.push_back({{"omega_rad_s", num(s.omega_rad_s)}, {"re", num(s.receptance.real())}, {"im", num(s.receptance.imag())}});
    j["frf"] = f;
  }
  if (!r.mode_shapes.empty()) j["mode_shapes"] = mode_shapes_json(scene, r.mode_shapes);
  const auto& xp = r.extrapolated;
  if (!xp.empty() || !xp.note.empty()) j["extrapolated"] = extrapolated_json(scene, xp);
  // Which values answer: the mesh's own, or the extrapolation's (Extrapolation::*_reported).
  j["values"] = {{"frequencies", xp.frequencies_reported ? "extrapolated" : "mesh"},
                 {"deflections", xp.deflections_reported ? "extrapolated" : "mesh"}};
  if (!r.transient.empty()) j["transient"] = transient_json(scene, r.transient);
  if (!r.campbell.empty() || scene.rotor) j["campbell"] = campbell_json(r.campbell);
}

}  // namespace

nlohmann::json to_json(const Scene& scene, const std::string& backend, const Discretization& mesh,
                       const Result& r) {
  nlohmann::json j;
  j["scene"] = scene.name;
  j["scene_file"] = scene.source;
  j["backend"] = backend;
  j["mesh"] = r.summary.mesh.empty() ? mesh.spec() : r.summary.mesh;  // the default mesh may have been refined
  summary_json(scene, r.summary, j);
  quantities_json(scene, r, j);
  nlohmann::json warnings = nlohmann::json::array();
  for (const auto& n : scene.notes) warnings.push_back("scene: " + n);
  for (const auto& w : r.summary.warnings) warnings.push_back(w);
  j["warnings"] = warnings;
  return j;
}

}  // namespace modalbench
