#pragma once
// Solving a prism model along x by segment dynamic stiffness (core's numerics kernels):
// each symmetry class of the fields is a Hamiltonian line problem. Global nodes sit only where
// they are needed (ends, steps, supports and masses between the ends, loads, probes, observation
// points, on a common spacing when these are commensurate); a node with a support or mass adds its
// springs and -omega^2 masses to K and holds what the support holds (the count stays exact: they
// are nodal terms); a stepped beam's segments take their own piece's state matrix; each segment's dynamic stiffness is built by doubling from a base piece short
// enough that exp(A h) is well conditioned and has no clamped natural frequency below the
// largest omega of interest (|p| h <= 1 for every wavenumber p of A at omega = 0 and at
// omega_max). The segments are assembled into a block-tridiagonal K(omega^2); the
// Wittrick-Williams count is the LDL^T inertia of K plus the segments' J0 (from the doubling).
//   - natural frequencies: count-driven bisection until an interval holds one eigenvalue of a
//     class, then Brent's method on det K * prod det Tdf (the characteristic function without
//     the segments' poles; one mesh for the whole range), its bracket kept by the count at every
//     evaluation, so that a polish stopped by a repeated determinant value (the rounding floor,
//     or a step below the lambda resolution of K) returns only a root the count has bracketed
//     to 1e-8 (else it bisects once more and polishes again); repeated values keep their
//     multiplicity; every mode is then counted again just below and above it on a second
//     discretization (other base pieces, other rounding): a mode that does not reproduce to
//     5e-5 is reported (rounding floor of stiff layers against very slender spans or soft
//     supports);
//   - statics: K(0) d = f, a distributed load entering as the equivalent nodal forces of its
//     particular solution (the augmented exponential over each segment) and added back between
//     nodes; the supports' reactions from K d - f on the held coordinates and -k d; a class with rigid motions of its own (beams) split into them and
//     its elastic part held at anchors (detail::RigidLine), so that springs far softer than the
//     rounding of K_int + K_springs (near-mechanisms) keep their digits and a mechanism is
//     recognized structurally (a rigid motion no support reaches);
//   - FRF: K(omega^2) d = f, or with structural damping (stiffness x (1 + i eta)) the complex
//     solve K(omega^2 / (1 + i eta)) d = f / (1 + i eta);
//   - mode shapes (shapes.cpp): the null vector of the mode's class K(omega^2) (inverse iteration
//     just off the root; a block of vectors for a repeated root, the null space of K(0) for the
//     rigid modes) on nodes at the sample positions and at most a base piece apart, the exact field
//     between nodes by exp(A s) from each node's state [q; f]; modal mass and participation by GSL
//     quadrature of that field; modes sharing a class and a frequency mass-orthonormalized.
//
// Usage:
//   LineAnalysis la(model);
//   ModeList modes = la.modes(6);
//   std::vector<Deflection> d = la.statics(scene.loads, probes);
//   ModeShapes ms = la.mode_shapes(modes, scene.shape_points(), scene.shape_components(), {false, false, true});

#include <array>
#include <complex>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "modalbench/dtfm/prism_model.hpp"
#include "modalbench/numerics/complex_block_tridiagonal.hpp"
#include "modalbench/numerics/spectrum_slicing.hpp"

namespace modalbench::dtfm {

struct SolveControls {
  double rel_tol = 1e-11;  ///< relative tolerance on omega^2 (the polish also stops at the determinant's rounding floor)
  double im_h = 1.0;       ///< base pieces: bound on |Im p| h (oscillatory wavenumbers: no clamped mode)
  /// Base pieces: bound on |Re p| h (evanescent: exp(A h) grows by e^8 ~ 3e3 at most). Shorter
  /// pieces mean more doubling levels, each condensing stiff layers against a lambda-dependent
  /// part that shrinks with h: at 4, a cantilever plate of 64 Kirchhoff strips had mode 1 move by
  /// 1e-4 between base pieces of h and h / 2 (2.626025, 2.625381, 2.627663 rad/s at 4, 2, 1),
  /// at 8 and 12 it is 2.626027 both.
  double re_h = 8.0;
  double family_threshold = 0.5;  ///< beam mode is labelled by its class if the rigid-section share of its kinetic energy reaches this
};

struct ModeList {
  std::vector<double> omega_rad_s;  ///< ascending, rigid ones 0
  std::vector<ModeFamily> family;
  std::vector<int> cls;             ///< symmetry class of each mode
  std::vector<double> family_share; ///< kinetic-energy share of the class's rigid-section motion (beams)
  std::vector<char> reproducible;   ///< per non-rigid mode: its count reproduces on a second discretization
  int rigid = 0;
  long evaluations = 0;             ///< count / determinant evaluations
  bool count_consistent = true;     ///< every mode reproduces (count just below / above it, second discretization)
  std::string count_message;
  /// Near-rigid modes (beams on springs below 1e-10 of the stiffness scale): how many, and the
  /// largest estimated relative error of their omega^2 (rigid-body Rayleigh-Ritz on the condensed
  /// springs, analysis_modes.cpp).
  int near_rigid = 0;
  double near_rigid_bound = 0;
  /// The largest relative bracket (in omega^2) of a sliced value whose polish stopped at the
  /// determinant's rounding floor (spectrum_slicing.hpp, kPolishFloor); 0 if none did.
  double polish_floor_width = 0;
};

/// A support's action on a beam at x: the section resultant (Fx, Fy, Fz, Mx, My, Mz) it exerts,
/// N and N*m, global axes.
struct PointReaction {
  double x = 0;
  std::array<double, 6> F{};
};

/// A static solution's fields integrated along x (plates: what the long edges' reactions need),
/// physical units over the model's fields: int_0^L q dx, int_0^L (x - L/2) q dx and q at x = 0
/// and L; and, per node with a condition, the generalized forces it exerts on the fields (K d - f
/// on its held coordinates, -k d for its springs).
struct FieldIntegrals {
  Eigen::VectorXd q, xq, q0, qL;
  std::map<double, Eigen::VectorXd> node_forces;
  bool complete = true;  ///< false where a loaded class was solved split into rigid motions (beams)
};

namespace detail {
struct RigidLine;
}

class LineAnalysis {
 public:
  explicit LineAnalysis(const PrismModel& model, SolveControls controls = {});
  ~LineAnalysis();
  LineAnalysis(const LineAnalysis&) = delete;
  LineAnalysis& operator=(const LineAnalysis&) = delete;

