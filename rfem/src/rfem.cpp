#include "modalbench/rfem/rfem.hpp"
#include "shared_supports.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "modalbench/rfem/analysis.hpp"
#include "modalbench/rfem/builders.hpp"
#include "modalbench/rfem/system.hpp"
#include "analysis_detail.hpp"
#include "rotor.hpp"

namespace modalbench::rfem {

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string mesh_source(const Scene& s) { return s.source.empty() ? "command line" : s.source; }

Eigen::Vector3d point_of(const Scene& s, const std::array<double, 2>& p) {
  return s.is_beam() ? Eigen::Vector3d(p[0], 0, 0) : Eigen::Vector3d(p[0], p[1], 0);
}

/// A complete eigendecomposition beats the projection (one factorization, a few modes and Ritz
/// vectors, a bound per sample) only on a very small model: many samples, a small constrained
/// space, and no viscous damping (structural damping K (1 + i eta) is proportional). Measured on
/// the paper beam's 200-point FRF: complete 1.5 ms at 62 unknowns, 4.3 ms at 126, 48 ms at 254,
/// 0.20 s at 510; the projection 2-3 ms at each.
bool complete_spectrum_pays(const System& sys, std::size_t samples) {
  return sys.C.nonZeros() == 0 && samples >= 20 && sys.n() - sys.m() <= 80 && sys.n() <= 200;
}

using detail::norm1;

ModeOptions mode_options(const ResolvedOptions& o, int modes) {
  ModeOptions mo;
  mo.modes = modes;
  const std::string& e = o.get_choice("eigen");
  mo.method = e == "dense" ? EigenMethod::Dense : e == "shift-invert" ? EigenMethod::ShiftInvert : EigenMethod::Auto;
  mo.dense_limit = o.get_integer("dense_limit");
  mo.tolerance = o.get_number("tolerance");
  mo.sturm_check = o.get_bool("sturm_check");
  mo.seed = static_cast<unsigned>(o.get_integer("seed"));
  return mo;
}

}  // namespace

Capability RfemSolver::supports(const Scene& s) const {
  Capability c;
  if (s.is_beam() || s.is_plate()) {
    c.modes = c.statics = c.frf = true;
    if (s.rotor) {
      c.reason = detail::rotor_scene_refusal(s);
      c.campbell = c.reason.empty();
    }
    return c;
  }
  c.reason = "rfem builds beams and plates only";
  return c;
}

