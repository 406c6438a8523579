#pragma once
// What a solver returns: frequencies, deflections, FRF samples and a summary that says how far
// each number can be trusted. Every field of Summary has one meaning in every back-end (stated
// here; tests/core/test_result_contract.cpp checks every registered back-end against it).

#include <array>
#include <complex>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace modalbench {

/// In order of severity: when several apply, the worst one is the result's status.
enum class Status {
  Success,         ///< every requested quantity computed and every check passed
  NotConverged,    ///< best result returned, marked; see message
  NumericalIssue,  ///< a check failed (residual, count, reproduction); numbers reported, see message
  ResourceLimit,   ///< the request's estimated memory or time exceeds a stated limit (refused before allocating)
  Unsupported,     ///< the back-end cannot do this scene; see message
  InvalidInput,    ///< the user's scene, mesh or options were rejected; see message
};
std::string to_string(Status);
/// 0 for success up to 5 for invalid input (the enum's order).
int severity(Status);

/// Which physical family a mode belongs to (never guessed: `unknown` if not known).
enum class ModeFamily { BendingXZ, BendingXY, Axial, Torsion, Plate, Rigid, Unknown };
std::string to_string(ModeFamily);  ///< bending-xz, bending-xy, axial, torsion, plate, rigid, unknown

/// Stress resultants at one point of the structure under the static loads.
/// Beam (N, N*m): axial force N (tension positive); bending moments My = EI_y w'' (x-z) and
/// Mz = EI_z v'' (x-y), so a sagging moment (concave towards +z, or +y) is positive; shear forces
/// Qz = dMy/dx and Qy = dMz/dx; torque T = GJ theta_x'. Plate (per unit length, N*m/m):
/// mx = D (w_xx + nu w_yy), my = D (w_yy + nu w_xx) (sagging positive) and mxy = D (1 - nu) w_xy
/// (Kirchhoff; a Mindlin plate the same with the rotations' derivatives). Where a point action or a
/// support sits at the probe, the value just beyond it (x + 0; at x = L, x - 0).
struct InternalForces {
  double N = 0, Qy = 0, Qz = 0, T = 0, My = 0, Mz = 0;
  double mx = 0, my = 0, mxy = 0;
};

/// Static response at one probe. Components a scene does not carry stay 0.
struct Deflection {
  std::array<double, 2> position{};  ///< beam: {x, 0}; plate: {x, y}, m
  double u = 0, v = 0, w = 0;        ///< m
  double theta_x = 0, theta_y = 0, theta_z = 0;  ///< rad, right-handed about the axes
  bool has_forces = false;  ///< whether `forces` was computed (the back-end gives them for this scene)
  /// Frames: the probe as written ("B", or "BC@0.5": member BC at half its length), its point in
  /// global axes (m), the displacements in global axes, the forces in the member's axes.
  std::string probe;
  std::array<double, 3> point{};
  InternalForces forces;
};

/// What one support (an end or edge, or a support between them) exerts on the structure under the
/// static loads, in global axes: force (N) and moment (N*m) at its point. With the applied loads
/// they balance: the sum of forces and of moments (about any point) is zero.
struct Reaction {
  std::string support;               ///< "x0", "xL", "points[0]", ...
  std::array<double, 2> position{};  ///< beam: {x, 0}, m
  std::array<double, 3> force{}, moment{};
  std::array<double, 3> point{};  ///< frames: the supported node, global axes, m
};

struct FrfSample {
  double omega_rad_s = 0;
  std::complex<double> receptance;  ///< w(observe) / Fz(excite), m/N
};

