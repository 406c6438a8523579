// The back-end's kernels for one request on one mesh (kernels.hpp): the model built, then each
// requested quantity's kernel run, timed and isolated, in the order every back-end shares.
#include <fmt/format.h>

#include <chrono>
#include <exception>
#include <functional>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>

#include "solve_internal.hpp"

namespace modalbench {

void Kernels::missing(const std::string& quantity) {
  throw std::logic_error("the back-end has no kernel for " + quantity + " (its Capability should not offer it)");
}

namespace detail {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// What a step's failure to go on (an exception) means for the result: the input's fault, or a
/// numerical breakdown named by the back-end and the quantity.
void raise_thrown(const std::string& backend, const Scene& scene, const std::string& quantity, Summary& sum) {
  try {
    throw;
  } catch (const std::bad_alloc&) {
    throw;  // the whole request: Status::ResourceLimit (solve_pipeline.cpp)
  } catch (const InputError& e) {
    sum.raise(Status::InvalidInput, e.what());
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    if (quantity == "statics" && what.rfind("mechanism", 0) == 0)
      sum.raise(Status::InvalidInput, scene.source + ": supports: static solve impossible: " + what);
    else
      sum.raise(Status::NumericalIssue, backend + ": " + quantity + ": " + what);
  } catch (const std::exception& e) {
    sum.raise(Status::NumericalIssue, backend + ": " + quantity + ": " + e.what());
  }
}

/// Runs one kernel with a status and message of its own (Summary::steps), timed into `phase`; the
/// summary's status and message become those before it and the step's, joined as Summary::raise
/// joins them. `threw`: whether the kernel stopped on an exception (its quantity is then not given).
StepOutcome run_step(const std::string& backend, const Scene& scene, const std::string& step,
                     const std::string& quantity, const std::function<void()>& kernel, double& phase, Result& r,
                     bool& threw) {
  Summary& sum = r.summary;
  const Status status_before = sum.status;
  std::string message_before = std::move(sum.message);
  sum.status = Status::Success;
  sum.message.clear();
  const auto t0 = Clock::now();
  threw = false;
  try {
    kernel();
  } catch (...) {
    threw = true;
    raise_thrown(backend, scene, quantity, sum);
  }
  phase += seconds_since(t0);
  StepOutcome out{step, sum.status, sum.message};
  sum.status = status_before;
  sum.message = std::move(message_before);
  sum.raise(out.status, out.message);
  return out;
}

}  // namespace

void run_kernels(const Solver& solver, const Scene& scene, const Discretization& mesh, const Options& options,
                 Result& r, std::string* statics_refused) {
  const auto t0 = Clock::now();
  const std::unique_ptr<Kernels> k = solver.build(scene, mesh, options, r);
  r.summary.timings_s.build += seconds_since(t0);
  const auto& rq = scene.request;
  PhaseTimes& t = r.summary.timings_s;
  const std::string name = solver.name();
  // Runs a kernel as a step; true where it stopped on an exception.
  auto step = [&](const std::string& id, const std::string& quantity, void (Kernels::*kernel)(Result&), double& phase) {
    bool threw = false;
    r.summary.steps.push_back(run_step(name, scene, id, quantity, [&] { (k.get()->*kernel)(r); }, phase, r, threw));
    return threw;
  };
  const bool modes_threw = rq.modes > 0 && step("modes", "natural frequencies", &Kernels::modes, t.modes);
  if (rq.modes > 0 && rq.shapes && !modes_threw && !r.frequencies_rad_s.empty())
    if (step("shapes", "mode shapes", &Kernels::shapes, t.modes)) r.mode_shapes = {};
  if (!rq.probes.empty()) {
    const Summary before = r.summary;
    const bool threw = step("statics", "statics", &Kernels::statics, t.statics);
    const StepOutcome s = r.summary.steps.back();
    if (s.status == Status::InvalidInput && statics_refused) {
      // Statics refused on a scene that asks them only for a time history's static correction:
      // the request goes on without them, as if no probe had been asked (the caller says so).
      *statics_refused = s.message;
      const PhaseTimes times = r.summary.timings_s;
      r.summary = before;
      r.summary.timings_s = times;
      r.deflections.clear();
      r.reactions.clear();
    } else if (threw) {
      r.deflections.clear();
      r.reactions.clear();
    }
  }
  if (rq.frf) step("frf", "FRF", &Kernels::frf, t.frf);
  if (scene.rotor) step("campbell", "Campbell diagram", &Kernels::campbell, t.campbell);
  k->close(r);
}

}  // namespace detail

}  // namespace modalbench