// Fitted to runs of `modalbench solve --json` on the 2-core machine (Release, /usr/bin/time peak
// resident memory less the ~20 MB of the process): beams of 10^4 to 1.6 * 10^5 segments in
// bending (6 modes 3.1 KB and 11 us, statics 1.8 KB and 3.6 us per segment, a direct FRF 3.4 KB and
// 0.23 us per segment and sample), Kirchhoff plates of 6,000 to 96,000 fragments (modes 7.5 KB and
// 37-54 us, statics 4.7 KB and 17-35 us per fragment, a direct FRF 4.4 KB and 3.6-7.4 us per fragment
// and sample). Per coordinate the costs scale with the DOFs an element carries; Mindlin plates
// carry about twice a Kirchhoff plate's coordinates.
ResourceEstimate RfemSolver::estimate(const Scene& s, const Discretization& mesh, const Options& options) const {
  ResourceEstimate e;
  const auto& rq = s.request;
  const bool modal_frf = rq.frf && options.resolved.get_integer("frf_modes") > 0;
  const double samples = rq.frf ? rq.frf->points : 0;
  const double k = std::max<double>(rq.modes, modal_frf ? static_cast<double>(options.resolved.get_integer("frf_modes")) : 0.0);
  if (s.is_beam() && mesh.counts.size() == 1) {
    const double n = mesh.counts[0];
    const double d = s.physics == Physics::Spatial   ? 3.0
                     : s.physics == Physics::Lateral ? 2.0
                     : s.physics == Physics::Planar  ? 1.5
                                                     : 1.0;
    double bytes = 0, t = 0;
    // Lanczos: ~k^1.5 per segment (measured 10 s for 200 modes of 8192 segments, 1.8 s for 6 of 160,000).
    if (k > 0) { bytes = std::max(bytes, 3.1e3 * n * d * (1 + k / 60)); t += n * d * (6e-6 + 4.3e-7 * std::pow(k, 1.5)); }
    if (!rq.probes.empty()) { bytes = std::max(bytes, 1.8e3 * n * d); t += 3.6e-6 * n * d; }
    if (rq.frf && !modal_frf) { bytes = std::max(bytes, 3.4e3 * n * d); t += 0.23e-6 * n * d * samples; }
    // A rotor: per spin, the stationary frame's projected sweep or Arnoldi (rotor.hpp's cost model,
    // which also chooses between them), Arnoldi in the rotating frame; Arnoldi's vectors 2 n x 40.
    // A lateral model has 4 coordinates per segment.
    const double spins = s.rotor ? static_cast<double>(s.rotor->spin.size()) : 0.0;
    if (spins > 0) {
      const double coordinates = 2.0 * n * d;
      const int roots = static_cast<int>(k);
      const bool projected = s.rotor->frame == Rotor::Frame::Stationary &&
                             detail::projected_sweep(options.resolved.get_choice("campbell_method"), coordinates, roots);
      bytes = std::max(bytes, 1.5e3 * n * d);
      t += spins * (projected ? detail::projected_seconds_per_spin(coordinates, roots)
                              : detail::arnoldi_seconds_per_spin(coordinates, roots));
    }
    e.bytes = bytes;
    e.seconds = t;
    e.basis = fmt::format("beam of {} segments, {} modes, {} FRF samples{}", mesh.counts[0], k, samples,
                          spins > 0 ? fmt::format(", {} spins", spins) : "");
  } else if (s.is_plate() && mesh.counts.size() == 2) {
    const double f = static_cast<double>(mesh.counts[0]) * mesh.counts[1];
    const double d = s.theory == Theory::Mindlin ? 2.0 : 1.0;
    const double growth = std::pow(std::max(1.0, f / 6000.0), 0.3);  // fill of the nested-dissection factor
    double bytes = 0, t = 0;
    if (k > 0) { bytes = std::max(bytes, 7.5e3 * f * d * (1 + k / 40)); t += 3.7e-5 * f * d * growth * (1 + k / 16); }
    if (!rq.probes.empty()) { bytes = std::max(bytes, 4.7e3 * f * d); t += 1.7e-5 * f * d * growth; }
    // FRF: one complex solve per sample on the factor's pattern (measured on the paper plate, 400
    // samples: 0.031 s at 40 x 32, 0.21 s at 80 x 64, 1.7 s at 152 x 122; 3.6e-6 had it 20x high).
    if (rq.frf && !modal_frf) { bytes = std::max(bytes, 4.4e3 * f * d * growth); t += 1.8e-7 * f * d * growth * samples; }
    e.bytes = bytes;
    e.seconds = t;
    e.basis = fmt::format("plate of {} x {} fragments, {} modes, {} FRF samples", mesh.counts[0], mesh.counts[1], k, samples);
  }
  return e;
}

