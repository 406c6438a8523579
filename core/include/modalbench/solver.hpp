#pragma once
// One interface for every method: Scene --(Solver::solve, Discretization, Options)--> Result.
//
// Usage:
//   Registry registry = ...;                      // see solvers/registry.hpp
//   const Solver& s = registry.get("exact");      // unknown names list the known ones
//   Scene scene = load_scene("scenes/paper_fixed_beam.toml");
//   Result r = s.solve_default(scene, Options{});          // or s.solve(scene, mesh, options)
//   if (!r.ok()) std::cerr << r.summary.message;

#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "modalbench/kernels.hpp"
#include "modalbench/result.hpp"
#include "modalbench/scene.hpp"

namespace modalbench {

/// A mesh specification such as "64", "100x60" or "4x4": integers separated by 'x'.
/// Its meaning is the back-end's (segments, rigid elements per side, prisms, ...).
struct Discretization {
  std::vector<int> counts;  ///< empty for methods without a mesh (`exact`)
  std::string spec() const;  ///< "64", "100x60", or "-" when empty
  /// Parses "N" or "NxM[xK]"; throws InputError(key "--mesh") on anything else.
  static Discretization parse(const std::string& spec);
};

/// Mass model of back-ends that offer two (difference_eq); the others state that it does not apply.
enum class MassModel { Consistent, Lumped };
std::string to_string(MassModel);  ///< consistent | lumped
/// "consistent" or "lumped"; anything else throws InputError(source, key, the reason).
MassModel parse_mass_model(const std::string& text, const std::string& source, const std::string& key);

/// One back-end option: key, type, default, valid values and meaning (`modalbench options NAME`).
struct OptionSpec {
  enum class Type { Bool, Integer, Number, Choice };
  std::string key;
  Type type = Type::Number;
  std::string default_value;         ///< as the user would write it
  std::vector<std::string> choices;  ///< Choice: the allowed values
  double min = -1e308, max = 1e308;  ///< Integer, Number: inclusive range
  std::string help;
};

/// The back-end options in force for one solve: every spec'd key with its value (given or
/// default). Filled and validated by Solver::solve from the scene's [backend.NAME] table and
/// the command line (which wins); read by the back-end.
class ResolvedOptions {
 public:
  bool get_bool(const std::string& key) const;
  long get_integer(const std::string& key) const;
  double get_number(const std::string& key) const;
  const std::string& get_choice(const std::string& key) const;
  /// "key=value (source), ..." for the keys that were given; "defaults" if none.
  std::string given() const;

  struct Entry {
    OptionSpec spec;
    std::string text;    ///< the value as text
    std::string source;  ///< "default", the scene file, or "command line"
  };
  std::vector<Entry> entries;

 private:
  const Entry& find(const std::string& key, OptionSpec::Type type) const;
};

/// Run-time options common to all methods. Each field's default is stated here.
struct Options {
  MassModel mass = MassModel::Consistent;  ///< where a back-end offers both
  /// Largest peak memory a request may be estimated to need, bytes; 0: 80 % of what this process
  /// may use (physical memory, `ulimit -v`, `ulimit -d`, whichever is least). A request estimated
  /// above it is refused before anything is allocated (Status::ResourceLimit).
  double max_memory_bytes = 0;
  /// Longest a request may be estimated to run, seconds (refused above it, like memory).
  double max_time_s = 600;
  /// Estimate the discretization error of a meshed result from a second, coarser mesh (and judge
  /// it against the scene's request.tolerance). Off only where the caller runs its own convergence
  /// study (the comparison's timed runs).
  bool estimate_error = true;
  /// The mesh is the back-end's default (no --mesh given): while the error estimate exceeds the
  /// scene's request.tolerance, refine it (at most MeshFamily::refinement_steps times, each within
  /// the limits above) and report the first mesh that meets it, or the finest tried.
  bool refine_to_tolerance = false;
  /// Back-end options from the command line (key -> value text), over the scene's [backend.NAME].
  std::vector<std::pair<std::string, std::string>> backend;
  /// Who gave `backend` (errors name it): "command line" (keys `--option KEY`), or e.g. "solve()"
  /// for the Python API (keys `options.KEY`).
  std::string origin = "command line";
  /// Filled by Solver::solve (validated, defaults applied) before the back-end runs.
  ResolvedOptions resolved;
};

/// What a request is estimated to cost, before anything is allocated.
struct ResourceEstimate {
  double bytes = 0;    ///< peak memory of the solve (the scene and the process excluded)
  double seconds = 0;  ///< wall time on one core of this class of machine
  std::string basis;   ///< the sizes the estimate rests on, in words
};

/// A coarser mesh of the same family as a given one, for a result's own discretization-error
/// estimate: Richardson with the family's order, |f_h - f_H| / (ratio^order - 1).
struct CoarserMesh {
  Discretization mesh;
  double ratio = 2;  ///< H / h
  double order = 2;  ///< the order at which this family's frequencies converge
  /// The order of the next term of the frequencies' error expansion (extrapolation.hpp), where a
  /// test has measured it for this family; NaN: results on this family are not extrapolated.
  double next_order = std::numeric_limits<double>::quiet_NaN();
};

/// A back-end's meshes for one scene, described once (Solver::meshes) and driven by core and the
/// harness: the default path starts from `default_mesh` and refines it by `finer` (at most
/// `refinement_steps` times) towards the tolerance; a result's error estimate solves the `coarser`
/// meshes; the comparison runs the `ladder`; the stability sweep `theory` and `stress`. A method
/// without a mesh (`exact`) has the empty mesh everywhere and neither coarser nor finer meshes.
struct MeshFamily {
  Discretization default_mesh;             ///< the mesh used when none is given
  std::vector<Discretization> ladder;      ///< coarse to fine, for convergence studies (each valid for the scene)
  /// The mesh on which the back-end's model is the scene's own theory (the Euler-Bernoulli or
  /// Timoshenko beam, the Kirchhoff or Mindlin plate), for sweeps that judge it against the exact
  /// solution of that theory; nullopt where no mesh is (an Euler-Bernoulli chain on a Timoshenko
  /// scene: that is model error, not stability).
  std::optional<Discretization> theory;
  std::vector<Discretization> stress;      ///< the largest meshes worth trying in the stability sweep
  /// The most refinement steps the default path takes (a family that refines by small, graded
  /// steps takes more of them).
  int refinement_steps = 3;
  /// The order at which the frequencies converge, for a check against a finer mesh where a mesh
  /// has no coarser one.
  double order = 2.0;
  /// The coarser mesh a result on a mesh is checked against (nullopt: none, or the method is exact
  /// for its model); empty: the family has none.
  std::function<std::optional<CoarserMesh>(const Discretization&)> coarser;
  /// A mesh of the family about `factor` (> 1) times finer in each direction, or the next of a
  /// graded sequence (nullopt: none); empty: the family has none.
  std::function<std::optional<Discretization>(const Discretization&, double factor)> finer;

