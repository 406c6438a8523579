#pragma once
// One interface for every method: Scene --(Solver::solve, Discretization, Options)--> Result.
//
// Usage:
//   Registry registry = ...;                      // see solvers/registry.hpp
//   const Solver& s = registry.get("exact");      // unknown names list the known ones
//   Scene scene = load_scene("scenes/paper_fixed_beam.toml");
//   Result r = s.solve(scene, s.default_mesh(scene), Options{});
//   if (!r.ok()) std::cerr << r.summary.message;

#include <memory>
#include <string>
#include <vector>

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

/// Back-end options common to all methods. Each field's default is stated here.
struct Options {
  std::string mass = "consistent";  ///< consistent | lumped (where a back-end offers both)
  int frf_modes = 0;                ///< 0: direct FRF solve; >0: modal superposition with this many modes
  bool validate_only = false;       ///< stop after validation (used by tests of error paths)
};

/// What a solver can compute for a scene, or why not.
struct Capability {
  bool modes = false, statics = false, frf = false;
  std::string reason;  ///< why something is not supported (empty if everything is)
  bool any() const { return modes || statics || frf; }
};

class Solver {
 public:
  virtual ~Solver() = default;
  virtual std::string name() const = 0;
  /// One line: what model this back-end solves.
  virtual std::string description() const = 0;
  virtual Capability supports(const Scene& scene) const = 0;
  /// The mesh used when none is given.
  virtual Discretization default_mesh(const Scene& scene) const = 0;
  /// Meshes from coarse to fine for convergence studies (each should be valid for the scene).
  virtual std::vector<Discretization> mesh_ladder(const Scene& scene) const { return {default_mesh(scene)}; }
  /// The largest meshes worth trying in the stability sweep (default: the finest of the ladder).
  virtual std::vector<Discretization> stress_meshes(const Scene& scene) const { return {mesh_ladder(scene).back()}; }

  /// Validates, times, and fills the summary; then calls the back-end. Never throws for
  /// numerical trouble or unsupported requests: those come back in `summary.status`.
  /// Invalid input (bad mesh for this back-end, a scene that fails validation) comes back
  /// as Status::InvalidInput with the reason.
  Result solve(const Scene& scene, const Discretization& mesh, const Options& options) const;

 protected:
  /// The back-end's work. May throw InputError for a bad discretization; any other
  /// exception becomes Status::NumericalIssue with its message.
  virtual void do_solve(const Scene& scene, const Discretization& mesh, const Options& options,
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

 private:
  std::vector<std::unique_ptr<Solver>> solvers_;
};

}  // namespace modalbench
