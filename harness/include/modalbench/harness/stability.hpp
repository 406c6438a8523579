#pragma once
// The stability sweep: slenderness L/h 0.5 ... 1e5 (Timoshenko and Euler-Bernoulli), each of the
// four end springs alone from K = 1e-12 to 1e15 (and all four together), free and cantilever
// plates, high modes (the 1000th of a beam, the 100th of a plate), each back-end's largest
// meshes. Each back-end runs where its model is the scene's theory (MeshFamily::theory), with its
// own error estimate; every run must return a finite, correctly counted, ordered result within
// its own estimate of the exact one, or say why not (flagged, refused). Nothing wrong may pass
// unflagged.

#include <ostream>
#include <string>
#include <vector>

#include "modalbench/result.hpp"
#include "modalbench/scene.hpp"
#include "modalbench/solver.hpp"

namespace modalbench {

struct StabilityCase {
  std::string group;  ///< slenderness | springs | high-modes | plates | size
  std::string label;
  Scene scene;
  bool stress_meshes = false;  ///< use each back-end's stress meshes (MeshFamily::stress) instead of its default mesh
};

enum class Verdict { Ok, Refused, Flagged, UnflaggedBad };
std::string to_string(Verdict);

struct StabilityRow {
  std::string group, label, backend, mesh;
  Verdict verdict = Verdict::Ok;
  Status status = Status::Success;
  std::string detail;           ///< why flagged / refused / bad
  int requested = 0, returned = 0;
  double max_error_vs_exact = 0;  ///< NaN if no exact reference
  double time_s = 0;
};

/// The built-in sweep. `quick` keeps a handful of cases per group (tests).
std::vector<StabilityCase> stability_cases(bool quick);

/// Runs every case with every back-end (the `exact` back-end is the reference, not a row).
std::vector<StabilityRow> run_stability(const std::vector<StabilityCase>& cases, const Registry& registry,
                                        std::ostream* progress);

/// Judges one result (exposed for tests).
StabilityRow judge(const StabilityCase& c, const std::string& backend, const Discretization& mesh, const Result& r,
                   const Result* exact);

/// stability.md, stability.html, stability.csv in `dir`. Returns the number of unflagged bad rows.
int write_stability_report(const std::vector<StabilityRow>& rows, const std::string& dir);

}  // namespace modalbench