/// Mode shapes sampled at common points (Scene::shape_points), one per reported frequency,
/// with their modal quantities. Normalization: unit modal mass of the model the back-end solves
/// (int rho A (u^2 + v^2 + w^2) + rotary terms dx for a beam, int rho h w^2 (+ rotary) dA for a
/// plate, phi' M phi for a discrete model), so amplitudes of different back-ends compare; sign:
/// the translation sample of largest magnitude is positive (a rotation, for a mode without
/// translation). Repeated frequencies: any orthonormal basis of the eigenspace.
struct ModeShapes {
  std::vector<std::array<double, 2>> points;  ///< beam {x, 0}, plate {x, y}, m
  std::vector<int> components;                ///< dofs::Index 0..5 (u, v, w, theta_x, theta_y, theta_z)
  /// values[mode][component][point]: m (translations) or rad (rotations) per sqrt(kg) of modal mass.
  std::vector<std::vector<std::vector<double>>> values;
  std::string normalization = "mass";
  std::string note;  ///< how the shapes were obtained (and anything a user should know)
  /// Per mode: phi' M phi of the reported shape (1 when normalized), kg.
  std::vector<double> generalized_mass;
  /// Per mode: participation factors phi' M r_d for unit rigid translations r_x, r_y, r_z, sqrt(kg).
  std::vector<std::array<double, 3>> participation;
  /// Per mode: effective modal masses Gamma_d^2 / generalized mass, kg.
  std::vector<std::array<double, 3>> effective_mass;
  /// moments[mode][point]: the mode's bending moment My (InternalForces' sign) at each point, N*m per
  /// sqrt(kg) of modal mass, where it was asked (ShapeRequest::moments) and the back-end gives it for
  /// the scene (beams); empty otherwise. At a point action or support, the value just beyond it.
  std::vector<std::vector<double>> moments;
  std::array<bool, 3> directions{};  ///< the translations the model carries (x, y, z)
  double total_mass = 0;             ///< of the model, kg
  bool empty() const { return values.empty(); }
};

/// Component name of a dofs index: u, v, w, theta_x, theta_y, theta_z.
std::string component_name(int dof);

/// Scales every mode to unit generalized mass, fixes its sign (see ModeShapes), and fills the
/// effective masses. The back-end fills points, components, values, generalized_mass (of the
/// raw values), participation (of the raw values), directions and total_mass first.
void finish_mode_shapes(ModeShapes& shapes);

/// Wall time per quantity, seconds. The same four phases in every back-end: `build` (reading the
/// scene into the back-end's model: assembly, operators), then the work of each requested
/// quantity, including the factorizations and checks it needs.
struct PhaseTimes {
  double build = 0, modes = 0, statics = 0, frf = 0;
  /// The coarser mesh solved for the discretization-error estimate (0 where none is made).
  double error_estimate = 0;
  /// The time history (request.transient): its modal solves and the superposition.
  double transient = 0;
  /// The Campbell diagram ([rotor]): the whirl at every spin and the critical speeds.
  double campbell = 0;
};


inline constexpr double kNotMeasured = std::numeric_limits<double>::quiet_NaN();

/// A meshed result's own estimate of its discretization error: the same request on coarser meshes
/// of the same family. Relative figures; NaN where not made.
///
/// Per quantity q (each nonzero mode, each probe), with h the mesh judged, H = r h the coarser one
/// and, where the family has it, 2H = r' H the next coarser:
///   e1 = |q_h - q_H| / (r^p - 1)                      (Richardson on the finest pair)
///   e2 = |q_H - q_2H| / (r'^p - 1) / r^p              (the coarser pair's estimate, carried to h)
///   estimate = max(3 e1, 1.25 e2) + the solve's own error bound
/// with p the family's formal order, or, for a frequency whose three meshes show a lower one
/// (differences above the solve's rounding), that observed order (at least 1/4).
/// 3 is Roache's factor of safety for a two-mesh estimate with the formal order p (a grid
/// convergence index), 1.25 his factor where a third mesh backs it. The guard e2 is there because
/// errors that change sign between meshes (two error terms of opposite signs: a Mindlin plate at
/// 20 and 40 fragments) make one pair's difference accidentally small. The solve's bound is the back-end's own (the diagnostic
/// `frequency_solve_error_bound`, e.g. from the eigen residuals): rounding, which refinement does
/// not reduce and Richardson does not see.
struct ErrorEstimate {
  double frequencies = kNotMeasured;   ///< max over paired nonzero modes of the estimate above, relative to f_h
  double deflections = kNotMeasured;   ///< max over probes, relative to max |w_h|
  double frequencies_solve = kNotMeasured;  ///< the solve's own bound included in `frequencies` (NaN: none given)
  /// A rotor's whirl frequencies (Result::campbell), each paired by rank at its spin: the largest
  /// estimate relative to |frequency| + spin (a rotating frame's frequency passes 0 at a critical).
  double campbell = kNotMeasured;
  double tolerance = kNotMeasured;     ///< the scene's request.tolerance it was judged against
  std::string coarse_mesh;            ///< the mesh it was checked against ("" when none)
  std::string coarser_mesh;           ///< the third mesh, 2H ("" when the family has none)
  double ratio = kNotMeasured, order = kNotMeasured;
  double safety_factor = kNotMeasured;  ///< the finest pair's: 3, or 1.25 where a fourth mesh confirmed every judged order
  std::string note;                   ///< how it was made, or why none was
};

