#include "modalbench/solver.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace modalbench {

std::string to_string(Status s) {
  switch (s) {
    case Status::Success: return "success";
    case Status::NotConverged: return "not-converged";
    case Status::NumericalIssue: return "numerical-issue";
    case Status::Unsupported: return "unsupported";
    case Status::InvalidInput: return "invalid-input";
  }
  return "?";
}

std::string to_string(ModeFamily f) {
  switch (f) {
    case ModeFamily::BendingXZ: return "bending-xz";
    case ModeFamily::BendingXY: return "bending-xy";
    case ModeFamily::Axial: return "axial";
    case ModeFamily::Torsion: return "torsion";
    case ModeFamily::Plate: return "plate";
    case ModeFamily::Rigid: return "rigid";
    case ModeFamily::Unknown: return "unknown";
  }
  return "unknown";
}

std::string Discretization::spec() const {
  if (counts.empty()) return "-";
  std::string s;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    if (i) s += 'x';
    s += std::to_string(counts[i]);
  }
  return s;
}

Discretization Discretization::parse(const std::string& spec) {
  Discretization d;
  if (spec.empty() || spec == "-") return d;
  std::size_t pos = 0;
  while (pos <= spec.size()) {
    std::size_t end = spec.find('x', pos);
    if (end == std::string::npos) end = spec.size();
    const std::string part = spec.substr(pos, end - pos);
    if (part.empty() || part.find_first_not_of("0123456789") != std::string::npos || part.size() > 9)
      throw InputError("command line", "--mesh",
                       "'" + spec + "' is not a mesh: expected positive integers joined by 'x' (e.g. 64, 100x60)");
    const int n = std::stoi(part);
    if (n <= 0) throw InputError("command line", "--mesh", "mesh counts must be >= 1 (got '" + spec + "')");
    d.counts.push_back(n);
    pos = end + 1;
  }
  return d;
}

Result Solver::solve(const Scene& scene, const Discretization& mesh, const Options& options) const {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  Result result;
  auto finish = [&](Status st, std::string msg) {
    result.summary.status = st;
    result.summary.message = std::move(msg);
  };
  try {
    validate(scene);
    if (options.mass != "consistent" && options.mass != "lumped")
      throw InputError("command line", "--mass", "must be consistent or lumped (got '" + options.mass + "')");
    const Capability cap = supports(scene);
    // Say exactly which requested quantities this back-end will not compute.
    std::vector<std::string> missing;
    const auto& rq = scene.request;
    if (rq.modes > 0 && !cap.modes) missing.push_back("natural frequencies");
    if (!rq.probes.empty() && !cap.statics) missing.push_back("static deflections");
    if (rq.frf && !cap.frf) missing.push_back("FRF");
    const bool wants_something = rq.modes > 0 || !rq.probes.empty() || rq.frf.has_value();
    const bool can_something = (rq.modes > 0 && cap.modes) || (!rq.probes.empty() && cap.statics) || (rq.frf && cap.frf);
    if (!cap.any() || (wants_something && !can_something)) {
      finish(Status::Unsupported, cap.reason.empty() ? "nothing requested is supported" : cap.reason);
    } else if (!options.validate_only) {
      do_solve(scene, mesh, options, result);
      if (!missing.empty()) {
        std::string what;
        for (const auto& m : missing) what += (what.empty() ? "" : ", ") + m;
        result.summary.warnings.push_back("not computed: " + what + (cap.reason.empty() ? "" : " (" + cap.reason + ")"));
      }
    }
  } catch (const InputError& e) {
    finish(Status::InvalidInput, e.what());
  } catch (const std::exception& e) {
    finish(Status::NumericalIssue, std::string(name()) + " failed: " + e.what());
  }
  // Nothing non-finite leaves a solver unflagged.
  bool finite = true;
  for (double w : result.frequencies_rad_s) finite = finite && std::isfinite(w);
  for (const auto& d : result.deflections)
    for (double v : {d.u, d.v, d.w, d.theta_x, d.theta_y, d.theta_z}) finite = finite && std::isfinite(v);
  for (const auto& f : result.frf) finite = finite && std::isfinite(std::abs(f.receptance));
  if (!finite && result.summary.status == Status::Success)
    finish(Status::NumericalIssue, "non-finite value in the result");
  if (result.mode_families.size() != result.frequencies_rad_s.size())
    result.mode_families.resize(result.frequencies_rad_s.size(), ModeFamily::Unknown);
  result.summary.total_time_s = std::chrono::duration<double>(clock::now() - t0).count();
  return result;
}

void Registry::add(std::unique_ptr<Solver> solver) {
  const std::string n = solver->name();
  for (auto& s : solvers_)
    if (s->name() == n) throw std::invalid_argument("solver '" + n + "' registered twice");
  solvers_.push_back(std::move(solver));
}

const Solver& Registry::get(const std::string& name) const {
  for (auto& s : solvers_)
    if (s->name() == name) return *s;
  std::string known;
  for (auto& s : solvers_) {
    if (!known.empty()) known += ", ";
    known += s->name();
  }
  throw std::invalid_argument("unknown back-end '" + name + "' (known: " + known + ")");
}

std::vector<const Solver*> Registry::all() const {
  std::vector<const Solver*> v;
  for (auto& s : solvers_) v.push_back(s.get());
  return v;
}

std::vector<std::string> Registry::names() const {
  std::vector<std::string> v;
  for (auto& s : solvers_) v.push_back(s->name());
  return v;
}

}  // namespace modalbench
