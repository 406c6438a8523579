#pragma once
// A back-end's model of one scene on one mesh, with one kernel per quantity: what core's pipeline
// (Solver::solve) runs for a request.
//
// The pipeline builds the model (Solver::build), then runs, in this order, the kernels of what the
// scene asks and the back-end's Capability offers:
//   modes     request.modes natural frequencies (ascending, repeated ones repeated) and families;
//   shapes    request.shapes, of the frequencies `modes` found (run only where it found some);
//   statics   deflections (and stress resultants) at request.probes under the static loads, and
//             the support reactions;
//   frf       request.frf's receptance samples;
//   campbell  a rotor's Campbell diagram and critical speeds ([rotor]);
// and last `close` (what the back-end reports of its model as a whole: sizes, counts, checks that
// span the quantities). Each kernel is timed into its phase (PhaseTimes: shapes are charged to
// modes) and has its own status and message (Summary::steps): a kernel that fails leaves the
// others' results standing, and the result's status is the worst of them.
//
// A kernel writes its quantity, diagnostics and warnings into the result, reports a failed check
// with Summary::raise, and throws only where it cannot go on: InputError for the user's input
// (Status::InvalidInput), std::bad_alloc (the whole request: Status::ResourceLimit), any other
// exception a numerical breakdown (Status::NumericalIssue, "BACKEND: QUANTITY: what"). A statics
// kernel that finds the supports leave a mechanism throws a std::runtime_error whose message
// starts with "mechanism": the input's fault (Status::InvalidInput, "SCENE: supports: static solve
// impossible: what"). A kernel the back-end does not provide is never asked for (its Capability
// does not offer the quantity); asked all the same, it fails with a numerical issue saying so.
//
// Usage (a back-end):
//   class MyKernels final : public Kernels {
//     void modes(Result& r) override { ... r.frequencies_rad_s, r.mode_families ... }
//   };
//   std::unique_ptr<Kernels> MySolver::build(const Scene& s, const Discretization& m, const Options& o,
//                                            Result& r) const { return std::make_unique<MyKernels>(...); }

#include <string>

namespace modalbench {

struct Result;

class Kernels {
 public:
  virtual ~Kernels() = default;
  virtual void modes(Result&) { missing("natural frequencies"); }
  virtual void shapes(Result&) { missing("mode shapes"); }
  virtual void statics(Result&) { missing("statics"); }
  virtual void frf(Result&) { missing("FRF"); }
  virtual void campbell(Result&) { missing("Campbell diagram"); }
  virtual void close(Result&) {}

 protected:
  /// Throws std::logic_error: the back-end was asked for a quantity it has no kernel for.
  [[noreturn]] static void missing(const std::string& quantity);
};

}  // namespace modalbench
