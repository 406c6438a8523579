#include "modalbench/rfem/rfem.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "modalbench/rfem/analysis.hpp"
#include "modalbench/rfem/builders.hpp"
#include "modalbench/rfem/system.hpp"

namespace modalbench::rfem {

namespace {

using Clock = std::chrono::steady_clock;

class Phases {
 public:
  explicit Phases(Result& r) : r_(r) {}
  void add(const std::string& phase, double s) {
    for (auto& [name, t] : r_.summary.timings_s)
      if (name == phase) {
        t += s;
        return;
      }
    r_.summary.timings_s.emplace_back(phase, s);
  }

 private:
  Result& r_;
};

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string mesh_source(const Scene& s) { return s.source.empty() ? "command line" : s.source; }

Eigen::Vector3d point_of(const Scene& s, const std::array<double, 2>& p) {
  return s.is_beam() ? Eigen::Vector3d(p[0], 0, 0) : Eigen::Vector3d(p[0], p[1], 0);
}

/// A complete eigendecomposition beats one factorization per frequency: many samples, a small
/// constrained space, and no viscous damping (structural damping K (1 + i eta) is proportional).
bool complete_spectrum_pays(const System& sys, std::size_t samples) {
  return sys.C.nonZeros() == 0 && samples >= 20 && sys.n() - sys.m() <= 600 && sys.n() <= 1500;
}

void set_status(Result& r, Status st, const std::string& msg) {
  if (r.summary.status == Status::Success) {
    r.summary.status = st;
    r.summary.message = msg;
  } else {
    r.summary.message += "; " + msg;
  }
}

}  // namespace

Capability RfemSolver::supports(const Scene& s) const {
  Capability c;
  if (s.is_beam() || s.is_plate()) {
    c.modes = c.statics = c.frf = true;
    return c;
  }
  c.reason = "rfem builds beams and plates only";
  return c;
}

Discretization RfemSolver::default_mesh(const Scene& s) const {
  if (s.is_beam()) return {{128}};
  const double a = s.geometry.length, b = s.geometry.width;
  const double longest = std::max(a, b);
  auto count = [&](double side) { return std::max(2, static_cast<int>(std::lround(16.0 * side / longest))); };
  return {{count(a), count(b)}};
}

std::vector<Discretization> RfemSolver::mesh_ladder(const Scene& s) const {
  std::vector<Discretization> v;
  if (s.is_beam()) {
    for (int n : {8, 16, 32, 64, 128, 256}) v.push_back({{n}});
    return v;
  }
  const double a = s.geometry.length, b = s.geometry.width, longest = std::max(a, b);
  const int nx0 = std::max(2, static_cast<int>(std::lround(10.0 * a / longest)));
  const int ny0 = std::max(2, static_cast<int>(std::lround(10.0 * b / longest)));
  for (int f : {1, 2, 4, 8}) v.push_back({{nx0 * f, ny0 * f}});
  return v;
}

std::vector<Discretization> RfemSolver::stress_meshes(const Scene& s) const {
  if (s.is_beam()) return {{{10000}}, {{100000}}};
  const double a = s.geometry.length, b = s.geometry.width, longest = std::max(a, b);
  return {{{std::max(2, static_cast<int>(std::lround(100.0 * a / longest))),
            std::max(2, static_cast<int>(std::lround(100.0 * b / longest)))}}};
}

Model RfemSolver::build(const Scene& s, const Discretization& mesh) {
  const std::string src = mesh_source(s);
  if (s.is_beam()) {
    if (mesh.counts.size() != 1)
      throw InputError(src, "--mesh",
                       fmt::format("a beam mesh is one count N (segments), e.g. 64 (got '{}')", mesh.spec()));
    const int n = mesh.counts[0];
    if (n < 1) throw InputError(src, "--mesh", fmt::format("a beam needs N >= 1 segments (got {})", n));
    if (n > 2000000) throw InputError(src, "--mesh", fmt::format("N = {} exceeds the limit of 2000000 segments", n));
    return build_beam(s, n);
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
  return build_plate(s, po);
}

void RfemSolver::do_solve(const Scene& s, const Discretization& mesh, const Options& options, Result& r) const {
  Phases phases(r);
  auto t0 = Clock::now();
  const Model model = build(s, mesh);
  const System sys = assemble(model);
  phases.add("assembly", since(t0));
  r.summary.dofs = sys.n();
  if (sys.n() == 0)
    throw InputError(mesh_source(s), "--mesh",
                     fmt::format("mesh {} is so coarse that the supports hold every DOF: refine it", mesh.spec()));

  std::string method = fmt::format(
      "rfem (lumped): {}; {} coordinates ({} held by rigid supports eliminated{}); mass: diagonal RFE mass "
      "(--mass {} does not apply); probes: (bi)linear interpolation of the motion of the RFE centres around P "
      "(second order, as the centres); loads: its transpose (the action shared by the same weights)",
      model.description, sys.n(), sys.held,
      sys.m() > 0 ? fmt::format(", {} rigid-link constraints as multipliers{}", sys.m(),
                                sys.redundant > 0 ? fmt::format(", {} dependent ones dropped", sys.redundant) : "")
                  : "",
      options.mass);

  // Modes (also the basis of a modal FRF).
  const int k = s.request.modes;
  const bool modal_frf = s.request.frf.has_value() && options.frf_modes > 0;
  const int k_solve = std::max(k, modal_frf ? options.frf_modes : 0);
  Modes md;
  if (k_solve > 0) {
    ModeOptions mo;
    mo.modes = k_solve;
    md = solve_modes(model, sys, mo);
    phases.add("factorization", md.factor_seconds);
    phases.add("eigen", md.eigen_seconds);
    r.summary.iterations = md.iterations;
    r.summary.max_residual = md.max_residual;
    for (const auto& w : md.warnings) r.summary.warnings.push_back(w);
    const long shown = std::min<long>(k, md.lambda.size());
    for (long i = 0; i < shown; ++i) {
      const double lam = md.lambda[i];
      if (lam < 0 && lam < -1e-8 * std::abs(md.lambda[md.lambda.size() - 1]))
        r.summary.warnings.push_back(fmt::format("mode {}: negative eigenvalue {:.3g} reported as 0", i + 1, lam));
      r.frequencies_rad_s.push_back(std::sqrt(std::max(0.0, lam)));
      r.mode_families.push_back(md.family[static_cast<std::size_t>(i)]);
    }
    if (shown < k)
      r.summary.warnings.push_back(fmt::format("{} of {} requested modes computed", shown, k));
    method += "; modes: " + md.method;
    if (!md.converged) set_status(r, Status::NotConverged, "eigen solve not converged: see warnings");
    else if (md.max_backward_error > 1e-8)
      set_status(r, Status::NumericalIssue,
                 fmt::format("eigen backward error {:.3g} above 1e-8 (residual {:.3g})", md.max_backward_error,
                             md.max_residual));
  }

  // Statics at the probes.
  if (!s.request.probes.empty()) {
    t0 = Clock::now();
    Eigen::VectorXd f = Eigen::VectorXd::Zero(sys.n());
    for (const auto& p : s.loads) {
      Vector6d act;
      act << p.Fx, p.Fy, p.Fz, p.Mx, p.My, p.Mz;
      f += point_load(model, sys, point_of(s, {p.x, p.y}), act);
    }
    const StaticSolution st = solve_static(model, sys, f);
    phases.add("factorization", st.factor_seconds);
    if (!st.ok) {
      set_status(r, st.mechanism ? Status::InvalidInput : Status::NumericalIssue,
                 fmt::format("{}: supports: {}", mesh_source(s), st.message));
    } else {
      for (const auto& p : s.request.probes) {
        const Eigen::Vector3d P = point_of(s, p);
        Deflection d;
        d.position = p;
        double v[6];
        for (int c = 0; c < 6; ++c) {
          v[c] = point_observer(model, sys, P, c).dot(st.z);
          // The singular part of the response to each load that interpolation misses.
          for (const auto& l : s.loads) {
            const double action[6] = {l.Fx, l.Fy, l.Fz, l.Mx, l.My, l.Mz};
            for (int a = 0; a < 6; ++a)
              if (action[a] != 0.0) v[c] += point_correction(model, P, c, point_of(s, {l.x, l.y}), a) * action[a];
          }
        }
        if (!std::isfinite(v[2])) {
          set_status(r, Status::NumericalIssue,
                     fmt::format("probe ({}, {}): the deflection under a point load on a Mindlin plate is infinite "
                                 "(logarithmic in the distance to the load); it is reported as null",
                                 p[0], p[1]));
        }
        d.u = v[0];
        d.v = v[1];
        d.w = v[2];
        d.theta_x = v[3];
        d.theta_y = v[4];
        d.theta_z = v[5];
        r.deflections.push_back(d);
      }
      if (st.residual > 1e-8)
        r.summary.warnings.push_back(fmt::format("static residual {:.3g} above 1e-8", st.residual));
      r.summary.max_residual = std::max(r.summary.max_residual, st.residual);
    }
    method += "; statics: sparse LDL' (AMD" + std::string(sys.m() > 0 ? ", saddle point with multipliers" : "") +
              "), mechanisms detected structurally";
    phases.add("statics", since(t0) - st.factor_seconds);
  }

  // FRF: receptance w(observe) / Fz(excite).
  if (s.request.frf) {
    t0 = Clock::now();
    const auto& fr = *s.request.frf;
    std::vector<double> omegas;
    for (int i = 0; i < fr.points; ++i)
      omegas.push_back(fr.omega_min + (fr.omega_max - fr.omega_min) * i / (fr.points - 1));
    Vector6d unit = Vector6d::Zero();
    unit[2] = 1.0;
    const Eigen::VectorXd f = point_load(model, sys, point_of(s, fr.excite), unit);
    const Eigen::VectorXd g = point_observer(model, sys, point_of(s, fr.observe), 2);
    // The singular part of the point response that interpolation between centres misses
    // (static in character: the same at every frequency).
    const double singular = point_correction(model, point_of(s, fr.observe), 2, point_of(s, fr.excite), 2);
    FrfResult res;
    if (modal_frf) {
      if (md.lambda.size() < options.frf_modes)
        r.summary.warnings.push_back(
            fmt::format("modal FRF: {} modes available of {} requested", md.lambda.size(), options.frf_modes));
      res = frf_modal(model, sys, md, f, g, omegas);
    } else if (complete_spectrum_pays(sys, omegas.size())) {
      // Many frequencies on a small model without viscous dampers: all modes of the discrete
      // model once, then the exact partial-fraction sum per frequency (no truncation).
      ModeOptions mo;
      mo.modes = static_cast<int>(sys.n() - sys.m());
      mo.method = EigenMethod::Dense;
      const Modes all = solve_modes(model, sys, mo);
      phases.add("eigen", all.eigen_seconds);
      if (all.lambda.size() == sys.n() - sys.m() && all.max_backward_error < 1e-10) {
        res = frf_modal(model, sys, all, f, g, omegas);
        res.method = fmt::format(
            "direct, by the complete spectral decomposition of the discrete model ({} modes, none truncated; equal to "
            "a per-frequency solve to rounding), eta = {}",
            all.lambda.size(), model.loss_factor);
      } else {
        res = frf_direct(model, sys, f, g, omegas);
        phases.add("factorization", res.factor_seconds);
      }
    } else {
      res = frf_direct(model, sys, f, g, omegas);
      phases.add("factorization", res.factor_seconds);
    }
    if (!std::isfinite(singular))
      set_status(r, Status::NumericalIssue,
                 "FRF: excitation and observation at one point of a Mindlin plate: the receptance is infinite "
                 "(logarithmic singularity of the point load)");
    for (std::size_t i = 0; i < res.omega.size(); ++i) r.frf.push_back({res.omega[i], res.receptance[i] + singular});
    if (res.skipped > 0)
      r.summary.warnings.push_back(
          fmt::format("FRF: {} sample(s) omitted (singular: on a natural frequency, or w = 0 of a free body)", res.skipped));
    method += "; FRF: " + res.method;
    phases.add("frf", since(t0) - res.factor_seconds);
  }
  r.summary.method = method;
}

}  // namespace modalbench::rfem