/// Richardson extrapolation of a meshed result from the meshes of its own error estimate
/// (extrapolation.hpp): values of a higher order than the mesh's, each with an estimate of its
/// error. An extra output beside the mesh's own numbers, which it never replaces; empty where not
/// made (fewer than three meshes, a back-end that states no next order, modes that do not pair,
/// a mesh whose solve failed its checks), and `note` says why.
struct Extrapolation {
  std::vector<double> frequencies_rad_s;  ///< per mode of the result (rigid-body zeros stay 0)
  std::vector<double> frequency_errors;   ///< per mode: estimated relative error (0 for a rigid zero)
  double frequency_error = kNotMeasured;  ///< the largest of frequency_errors
  /// Per mode: the order the three meshes show (NaN where their differences are within rounding).
  /// Where it is more than 20 % from `order`, or the two coarser meshes differ by more than 5 %, the
  /// meshes are not in the asymptotic range, and that mode's estimate is no better than the mesh's
  /// own: max(the extrapolation's, 3 |q(h) - q(H)| / (r^p - 1)).
  std::vector<double> observed_orders;
  std::vector<Deflection> deflections;    ///< per probe
  double deflection_error = kNotMeasured; ///< estimated, relative to the largest translation
  std::string meshes;                     ///< the three meshes, fine to coarse ("64, 32, 16")
  double order = kNotMeasured;            ///< p: the order removed
  double next_order = kNotMeasured;       ///< s: the order assumed to remain (frequencies)
  double deflection_next_order = kNotMeasured;  ///< s for deflections: p (no gain assumed)
  std::string note;
  /// Whether the result reports these values as its answer (Result::frequencies_rad_s,
  /// Result::deflections): on the default path (a default mesh refined to the tolerance) where their
  /// own estimate meets the tolerance and the mesh's does not. The mesh's own values are then kept
  /// in mesh_frequencies_rad_s / mesh_deflections (else those stay empty).
  bool frequencies_reported = false, deflections_reported = false;
  std::vector<double> mesh_frequencies_rad_s;
  std::vector<Deflection> mesh_deflections;
  bool empty() const { return frequencies_rad_s.empty() && deflections.empty(); }
};

/// The time history of `[request.transient]` (transient.hpp): modal superposition of the modes the
/// back-end gave, each integrated exactly for the load's time function.
struct TransientPeak {
  double w = 0;       ///< the value of w of largest magnitude over [0, duration], with its sign, m
  double time_s = 0;  ///< when it occurs (located on the modes' closed forms, not the output grid)
};
struct Transient {
  std::vector<double> time_s;  ///< 0, step, 2 step, ... duration; t = 0 is the instant after loading (0+)
  std::vector<int> components;  ///< dofs indices of the histories (the scene's shape components)
  /// values[probe][component][time]: m (translations) or rad (rotations).
  std::vector<std::vector<std::vector<double>>> values;
  std::vector<TransientPeak> peaks;  ///< per probe
  /// moments[probe][time]: the bending moment My (InternalForces' sign), N*m, where the back-end's
  /// modes carry it (ModeShapes::moments) and, with the static correction, its statics too; empty
  /// otherwise. moment_peaks: per probe, the My of largest magnitude with its sign (TransientPeak::w
  /// holds it, N*m), located like the peaks of w.
  std::vector<std::vector<double>> moments;
  std::vector<TransientPeak> moment_peaks;
  /// The truncation estimate of the moment histories, relative to the largest |My| peak (as
  /// error_estimate's for w; kNotMeasured without moments).
  double moment_error_estimate = kNotMeasured;
  int modes_used = 0;                ///< modes superposed (rigid-body modes included)
  int rigid_modes = 0;               ///< of them, with omega = 0
  bool static_correction = false;    ///< whether the truncated modes' static share was added
  /// Estimated truncation error of the histories: the largest change over the probes and the
  /// time span when the modes used are halved, or the first neglected mode's response, whichever
  /// is larger, relative to the largest |w| peak.
  double error_estimate = kNotMeasured;
  std::string load;  ///< the time function, in words
  std::string note;  ///< how it was made, and anything a user should know
  bool empty() const { return time_s.empty(); }
};