  std::optional<CoarserMesh> coarser_than(const Discretization& mesh) const;
  std::optional<Discretization> finer_than(const Discretization& mesh, double factor) const;
  /// One mesh for every purpose, without coarser or finer ones (a method without a mesh: the empty one).
  static MeshFamily single(const Discretization& mesh);
};

/// 80 % of the memory this process may use (physical memory, RLIMIT_AS, RLIMIT_DATA), bytes.
double default_memory_limit();

/// Lets the allocator keep freed blocks of up to 64 MiB for reuse instead of returning them to the
/// system (glibc: mallopt). A process-wide setting: the command-line tool and the benchmarks call it
/// once at start; a library user decides for their own process.
void reuse_freed_memory();

/// What a solver can compute for a scene, or why not.
struct Capability {
  bool modes = false, statics = false, frf = false;
  std::string reason;  ///< why something is not supported (empty if everything is)
  bool campbell = false;  ///< a rotor scene's Campbell diagram and critical speeds ([rotor])
  bool any() const { return modes || statics || frf || campbell; }
};

class Solver;
namespace detail {
void run_kernels(const Solver&, const Scene&, const Discretization&, const Options&, Result&, std::string*);
}  // namespace detail

class Solver {
 public:
  virtual ~Solver() = default;
  virtual std::string name() const = 0;
  /// One line: what model this back-end solves.
  virtual std::string description() const = 0;
  virtual Capability supports(const Scene& scene) const = 0;
  /// The back-end's meshes for the scene (MeshFamily). `options`: the mass model and the back-end
  /// options where the family's orders depend on them.
  virtual MeshFamily meshes(const Scene& scene, const Options& options) const = 0;
  /// The back-end's options (scene table [backend.NAME], command line --option KEY=VALUE).
  virtual std::vector<OptionSpec> option_specs() const { return {}; }
  /// Peak memory and time the request (scene, mesh) is estimated to need. May throw InputError
  /// for a mesh the back-end rejects. Default: nothing worth estimating.
  virtual ResourceEstimate estimate(const Scene&, const Discretization&, const Options&) const { return {}; }

  /// Validates the scene and the options, estimates the cost (refused above options' limits),
  /// times, and fills the summary; then runs the back-end's kernels (Kernels) for what the scene
  /// asks, and, for a meshed result, solves the coarser meshes to estimate its discretization
  /// error (Summary::error_estimate). Never throws for numerical trouble or unsupported requests:
  /// those come back in `summary.status`. Invalid input (bad mesh or option for this back-end, a
  /// scene that fails validation) comes back as Status::InvalidInput with the file, key and reason.
  Result solve(const Scene& scene, const Discretization& mesh, const Options& options) const;
  /// The default path: the family's default mesh, refined to the scene's tolerance
  /// (Options::refine_to_tolerance set), as `modalbench solve` without --mesh.
  Result solve_default(const Scene& scene, Options options) const;

 protected:
  // solve()'s kernel step (core/src/solve_kernels.cpp) builds the model and runs its kernels.
  friend void detail::run_kernels(const Solver&, const Scene&, const Discretization&, const Options&, Result&,
                                  std::string*);
  /// The back-end's model of `scene` on `mesh` (options.resolved is filled), with its kernels;
  /// what the model is (Summary::model, method, unknowns, modelling notes) goes into `result`.
  /// May throw InputError for a bad discretization; std::bad_alloc becomes Status::ResourceLimit,
  /// any other exception Status::NumericalIssue with its message.
  virtual std::unique_ptr<Kernels> build(const Scene& scene, const Discretization& mesh, const Options& options,
                                         Result& result) const = 0;
};

/// The only place that knows every back-end by name.
class Registry {
 public:
  void add(std::unique_ptr<Solver> solver);
  /// Throws std::invalid_argument naming the known solvers when `name` is unknown.
  const Solver& get(const std::string& name) const;
  std::vector<const Solver*> all() const;
  std::vector<std::string> names() const;
  /// Throws InputError (scene file, "backend.NAME") if the scene has options for a back-end
  /// that is not registered.
  void check_backend_tables(const Scene& scene) const;

 private:
  std::vector<std::unique_ptr<Solver>> solvers_;
};

}  // namespace modalbench
