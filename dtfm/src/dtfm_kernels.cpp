// dtfm's kernels (kernels.hpp in core): the modes, shapes, statics, FRF and Campbell diagram of one
// prism model solved by its segment dynamic stiffness (LineAnalysis).
#include "dtfm_kernels.hpp"
#include "staircase.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "modalbench/equilibrium.hpp"
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

/// Where an option's value came from: "default", the scene file, or "command line".
const std::string& option_source(const ResolvedOptions& o, const std::string& key) {
  for (const auto& e : o.entries)
    if (e.spec.key == key) return e.source;
  throw std::logic_error("dtfm: no option " + key);
}

/// Mass-normalized shapes of the modes `ml` (scene.request.shapes).
ModeShapes mode_shapes(const Scene& scene, LineAnalysis& la, const ModeList& ml) {
  const bool beam = scene.is_beam();
  const std::array<bool, 3> directions = {beam && carries_axial(scene.physics), beam && carries_xy(scene.physics), true};
  const bool moments = beam && scene.request.shapes && scene.request.shapes->moments;
  ModeShapes ms = la.mode_shapes(ml, scene.shape_points(), scene.shape_components(), directions, moments);
  const auto& g = scene.geometry;
  ms.total_mass = scene.material.rho * g.length * g.width * g.height;
  if (beam) {
    ms.total_mass = 0;
    for (const Segment& p : scene.beam_pieces()) ms.total_mass += p.mass();
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

/// The model and solve options in force: the solver's model options with the back-end options
/// over them.
struct Setup {
  ModelOptions mo;
  SolveControls controls;
  bool polish_from_tolerance = false;  ///< a plate's polish follows the request's tolerance
};

Setup setup_of(const Scene& scene, const ResolvedOptions& o, const ModelOptions& base) {
  Setup st;
  ModelOptions& mo = st.mo;
  mo = base;
  const std::string& layers = o.get_choice("layers");
  mo.layers = layers == "paper" ? LayerModel::Paper : layers == "staggered" ? LayerModel::Staggered : LayerModel::Consistent;
  mo.kirchhoff_penalty = o.get_number("kirchhoff_penalty");
  SolveControls& controls = st.controls;
  controls.rel_tol = o.get_number("rel_tol");
  // A plate's strips carry a discretization error of the order of the tolerance: by default the
  // polish stops at 1e-4 of it (free plate of 180 strips: the count's determinant is rounded at
  // 1e-7 relative, and polishing to that floor took some 20 counts per mode, half of them on the
  // last digits). The bracket is then the solve's bound (below), and a rel_tol given is kept.
  st.polish_from_tolerance = scene.is_plate() && option_source(o, "rel_tol") == "default" &&
                             1e-4 * scene.request.tolerance > controls.rel_tol;
  if (st.polish_from_tolerance) controls.rel_tol = 1e-4 * scene.request.tolerance;
  controls.im_h = o.get_number("im_h");
  controls.re_h = o.get_number("re_h");
  controls.family_threshold = o.get_number("family_threshold");
  return st;
}

/// What the model is (Summary::model, method, fields) and its modelling notes.
void describe_model(const Scene& scene, const Options& options, const Setup& st, const PrismModel& model, Result& r) {
  auto& sum = r.summary;
  sum.method = "dtfm: " + model.description + "; segment dynamic stiffness, Wittrick-Williams count with Brent polish" +
               (st.polish_from_tolerance
                    ? fmt::format(" to {:.2g} in omega^2 (1e-4 of the tolerance)", st.controls.rel_tol)
                    : std::string());
  // Modelling notes (not doubts about the numbers) belong to the method, not the warnings.
  for (const auto& n : model.notes) sum.method += "; " + n;
  // One prism is the scene's beam theory exactly; finer sections tend to a 3D-like model. Plate
  // strips tend to the Kirchhoff or Mindlin plate, except with the paper's own layer model.
  sum.converges_to_scene_theory =
      scene.is_beam() ? model.ny * model.nz == 1 : st.mo.layers != LayerModel::Paper;
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
}

class DtfmKernels final : public Kernels {
 public:
  /// `owned`: the scene the kernels solve where it is not the caller's (a tapered beam's staircase).
  DtfmKernels(const Scene& scene, const Setup& setup, PrismModel model, std::shared_ptr<const Scene> owned = {})
      : owned_(std::move(owned)),
        scene_(owned_ ? *owned_ : scene),
        setup_(setup),
        model_(std::move(model)),
        la_(model_, setup_.controls) {}
  const PrismModel& model() const { return model_; }

  void modes(Result& r) override {
    auto& sum = r.summary;
    const Scene& scene = scene_;
    const int k = scene.request.modes;
    std::vector<ModeFamily> families;
    if (scene.is_beam() && scene.physics == Physics::Bending) families = {ModeFamily::BendingXZ};
    ml_ = la_.modes(k, families);
    r.frequencies_rad_s = ml_.omega_rad_s;
    r.mode_families = ml_.family;
    int unknown = 0;
    for (auto f : ml_.family) unknown += f == ModeFamily::Unknown;
    if (unknown)
      sum.warnings.push_back(fmt::format(
          "{} mode(s) labelled unknown: their rigid-section share of kinetic energy is below one half", unknown));
    if (!ml_.count_consistent) sum.raise(Status::NumericalIssue, "dtfm: " + ml_.count_message);
    // The solve's own error bound on the frequencies (half the eigenvalues'): the near-rigid
    // modes' Rayleigh-Ritz bound, the bracket of any value polished only to the determinant's
    // rounding floor, and a plate's polish tolerance where it followed the request's.
    const double polished = setup_.polish_from_tolerance ? setup_.controls.rel_tol : 0.0;
    if (ml_.near_rigid > 0 || ml_.polish_floor_width > 0 || polished > 0)
      sum.set_diagnostic("frequency_solve_error_bound",
                         0.5 * std::max({ml_.near_rigid_bound, ml_.polish_floor_width, polished}));
    if (ml_.polish_floor_width > 0) sum.set_diagnostic("polish_floor_frequency_error_bound", 0.5 * ml_.polish_floor_width);
    if (ml_.near_rigid > 0) {
      const double bound = 0.5 * ml_.near_rigid_bound;
      sum.set_diagnostic("near_rigid_frequency_error_bound", bound);
      if (!(bound <= 1e-2 * scene.request.tolerance))
        sum.raise(Status::NumericalIssue,
                  fmt::format("dtfm: {} near-rigid mode(s): their rigid-body Rayleigh-Ritz frequencies are only known "
                              "to {:.2g}, above 1 % of the tolerance {:.2g}",
                              ml_.near_rigid, bound, scene.request.tolerance));
    }
    if (static_cast<int>(ml_.omega_rad_s.size()) < k)
      sum.raise(Status::NotConverged, fmt::format("dtfm: only {} of {} modes found", ml_.omega_rad_s.size(), k));
  }
  void shapes(Result& r) override {
    r.mode_shapes = mode_shapes(scene_, la_, ml_);
    r.summary.set_diagnostic("shape_unknowns", static_cast<double>(la_.max_shape_unknowns()));
  }
  void statics(Result& r) override {
    const Scene& scene = scene_;
    // A plate's rigid motions that no edge restrains, from the supports' pattern: the count
    // near zero in statics() cannot see them behind a fine mesh's stiff penalty layers (50
    // strips of a plate guided on every edge counted none, and w came out 184 m).
    if (const std::vector<std::string> free = free_plate_rigid_motions(scene); !free.empty())
      throw std::runtime_error(fmt::format("mechanism: the supports leave {} rigid-body motion(s) free ({})",
                                           free.size(), fmt::join(free, "; ")));
    std::vector<PointReaction> pr;
    FieldIntegrals fi;
    r.deflections = la_.statics(scene.all_point_loads(), scene.request.probes, scene.all_distributed_loads(),
                               scene.is_beam() ? &pr : nullptr, scene.is_plate() ? &fi : nullptr);
    if (scene.is_beam()) add_reactions_and_forces(scene, pr, r);
    else if (fi.complete) add_plate_reactions(scene, model_, fi, r);
  }
  void frf(Result& r) override {
    auto& sum = r.summary;
    const Scene& scene = scene_;
    const auto& f = *scene.request.frf;
    std::vector<double> omegas;
    for (int i = 0; i < f.points; ++i) omegas.push_back(f.omega_min + (f.omega_max - f.omega_min) * i / (f.points - 1));
    int skipped = 0;
    std::string reason;
    const auto H = la_.receptance(f.excite, f.observe, omegas, scene.material.loss_factor, &skipped, &reason);
    for (std::size_t i = 0; i < omegas.size(); ++i)
      if (std::isfinite(std::abs(H[i]))) r.frf.push_back({omegas[i], H[i]});
    note_frf_omissions(sum, skipped, f.points, reason);
  }
  void campbell(Result& r) override {
    r.campbell = detail::rotor_campbell(scene_, setup_.mo, setup_.controls, r.summary);
    r.summary.method += "; Campbell: " + r.campbell.note;
  }
  void close(Result& r) override {
    auto& sum = r.summary;
  sum.set_diagnostic("count_evaluations",
                     std::max(0.0, sum.diagnostic("count_evaluations")) + static_cast<double>(la_.evaluations()));
  sum.set_diagnostic("segment_asymmetry", la_.max_asymmetry());
  sum.unknowns = la_.max_unknowns();
  sum.threads = std::max(sum.threads, la_.threads_used());
  if (la_.max_asymmetry() > 1e-6)
    sum.warnings.push_back(fmt::format("segment matrices asymmetric to {:.2e}: the state matrices are not "
                                       "Hamiltonian to working precision",
                                       la_.max_asymmetry()));
  }

 private:
  const std::shared_ptr<const Scene> owned_;
  const Scene& scene_;
  const Setup setup_;
  const PrismModel model_;
  LineAnalysis la_;
  ModeList ml_;
};

}  // namespace

std::unique_ptr<Kernels> make_kernels(const Scene& scene, const Discretization& mesh, const Options& options,
                                      const ModelOptions& base, Result& r) {
  const Setup st = setup_of(scene, options.resolved, base);
  if (scene.has_tapered_pieces()) {
    // Tapered pieces as staircases of uniform prisms, with the discretization error that brings.
    const int steps = detail::staircase_steps(mesh);
    auto stairs = std::make_shared<const Scene>(detail::staircase(scene, steps));
    auto kernels = std::make_unique<DtfmKernels>(scene, st, build_model(*stairs, Discretization{{1, 1}}, st.mo), stairs);
    describe_model(*stairs, options, st, kernels->model(), r);
    r.summary.model = fmt::format("one prism per section, each tapered piece as {} uniform steps (the section at each "
                                  "step's middle), tending to the tapered {} beam at second order",
                                  steps, to_string(scene.theory));
    r.summary.method += fmt::format("; tapered pieces as staircases of {} uniform prisms each", steps);
    return kernels;
  }
  auto kernels = std::make_unique<DtfmKernels>(scene, st, build_model(scene, mesh, st.mo));
  const PrismModel& model = kernels->model();
  describe_model(scene, options, st, model, r);
  // A one-prism beam is the beam of its section itself: no discretization error to estimate. (Its
  // polish tolerance is no bound: on a shaft with E scaled by 1e-6 the axial mode came out 1.7e-8
  // from the transfer-matrix value, fuzz seed 1, case 613.)
  if (scene.is_beam() && model.prisms.size() == 1) r.summary.set_diagnostic("exact_segments", 1.0);
  return kernels;
}

}  // namespace modalbench::dtfm