std::vector<OptionSpec> RfemSolver::option_specs() const {
  using T = OptionSpec::Type;
  return {
      {"eigen", T::Choice, "auto", {"auto", "dense", "shift-invert"}, 0, 0,
       "eigensolver: dense (complete, refined) or Lanczos in shift-invert mode; auto picks by size"},
      {"dense_limit", T::Integer, "40", {}, 1, 1e6,
       "auto: the dense path up to this many coordinates (measured: shift-invert Lanczos is faster from 30 up)"},
      {"tolerance", T::Number, "1e-10", {}, 1e-15, 1e-3, "Lanczos relative tolerance"},
      {"sturm_check", T::Bool, "true", {}, 0, 0,
       "count the eigenvalues below the last mode by an LDL' inertia (on a second core) to prove none is missed"},
      {"seed", T::Integer, "20240917", {}, 0, 4294967295.0, "Lanczos start vector"},
      {"frf_modes", T::Integer, "0", {}, 0, 1e6,
       "0: FRF by direct solves (or the complete spectral decomposition of small models); N > 0: modal "
       "superposition over N modes (truncated: an approximation)"},
      {"frf_method", T::Choice, "auto", {"auto", "direct", "projected"}, 0, 0,
       "FRF without frf_modes: direct (one sparse solve per frequency), projected (modes below twice the top "
       "frequency plus load-dependent Ritz vectors, each sample's error bounded, those over the tolerance (at most 0.05 dB) solved "
       "directly), or auto (projected from 20 samples)"},
      {"campbell_method", T::Choice, "auto", {"auto", "projected", "arnoldi"}, 0, 0,
       "rotors, stationary frame: projected (K factored once; per spin the projected gyroscopic problem on a basis "
       "enriched by K^-1 residuals, each root's frequency bounded by its residual to 1e-9 (or, where rounding stops "
       "it, to at most 1e-7, reported), Arnoldi where not met; "
       "with sturm_check, a count at the top spin) or arnoldi (shift-invert Arnoldi on the companion form at every "
       "spin); auto: the cheaper by rfem's cost model (projected for few roots: 6 on 2000 coordinates, 5x faster; "
       "Arnoldi for many: 20 on 400); the rotating frame always uses Arnoldi"},
      {"beam_rigid_shear", T::Choice, "multipliers", {"multipliers", "joint-coordinates"}, 0, 0,
       "Euler-Bernoulli beams: rigid shear springs as constraints with multipliers, or by joint coordinates"},
      {"plate_rigid_shear", T::Choice, "corner-coordinates", {"corner-coordinates", "multipliers"}, 0, 0,
       "Kirchhoff plates: rigid transverse shear by corner-value coordinates, or constraints with multipliers"},
      {"plate_bending_correction", T::Bool, "true", {}, 0, 0,
       "plates: per-fragment Poisson coupling and Mindlin twist form (false: Table A1.1 springs as printed)"},
  };
}

Model RfemSolver::build(const Scene& s, const Discretization& mesh, const ResolvedOptions* options) {
  const std::string src = mesh_source(s);
  if (s.is_beam()) {
    if (mesh.counts.size() != 1)
      throw InputError(src, "--mesh",
                       fmt::format("a beam mesh is one count N (segments), e.g. 64 (got '{}')", mesh.spec()));
    const int n = mesh.counts[0];
    if (n < 1) throw InputError(src, "--mesh", fmt::format("a beam needs N >= 1 segments (got {})", n));
    if (n > 2000000) throw InputError(src, "--mesh", fmt::format("N = {} exceeds the limit of 2000000 segments", n));
    BeamOptions bo;
    // A rotor's Campbell diagram solves the quadratic eigenproblem without multipliers.
    if ((options && options->get_choice("beam_rigid_shear") == "joint-coordinates") || s.rotor)
      bo.rigid_shear = RigidShear::JointCoordinates;
    return build_beam(s, n, bo);
  }
  if (mesh.counts.size() != 2)
    throw InputError(src, "--mesh",
                     fmt::format("a plate mesh is NXxNY (fragments along x and y), e.g. 20x12 (got '{}')", mesh.spec()));
  const int nx = mesh.counts[0], ny = mesh.counts[1];
  if (nx < 2 || ny < 2)
    throw InputError(src, "--mesh", fmt::format("a plate needs at least 2x2 fragments (got {}x{})", nx, ny));
  if (static_cast<double>(nx) * ny > 4.0e6)
    throw InputError(src, "--mesh", fmt::format("{}x{} exceeds the limit of 4e6 fragments", nx, ny));
  PlateOptions po;
  po.nx = nx;
  po.ny = ny;
  if (options) {
    po.rigid_shear = options->get_choice("plate_rigid_shear") == "multipliers" ? RigidShear::Multipliers
                                                                               : RigidShear::JointCoordinates;
    po.bending_correction = options->get_bool("plate_bending_correction");
  }
  return build_plate(s, po);
}

