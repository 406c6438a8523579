// A spinning shaft on rfem's lateral model (rotor.hpp): the spin's matrices, what is refused, and the
// Campbell diagram with its critical speeds.
#include "rotor.hpp"

#include "modalbench/whirl.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "modalbench/rfem/builders.hpp"
#include "modalbench/rotor_scene.hpp"
#include "analysis_detail.hpp"

namespace modalbench::rfem::detail {

namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

SpMat over_z(const Model& model, const System& sys, const Triplets& t) {
  SpMat A(model.body_dofs(), model.body_dofs());
  A.setFromTriplets(t.begin(), t.end());
  SpMat Az = SpMat(sys.T.transpose()) * A * sys.T;
  Az.makeCompressed();
  return Az;
}

/// The polar inertia of each rigid element's gyroscopic moment about y and z (its Jx).
double polar(const RigidElement& r) { return r.inertia[0]; }

/// Whether every rigid element has one diametral inertia (Jy = Jz).
bool round_elements(const Model& model) {
  return std::all_of(model.elements.begin(), model.elements.end(), [](const RigidElement& r) {
    return std::abs(r.inertia[1] - r.inertia[2]) <= 1e-12 * std::max(r.inertia[1], r.inertia[2]);
  });
}

/// The lowest critical speeds of an axisymmetric shaft per whirl direction: its x-z model with the
/// tilt inertias J_t - s J_p (synchronous whirl), K x = Omega^2 (M - s G_p) x.
std::pair<std::vector<double>, std::vector<double>> axisymmetric_criticals(const Scene& s, const Model& model, double top) {
  Scene plane = s;
  plane.physics = Physics::Bending;
  plane.rotor.reset();
  BeamOptions bo;
  if (s.theory == Theory::EulerBernoulli) bo.rigid_shear = RigidShear::JointCoordinates;
  const Model pm = build_beam(plane, static_cast<int>(model.elements.size()) - 1, bo);
  const System ps = assemble(pm);
  const int ry = pm.local_index(dofs::Ry);
  Triplets t;
  for (std::size_t e = 0; e < pm.elements.size(); ++e)
    t.emplace_back(static_cast<int>(e) * pm.dofs_per_element() + ry, static_cast<int>(e) * pm.dofs_per_element() + ry,
                   polar(model.elements[e]));
  const SpMat Gp = over_z(pm, ps, t);
  return {synchronous_speeds(ps.K, SpMat(ps.M - Gp), top), synchronous_speeds(ps.K, SpMat(ps.M + Gp), top)};
}

}  // namespace

RotorMatrices rotor_matrices(const Model& model, const System& sys) {
  const int na = model.dofs_per_element();
  const int iv = model.local_index(dofs::Uy), iw = model.local_index(dofs::Uz);
  const int iy = model.local_index(dofs::Ry), iz = model.local_index(dofs::Rz);
  Triplets g, cr, kc;
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    const RigidElement& r = model.elements[e];
    const int b = static_cast<int>(e) * na;
    const double m = r.mass, jt = r.inertia[1], jp = polar(r);
    g.emplace_back(b + iy, b + iz, jp);
    g.emplace_back(b + iz, b + iy, -jp);
    cr.emplace_back(b + iv, b + iw, -2 * m);
    cr.emplace_back(b + iw, b + iv, 2 * m);
    cr.emplace_back(b + iy, b + iz, -(2 * jt - jp));
    cr.emplace_back(b + iz, b + iy, 2 * jt - jp);
    for (int d : {iv, iw}) kc.emplace_back(b + d, b + d, m);
    for (int d : {iy, iz}) kc.emplace_back(b + d, b + d, jt - jp);
  }
  return {over_z(model, sys, g), over_z(model, sys, cr), over_z(model, sys, kc)};
}

