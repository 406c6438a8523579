// difference_eq's kernels (kernels.hpp in core): the modes, shapes, statics and Campbell diagram of
// the regular discrete beam of a scene, in closed form, each checked against the assembled model.
#include "difference_eq_kernels.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "modalbench/difference_eq/assembled.hpp"
#include "modalbench/difference_eq/difference_eq.hpp"
#include "modalbench/equilibrium.hpp"
#include "attachments.hpp"
#include "rotor.hpp"

namespace modalbench::difference_eq {

namespace {

/// Modes with supports or masses at nodes (attachments.hpp): the sub-chain count and bisection;
/// every frequency confirmed by the assembled model's own Sturm count (another computation, O(R))
/// up to 20000 elements, and for R up to `max_check_R` by its mode shape's residual. Returns the spectrum.
Spectrum attached_modes(const Scene& s, const RegularBeam& beam, MassModel mass, const std::vector<NodalAttachment>& at,
                        long max_check_R, Result& res) {
  auto& sum = res.summary;
  std::string problem;
  const Spectrum sp = natural_frequencies_attached(beam, mass, at, s.request.modes, problem);
  if (!problem.empty()) sum.raise(Status::NumericalIssue, "difference_eq: " + problem);
  sum.set_diagnostic("count_evaluations", static_cast<double>(sp.count_evaluations));
  for (std::size_t i = 0; i < sp.omega_rad_s.size(); ++i) {
    res.frequencies_rad_s.push_back(sp.omega_rad_s[i]);
    res.mode_families.push_back(static_cast<int>(i) < sp.rigid ? ModeFamily::Rigid : ModeFamily::BendingXZ);
  }
  if (static_cast<int>(sp.omega_rad_s.size()) < s.request.modes)
    sum.warnings.push_back(fmt::format("the model has only {} natural frequencies ({} mass, R={}); {} requested",
                                       sp.available, to_string(mass), beam.R, s.request.modes));
  // The assembled count in double resolves omega^2 (1 -+ 1e-8) only while its rounding, growing
  // like R^4 with the chain's stiffness ratios, stays below that window (Friswell's rotor, bearings
  // 1e6 N/m: every frequency confirmed on 96 elements, one not on 192, four on 384, while the
  // frequencies agreed to 1e-12 from mesh to mesh); where it cannot, the count in binary128 decides.
  constexpr long kAssembledCountMaxR = 20000;
  long unconfirmed = 0, quad = 0;
  double worst = 0;
  for (std::size_t i = static_cast<std::size_t>(sp.rigid); i < sp.omega_rad_s.size(); ++i) {
    const double l = sp.omega_rad_s[i] * sp.omega_rad_s[i];
    const long index = static_cast<long>(i);
    if (beam.R <= kAssembledCountMaxR && !(assembled_count_attached(beam, mass, at, l * (1.0 - 1e-8)) <= index &&
                                           assembled_count_attached(beam, mass, at, l * (1.0 + 1e-8)) >= index + 1)) {
      if (assembled_count_confirms(beam, mass, at, l, index)) ++quad;
      else ++unconfirmed;
    }
    if (beam.R <= max_check_R) {
      double be = 0;
      mode_shape_attached(beam, mass, at, sp.omega_rad_s[i], be);
      worst = std::max(worst, be);
    }
  }
  sum.set_diagnostic("root_bracket_relative", sp.max_bracket);
  if (quad > 0) sum.set_diagnostic("count_confirmations_binary128", static_cast<double>(quad));
  if (unconfirmed > 0)
    sum.raise(Status::NumericalIssue,
              fmt::format("{} frequency(ies) not confirmed by the assembled model's count at omega^2 (1 -+ 1e-8) "
                          "in double or binary128",
                          unconfirmed));
  if (beam.R <= max_check_R) sum.note_backward_error(worst);
  return sp;
}

/// The supports' reactions (what each exerts on the beam: Fz, and My = -(the moment conjugate to the
/// slope), theta_y being -dw/dx) and, from them by the equilibrium of the free body left of each
/// probe, its bending moment and shear force (bending in x-z: the other resultants are not modelled).
void add_reactions_and_forces(const Scene& s, const RegularBeam& beam, const StaticSolution& st,
                              const std::vector<std::array<double, 2>>& point_reactions, Result& res) {
  auto add = [&](const std::string& name, double x, double force, double moment) {
    Reaction r;
    r.support = name;
    r.position = {x, 0.0};
    r.force = {0.0, 0.0, force};
    r.moment = {0.0, -moment, 0.0};
    res.reactions.push_back(r);
  };
  if (beam.k0 > 0 || beam.r0 > 0) add("x0", 0.0, st.reactions[0], st.reactions[1]);
  if (beam.kL > 0 || beam.rL > 0) add("xL", beam.L, st.reactions[2], st.reactions[3]);
  for (std::size_t i = 0; i < s.point_supports.size(); ++i)  // attachments_of: the supports first
    add(fmt::format("points[{}]", i), s.point_supports[i].x, point_reactions[i][0], point_reactions[i][1]);
  for (Deflection& d : res.deflections) {
    const InternalForces f = free_body_forces(s, res.reactions, d.position[0]);
    d.forces = {};
    d.forces.My = f.My;
    d.forces.Qz = f.Qz;
    d.has_forces = true;
  }
}

/// The beam of a scene on R elements with what acts on it: supports and masses at nodes, point
/// loads on nodes and line loads as their exact nodal equivalents. Throws InputError for a point
/// load off the nodes.
struct Chain {
  RegularBeam beam;
  std::vector<NodalAttachment> attached;
  std::vector<ElementLoad> element_loads;
  std::vector<NodalLoad> loads;
  bool other_components = false;  ///< load or gravity components that bending in x-z does not take
};

Chain chain_of(const Scene& s, long R) {
  Chain c;
  c.beam = beam_of(s, R);
  const double L = c.beam.L;
  const RegularBeam& beam = c.beam;
  std::vector<NodalLoad>& loads = c.loads;
  bool& other_components = c.other_components;
  // Loads, supports between the ends and masses must sit on nodes.
  c.attached = attachments_of(s, R);
  c.element_loads = element_loads_of(s, R);
  const std::vector<PointLoad> point_loads = s.all_point_loads();
  for (std::size_t i = 0; i < point_loads.size(); ++i) {
    const auto& l = point_loads[i];
    const long r = node_at(l.x, L, R);
    if (r < 0)
      throw InputError(s.source, i < s.loads.size() ? fmt::format("loads[{}].x", i) : fmt::format("masses[{}].x", i - s.loads.size()),
                       fmt::format("not at a node of mesh R={}: x = {} m, nodes at multiples of L/R = {} m "
                                   "(nearest x = {} m)",
                                   R, l.x, L / static_cast<double>(R),
                                   static_cast<double>(std::lround(l.x / L * static_cast<double>(R))) * L / static_cast<double>(R)));
    loads.push_back({r, l.Fz, -l.My});
    other_components = other_components || l.Fx != 0 || l.Fy != 0 || l.Mx != 0 || l.Mz != 0;
  }
  for (const NodalLoad& l : equivalent_nodal_loads(beam, c.element_loads)) loads.push_back(l);
  for (const auto& q : s.line_loads)
    other_components = other_components || q.qx[0] != 0 || q.qx[1] != 0 || q.qy[0] != 0 || q.qy[1] != 0;
  if (s.gravity) other_components = other_components || (*s.gravity)[0] != 0 || (*s.gravity)[1] != 0;

  return c;
}

class DifferenceEqKernels final : public Kernels {
 public:
  DifferenceEqKernels(const Scene& s, const Options& options, Chain chain)
      : s_(s), mass_(options.mass), chain_(std::move(chain)),
        static_method_(options.resolved.get_choice("static_method") == "piecewise-cubic"
                           ? StaticMethod::PiecewiseCubic
                           : StaticMethod::EigenfunctionExpansion),
        residual_check_max_R_(options.resolved.get_integer("residual_check_max_R")) {}
  const Chain& chain() const { return chain_; }
  StaticMethod static_method() const { return static_method_; }
  long residual_check_max_R() const { return residual_check_max_R_; }