  /// The k lowest natural frequencies over the classes whose family is in `families` (all
  /// classes when empty). Throws std::runtime_error on an unstable (omega^2 < 0) system.
  ModeList modes(int k, const std::vector<ModeFamily>& families = {});
  /// Number of natural frequencies with omega^2 < lambda over the chosen classes (mesh for lambda).
  int count_below(double lambda, const std::vector<ModeFamily>& families = {});
  /// Static response at probes (x, y) under point loads and distributed ones. Throws std::runtime_error starting
  /// "mechanism" if a loaded class is not restrained (the input's fault), another message if the
  /// solve breaks down numerically.
  /// `distributed`: beam line loads (linear over their ranges) or plate pressures, their particular
  /// solutions exact along x. `reactions` (beams): what each node with a support or mass exerts on
  /// the beam (a mass-only node: zero), ascending x. `integrals`: the fields' integrals along x (a
/// mesh of base pieces then, as under distributed loads).
  std::vector<Deflection> statics(const std::vector<PointLoad>& loads, const std::vector<std::array<double, 2>>& probes,
                                  const std::vector<DistributedLoad>& distributed = {},
                                  std::vector<PointReaction>* reactions = nullptr, FieldIntegrals* integrals = nullptr);
  /// Receptance w(observe) / Fz(excite) at each omega; `eta` structural loss factor. A sample
  /// at an undamped natural frequency is not finite: it is returned as NaN and counted.
  std::vector<std::complex<double>> receptance(std::array<double, 2> excite, std::array<double, 2> observe,
                                               const std::vector<double>& omegas, double eta, int* skipped = nullptr,
                                               std::string* reason = nullptr);
  /// Shapes of the modes `modes` (from modes()) at `points` ((x, y); beams: y unused), the
  /// section response (PrismModel::section_response) per component (dofs index), with their raw
  /// generalized masses int q^T M q dx and participations int q^T M r_d dx (r_d: unit rigid
  /// translation of the section; 0 where `directions` is false). Not normalized and without
  /// total mass or note: the caller finishes them (finish_mode_shapes). With `moments` (beams), the
  /// bending moment My at the points too: the section resultant of the state's forces there (the
  /// value just beyond a node, x + 0; at x = L, L - 0). Throws std::runtime_error if a null vector
  /// or an integral cannot be computed.
  ModeShapes mode_shapes(const ModeList& modes, const std::vector<std::array<double, 2>>& points,
                         const std::vector<int>& components, std::array<bool, 3> directions, bool moments = false);
  /// Largest |K - K^T| / |K| of the segment matrices computed so far (rounding-small when
  /// the state matrices are Hamiltonian: a check on the operator).
  double max_asymmetry() const { return max_asymmetry_; }
  long evaluations() const { return evaluations_; }
  /// Free DOFs of the largest K(omega^2) assembled so far (the size of the system solved).
  long max_unknowns() const { return max_unknowns_; }
  /// Free DOFs of the largest K solved for mode shapes (not counted in max_unknowns: shapes
  /// leave the modes' figures as they are).
  long max_shape_unknowns() const { return max_shape_unknowns_; }
  int classes() const { return static_cast<int>(lines_.size()); }
  /// Threads that worked at once in the calls so far (2 where classes or FRF samples ran side by side).
  int threads_used() const { return threads_used_; }

  struct ClassLine;  // one symmetry class as a scaled line problem (src/analysis_detail.hpp)