std::string rotor_scene_refusal(const Scene& s) {
  if (!rotor_held(s)) return "rfem solves rotors on supports that hold them (a free rotor's rigid whirl is not solved yet)";
  if (s.rotor->frame == Rotor::Frame::Rotating && s.theory == Theory::Timoshenko && !axisymmetric_shaft(s))
    return "rfem's rotating frame takes one diametral inertia per rigid element: an asymmetric section's rotary "
           "inertias (Timoshenko theory) differ; use Euler-Bernoulli theory for an asymmetric shaft";
  return "";
}

std::string campbell_refusal(const Scene& s, const Model& model, const System& sys) {
  if (model.active != dofs::kLateral) return "rfem's Campbell diagram needs the lateral model (physics = \"lateral\")";
  if (sys.m() > 0)
    return "rfem's Campbell diagram needs a model without rigid-link multipliers (Euler-Bernoulli: joint "
           "coordinates, which rotor scenes use)";
  if (free_rigid_modes(model, sys).Z.cols() > 0)
    return "rfem solves rotors on supports that hold them (a free rotor's rigid whirl is not solved yet)";
  if (s.rotor->frame == Rotor::Frame::Rotating && !round_elements(model))
    return "rfem's rotating frame takes one diametral inertia per rigid element: an asymmetric section's rotary "
           "inertias (Timoshenko theory) differ; use Euler-Bernoulli theory for an asymmetric shaft";
  return "";
}

namespace {

/// An orbit given at the rigid elements' centres (ascending x), at the points xs: linear between the
/// centres around each point (beyond the first or last centre, the line through the two nearest),
/// normalized.
Orbit orbit_at(const Model& model, const std::vector<std::complex<double>>& V, const std::vector<std::complex<double>>& W,
               const std::vector<double>& xs) {
  Orbit o;
  const std::size_t n = model.elements.size();
  for (double x : xs) {
    if (n < 2) {
      o.v.push_back(V.at(0));
      o.w.push_back(W.at(0));
      continue;
    }
    std::size_t i = 0;
    while (i + 2 < n && model.elements[i + 1].centre.x() < x) ++i;
    const double x0 = model.elements[i].centre.x(), x1 = model.elements[i + 1].centre.x(), t = (x - x0) / (x1 - x0);
    o.v.push_back((1 - t) * V[i] + t * V[i + 1]);
    o.w.push_back((1 - t) * W[i] + t * W[i + 1]);
  }
  normalize(o);
  return o;
}

}  // namespace