  void modes(Result& res) override {
    if (!chain_.attached.empty()) {
      const Spectrum sp = attached_modes(s_, chain_.beam, mass_, chain_.attached, residual_check_max_R_, res);
      omegas_ = sp.omega_rad_s;
      rigid_ = sp.rigid;
      return;
    }
    const Spectrum sp = plain_modes(res);
    check_plain_modes(sp, res);
    omegas_ = sp.omega_rad_s;
    rigid_ = sp.rigid;
  }
  void shapes(Result& res) override {
    res.mode_shapes = DifferenceEqSolver::shapes(s_, chain_.beam, mass_, omegas_, rigid_);
  }
  void statics(Result& res) override;
  void campbell(Result& res) override {
    auto& sum = res.summary;
    if (s_.rotor->frame == Rotor::Frame::Rotating && mass_ != MassModel::Consistent) {
      sum.raise(Status::Unsupported, "difference_eq: the rotating frame's matrices (the appendix's A3) are the "
                                     "consistent mass's: its Campbell diagram needs --mass consistent");
      return;
    }
    res.campbell = rotor_campbell(s_, chain_.beam.R, mass_, sum);
    sum.method += "; Campbell: " + res.campbell.note;
  }

 private:
  /// The frequencies of the beam without attachments, in closed form.
  Spectrum plain_modes(Result& res) const {
    auto& sum = res.summary;
    const RegularBeam& beam = chain_.beam;
    const MassModel mass = mass_;
    const long R = beam.R;
    const int k = s_.request.modes;
    const Spectrum sp = natural_frequencies(beam, mass, k);
    sum.set_diagnostic("count_evaluations", static_cast<double>(sp.count_evaluations));
    sum.set_diagnostic("determinant_evaluations", static_cast<double>(sp.determinant_evaluations));
    for (std::size_t i = 0; i < sp.omega_rad_s.size(); ++i) {
      res.frequencies_rad_s.push_back(sp.omega_rad_s[i]);
      res.mode_families.push_back(static_cast<int>(i) < sp.rigid ? ModeFamily::Rigid : ModeFamily::BendingXZ);
    }
    if (static_cast<int>(sp.omega_rad_s.size()) < k)
      sum.warnings.push_back(fmt::format("the model has only {} natural frequencies ({} mass, R={}); {} requested",
                                         sp.available, to_string(mass), R, k));
    return sp;
  }

