#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "modalbench/dtfm/dtfm.hpp"
#include "modalbench/equilibrium.hpp"
#include "modalbench/timer.hpp"
#include "plate_reactions.hpp"
#include "rotor.hpp"

namespace modalbench::dtfm {

namespace {

/// The supports' actions as the result's reactions (named by the scene's supports; a node that only
/// carries a mass has none) and, from them, the resultants at the probes by the equilibrium of the
/// free body left of each (those of the scene's physics; the others stay 0).
void add_reactions_and_forces(const Scene& s, const std::vector<PointReaction>& pr, Result& r) {
  const double L = s.geometry.length;
  for (const PointReaction& p : pr) {
    std::string name;
    if (std::abs(p.x) <= 1e-12 * L && !s.x0.is_free()) name = "x0";
    if (std::abs(p.x - L) <= 1e-12 * L && !s.xL.is_free()) name = "xL";
    for (std::size_t i = 0; i < s.point_supports.size(); ++i)
      if (std::abs(s.point_supports[i].x - p.x) <= 1e-12 * L) name = fmt::format("points[{}]", i);
    if (name.empty()) continue;
    Reaction re;
    re.support = name;
    re.position = {p.x, 0.0};
    re.force = {p.F[0], p.F[1], p.F[2]};
    re.moment = {p.F[3], p.F[4], p.F[5]};
    r.reactions.push_back(re);
  }
  for (Deflection& d : r.deflections) {
    const InternalForces f = free_body_forces(s, r.reactions, d.position[0]);
    d.forces = {};
    d.forces.My = f.My;
    d.forces.Qz = f.Qz;
    if (carries_axial(s.physics)) d.forces.N = f.N;
    if (carries_xy(s.physics)) {
      d.forces.Mz = f.Mz;
      d.forces.Qy = f.Qy;
    }
    if (carries_torsion(s.physics)) d.forces.T = f.T;
    d.has_forces = true;
  }
}

/// A plate's reactions (detail::plate_reactions), with how well they balance the loads: their sum
/// against the total load, the rounding of K d - f on the held fields (stiff layers: 1e-9 of the
/// load at 32 strips, 3e-7 at 88); above 1e-6 a warning says so.
void add_plate_reactions(const Scene& s, const PrismModel& model, const FieldIntegrals& fi, Result& r) {
  r.reactions = detail::plate_reactions(s, model, fi);
  double load = 0, total = 0, scale = 0;
  for (const PointLoad& p : s.all_point_loads()) {
    load += p.Fz;
    scale += std::abs(p.Fz);
  }
  for (const DistributedLoad& d : s.all_distributed_loads()) {
    const double F = d.qz[0] * (d.to[0] - d.from[0]) * (d.to[1] - d.from[1]);
    load += F;
    scale += std::abs(F);
  }
  for (const Reaction& e : r.reactions) total += e.force[2];
  const double imbalance = scale > 0 ? std::abs(total + load) / scale : 0.0;
  r.summary.set_diagnostic("reaction_balance_relative", imbalance);
  if (imbalance > 1e-6)
    r.summary.warnings.push_back(fmt::format("plate reactions balance the loads only to {:.1e} of them (rounding of "
                                             "the stiff strip layers)",
                                             imbalance));
}

}  // namespace

Capability DtfmSolver::supports(const Scene& s) const {
  Capability c;
  c.modes = c.statics = c.frf = true;
  if (s.rotor) {
    c.reason = detail::rotor_refusal(s);
    c.campbell = c.reason.empty();
  }
  return c;
}

namespace {

/// The least strip count in [lo, hi] that is a multiple of 4 and puts every point of the plate's
/// loads, probes, point supports, masses and FRF points on a strip line (y = j b / n) on it and on
/// its two halvings (the error estimate's meshes), or -1 where none does or there is no such point
/// off the edges. Off the lines a point is
/// shared between the two lines around it, in proportions that change from mesh to mesh: the
/// deflection under the paper plate's point load (y = b / 3) came out 9.7e-4 off on 92 strips
/// (refined from 24) where the estimate from 61 and 92 said 2.1e-4; on 96 strips it is 1.5e-4 off,
/// estimated 3.9e-4.
int strips_on_points(const Scene& s, long lo, long hi) {
  std::vector<double> ys;
  for (const PointLoad& p : s.all_point_loads()) ys.push_back(p.y);
  for (const auto& p : s.request.probes) ys.push_back(p[1]);
  for (const PointSupport& p : s.point_supports) ys.push_back(p.y);
  for (const PointMass& p : s.masses) ys.push_back(p.y);
  if (s.request.frf) ys.insert(ys.end(), {s.request.frf->excite[1], s.request.frf->observe[1]});
  // The edges are lines of every mesh; a plate without inner points keeps its count.
  std::erase_if(ys, [&](double y) { return y <= 0.0 || y >= s.geometry.width; });
  if (ys.empty()) return -1;
  for (long n = lo + (4 - lo % 4) % 4; n <= hi; n += 4) {
    bool on = true;
    for (double y : ys) {
      const double t = y / s.geometry.width * static_cast<double>(n / 4);
      on = on && std::abs(t - std::round(t)) <= 1e-9 * static_cast<double>(n);
    }
    if (on) return static_cast<int>(n);
  }
  return -1;
}

/// Where an option's value came from: "default", the scene file, or "command line".
const std::string& option_source(const ResolvedOptions& o, const std::string& key) {
  for (const auto& e : o.entries)
    if (e.spec.key == key) return e.source;
  throw std::logic_error("dtfm: no option " + key);
}

}  // namespace

Discretization DtfmSolver::default_mesh(const Scene& scene) const {
  // A beam: one prism, the beam of the scene's theory itself (no discretization error). A section
  // cut into prisms (2x2, ...) tends to 3D elasticity, another model: a deliberate --mesh choice.
  if (!scene.is_plate()) return Discretization::parse("1x1");
  // Strips across the width: about 6 per half-wave across it among the requested modes, and the
  // points on strip lines where a count below twice that puts them there.
  const int n_max = plate_half_waves(scene.geometry.length, scene.geometry.width, std::max(1, scene.request.modes)).second;
  // A tolerance below 6e-4 starts (6e-4 / tolerance)^(1/4) times finer where the strip ends are
  // held (the family whose frequencies are extrapolated at fourth order): on the paper plate as a
  // Mindlin plate (8 modes) the 24 strips of 6 per half-wave gave an extrapolated estimate of 2.5e-3
  // (mode 8 not yet asymptotic), 36 strips 9.5e-5 and 48 strips 2.0e-5, so at 1e-4 the refinement
  // went 24 -> 60 (0.42 s) where 38 strips meet it at once.
  const auto held = [](const Support& e) { return e.kind == "pinned" || e.kind == "clamped"; };
  const double tol = scene.request.tolerance;
  const double finer = held(scene.x0) && held(scene.xL) && tol > 0 && tol < 6e-4 ? std::pow(6e-4 / tol, 0.25) : 1.0;
  const int n = std::clamp(static_cast<int>(std::ceil(6 * (n_max + 1) * finer)), 10, 400);
  const int on = strips_on_points(scene, n, std::min(2 * n, 400));
  return Discretization{{on > 0 ? on : n}};
}

std::optional<Discretization> DtfmSolver::theory_mesh(const Scene& scene) const {
  if (scene.is_plate()) return default_mesh(scene);
  return Discretization::parse("1x1");
}

std::optional<CoarserMesh> DtfmSolver::coarser_mesh(const Scene& scene, const Discretization& mesh, const Options&) const {
  if (scene.is_plate()) {
    if (mesh.counts.size() != 1 || mesh.counts[0] < 4) return std::nullopt;
    const int n = mesh.counts[0] / 2;
    // Strips: the extrapolated frequencies converge at fourth order where both strip ends (x0, xL)
    // are held, pinned or clamped (tests/solvers/test_extrapolation_orders: the paper plate; its
    // variants with the long edges clamped or free were within their estimates too). A free or
    // sprung end is not extrapolated: on NAFEMS FV16's cantilever the 32-strip values came out
    // 1.7e-4 and 4.8e-4 off (modes 2 and 5) where the estimates said 1.8e-5 and 3.0e-5 (against
    // rfem's 192 x 192 extrapolation, itself within 1.7e-5).
    const auto held = [](const Support& e) { return e.kind == "pinned" || e.kind == "clamped"; };
    const double next = held(scene.x0) && held(scene.xL) ? 4.0 : std::numeric_limits<double>::quiet_NaN();
    return CoarserMesh{{{n}}, static_cast<double>(mesh.counts[0]) / n, 2.0, next};
  }
  // A one-prism beam is the exact Timoshenko beam of its section: no discretization error.
  if (mesh.counts.empty() || *std::max_element(mesh.counts.begin(), mesh.counts.end()) < 2) return std::nullopt;
  CoarserMesh c;
  c.ratio = 1;
  for (int n : mesh.counts) {
    c.mesh.counts.push_back(std::max(1, n / 2));
    c.ratio = std::max(c.ratio, static_cast<double>(n) / c.mesh.counts.back());
  }
  if (c.mesh.counts.size() == 1) c.mesh.counts.push_back(c.mesh.counts[0]);
  c.order = 2;
  return c;
}

std::optional<Discretization> DtfmSolver::finer_mesh(const Scene& scene, const Discretization& mesh, double factor) const {
  if (!scene.is_plate() || mesh.counts.size() != 1) return std::nullopt;  // sections tend to 3D: not a default
  const long n = std::lround(std::ceil(mesh.counts[0] * factor));
  if (n > 400) return std::nullopt;
  const int on = strips_on_points(scene, n, std::min<long>(2 * n, 400));  // the points on strip lines
  return Discretization{{on > 0 ? on : static_cast<int>(n)}};
}

// Fitted to bench_dtfm_timing on the 2-core machine, built with MODALBENCH_ARCH=none (the slower of
// the two builds; x86-64-v3 takes 0.13 s): a 40-strip plate takes 0.21 s for 8 modes (its two
// symmetry classes side by side, about 111 count evaluations) and the cost grows about 5- to 8-fold
// per doubling of strips (the segment exponentials and doublings); the spatial 6 x 6 beam (216
// fields) 0.23 s for 8 modes with x86-64-v3; a FRF sample costs about one count evaluation. Memory
// is a few dense blocks per line and segment.
ResourceEstimate DtfmSolver::estimate(const Scene& scene, const Discretization& mesh, const Options&) const {
  ResourceEstimate e;
  double fields = 0;  // prism DOF fields in the model
  if (scene.is_plate() && mesh.counts.size() == 1) fields = 3.0 * (mesh.counts[0] + 1);
  else if (!scene.is_plate() && !mesh.counts.empty()) {
    const double per = scene.physics == Physics::Spatial   ? 6
                       : scene.physics == Physics::Lateral ? 4
                       : scene.physics == Physics::Planar  ? 3
                                                           : 2;
    fields = per * mesh.counts[0] * (mesh.counts.size() > 1 ? mesh.counts[1] : mesh.counts[0]);
  }
  if (fields <= 0) return e;
  const double scale = std::pow(fields / 123.0, 3.0);  // 40 strips: 123 fields
  const double per_eval = 0.21 / 111.0 * scale;       // ~111 count evaluations for 8 modes
  const auto& rq = scene.request;
  e.seconds = per_eval * (20.0 * std::max(0, rq.modes) + 10.0 * static_cast<double>(rq.probes.size()) + (rq.frf ? rq.frf->points : 0));
  // A rotor (one prism): two whirl lines per spin, each sliced like the modes, and the criticals
  // (measured: 86 ms for the Timoshenko shaft's 31 spins of 4 roots, 89 ms for Friswell's 21 of 6,
  // 76 ms for a stepped shaft's 7 of 6).
  if (scene.rotor) e.seconds += 0.02 + 0.5e-3 * std::max(1, rq.modes) * static_cast<double>(scene.rotor->spin.size());
  e.bytes = 8.0 * fields * fields * 200.0;
  e.basis = fmt::format("{} prism fields, {} modes, {} FRF samples", fields, rq.modes, rq.frf ? rq.frf->points : 0);
  return e;
}

std::vector<Discretization> DtfmSolver::mesh_ladder(const Scene& scene) const {
  std::vector<const char*> specs;
  if (scene.is_plate()) specs = {"4", "7", "10", "20", "40"};
  else if (scene.cross_section.shape != SectionShape::Rectangle || scene.is_stepped() ||
           scene.physics == Physics::Lateral)
    specs = {"1x1"};  // only uniform rectangles are cut, and not for a rotor's lateral model
  else if (scene.physics == Physics::Spatial) specs = {"1x1", "2x2", "4x4", "6x6"};  // 6 fields per prism
  else specs = {"1x1", "2x2", "4x4", "8x8"};
  std::vector<Discretization> out;
  for (const char* m : specs) out.push_back(Discretization::parse(m));
  return out;
}

std::vector<Discretization> DtfmSolver::stress_meshes(const Scene& scene) const {
  return {mesh_ladder(scene).back()};
}

std::vector<OptionSpec> DtfmSolver::option_specs() const {
  using T = OptionSpec::Type;
  const SolveControls c;
  auto num = [](double v) { return fmt::format("{}", v); };
  return {
      {"layers", T::Choice, to_string(options_.layers), {"consistent", "staggered", "paper"}, 0, 0,
       "spring layers between prisms: consistent (Eq. (25) springs + cross terms), staggered, or paper (Eq. (25) "
       "as printed)"},
      {"kirchhoff_penalty", T::Number, num(options_.kirchhoff_penalty), {}, 1e-3, 1e6,
       "Kirchhoff plates: layer shear penalty in units of 12 D / dy^3"},
      {"rel_tol", T::Number, num(c.rel_tol), {}, 1e-15, 1e-3,
       "relative tolerance on omega^2 (plates, where not given: 1e-4 of [request] tolerance if larger)"},
      {"im_h", T::Number, num(c.im_h), {}, 1e-3, 3.0, "base pieces: bound on |Im p| h"},
      {"re_h", T::Number, num(c.re_h), {}, 1e-3, 20.0, "base pieces: bound on |Re p| h"},
      {"family_threshold", T::Number, num(c.family_threshold), {}, 0.0, 1.0,
       "beam modes are labelled by family when the rigid-section share of kinetic energy reaches this"},
  };
}

ModeShapes DtfmSolver::shapes(const Scene& scene, LineAnalysis& la, const ModeList& ml) {
  const bool beam = scene.is_beam();
  const std::array<bool, 3> directions = {beam && carries_axial(scene.physics), beam && carries_xy(scene.physics), true};
  const bool moments = beam && scene.request.shapes && scene.request.shapes->moments;
  ModeShapes ms = la.mode_shapes(ml, scene.shape_points(), scene.shape_components(), directions, moments);
  const auto& g = scene.geometry;
  ms.total_mass = scene.material.rho * g.length * g.width * g.height;
  if (beam) {
    ms.total_mass = 0;
    for (const Segment& p : scene.beam_pieces()) ms.total_mass += p.material.rho * p.properties().A * p.length();
    for (const PointMass& pm : scene.masses) ms.total_mass += pm.mass;
  }
  ms.note = std::string("dtfm: null vector of each mode's symmetry-class dynamic stiffness K(omega^2) (rigid modes: "
                        "its null space at omega = 0; repeated roots: mass-orthonormalized), the exact prism fields "
                        "between nodes by the transfer matrix, modal mass and participation by GSL quadrature of "
                        "them; values are the section response at nodes (") +
            (beam ? "rigid-body fit of the prisms" : "linear in y between strip lines") + ")" +
            (moments ? "; moments My: the section resultant of the state's forces at the nodes" : "");
  finish_mode_shapes(ms);
  return ms;
}

void DtfmSolver::do_solve(const Scene& scene, const Discretization& mesh, const Options& options,
                          Result& r) const {
  Timer timer;
  const ResolvedOptions& o = options.resolved;
  ModelOptions mo = options_;
  const std::string& layers = o.get_choice("layers");
  mo.layers = layers == "paper" ? LayerModel::Paper : layers == "staggered" ? LayerModel::Staggered : LayerModel::Consistent;
  mo.kirchhoff_penalty = o.get_number("kirchhoff_penalty");
  SolveControls controls;
  controls.rel_tol = o.get_number("rel_tol");
  // A plate's strips carry a discretization error of the order of the tolerance: by default the
  // polish stops at 1e-4 of it (free plate of 180 strips: the count's determinant is rounded at
  // 1e-7 relative, and polishing to that floor took some 20 counts per mode, half of them on the
  // last digits). The bracket is then the solve's bound (below), and a rel_tol given is kept.
  const bool polish_from_tolerance = scene.is_plate() && option_source(o, "rel_tol") == "default" &&
                                     1e-4 * scene.request.tolerance > controls.rel_tol;
  if (polish_from_tolerance) controls.rel_tol = 1e-4 * scene.request.tolerance;
  controls.im_h = o.get_number("im_h");
  controls.re_h = o.get_number("re_h");
  controls.family_threshold = o.get_number("family_threshold");
  const PrismModel model = build_model(scene, mesh, mo);
  auto& sum = r.summary;
  sum.method = "dtfm: " + model.description +
               "; segment dynamic stiffness, Wittrick-Williams count with Brent polish" +
               (polish_from_tolerance ? fmt::format(" to {:.2g} in omega^2 (1e-4 of the tolerance)", controls.rel_tol)
                                      : std::string());
  // Modelling notes (not doubts about the numbers) belong to the method, not the warnings.
  for (const auto& n : model.notes) sum.method += "; " + n;
  // One prism is the scene's beam theory exactly; finer sections tend to a 3D-like model. Plate
  // strips tend to the Kirchhoff or Mindlin plate, except with the paper's own layer model.
  sum.converges_to_scene_theory =
      scene.is_beam() ? model.ny * model.nz == 1 : mo.layers != LayerModel::Paper;
  if (scene.is_beam())
    sum.model = sum.converges_to_scene_theory
                    ? fmt::format("one prism: the {} beam itself", to_string(scene.theory))
                    : fmt::format("a {}x{} prism section, tending to 3D elasticity", model.ny, model.nz);
  else
    sum.model = sum.converges_to_scene_theory
                    ? fmt::format("prism strips, tending to the {} plate", to_string(scene.theory))
                    : "prism strips with the paper's layer model, tending to that model";
  sum.set_diagnostic("fields", model.m);
  if (options.mass == MassModel::Lumped)
    sum.warnings.push_back("--mass lumped does not apply: the prisms' mass is distributed (consistent) along x");
  // A modelling note as well: the scene's theory names what `exact` solves; the prism model is
  // its own model of the section, as for the 3D references.
  if (scene.is_beam() && scene.theory == Theory::EulerBernoulli && (model.nz > 1 || model.ny > 1))
    sum.method += fmt::format(
        "; scene theory euler-bernoulli applies to each prism only: the {}x{} section's layers deform in shear, so the "
        "beam as a whole carries shear deformation (like a Timoshenko or 3D model) and its higher bending modes lie "
        "below the Euler-Bernoulli values (use --mesh 1x1 for the Euler-Bernoulli beam itself)",
        model.ny, model.nz);
  LineAnalysis la(model, controls);
  sum.timings_s.build += timer.lap();

  // A one-prism beam is the beam of its section itself: no discretization error to estimate. (Its
  // polish tolerance is no bound: on a shaft with E scaled by 1e-6 the axial mode came out 1.7e-8
  // from the transfer-matrix value, fuzz seed 1, case 613.)
  if (scene.is_beam() && model.prisms.size() == 1) sum.set_diagnostic("exact_segments", 1.0);
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
    if (!ml.count_consistent) sum.raise(Status::NumericalIssue, "dtfm: " + ml.count_message);
    // The solve's own error bound on the frequencies (half the eigenvalues'): the near-rigid
    // modes' Rayleigh-Ritz bound, the bracket of any value polished only to the determinant's
    // rounding floor, and a plate's polish tolerance where it followed the request's.
    const double polished = polish_from_tolerance ? controls.rel_tol : 0.0;
    if (ml.near_rigid > 0 || ml.polish_floor_width > 0 || polished > 0)
      sum.set_diagnostic("frequency_solve_error_bound",
                         0.5 * std::max({ml.near_rigid_bound, ml.polish_floor_width, polished}));
    if (ml.polish_floor_width > 0) sum.set_diagnostic("polish_floor_frequency_error_bound", 0.5 * ml.polish_floor_width);
    if (ml.near_rigid > 0) {
      const double bound = 0.5 * ml.near_rigid_bound;
      sum.set_diagnostic("near_rigid_frequency_error_bound", bound);
      if (!(bound <= 1e-2 * scene.request.tolerance))
        sum.raise(Status::NumericalIssue,
                  fmt::format("dtfm: {} near-rigid mode(s): their rigid-body Rayleigh-Ritz frequencies are only known "
                              "to {:.2g}, above 1 % of the tolerance {:.2g}",
                              ml.near_rigid, bound, scene.request.tolerance));
    }
    if (static_cast<int>(ml.omega_rad_s.size()) < k)
      sum.raise(Status::NotConverged, fmt::format("dtfm: only {} of {} modes found", ml.omega_rad_s.size(), k));
    if (scene.request.shapes && !ml.omega_rad_s.empty()) {
      try {
        r.mode_shapes = shapes(scene, la, ml);
        sum.set_diagnostic("shape_unknowns", static_cast<double>(la.max_shape_unknowns()));
      } catch (const std::exception& e) {
        r.mode_shapes = {};
        sum.raise(Status::NumericalIssue, std::string("dtfm: mode shapes: ") + e.what());
      }
    }
    sum.timings_s.modes += timer.lap();
  }
  if (!scene.request.probes.empty()) {
    try {
      // A plate's rigid motions that no edge restrains, from the supports' pattern: the count
      // near zero in statics() cannot see them behind a fine mesh's stiff penalty layers (50
      // strips of a plate guided on every edge counted none, and w came out 184 m).
      if (const std::vector<std::string> free = free_plate_rigid_motions(scene); !free.empty())
        throw std::runtime_error(fmt::format("mechanism: the supports leave {} rigid-body motion(s) free ({})",
                                             free.size(), fmt::join(free, "; ")));
      std::vector<PointReaction> pr;
      FieldIntegrals fi;
      r.deflections = la.statics(scene.all_point_loads(), scene.request.probes, scene.all_distributed_loads(),
                                 scene.is_beam() ? &pr : nullptr, scene.is_plate() ? &fi : nullptr);
      if (scene.is_beam()) add_reactions_and_forces(scene, pr, r);
      else if (fi.complete) add_plate_reactions(scene, model, fi, r);
    } catch (const std::runtime_error& e) {
      r.deflections.clear();
      // Only a mechanism is the input's fault; any other failure is a numerical breakdown.
      if (std::string(e.what()).rfind("mechanism", 0) == 0)
        sum.raise(Status::InvalidInput, scene.source + ": supports: static solve impossible: " + e.what());
      else
        sum.raise(Status::NumericalIssue, std::string("dtfm: statics: ") + e.what());
    }
    sum.timings_s.statics += timer.lap();
  }
  if (scene.request.frf) {
    const auto& f = *scene.request.frf;
    std::vector<double> omegas;
    for (int i = 0; i < f.points; ++i) omegas.push_back(f.omega_min + (f.omega_max - f.omega_min) * i / (f.points - 1));
    int skipped = 0;
    std::string reason;
    const auto H = la.receptance(f.excite, f.observe, omegas, scene.material.loss_factor, &skipped, &reason);
    for (std::size_t i = 0; i < omegas.size(); ++i)
      if (std::isfinite(std::abs(H[i]))) r.frf.push_back({omegas[i], H[i]});
    note_frf_omissions(sum, skipped, f.points, reason);
    sum.timings_s.frf += timer.lap();
  }
  if (scene.rotor) {
    // Its failure is the Campbell diagram's alone: the modes and statics stand.
    try {
      r.campbell = detail::rotor_campbell(scene, mo, controls, sum);
      sum.method += "; Campbell: " + r.campbell.note;
    } catch (const std::runtime_error& e) {
      sum.raise(Status::NumericalIssue, std::string("dtfm: Campbell diagram: ") + e.what());
    }
    sum.timings_s.campbell += timer.lap();
  }
  sum.set_diagnostic("count_evaluations",
                     std::max(0.0, sum.diagnostic("count_evaluations")) + static_cast<double>(la.evaluations()));
  sum.set_diagnostic("segment_asymmetry", la.max_asymmetry());
  sum.unknowns = la.max_unknowns();
  sum.threads = std::max(sum.threads, la.threads_used());
  if (la.max_asymmetry() > 1e-6)
    sum.warnings.push_back(fmt::format("segment matrices asymmetric to {:.2e}: the state matrices are not "
                                       "Hamiltonian to working precision",
                                       la.max_asymmetry()));
}

}  // namespace modalbench::dtfm