namespace {

/// How the roots of each spin were found: the projected sweep where it applies (stationary frame,
/// campbell_method auto or projected), Arnoldi elsewhere and at the spins it leaves.
struct SweepLog {
  long arnoldi_spins = 0, arnoldi_restarts = 0, projected_spins = 0, solves = 0, basis = 0;
  double bound = 0;   ///< the projected roots' largest frequency bound
  long count = -2;    ///< the count at the top spin (-2: not taken, -1: a zero pivot)
  long found = 0;     ///< the roots below its point
  double count_at = 0;
};

/// The sweep's whirl roots, spin by spin, into c.points (orbits at c.orbit_points_m).
void sweep_roots(const Scene& s, const Model& model, const System& sys, const RotorMatrices& rm, bool projected,
                 bool count, Campbell& c, SweepLog& log) {
  const bool rotating = s.rotor->frame == Rotor::Frame::Rotating;
  const int k = s.request.modes;
  Eigen::SparseLU<SpMat> fixed;  // the stationary frame's K for Arnoldi, factored where first needed
  bool factored = false;
  std::optional<GyroscopicSweep> sweep;
  if (projected) sweep.emplace(sys.M, rm.G, sys.K, k);
  Eigen::VectorXd start;  // the previous Arnoldi spin's roots: a warm start along the sweep
  for (double spin : s.rotor->spin) {
    const SpMat K = rotating ? SpMat(sys.K - spin * spin * rm.Kc) : sys.K;
    const SpMat C = spin * (rotating ? rm.Cr : rm.G);
    WhirlRoots w;
    GyroscopicSweep::Roots pr;
    if (sweep) pr = sweep->solve(spin);
    if (pr.converged) {
      w = collect_roots(model, sys, K, C, k, pr.lambda, pr.X, pr.backward_error);
      ++log.projected_spins;
      log.bound = std::max(log.bound, pr.bound);
      if (count && spin == s.rotor->spin.back()) {  // every root below the k-th's bound was found
        log.count_at = pr.lambda.back().imag() * (1 + 2 * pr.bound) + 1e-12;
        log.count = whirl_count(sys.M, rm.G, sys.K, spin, log.count_at);
        log.found = k + (pr.next <= log.count_at ? 1 : 0);
      }
    } else {
      Eigen::SparseLU<SpMat> own;
      if (!rotating && !factored) {
        fixed.compute(sys.K);
        if (fixed.info() != Eigen::Success) throw std::runtime_error("rfem rotor: the stiffness could not be factored");
        factored = true;
      }
      if (rotating) {
        own.compute(K);
        if (own.info() != Eigen::Success)
          throw std::runtime_error(fmt::format("rfem rotor: K - Omega^2 K_c is singular at spin {:g} rad/s (a critical "
                                               "speed of the rotating frame): move the spin off it", spin));
      }
      w = whirl_roots(model, sys, K, rotating ? own : fixed, C, k, start);
      start = std::move(w.start);
      log.arnoldi_restarts += w.iterations;
      ++log.arnoldi_spins;
    }
    CampbellPoint p;
    p.spin_rad_s = spin;
    p.frequencies_rad_s = w.omega;
    p.whirl = w.whirl;
    p.growth_rates_1_s = w.growth;
    if (!c.orbit_points_m.empty())
      for (std::size_t i = 0; i < w.omega.size(); ++i)
        p.orbits.push_back(orbit_at(model, w.orbit_v[i], w.orbit_w[i], c.orbit_points_m));
    for (double be : w.backward_error) c.max_backward_error = std::max(c.max_backward_error, be);
    if (std::any_of(w.growth.begin(), w.growth.end(), [](double g) { return g > 0; })) c.unstable_spins.push_back(spin);
    c.points.push_back(std::move(p));
  }
  if (sweep) {
    log.solves = sweep->solves();
    log.basis = sweep->largest_basis();
  }
}

/// How the sweep's roots were found, for the Campbell note.
std::string sweep_note(const SweepLog& log, bool rotating) {
  if (log.projected_spins == 0)
    return fmt::format("the quadratic eigenproblem by shift-invert Arnoldi (Spectra) on its companion form, {}",
                       rotating ? "K - Omega^2 K_c factored per spin" : "K factored once for every spin");
  std::string note = fmt::format(
      "K factored once for every spin; the roots by projection (Voss's nonlinear Arnoldi: the projected "
      "gyroscopic problem on a basis of at most {} vectors enriched by K^-1 of the residuals, {} solves), each "
      "root's frequency within {:.2g} (relative) of a true one by its residual in the K^-1 norm, or where that "
      "bound stops falling (rounding) within {:.2g} (largest bound {:.2g}, added to the Campbell estimate)",
      log.basis, log.solves, GyroscopicSweep::kBound, GyroscopicSweep::kFloorBound, log.bound);
  if (log.count >= 0)
    note += fmt::format("; the count of whirl frequencies below {:.8g} rad/s at the top spin (LDL' inertia of "
                        "P(i w)) is {}, the roots found there {}", log.count_at, log.count, log.found);
  if (log.arnoldi_spins > 0)
    note += fmt::format("; {} spin(s) by shift-invert Arnoldi, where the projection did not meet its bound",
                        log.arnoldi_spins);
  return note;
}

}  // namespace