  /// Every frequency confirmed by the mode count, nothing missed below the first, and the mode
  /// shapes' residuals in the assembled equations.
  void check_plain_modes(const Spectrum& sp, Result& res) const {
    auto& sum = res.summary;
    const RegularBeam& beam = chain_.beam;
    const MassModel mass = mass_;
    const long R = beam.R;
    const long residual_check_max_R = residual_check_max_R_;
    // Checks. Every frequency is confirmed by the exact count just below and above it (O(1)
    // each; 1e-8 relative: near a mechanism the count resolves a near-rigid mode only to about
    // eps / K, K the dimensionless spring); for R up to residual_check_max_R the closed-form mode
    // shapes must also satisfy the assembled equations (normwise backward error, O(R) per mode).
    // Where the closed-form count cannot resolve a frequency (soft springs of 1e-13 of EI / a^3:
    // near-rigid modes, and the count's rounding near every mode of such a beam), the same
    // model's assembled banded K - lambda M decides in binary128 (assembled.hpp): its inertia
    // resolves what double cannot. Up to kQuadCountMaxR elements (cost O(R) software floats).
    constexpr long kQuadCountMaxR = 20000;
    long unconfirmed = 0, quad = 0;
    for (std::size_t i = sp.rigid; i < sp.omega_rad_s.size(); ++i) {
      const double l = sp.omega_rad_s[i] * sp.omega_rad_s[i];
      auto confirmed = [&](long below, long above) {
        return below <= static_cast<long>(i) && above >= static_cast<long>(i) + 1;
      };
      if (confirmed(count_below(beam, mass, l * (1.0 - 1e-8)), count_below(beam, mass, l * (1.0 + 1e-8)))) continue;
      if (beam.R <= kQuadCountMaxR) {
        const __float128 lq = static_cast<__float128>(l);
        const __float128 tau = static_cast<__float128>(1e-8);
        if (confirmed(assembled::count_below<__float128>(beam, mass, lq * (1 - tau)),
                      assembled::count_below<__float128>(beam, mass, lq * (1 + tau)))) {
          ++quad;
          continue;
        }
      }
      ++unconfirmed;
    }
    // Nothing missed below the first mode. The double count can miss near-rigid modes altogether
    // (springs of 4e-17 of EI / L^3: a heave at 1.3e5 rad/s missed, 9.1e6 reported as mode 1 and
    // confirmed, success); the binary128 count must find exactly the rigid ones below it.
    long missed = 0;
    if (sp.omega_rad_s.size() > static_cast<std::size_t>(sp.rigid) && beam.R <= kQuadCountMaxR) {
      const double l0 = sp.omega_rad_s[static_cast<std::size_t>(sp.rigid)] * sp.omega_rad_s[static_cast<std::size_t>(sp.rigid)];
      missed = assembled::count_below<__float128>(beam, mass, static_cast<__float128>(l0) * (1 - static_cast<__float128>(1e-8))) -
               sp.rigid;
      if (missed != 0)
        sum.raise(Status::NumericalIssue,
                  fmt::format("the binary128 count finds {} frequency(ies) below the first one reported ({:.6g} rad/s) "
                              "besides the {} rigid-body mode(s): near-rigid modes on soft springs that the "
                              "closed-form count in double does not resolve",
                              missed, sp.omega_rad_s[static_cast<std::size_t>(sp.rigid)], sp.rigid));
    }
    sum.set_diagnostic("root_bracket_relative", sp.max_bracket);
    if (quad > 0) sum.set_diagnostic("count_confirmations_binary128", static_cast<double>(quad));
    if (unconfirmed > 0)
      sum.raise(Status::NumericalIssue,
                fmt::format("{} frequency(ies) not confirmed by the mode count at omega^2 (1 -+ 1e-8){}", unconfirmed,
                            beam.R <= kQuadCountMaxR ? " in double or binary128"
                                                     : fmt::format(" (binary128 recount only up to {} elements)",
                                                                   kQuadCountMaxR)));
    if (R <= residual_check_max_R) {
      double worst = 0;
      for (std::size_t i = sp.rigid; i < sp.omega_rad_s.size(); ++i) {
        const ModeShape u = mode_shape(beam, mass, sp.omega_rad_s[i]);
        worst = std::max(worst, eigen_residual(beam, mass, sp.omega_rad_s[i], u));
      }
      sum.note_backward_error(worst);
    }
  }