void RfemSolver::do_solve(const Scene& s, const Discretization& mesh, const Options& options, Result& r) const {
  auto& sum = r.summary;
  const ResolvedOptions& opt = options.resolved;
  auto t0 = Clock::now();
  detail::reserve_blas_workspace();
  const Model model = build(s, mesh, &opt);
  const System sys = assemble(model);
  sum.timings_s.build = since(t0);
  sum.unknowns = sys.n() + sys.m();
  // Rigid elements tend to the scene's beam or plate theory; Table A1.1's springs as printed
  // (no Poisson coupling) tend to a plate with the mixed term 2D(1 - nu) instead (ERRATA 3).
  sum.converges_to_scene_theory = s.is_beam() || opt.get_bool("plate_bending_correction");
  sum.model = sum.converges_to_scene_theory
                  ? fmt::format("rigid finite elements, tending to the {} {}", to_string(s.theory), to_string(s.kind))
                  : "rigid finite elements with Table A1.1's springs as printed, tending to a plate whose mixed "
                    "term is 2D(1 - nu) (ERRATA 3)";
  if (sys.n() == 0)
    throw InputError(mesh_source(s), "--mesh",
                     fmt::format("mesh {} is so coarse that the supports hold every DOF: refine it", mesh.spec()));
  if (const std::string shared = detail::supports_sharing_an_element(s, s.is_beam() ? mesh.counts[0] : 0); !shared.empty())
    sum.raise(Status::NotConverged, shared);
  sum.set_diagnostic("coordinates", static_cast<double>(sys.n()));
  sum.set_diagnostic("multipliers", static_cast<double>(sys.m()));

  std::string method = fmt::format(
      "rfem (lumped): {}; {} coordinates ({} held by rigid supports eliminated{}); mass: diagonal RFE mass "
      "(--mass {} does not apply); probes: (bi)linear interpolation of the motion of the RFE centres around P "
      "(second order, as the centres) plus the point action's singular response in closed form; loads: the "
      "transpose (the action shared by the same weights)",
      model.description, sys.n(), sys.held,
      sys.m() > 0 ? fmt::format(", {} rigid-link constraints as multipliers{}", sys.m(),
                                sys.redundant > 0 ? fmt::format(", {} dependent ones dropped", sys.redundant) : "")
                  : "",
      to_string(options.mass));

  // Modes (also the basis of a modal FRF).
  const int k = s.request.modes;
  const int frf_modes = static_cast<int>(opt.get_integer("frf_modes"));
  const bool modal_frf = s.request.frf.has_value() && frf_modes > 0;
  const int k_solve = std::max(k, modal_frf ? frf_modes : 0);
  Modes md;
  if (k_solve > 0) {
    t0 = Clock::now();
    md = solve_modes(model, sys, mode_options(opt, k_solve));
    if (md.sturm_count >= 0) sum.threads = 2;  // the Sturm analysis overlaps the Lanczos iteration
    sum.set_diagnostic("lanczos_restarts", static_cast<double>(md.iterations));
    sum.set_diagnostic("max_eigen_residual", md.max_residual);
    sum.note_backward_error(md.max_backward_error);
    for (const auto& w : md.warnings) sum.warnings.push_back(w);
    for (const auto& f : md.fallbacks) sum.fallbacks.push_back(f);
    const long shown = std::min<long>(k, md.lambda.size());
    for (long i = 0; i < shown; ++i) {
      const double lam = md.lambda[i];
      if (lam < 0 && lam < -1e-8 * std::abs(md.lambda[md.lambda.size() - 1]))
        sum.warnings.push_back(fmt::format("mode {}: negative eigenvalue {:.3g} reported as 0", i + 1, lam));
      r.frequencies_rad_s.push_back(std::sqrt(std::max(0.0, lam)));
      r.mode_families.push_back(md.family[static_cast<std::size_t>(i)]);
    }
    if (shown < k) sum.warnings.push_back(fmt::format("{} of {} requested modes computed", shown, k));
    if (s.request.shapes && shown > 0) r.mode_shapes = sample_shapes(s, model, sys, md.Z, md.lambda, shown);
    method += "; modes: " + md.method;
    if (md.near_rigid_bound > 0) {
      // Relative error bound of the near-rigid frequencies (half that of their eigenvalues): it
      // must stay well inside the accuracy asked (1 % of the tolerance).
      const double bound = 0.5 * md.near_rigid_bound;
      sum.set_diagnostic("near_rigid_frequency_error_bound", bound);
      if (!(bound <= 1e-2 * s.request.tolerance))
        sum.raise(Status::NumericalIssue,
                  fmt::format("near-rigid modes: their Rayleigh-Ritz frequencies are only known to {:.2g} (Kato-Temple "
                              "bound), above 1 % of the tolerance {:.2g}", bound, s.request.tolerance));
    }
    // The solve's own bound on the frequencies (rounding; half the eigenvalues' relative bound),
    // worst over the modes reported: part of the error estimate, and past the tolerance a
    // numerical issue (a finer mesh makes it worse).
    {
      double worst = 0;
      long worst_mode = 0;
      for (long i = 0; i < shown && i < static_cast<long>(md.forward_bounds.size()); ++i)
        if (0.5 * md.forward_bounds[static_cast<std::size_t>(i)] > worst)
          worst = 0.5 * md.forward_bounds[static_cast<std::size_t>(i)], worst_mode = i + 1;
      const double bound = std::max(worst, 0.5 * md.near_rigid_bound);
      sum.set_diagnostic("frequency_solve_error_bound", bound);
      if (worst > s.request.tolerance)
        sum.raise(Status::NumericalIssue,
                  fmt::format("mode {}: its frequency is only known to {:.2g} (rounding: eigen backward error plus eps, "
                              "times the mode's componentwise condition), above the tolerance {:.2g}; the condition "
                              "grows with the mesh (e.g. stiff springs, a slender Timoshenko beam, nu near -1): a "
                              "coarser mesh is more accurate here",
                              worst_mode, worst, s.request.tolerance));
    }
    if (!md.converged) sum.raise(Status::NotConverged, "eigen solve not converged: see warnings");
    else if (md.max_backward_error > 1e-8 && !(sum.diagnostic("frequency_solve_error_bound") > s.request.tolerance))
      // Not a verdict on the frequencies: a componentwise backward error is not what an eigensolver
      // guarantees when the stiffnesses span many decades (a short, finely cut Euler-Bernoulli beam
      // reached 3.9e-7 with its frequencies 1.2e-4 from the exact beam). Their forward bound above
      // (this backward error times each mode's condition) is the check.
      sum.warnings.push_back(fmt::format("eigen backward error {:.3g} above 1e-8 (residual {:.3g}): the frequencies "
                                         "are judged by their forward bound ({:.2g}, within the tolerance); the mode "
                                         "shapes carry this backward error",
                                         md.max_backward_error, md.max_residual,
                                         sum.diagnostic("frequency_solve_error_bound")));
    sum.timings_s.modes += since(t0);
  }

  if (!s.request.probes.empty()) {
    t0 = Clock::now();
    solve_statics(s, model, sys, r);
    method += "; statics: sparse LDL' (AMD" + std::string(sys.m() > 0 ? ", saddle point with multipliers" : "") +
              "), mechanisms detected structurally";
    sum.timings_s.statics += since(t0);
  }

  if (s.request.frf) {
    t0 = Clock::now();
    method += "; FRF: " + solve_frf(s, model, sys, modal_frf ? &md : nullptr, frf_modes, opt, r);
    sum.timings_s.frf += since(t0);
  }
  if (s.rotor) {
    t0 = Clock::now();
    if (const std::string why = detail::campbell_refusal(s, model, sys); !why.empty()) {
      sum.raise(Status::Unsupported, why);
    } else {
      // Its failure is the Campbell diagram's alone: the modes and statics stand.
      try {
        r.campbell = detail::rotor_campbell(s, model, sys, opt, sum);
        method += "; Campbell: " + r.campbell.note;
      } catch (const std::runtime_error& e) {
        sum.raise(Status::NumericalIssue, std::string("rfem: Campbell diagram: ") + e.what());
      }
    }
    sum.timings_s.campbell += since(t0);
  }
  sum.method = method;
}