Campbell rotor_campbell(const Scene& s, const Model& model, const System& sys, const ResolvedOptions& opt, Summary& sum) {
  const RotorMatrices rm = rotor_matrices(model, sys);
  const bool rotating = s.rotor->frame == Rotor::Frame::Rotating;
  const int k = s.request.modes;
  Campbell c;
  c.frame = to_string(s.rotor->frame);
  if (s.request.shapes) {
    for (const auto& p : s.shape_points()) c.orbit_points_m.push_back(p[0]);
    c.orbit_note = "each root's eigenvector: v and w of the rigid elements (a pure tilt: the tilt axis), linear "
                   "between the elements' centres";
  }
  c.max_backward_error = 0;
  const bool projected = !rotating && projected_sweep(opt.get_choice("campbell_method"), static_cast<double>(sys.n()), k);
  SweepLog log;
  sweep_roots(s, model, sys, rm, projected, opt.get_bool("sturm_check"), c, log);
  const long short_spins = std::count_if(c.points.begin(), c.points.end(), [&](const CampbellPoint& p) {
    return static_cast<int>(p.frequencies_rad_s.size()) < k;
  });
  const double top = s.rotor->spin.back();
  if (round_elements(model) && !rotating) {
    std::tie(c.forward_criticals, c.backward_criticals) = axisymmetric_criticals(s, model, top);
    c.criticals_note = "synchronous whirl per direction on the x-z model with tilt inertias J_t -+ J_p: K x = Omega^2 "
                       "(M -+ G_p) x, every critical speed up to the highest spin and the next above";
  } else if (rotating) {
    c.forward_criticals = synchronous_speeds(sys.K, rm.Kc, top);
    c.criticals_note = "forward: where a rotating-frame frequency is 0, K x = Omega^2 K_c x (for an asymmetric shaft "
                       "the ends of its unstable ranges); backward critical speeds are not given in the rotating frame";
  }
  c.note = fmt::format("rfem lateral model, {} frame: {}; {}; each pair +-lambda once, growth rate abs(Re lambda) "
                       "where it exceeds max(1e-8, 10 sqrt(backward error)) abs(lambda); whirl from the orbits of v, w "
                       "at the rigid elements; undamped (material.loss_factor is not applied)",
                       c.frame,
                       rotating ? "Coriolis -+2 m Omega, (2 J_t - J_p) Omega and spin softening m Omega^2, (J_t - J_p) "
                                  "Omega^2 per rigid element"
                                : "gyroscopic J_p Omega per rigid element",
                       sweep_note(log, rotating));
  sum.set_diagnostic("campbell_arnoldi_restarts", static_cast<double>(log.arnoldi_restarts));
  sum.set_diagnostic("campbell_arnoldi_spins", static_cast<double>(log.arnoldi_spins));
  sum.set_diagnostic("campbell_projected_solves", static_cast<double>(log.solves));
  sum.set_diagnostic("campbell_projected_basis", static_cast<double>(log.basis));
  if (log.projected_spins > 0) sum.set_diagnostic("campbell_solve_error_bound", log.bound);
  if (log.count == -1)
    sum.raise(Status::NumericalIssue, "rfem rotor: the count at the top spin met a zero pivot; no root is proven not missed");
  else if (log.count >= 0 && log.count != log.found)
    sum.raise(Status::NumericalIssue,
              fmt::format("rfem rotor: {} whirl frequencies lie below {:.8g} rad/s at the top spin, {} were found there",
                          log.count, log.count_at, log.found));
  if (short_spins > 0)
    sum.raise(Status::NumericalIssue, fmt::format("rfem rotor: fewer than {} whirl roots found at {} spin(s)", k, short_spins));
  if (!(c.max_backward_error <= 1e-8))
    sum.raise(Status::NumericalIssue,
              fmt::format("rfem rotor: a whirl eigenpair's backward error {:.2g} exceeds 1e-8", c.max_backward_error));
  sum.note_backward_error(c.max_backward_error);
  return c;
}

}  // namespace modalbench::rfem::detail