  const Scene& s_;
  const MassModel mass_;
  const Chain chain_;
  const StaticMethod static_method_;
  const long residual_check_max_R_;
  std::vector<double> omegas_;  ///< the frequencies reported, rad/s
  int rigid_ = 0;               ///< of which rigid-body modes
};

/// Deflections at the probes (on nodes exact, between them by the element's Hermite interpolation
/// plus its clamped-clamped solution), the reactions and stress resultants, and the assembled
/// residual of the static solution.
void DifferenceEqKernels::statics(Result& res) {
  auto& sum = res.summary;
  const Scene& s = s_;
  const RegularBeam& beam = chain_.beam;
  const double L = beam.L;
  const long R = beam.R;
  const auto& loads = chain_.loads;
  const auto& attached = chain_.attached;
  const auto& element_loads = chain_.element_loads;
  const StaticMethod static_method = static_method_;
StaticSolution st;
std::vector<std::array<double, 2>> point_reactions;
try {
  st = solve_static_attached(beam, loads, attached, static_method, point_reactions);
} catch (const Mechanism& e) {
  sum.raise(Status::InvalidInput,
            InputError(s.source, "supports", std::string("static solve impossible: ") + e.what()).what());
  return;
}
int between = 0;
for (const auto& p : s.request.probes) {
  Deflection d;
  d.position = {p[0], 0.0};
  if (const long r = node_at(p[0], L, R); r >= 0) {
    d.w = st.w[r];
    d.theta_y = -st.slope[r];
  } else {
    const auto v = interpolate_loaded(beam, st, element_loads, p[0]);
    d.w = v[0];
    d.theta_y = -v[1];
    ++between;
  }
  res.deflections.push_back(d);
}
if (between)
  sum.warnings.push_back(fmt::format("{} probe(s) between nodes: Hermite interpolation of the element's nodal "
                                     "values, plus its clamped-clamped solution under a line load (exact)",
                                     between));
for (const auto& w : st.warnings) sum.warnings.push_back(w);
add_reactions_and_forces(s, beam, st, point_reactions, res);
sum.set_diagnostic("support_condition", st.support_condition);
// Near a mechanism (support_flexibility above 1e4 L^3/EI) the deflections are mostly
// rigid-body motion; the closed form keeps their digits, so this is information, not a warning.
sum.set_diagnostic("support_flexibility", st.support_flexibility);
sum.note_backward_error(attached_static_residual(beam, loads, attached, st, point_reactions));
}

}  // namespace

std::unique_ptr<Kernels> make_kernels(const Scene& s, long R, const Options& options, Result& res) {
  auto kernels = std::make_unique<DifferenceEqKernels>(s, options, chain_of(s, R));
  const Chain& c = kernels->chain();
  const RegularBeam& beam = c.beam;
  const auto& attached = c.attached;
  const auto& element_loads = c.element_loads;
  const bool other_components = c.other_components;
  const MassModel mass = options.mass;
  const StaticMethod static_method = kernels->static_method();
  const long residual_check_max_R = kernels->residual_check_max_R();
  auto& sum = res.summary;
  const int held = std::isinf(beam.k0) + std::isinf(beam.r0) + std::isinf(beam.kL) + std::isinf(beam.rL);
  sum.unknowns = 2 * (R + 1) - held;
  sum.converges_to_scene_theory = s.theory == Theory::EulerBernoulli;
  sum.model = "a regular chain of Hermite Euler-Bernoulli elements, tending to the euler-bernoulli beam";
  sum.method = fmt::format(
      "difference_eq: regular discrete Euler-Bernoulli beam, R={} Hermite elements (bending in x-z); "
      "modes: {} mass, 4x4 characteristic determinant in the difference-equation roots (scaled cosh/sinh) "
      "+ Wittrick-Williams count, Brent; statics: clamped-clamped {} + 4x4 spring superposition (closed form); "
      "checks: count at omega^2 (1 -+ 1e-8) per mode, assembled residuals (statics; mode shapes for R <= {})",
      R, to_string(mass), to_string(static_method), residual_check_max_R);
  if (s.theory == Theory::Timoshenko)
    sum.warnings.push_back("Euler-Bernoulli model used for a Timoshenko scene: shear deformation and rotary "
                           "inertia are neglected");
  if (s.physics != Physics::Bending)
    sum.warnings.push_back("physics '" + to_string(s.physics) +
                           "': only bending in x-z is solved (axial, torsion and x-y bending are not modelled)");
  if (other_components)
    sum.warnings.push_back("load and gravity components other than those of bending in x-z (Fz, My, qz, g_z) are "
                           "ignored");
  if (!attached.empty() || !element_loads.empty())
    sum.method += fmt::format("; {} support(s) / mass(es) at nodes: sub-chain closed forms assembled over their nodes "
                              "(count sum J0 + neg K), statics by superposing the point reactions; {} line load(s) "
                              "as their exact nodal equivalents",
                              attached.size(), element_loads.size());
  return kernels;
}

}  // namespace modalbench::difference_eq
