// rfem's kernels (kernels.hpp in core): the modes, shapes, statics, FRF and Campbell diagram of one
// model (rigid elements and spring-damping elements assembled for a scene and a mesh).
#include "rfem_kernels.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "modalbench/rfem/analysis.hpp"
#include "modalbench/rfem/rfem.hpp"
#include "analysis_detail.hpp"
#include "rotor.hpp"
#include "shared_supports.hpp"

namespace modalbench::rfem::detail {

namespace {

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

void note_static_backward_error(const System& sys, const Eigen::VectorXd& f, const StaticSolution& st, Summary& sum) {
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

namespace {

/// Deflections at the probes (with the point actions' singular part), the reactions and the static
/// solve's backward error.
void solve_statics(const Scene& s, const Model& model, const System& sys, Result& r) {
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
  note_static_backward_error(sys, f, st, sum);
}

/// Fills r.frf; returns the method used. `modes`: modal superposition over them (null: direct).
std::string solve_frf(const Scene& s, const Model& model, const System& sys, const Modes* modes, int frf_modes,
                      const ResolvedOptions& options, Result& r) {
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
  if (res.skipped > 0 && res.omega.empty())
    sum.raise(Status::NumericalIssue,
              fmt::format("FRF: all {} sample(s) omitted (singular: on a natural frequency, or w = 0 of a free body)",
                          res.skipped));
  else if (res.skipped > 0)
    sum.warnings.push_back(
        fmt::format("FRF: {} sample(s) omitted (singular: on a natural frequency, or w = 0 of a free body)", res.skipped));
  return res.method;
}

class RfemKernels final : public Kernels {
 public:
  RfemKernels(const Scene& s, const Options& options, Model model, int frame_mesh)
      : s_(s), options_(options), model_(std::move(model)), sys_(assemble(model_)), frame_mesh_(frame_mesh) {}
  const System& system() const { return sys_; }
  const Model& model() const { return model_; }

  void modes(Result& r) override {
    find_modes(r);
    check_frequency_bounds(r);
  }
  void shapes(Result& r) override { r.mode_shapes = sample_shapes(s_, model_, sys_, md_.Z, md_.lambda, shown_); }
  void statics(Result& r) override {
    if (s_.is_frame()) frame_statics(s_, model_, sys_, frame_mesh_, r);
    else solve_statics(s_, model_, sys_, r);
    r.summary.method += "; statics: sparse LDL' (AMD" + std::string(sys_.m() > 0 ? ", saddle point with multipliers" : "") +
                        "), mechanisms detected structurally";
  }
  void frf(Result& r) override {
    const int frf_modes = static_cast<int>(options_.resolved.get_integer("frf_modes"));
    const bool modal = frf_modes > 0;
    if (modal && !solved_) {  // a modal FRF without modes asked: its basis, with the modes' checks
      find_modes(r);
      check_frequency_bounds(r);
    }
    r.summary.method += "; FRF: " + solve_frf(s_, model_, sys_, modal ? &md_ : nullptr, frf_modes, options_.resolved, r);
  }
  void campbell(Result& r) override {
    if (const std::string why = campbell_refusal(s_, model_, sys_); !why.empty()) {
      r.summary.raise(Status::Unsupported, why);
      return;
    }
    r.campbell = rotor_campbell(s_, model_, sys_, options_.resolved, r.summary);
    r.summary.method += "; Campbell: " + r.campbell.note;
  }

 private:
  /// The request's modes (and, for a modal FRF, its basis: the larger count), with the
  /// eigensolver's diagnostics, and the frequencies reported.
  void find_modes(Result& r) {
    auto& sum = r.summary;
    const Scene& s = s_;
    const ResolvedOptions& opt = options_.resolved;
    const int k = s.request.modes;
    const int frf_modes = static_cast<int>(opt.get_integer("frf_modes"));
    const bool modal_frf = s.request.frf.has_value() && frf_modes > 0;
    const int k_solve = std::max(k, modal_frf ? frf_modes : 0);
    md_ = rfem::solve_modes(model_, sys_, mode_options(opt, k_solve));
    solved_ = true;
    const Modes& md = md_;
    if (md.sturm_count >= 0) sum.threads = 2;  // the Sturm analysis overlaps the Lanczos iteration
    sum.set_diagnostic("lanczos_restarts", static_cast<double>(md.iterations));
    sum.set_diagnostic("max_eigen_residual", md.max_residual);
    sum.note_backward_error(md.max_backward_error);
    for (const auto& w : md.warnings) sum.warnings.push_back(w);
    for (const auto& f : md.fallbacks) sum.fallbacks.push_back(f);
    shown_ = std::min<long>(k, md.lambda.size());
    for (long i = 0; i < shown_; ++i) {
      const double lam = md.lambda[i];
      if (lam < 0 && lam < -1e-8 * std::abs(md.lambda[md.lambda.size() - 1]))
        sum.warnings.push_back(fmt::format("mode {}: negative eigenvalue {:.3g} reported as 0", i + 1, lam));
      r.frequencies_rad_s.push_back(std::sqrt(std::max(0.0, lam)));
      r.mode_families.push_back(md.family[static_cast<std::size_t>(i)]);
    }
    if (shown_ < k) sum.warnings.push_back(fmt::format("{} of {} requested modes computed", shown_, k));
    sum.method += "; modes: " + md.method;
  }

  /// The near-rigid modes' and every reported frequency's own error bounds against the tolerance,
  /// and the eigensolver's convergence.
  void check_frequency_bounds(Result& r) {
    auto& sum = r.summary;
    const Scene& s = s_;
    const Modes& md = md_;
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
      for (long i = 0; i < shown_ && i < static_cast<long>(md.forward_bounds.size()); ++i)
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
  }

  const Scene& s_;
  const Options& options_;
  const Model model_;
  const System sys_;
  const int frame_mesh_;  ///< a frame's mesh n (segments on its shortest member); 0 otherwise
  Modes md_;
  bool solved_ = false;
  long shown_ = 0;  ///< the modes reported (at most request.modes)
};

}  // namespace

std::unique_ptr<Kernels> make_kernels(const Scene& s, const Discretization& mesh, const Options& options, Model model,
                                      Result& r) {
  auto& sum = r.summary;
  const ResolvedOptions& opt = options.resolved;
  auto kernels = std::make_unique<RfemKernels>(s, options, std::move(model), s.is_frame() ? mesh.counts.at(0) : 0);
  const Model& m = kernels->model();
  const System& sys = kernels->system();
  sum.unknowns = sys.n() + sys.m();
  // Rigid elements tend to the scene's beam or plate theory; Table A1.1's springs as printed
  // (no Poisson coupling) tend to a plate with the mixed term 2D(1 - nu) instead (docs/sources.md, R3).
  sum.converges_to_scene_theory = s.is_beam() || opt.get_bool("plate_bending_correction");
  sum.model = sum.converges_to_scene_theory
                  ? fmt::format("rigid finite elements, tending to the {} {}", to_string(s.theory), to_string(s.kind))
                  : "rigid finite elements with Table A1.1's springs as printed, tending to a plate whose mixed "
                    "term is 2D(1 - nu) (docs/sources.md, R3)";
  if (sys.n() == 0)
    throw InputError(mesh_source(s), "--mesh",
                     fmt::format("mesh {} is so coarse that the supports hold every DOF: refine it", mesh.spec()));
  if (const std::string shared = supports_sharing_an_element(s, s.is_beam() ? mesh.counts[0] : 0); !shared.empty())
    sum.raise(Status::NotConverged, shared);
  sum.set_diagnostic("coordinates", static_cast<double>(sys.n()));
  sum.set_diagnostic("multipliers", static_cast<double>(sys.m()));
  sum.method = fmt::format(
      "rfem (lumped): {}; {} coordinates ({} held by rigid supports eliminated{}); mass: diagonal RFE mass "
      "(--mass {} does not apply); probes: (bi)linear interpolation of the motion of the RFE centres around P "
      "(second order, as the centres) plus the point action's singular response in closed form; loads: the "
      "transpose (the action shared by the same weights)",
      m.description, sys.n(), sys.held,
      sys.m() > 0 ? fmt::format(", {} rigid-link constraints as multipliers{}", sys.m(),
                                sys.redundant > 0 ? fmt::format(", {} dependent ones dropped", sys.redundant) : "")
                  : "",
      to_string(options.mass));
  return kernels;
}

}  // namespace modalbench::rfem::detail
