#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "modalbench/dtfm/dtfm.hpp"
#include "modalbench/timer.hpp"

namespace modalbench::dtfm {

Capability DtfmSolver::supports(const Scene&) const {
  Capability c;
  c.modes = c.statics = c.frf = true;
  return c;
}

Discretization DtfmSolver::default_mesh(const Scene& scene) const {
  return Discretization::parse(scene.is_plate() ? "10" : "2x2");
}

std::vector<Discretization> DtfmSolver::mesh_ladder(const Scene& scene) const {
  std::vector<const char*> specs;
  if (scene.is_plate()) specs = {"4", "7", "10", "20", "40"};
  else if (scene.physics == Physics::Spatial) specs = {"1x1", "2x2", "4x4", "6x6"};  // 6 fields per prism
  else specs = {"1x1", "2x2", "4x4", "8x8"};
  std::vector<Discretization> out;
  for (const char* m : specs) out.push_back(Discretization::parse(m));
  return out;
}

std::vector<Discretization> DtfmSolver::stress_meshes(const Scene& scene) const {
  return {mesh_ladder(scene).back()};
}

void DtfmSolver::do_solve(const Scene& scene, const Discretization& mesh, const Options& options,
                          Result& r) const {
  Timer timer;
  const PrismModel model = build_model(scene, mesh, options_);
  auto& sum = r.summary;
  sum.method = "dtfm: " + model.description +
               "; segment dynamic stiffness, Wittrick-Williams count with Brent polish";
  // Modelling notes (not doubts about the numbers) belong to the method, not the warnings.
  for (const auto& n : model.notes) sum.method += "; " + n;
  sum.dofs = model.m;
  if (options.mass == "lumped")
    sum.warnings.push_back("--mass lumped does not apply: the prisms' mass is distributed (consistent) along x");
  if (options.frf_modes > 0)
    sum.warnings.push_back("frf_modes ignored: dtfm computes every FRF sample by a direct dynamic-stiffness solve");
  // A modelling note as well: the scene's theory names what `exact` solves; the prism model is
  // its own model of the section, as for the 3D references.
  if (scene.is_beam() && scene.theory == Theory::EulerBernoulli && (model.nz > 1 || model.ny > 1))
    sum.method += fmt::format(
        "; scene theory euler-bernoulli applies to each prism only: the {}x{} section's layers deform in shear, so the "
        "beam as a whole carries shear deformation (like a Timoshenko or 3D model) and its higher bending modes lie "
        "below the Euler-Bernoulli values (use --mesh 1x1 for the Euler-Bernoulli beam itself)",
        model.ny, model.nz);
  LineAnalysis la(model);
  sum.timings_s.emplace_back("build", timer.lap());

  const int k = scene.request.modes;
  if (k > 0) {
    std::vector<ModeFamily> families;
    if (scene.is_beam() && scene.physics == Physics::Bending) families = {ModeFamily::BendingXZ};
    const ModeList ml = la.modes(k, families);
    r.frequencies_rad_s = ml.omega_rad_s;
    r.mode_families = ml.family;
    int unknown = 0;
    for (auto f : ml.family) unknown += f == ModeFamily::Unknown;
    if (unknown)
      sum.warnings.push_back(fmt::format(
          "{} mode(s) labelled unknown: their rigid-section share of kinetic energy is below one half", unknown));
    if (!ml.count_consistent) {
      sum.status = Status::NumericalIssue;
      sum.message = "dtfm: " + ml.count_message;
    }
    if (static_cast<int>(ml.omega_rad_s.size()) < k) {
      sum.status = Status::NotConverged;
      sum.message = fmt::format("dtfm: only {} of {} modes found", ml.omega_rad_s.size(), k);
    }
    sum.timings_s.emplace_back("frequencies", timer.lap());
  }
  if (!scene.request.probes.empty()) {
    try {
      r.deflections = la.statics(scene.loads, scene.request.probes);
    } catch (const std::runtime_error& e) {
      r.deflections.clear();
      sum.status = Status::InvalidInput;
      sum.message = scene.source + ": supports: static solve impossible: " + e.what();
    }
    sum.timings_s.emplace_back("statics", timer.lap());
  }
  if (scene.request.frf) {
    const auto& f = *scene.request.frf;
    std::vector<double> omegas;
    for (int i = 0; i < f.points; ++i) omegas.push_back(f.omega_min + (f.omega_max - f.omega_min) * i / (f.points - 1));
    int skipped = 0;
    const auto H = la.receptance(f.excite, f.observe, omegas, scene.material.loss_factor, &skipped);
    for (std::size_t i = 0; i < omegas.size(); ++i)
      if (std::isfinite(std::abs(H[i]))) r.frf.push_back({omegas[i], H[i]});
    if (skipped)
      sum.warnings.push_back(fmt::format("FRF: {} sample(s) on a natural frequency omitted", skipped));
    sum.timings_s.emplace_back("frf", timer.lap());
  }
  sum.iterations = la.evaluations();
  sum.max_residual = la.max_asymmetry();
  if (la.max_asymmetry() > 1e-6)
    sum.warnings.push_back(fmt::format("segment matrices asymmetric to {:.2e}: the state matrices are not "
                                       "Hamiltonian to working precision",
                                       la.max_asymmetry()));
}

}  // namespace modalbench::dtfm