/// The sense of a whirl orbit: forward (in the spin's sense, from +y towards +z), backward, mixed
/// (the stations of one mode disagree), planar (the orbit is a line: no sense, e.g. an asymmetric
/// shaft at spin 0), or none (a root that does not oscillate: frequency 0).
enum class Whirl { Forward, Backward, Mixed, Planar, None };
std::string to_string(Whirl);  ///< forward, backward, mixed, planar, none

/// The whirl of a spinning shaft at one spin speed (scene [rotor]), in the scene's frame.
/// A whirl root's orbit at the points of [request.shapes] (Campbell::orbit_points_m): the lateral
/// motion v(t) = Re(v e^{i omega t}), w(t) = Re(w e^{i omega t}) (times e^{growth t}), normalized so
/// that the largest |v|^2 + |w|^2 is 1 and v there (w, where v vanishes) is real and positive. A
/// forward circle has w = -i v (turning from +y towards +z, the spin's sense), a backward one w = +i v.
struct Orbit {
  std::vector<std::complex<double>> v, w;
};

struct CampbellPoint {
  double spin_rad_s = 0;
  /// The lowest request.modes whirl frequencies |Im lambda|, rad/s, ascending (each whirl mode once;
  /// at spin 0 a forward and backward pair are the two planes' repeated frequency).
  std::vector<double> frequencies_rad_s;
  std::vector<Whirl> whirl;               ///< per frequency
  std::vector<double> growth_rates_1_s;   ///< per frequency, Re lambda, 1/s (> 0: unstable)
  std::vector<Orbit> orbits;              ///< per frequency, where [request.shapes] asks (else empty)
};
/// A Campbell diagram: whirl against spin, and the critical speeds (a whirl frequency, seen from the
/// ground, equal to the spin), solved for, not read off the samples.
struct Campbell {
  std::string frame;  ///< stationary | rotating
  std::vector<CampbellPoint> points;
  std::vector<double> orbit_points_m;  ///< x of the orbits' points (the shape points), m; empty: no orbits
  std::string orbit_note;              ///< how the orbits were found, or why they are not given
  /// Critical speeds, rad/s, ascending: every one up to the highest spin asked, and the next above.
  std::vector<double> forward_criticals, backward_criticals;
  std::string criticals_note;  ///< how they were found, or why a list is not given
  std::vector<double> unstable_spins;  ///< the spins asked with a growth rate above the checks' rounding
  /// Largest normwise backward error of the whirl eigenpairs (kNotMeasured where not checked so).
  double max_backward_error = kNotMeasured;
  std::string note;  ///< the method, and anything a user should know
  bool empty() const { return points.empty(); }
};

/// One step of a solve (a kernel of the back-end: Kernels) and how it ended.
struct StepOutcome {
  std::string step;  ///< modes | shapes | statics | frf | campbell
  Status status = Status::Success;
  std::string message;  ///< what it raised, joined by "; " (empty on success)
};