void RfemSolver::solve_statics(const Scene& s, const Model& model, const System& sys, Result& r) {
  auto& sum = r.summary;
  const std::vector<PointLoad> loads = s.all_point_loads();
  std::vector<PointAction> actions = distributed_actions(model, s);
  for (const auto& p : loads) {
    Vector6d act;
    act << p.Fx, p.Fy, p.Fz, p.Mx, p.My, p.Mz;
    actions.emplace_back(point_of(s, {p.x, p.y}), act);
  }
  const Eigen::VectorXd f = point_loads(model, sys, actions);
  const StaticSolution st = solve_static(model, sys, f);
  if (!st.ok) {
    sum.raise(st.mechanism ? Status::InvalidInput : Status::NumericalIssue,
              fmt::format("{}: supports: {}", mesh_source(s), st.message));
    return;
  }
  // Rigid motions held only by soft springs, split off in the solve (provenance of the deflections).
  if (st.near_mechanism > 0) sum.set_diagnostic("near_mechanism_rigid_motions", st.near_mechanism);
  for (const auto& p : s.request.probes) {
    const Eigen::Vector3d P = point_of(s, p);
    Deflection d;
    d.position = p;
    double v[6];
    for (int c = 0; c < 6; ++c) {
      v[c] = point_observer(model, sys, P, c).dot(st.z);
      // The singular part of the response to each load that interpolation misses.
      for (const auto& l : loads) {
        const double action[6] = {l.Fx, l.Fy, l.Fz, l.Mx, l.My, l.Mz};
        for (int a = 0; a < 6; ++a)
          if (action[a] != 0.0) v[c] += point_correction(model, P, c, point_of(s, {l.x, l.y}), a) * action[a];
      }
    }
    if (!std::isfinite(v[2]))
      sum.raise(Status::NumericalIssue,
                fmt::format("probe ({}, {}): the deflection under a point load on a Mindlin plate is infinite "
                            "(logarithmic in the distance to the load); it is reported as null",
                            p[0], p[1]));
    d.u = v[0];
    d.v = v[1];
    d.w = v[2];
    d.theta_x = v[3];
    d.theta_y = v[4];
    d.theta_z = v[5];
    r.deflections.push_back(d);
  }
  if (s.is_beam()) detail::beam_reactions(s, model, sys, st.z, actions, r);
  else detail::plate_reactions(s, model, sys, st.z, actions, r);
  // Normwise backward error of the static solve, from its relative residual ||K z - f|| / ||f||.
  const double fn = f.norm(), backward = fn > 0 ? st.residual * fn / (norm1(sys.K) * st.z.norm() + fn) : 0.0;
  sum.set_diagnostic("static_relative_residual", st.residual);
  sum.note_backward_error(backward);
  if (backward > 1e-8)
    sum.raise(Status::NumericalIssue,
              fmt::format("static solve: backward error {:.3g} above 1e-8 (relative residual {:.3g}): the deflections "
                          "are not trustworthy",
                          backward, st.residual));
}