 private:
  const PrismModel& model_;
  SolveControls ctl_;
  std::vector<std::unique_ptr<ClassLine>> lines_;
  double max_asymmetry_ = 0;
  long max_unknowns_ = 0;
  long max_shape_unknowns_ = 0;
  long evaluations_ = 0;
  int threads_used_ = 1;
  /// The running figures above as gathered on one thread while tasks run side by side: merged
  /// into them when the threads join.
  struct Tally {
    double asymmetry = 0;
    long unknowns = 0, evaluations = 0;
  };
  static thread_local Tally* tally_;  ///< this thread's, inside side_by_side (else the members)
  /// Runs task(i) for i in [0, n) on this thread (even i) and a second one (odd i) where the machine
  /// has two cores, else in order here. Tasks of different i must share nothing they write but
  /// their own slots (each class is its own line problem). Rethrows the first exception.
  void side_by_side(std::size_t n, const std::function<void(std::size_t)>& task);

  /// Global nodes and the longest base piece for lambda in [0, lambda_max].
  struct Mesh {
    std::vector<double> x;
    double h_base = 0;
    double h_im = 0, h_re = 0;  ///< the two bounds behind h_base (oscillatory, evanescent)
  };
  /// Below this omega^2 (and above minus it) the last modes() call counted only rigid-body modes:
  /// the mode shapes' inverse iteration for them shifts below it.
  double rigid_shift_ = 0;
  struct Band {  ///< a range of lambda sliced on one mesh
    double lo, hi;
    Mesh mesh;
  };
  struct Assembled;

  std::vector<int> pick(const std::vector<ModeFamily>& families) const;
  Mesh mesh_for(ClassLine& c, double lambda_max, const std::vector<double>& required, int min_nodes = 0);
  static Mesh refined(const Mesh& mesh);
  Assembled assemble(const ClassLine& c, double lambda, const Mesh& mesh);
  ComplexBlockTridiagonal assemble(const ClassLine& c, std::complex<double> lambda, const Mesh& mesh);
  CountDet count_det(const ClassLine& c, double lambda, const Mesh& mesh);
  void repolish_near_poles(ClassLine& c, const Mesh& mesh, double lambda_max, std::vector<double>& vals,
                           ModeList& out, SliceStats* st);
  double family_share(ClassLine& c, double lambda);
  /// modes()' phases in order, and the state they hand on (analysis_modes.cpp).
  struct ModeSearch;
  void modes_refresh(ModeSearch& s, double lam);
  int modes_total(ModeSearch& s, double lam);
  double modes_rigid_threshold(ModeSearch& s);
  void modes_near_rigid(ModeSearch& s, double rigid_below, ModeList& out);
  void modes_bracket(ModeSearch& s);
  void modes_rigid_found(ModeSearch& s, ModeList& out);
  void modes_bands(ModeSearch& s, int c);
  void modes_slice(ModeSearch& s, ModeList& out);
  void modes_label(ModeSearch& s, ModeList& out);
  void modes_reproducibility(ModeSearch& s, ModeList& out);
  /// A free plate's rigid threshold from the total count over its classes (analysis_modes.cpp).
  double plate_rigid_threshold(double delta, double scale, const std::function<int(double)>& total) const;
  /// The lowest eigenvalues of class c, `below` of them under the count's threshold: rigid-body
  /// modes and near-rigid ones (analysis_modes.cpp).
  struct NearRigid {
    int rigid = 0;                 ///< rigid-body modes (0)
    std::vector<double> lambdas;   ///< near-rigid omega^2, ascending
    double bound = 0;              ///< their largest estimated relative error
    std::string problem;           ///< why they could not be resolved (then all `below` are in `rigid`)
    double lo = 0;                 ///< the class is sliced from here (the threshold)
    int below_lo = 0;              ///< its count at lo
    /// Above the threshold: Ritz values l_RR with bounds b enclosing the class's lowest sliced
    /// values in [l_RR / (1 + b), l_RR]; a sliced value outside is replaced.
    std::vector<std::pair<double, double>> enclosures;
  };
  NearRigid near_rigid(ClassLine& c, int below);
  /// A lower bound on the lowest eigenvalue of c's line held at rl's anchors (analysis_near_rigid.cpp).
  double anchored_lowest(ClassLine& c0, const detail::RigidLine& rl, const std::vector<double>& ritz, int n_near);
  /// Adds to `react` (per node x, over the fields) the supports' actions of one class's static
  /// solution: K d - f on the held coordinates, -k d of the springs (analysis_response.cpp).
  void add_reactions(const ClassLine& c, const Mesh& mesh, const detail::RigidLine* rl, const Eigen::VectorXd& d,
                     const Eigen::VectorXd& amp, const Eigen::VectorXd& f, std::map<double, Eigen::VectorXd>& react);
  /// The shapes of the modes `which` (one class, one lambda; 0: rigid) into `out` (shapes.cpp).
  void cluster_shapes(ClassLine& c, double lambda, const std::vector<std::size_t>& which,
                      const std::vector<double>& xs, const Eigen::MatrixXd& translations, bool moments,
                      ModeShapes& out);
  /// The null space of c's K at lambda on mesh, p vectors, by inverse iteration (shapes.cpp).
  Eigen::MatrixXd shape_null_space(ClassLine& c, double lambda, const Mesh& mesh, Eigen::Index p);
};

}  // namespace modalbench::dtfm