struct Summary {
  Status status = Status::Success;
  /// Every message raised, in order, joined by "; " (empty on success).
  std::string message;
  /// What the back-end was asked to do: its options as given (scene [backend.NAME], command line),
  /// "defaults" when none were given.
  std::string method_requested = "defaults";
  /// What was actually used, in words (discretization, algorithms, checks).
  std::string method;
  /// Whether this run's model tends, under mesh refinement, to the continuum theory the `exact`
  /// back-end solves for the scene (scene.theory): then `exact` is its own converged limit and its
  /// distance to it is discretization error. False where the back-end refines towards another model
  /// (a multi-prism section tends to 3D elasticity; an Euler-Bernoulli chain on a Timoshenko scene
  /// to Euler-Bernoulli; a 3D solid to 3D elasticity): its limit is then its own ladder's.
  bool converges_to_scene_theory = false;
  /// The model this run solved, in words: what its numbers converge to ("the exact Timoshenko
  /// beam", "rigid finite elements, tending to the Kirchhoff plate", ...). Empty where the
  /// back-end did not get as far as building one.
  std::string model;
  /// Each fall-back taken: what failed and what was used instead (empty: none).
  std::vector<std::string> fallbacks;
  /// Threads that worked at once (1, or 2 where a check overlaps the main solve).
  int threads = 1;
  /// Size of the linear or eigen system actually solved (the largest, when several are): for
  /// rfem its coordinates, for difference_eq the free nodal DOFs of the banded system, for the
  /// dynamic-stiffness methods (dtfm, exact) the free DOFs of the assembled K(omega).
  long unknowns = 0;
  /// Largest normwise backward error of the reported numbers: eigenpairs
  /// ||K phi - lambda M phi|| / ((||K|| + |lambda| ||M||) ||phi||), static solves
  /// ||K x - f|| / (||K|| ||x|| + ||f||), determinant roots |det K(lambda)| relative to its scale.
  /// kNotMeasured (NaN, JSON null) where the back-end has no such check.
  double max_backward_error = kNotMeasured;
  /// Back-end-specific figures, by name (e.g. "iterations", "segment_asymmetry", "series_tail").
  std::vector<std::pair<std::string, double>> diagnostics;
  PhaseTimes timings_s;  ///< mode shapes are charged to `modes`
  ErrorEstimate error_estimate;
  /// The mesh actually solved ("-" for none).
  std::string mesh;
  std::vector<std::string> warnings;
  /// The back-end's kernels run on the mesh kept, in order, each with its own status and message
  /// (the status above is the worst of theirs and of the pipeline's own checks).
  std::vector<StepOutcome> steps;
  double total_time_s = 0;

  /// Records a problem: the status becomes the worse of the current one and `s`; the message is kept.
  void raise(Status s, const std::string& text);
  /// Sets (or replaces) a named diagnostic.
  void set_diagnostic(const std::string& name, double value);
  /// A named diagnostic, or kNotMeasured.
  double diagnostic(const std::string& name) const;
  /// Raises the backward error to at least `e` (NaN ignored).
  void note_backward_error(double e);
};

/// Records FRF samples that could not be computed: up to two are omitted with a warning (on or
/// within rounding of a natural frequency, K(omega) is singular); more cannot all be resonances,
/// and make the result numerical-issue with `reason` (the first failure, in words), as does
/// omitting every sample asked (an FRF requested and none reported is not a success).
void note_frf_omissions(Summary& sum, int skipped, int points, const std::string& reason);

struct Result {
  std::vector<double> frequencies_rad_s;  ///< ascending, repeated ones repeated
  std::vector<ModeFamily> mode_families;  ///< parallel to frequencies_rad_s
  std::vector<Deflection> deflections;    ///< one per requested probe
  /// Static support reactions (beams, `exact`): one per support with a spring or a hold.
  std::vector<Reaction> reactions;
  std::vector<FrfSample> frf;
  ModeShapes mode_shapes;  ///< when the scene asks for them (request.shapes)
  Extrapolation extrapolated;  ///< Richardson values from the error estimate's meshes (may be empty)
  Transient transient;  ///< when the scene asks for it (request.transient)
  Campbell campbell;    ///< a rotor scene's whirl against spin ([rotor])
  Summary summary;

  bool ok() const { return summary.status == Status::Success; }
  /// The estimate of the frequencies reported: the extrapolation's where they are its values
  /// (Extrapolation::frequencies_reported), else the mesh's (summary.error_estimate.frequencies).
  double frequency_estimate() const {
    return extrapolated.frequencies_reported ? extrapolated.frequency_error : summary.error_estimate.frequencies;
  }
};

}  // namespace modalbench
