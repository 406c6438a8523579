#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "modalbench/difference_eq/assembled.hpp"
#include "modalbench/difference_eq/difference_eq.hpp"
#include "modalbench/timer.hpp"
#include "attachments.hpp"
#include "rotor.hpp"
#include "modalbench/equilibrium.hpp"

namespace modalbench::difference_eq {

namespace {

// Node tolerance: x = r L / R within 1e-9 L.
constexpr double kNodeTol = 1e-9;

// Smallest q <= qmax with x / L within kNodeTol of a multiple of 1/q (0 if none).
long denominator(double x_over_L, long qmax) {
  for (long q = 1; q <= qmax; ++q) {
    const double v = x_over_L * static_cast<double>(q);
    if (std::abs(v - std::round(v)) <= kNodeTol * static_cast<double>(q)) return q;
  }
  return 0;
}

// Least R that puts every load, support and mass (and with `probes`, every probe) on a node (0 if
// they are not commensurate). Loads, supports and masses must be nodes; a probe between nodes is
// interpolated (Hermite, plus the element's clamped-clamped solution), on a node it is exact.
long base_mesh(const Scene& s, bool probes) {
  std::vector<double> xs;
  for (const auto& l : s.loads) xs.push_back(l.x);
  if (probes)
    for (const auto& p : s.request.probes) xs.push_back(p[0]);
  for (const auto& p : s.point_supports) xs.push_back(p.x);
  for (const auto& m : s.masses) xs.push_back(m.x);
  for (const auto& q : s.line_loads) xs.insert(xs.end(), {q.from[0], q.to[0]});
  long base = 1;
  for (double x : xs) {
    const long q = denominator(x / s.geometry.length, 4096);
    if (q == 0) return 0;
    base = std::lcm(base, q);
    if (base > 1'000'000) return 0;
  }
  return base;
}

/// Modes with supports or masses at nodes (attachments.hpp): the sub-chain count and bisection;
/// every frequency confirmed by the assembled model's own Sturm count (another computation, O(R))
/// up to 20000 elements, and for R up to `max_check_R` by its mode shape's residual.
void attached_modes(const Scene& s, const RegularBeam& beam, MassModel mass, const std::vector<NodalAttachment>& at,
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
  constexpr long kAssembledCountMaxR = 20000;
  long unconfirmed = 0;
  double worst = 0;
  for (std::size_t i = static_cast<std::size_t>(sp.rigid); i < sp.omega_rad_s.size(); ++i) {
    const double l = sp.omega_rad_s[i] * sp.omega_rad_s[i];
    if (beam.R <= kAssembledCountMaxR &&
        !(assembled_count_attached(beam, mass, at, l * (1.0 - 1e-8)) <= static_cast<long>(i) &&
          assembled_count_attached(beam, mass, at, l * (1.0 + 1e-8)) >= static_cast<long>(i) + 1))
      ++unconfirmed;
    if (beam.R <= max_check_R) {
      double be = 0;
      mode_shape_attached(beam, mass, at, sp.omega_rad_s[i], be);
      worst = std::max(worst, be);
    }
  }
  sum.set_diagnostic("root_bracket_relative", sp.max_bracket);
  if (unconfirmed > 0)
    sum.raise(Status::NumericalIssue,
              fmt::format("{} frequency(ies) not confirmed by the assembled model's count at omega^2 (1 -+ 1e-8)",
                          unconfirmed));
  if (beam.R <= max_check_R) sum.note_backward_error(worst);
  if (s.request.shapes && !sp.omega_rad_s.empty())
    res.mode_shapes = DifferenceEqSolver::shapes(s, beam, mass, sp.omega_rad_s, sp.rigid);
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

}  // namespace

RegularBeam beam_of(const Scene& s, long R) {
  const Section sec = s.section();
  RegularBeam b;
  b.EI = s.material.E * sec.Iy;
  b.rhoA = s.material.rho * sec.A;
  b.L = s.geometry.length;
  b.R = R;
  b.k0 = s.x0.translational;
  b.r0 = s.x0.rotational;
  b.kL = s.xL.translational;
  b.rL = s.xL.rotational;
  return b;
}

Capability DifferenceEqSolver::supports(const Scene& s) const {
  Capability c;
  if (!s.is_beam()) {
    c.reason = "difference_eq solves beams only (a regular chain of Hermite beam elements); plates are not supported";
    return c;
  }
  if (s.is_stepped()) {
    c.reason = "difference_eq cannot model a stepped beam ([[segments]]): its closed forms need a regular chain of "
               "identical elements";
    return c;
  }
  c.modes = c.statics = true;
  c.frf = false;
  // The model restrictions (Euler-Bernoulli, bending in x-z) are stated by do_solve in the
  // result's warnings; here only what is not computed at all.
  c.reason = "FRF is not implemented by difference_eq (modes and statics only)";
  if (s.rotor) {
    const std::string why = rotor_refusal(s);
    c.campbell = why.empty();
    if (!why.empty()) c.reason += "; " + why;
  }
  if (!s.point_supports.empty() && rigid_body_modes(beam_of(s, 1)) > 0) {
    c.statics = false;
    c.reason += "; statics with supports between the ends need end supports that hold the beam by themselves "
                "(the points' reactions are superposed on that beam's closed form)";
  }
  return c;
}

/// The least R of base_mesh with the probes on nodes where they can be, else without them.
long base_mesh(const Scene& s) {
  const long with_probes = base_mesh(s, true);
  return with_probes > 0 ? with_probes : base_mesh(s, false);
}

Discretization DifferenceEqSolver::default_mesh(const Scene& s) const {
  const long base = base_mesh(s);
  const long want = std::max<long>(32, 8L * s.request.modes);
  if (base == 0) return Discretization{{64}};
  long R = base * ((want + base - 1) / base);
  if (R > 1'000'000) R = base;
  return Discretization{{static_cast<int>(R)}};
}

std::vector<Discretization> DifferenceEqSolver::mesh_ladder(const Scene& s) const {
  const long base = base_mesh(s);
  std::vector<Discretization> out;
  if (base == 0 || base > 4096) return {default_mesh(s)};
  long R = base;
  while (R < 4) R *= 2;
  for (; R <= 4096; R *= 2) out.push_back(Discretization{{static_cast<int>(R)}});
  return out;
}

std::vector<Discretization> DifferenceEqSolver::stress_meshes(const Scene& s) const {
  std::vector<Discretization> out{mesh_ladder(s).back()};
  const long base = base_mesh(s);
  if (base == 0) return out;
  const long R = base * (1'000'000 / base);
  if (R > out.back().counts[0]) out.push_back(Discretization{{static_cast<int>(R)}});
  return out;
}

std::optional<CoarserMesh> DifferenceEqSolver::coarser_mesh(const Scene& s, const Discretization& mesh,
                                                             const Options& options) const {
  if (mesh.counts.size() != 1 || mesh.counts[0] < 4 || mesh.counts[0] % 2) return std::nullopt;
  const long base = base_mesh(s, false);
  const int half = mesh.counts[0] / 2;
  if (base == 0 || half % base) return std::nullopt;  // loads, supports or masses would leave the nodes
  // Hermite cubics: eigenvalues converge at h^4 with the consistent mass, h^2 with the lumped one.
  // The expansions are even in h: h^4 then h^6 (consistent), h^2 then h^4 (lumped).
  return options.mass == MassModel::Consistent ? CoarserMesh{{{half}}, 2.0, 4.0, 6.0} : CoarserMesh{{{half}}, 2.0, 2.0, 4.0};
}

std::optional<Discretization> DifferenceEqSolver::finer_mesh(const Scene& s, const Discretization& mesh,
                                                              double factor) const {
  const long base = base_mesh(s);
  if (mesh.counts.size() != 1 || base == 0) return std::nullopt;
  long R = std::lround(std::ceil(mesh.counts[0] * factor));
  R = base * ((R + 2 * base - 1) / (2 * base)) * 2;  // even, loads (and probes where they can be) on nodes
  if (R > 1'000'000) return std::nullopt;
  return Discretization{{static_cast<int>(R)}};
}

// The closed forms cost O(1) per mode and O(R) per load; the banded FE check O(R) per solve.
ResourceEstimate DifferenceEqSolver::estimate(const Scene& s, const Discretization& mesh, const Options&) const {
  ResourceEstimate e;
  if (mesh.counts.size() != 1) return e;
  const double R = mesh.counts[0];
  const double loads = static_cast<double>(s.loads.size()), probes = static_cast<double>(s.request.probes.size());
  e.bytes = 400.0 * R + 64.0 * loads * probes;
  e.seconds = 2e-7 * R * (2 + loads) + 1e-7 * loads * probes + 2e-4 * s.request.modes;
  e.basis = fmt::format("R = {} elements, {} loads, {} probes, {} modes", mesh.counts[0], s.loads.size(),
                        s.request.probes.size(), s.request.modes);
  return e;
}

std::vector<OptionSpec> DifferenceEqSolver::option_specs() const {
  using T = OptionSpec::Type;
  return {{"static_method", T::Choice,
           config_.static_method == StaticMethod::PiecewiseCubic ? "piecewise-cubic" : "eigenfunction-expansion",
           {"piecewise-cubic", "eigenfunction-expansion"}, 0, 0,
           "statics: clamped-clamped solution by the closed piecewise cubic (O(R)) or by the paper's eigenfunction "
           "expansion (7) (O(R^2))"},
          {"residual_check_max_R", T::Integer, std::to_string(config_.residual_check_max_R), {}, 0, 1e7,
           "check the closed-form mode shapes against the assembled equations up to this R (O(R) per mode)"}};
}

void DifferenceEqSolver::do_solve(const Scene& s, const Discretization& mesh, const Options& options,
                                  Result& res) const {
  if (mesh.counts.size() != 1)
    throw InputError("command line", "--mesh",
                     "difference_eq takes one integer R >= 1, the number of elements (got '" + mesh.spec() + "')");
  const long R = mesh.counts[0];
  if (R < 1 || R > RegularBeam::kMaxElements)
    throw InputError("command line", "--mesh",
                     fmt::format("R must satisfy 1 <= R <= {} (got '{}')", RegularBeam::kMaxElements, mesh.spec()));
  const MassModel mass = options.mass;
  const StaticMethod static_method = options.resolved.get_choice("static_method") == "piecewise-cubic"
                                         ? StaticMethod::PiecewiseCubic
                                         : StaticMethod::EigenfunctionExpansion;
  const long residual_check_max_R = options.resolved.get_integer("residual_check_max_R");
  Timer timer;
  auto& sum = res.summary;
  const RegularBeam beam = beam_of(s, R);
  const double L = beam.L;
  const int held = std::isinf(beam.k0) + std::isinf(beam.r0) + std::isinf(beam.kL) + std::isinf(beam.rL);
  sum.unknowns = 2 * (R + 1) - held;
  sum.converges_to_scene_theory = s.theory == Theory::EulerBernoulli;
  sum.model = "a regular chain of Hermite Euler-Bernoulli elements, tending to the euler-bernoulli beam";

  // Loads, supports between the ends and masses must sit on nodes.
  const std::vector<NodalAttachment> attached = attachments_of(s, R);
  const std::vector<ElementLoad> element_loads = element_loads_of(s, R);
  std::vector<NodalLoad> loads;
  bool other_components = false;
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
  for (const NodalLoad& l : equivalent_nodal_loads(beam, element_loads)) loads.push_back(l);
  for (const auto& q : s.line_loads)
    other_components = other_components || q.qx[0] != 0 || q.qx[1] != 0 || q.qy[0] != 0 || q.qy[1] != 0;
  if (s.gravity) other_components = other_components || (*s.gravity)[0] != 0 || (*s.gravity)[1] != 0;

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

  sum.timings_s.build += timer.lap();

  // Free vibration.
  const int k = s.request.modes;
  if (k > 0 && !attached.empty()) {
    attached_modes(s, beam, mass, attached, residual_check_max_R, res);
    sum.timings_s.modes += timer.lap();
  } else if (k > 0) {
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
    if (s.request.shapes && !sp.omega_rad_s.empty()) res.mode_shapes = shapes(s, beam, mass, sp.omega_rad_s, sp.rigid);
    sum.timings_s.modes += timer.lap();
  }

  // A rotor's whirl (the appendix's A3 chain, per mode).
  if (s.rotor && s.rotor->frame == Rotor::Frame::Rotating && mass != MassModel::Consistent) {
    sum.raise(Status::Unsupported, "difference_eq: the rotating frame's matrices (the appendix's A3) are the "
                                   "consistent mass's: its Campbell diagram needs --mass consistent");
  } else if (s.rotor) {
    try {
      res.campbell = rotor_campbell(s, R, mass, sum);
      sum.method += "; Campbell: " + res.campbell.note;
    } catch (const std::exception& e) {
      sum.raise(Status::NumericalIssue, std::string("difference_eq: Campbell diagram: ") + e.what());
    }
    sum.timings_s.campbell += timer.lap();
  }

  // Statics at the probes.
  if (!s.request.probes.empty()) {
    StaticSolution st;
    std::vector<std::array<double, 2>> point_reactions;
    try {
      st = solve_static_attached(beam, loads, attached, static_method, point_reactions);
    } catch (const Mechanism& e) {
      sum.raise(Status::InvalidInput,
                InputError(s.source, "supports", std::string("static solve impossible: ") + e.what()).what());
      sum.timings_s.statics += timer.lap();
      return;
    } catch (const std::runtime_error& e) {
      sum.raise(Status::NumericalIssue, std::string("difference_eq: statics: ") + e.what());
      sum.timings_s.statics += timer.lap();
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
    sum.timings_s.statics += timer.lap();
  }
}

}  // namespace modalbench::difference_eq