std::string RfemSolver::solve_frf(const Scene& s, const Model& model, const System& sys, const Modes* modes,
                                  int frf_modes, const ResolvedOptions& options, Result& r) {
  auto& sum = r.summary;
  const auto& fr = *s.request.frf;
  std::vector<double> omegas;
  for (int i = 0; i < fr.points; ++i) omegas.push_back(fr.omega_min + (fr.omega_max - fr.omega_min) * i / (fr.points - 1));
  Vector6d unit = Vector6d::Zero();
  unit[2] = 1.0;
  const Eigen::VectorXd f = point_load(model, sys, point_of(s, fr.excite), unit);
  const Eigen::VectorXd g = point_observer(model, sys, point_of(s, fr.observe), 2);
  // The singular part of the point response that interpolation between centres misses
  // (static in character: the same at every frequency).
  const double singular = point_correction(model, point_of(s, fr.observe), 2, point_of(s, fr.excite), 2);
  FrfResult res;
  if (modes) {
    if (modes->lambda.size() < frf_modes)
      sum.warnings.push_back(fmt::format("modal FRF: {} modes available of {} requested", modes->lambda.size(), frf_modes));
    res = frf_modal(model, sys, *modes, f, g, omegas);
  } else if (options.get_choice("frf_method") != "projected" && complete_spectrum_pays(sys, omegas.size())) {
    // Many frequencies on a small model without viscous dampers: all modes of the discrete
    // model once, then the exact partial-fraction sum per frequency (no truncation).
    ModeOptions mo;
    mo.modes = static_cast<int>(sys.n() - sys.m());
    mo.method = EigenMethod::Dense;
    const Modes all = solve_modes(model, sys, mo);
    if (all.lambda.size() == sys.n() - sys.m() && all.max_backward_error < 1e-10) {
      res = frf_modal(model, sys, all, f, g, omegas);
      res.method = fmt::format(
          "direct, by the complete spectral decomposition of the discrete model ({} modes, none truncated; equal to "
          "a per-frequency solve to rounding), eta = {}",
          all.lambda.size(), model.loss_factor);
    } else {
      sum.fallbacks.push_back(fmt::format(
          "FRF: the complete spectral decomposition was not accurate enough (backward error {:.2g}): one solve per "
          "frequency instead",
          all.max_backward_error));
      res = frf_direct(model, sys, f, g, omegas);
    }
  } else {
    // Many frequencies: the projection with its per-sample error bound (samples that miss the
    // target solved directly), about one eigen solve for the whole sweep; else one solve each.
    const std::string& how = options.get_choice("frf_method");
    bool done = false;
    if (how == "projected" || (how == "auto" && omegas.size() >= 20)) {
      ProjectedFrfOptions po;
      po.modes = mode_options(options, 0);
      po.target = std::clamp(s.request.tolerance, 1e-10, 5.8e-3);  // 5.8e-3: 0.05 dB
      done = frf_projected(model, sys, f, g, omegas, po, res);
      if (done) {
        sum.set_diagnostic("frf_error_bound", res.max_error_bound);
        sum.set_diagnostic("frf_direct_samples", static_cast<double>(res.direct_samples));
      }
      else if (how == "projected")
        sum.fallbacks.push_back("FRF: the projection does not apply (viscous dampers, more than 400 modes below twice "
                                "the top frequency, or a failed factorization): one solve per frequency instead");
    }
    if (!done) res = frf_direct(model, sys, f, g, omegas);
  }
  if (!std::isfinite(singular))
    sum.raise(Status::NumericalIssue,
              "FRF: excitation and observation at one point of a Mindlin plate: the receptance is infinite "
              "(logarithmic singularity of the point load)");
  for (std::size_t i = 0; i < res.omega.size(); ++i) r.frf.push_back({res.omega[i], res.receptance[i] + singular});
  if (res.skipped > 0)
    sum.warnings.push_back(
        fmt::format("FRF: {} sample(s) omitted (singular: on a natural frequency, or w = 0 of a free body)", res.skipped));
  return res.method;
}

}  // namespace modalbench::rfem
