#include "modalbench/solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <new>
#include <cmath>
#include <stdexcept>

namespace modalbench {

std::string to_string(Status s) {
  switch (s) {
    case Status::Success: return "success";
    case Status::NotConverged: return "not-converged";
    case Status::NumericalIssue: return "numerical-issue";
    case Status::ResourceLimit: return "resource-limit";
    case Status::Unsupported: return "unsupported";
    case Status::InvalidInput: return "invalid-input";
  }
  return "?";
}

int severity(Status s) { return static_cast<int>(s); }

void Summary::raise(Status s, const std::string& text) {
  if (severity(s) > severity(status)) status = s;
  if (!text.empty()) message += (message.empty() ? "" : "; ") + text;
}

void Summary::set_diagnostic(const std::string& name, double value) {
  for (auto& [n, v] : diagnostics)
    if (n == name) {
      v = value;
      return;
    }
  diagnostics.emplace_back(name, value);
}

double Summary::diagnostic(const std::string& name) const {
  for (const auto& [n, v] : diagnostics)
    if (n == name) return v;
  return kNotMeasured;
}

void Summary::note_backward_error(double e) {
  if (std::isnan(e)) return;
  max_backward_error = std::isnan(max_backward_error) ? e : std::max(max_backward_error, e);
}

std::string to_string(MassModel m) { return m == MassModel::Consistent ? "consistent" : "lumped"; }

MassModel parse_mass_model(const std::string& text, const std::string& source, const std::string& key) {
  if (text == "consistent") return MassModel::Consistent;
  if (text == "lumped") return MassModel::Lumped;
  throw InputError(source, key, "must be consistent or lumped (got '" + text + "')");
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

namespace {

bool parse_bool(const std::string& t, bool& out) {
  if (t == "true") out = true;
  else if (t == "false") out = false;
  else return false;
  return true;
}

/// Checks `text` against `spec`; returns the reason it is not valid, or "".
std::string check_option(const OptionSpec& spec, const std::string& text) {
  switch (spec.type) {
    case OptionSpec::Type::Bool: {
      bool b;
      return parse_bool(text, b) ? "" : "must be true or false (got '" + text + "')";
    }
    case OptionSpec::Type::Choice: {
      if (std::find(spec.choices.begin(), spec.choices.end(), text) != spec.choices.end()) return "";
      std::string list;
      for (const auto& c : spec.choices) list += (list.empty() ? "" : ", ") + c;
      return "must be one of " + list + " (got '" + text + "')";
    }
    case OptionSpec::Type::Integer:
    case OptionSpec::Type::Number: {
      const bool integer = spec.type == OptionSpec::Type::Integer;
      char* end = nullptr;
      errno = 0;
      const double v = integer ? static_cast<double>(std::strtoll(text.c_str(), &end, 10)) : std::strtod(text.c_str(), &end);
      if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v))
        return fmt::format("must be {} (got '{}')", integer ? "an integer" : "a finite number", text);
      if (!(v >= spec.min && v <= spec.max)) return fmt::format("must lie in [{}, {}] (got {})", spec.min, spec.max, text);
      return "";
    }
  }
  return "";
}

ResolvedOptions resolve_options(const Solver& solver, const Scene& scene, const Options& options) {
  const std::vector<OptionSpec> specs = solver.option_specs();
  ResolvedOptions out;
  for (const auto& spec : specs) out.entries.push_back({spec, spec.default_value, "default"});
  std::string allowed;
  for (const auto& spec : specs) allowed += (allowed.empty() ? "" : ", ") + spec.key;
  if (allowed.empty()) allowed = "none";
  auto apply = [&](const std::string& key, const std::string& text, const std::string& source,
                   const std::string& full_key) {
    for (auto& e : out.entries)
      if (e.spec.key == key) {
        const std::string why = check_option(e.spec, text);
        if (!why.empty()) throw InputError(source, full_key, why);
        e.text = text;
        e.source = source;
        return;
      }
    throw InputError(source, full_key, "unknown option of back-end " + solver.name() + " (allowed: " + allowed + ")");
  };
  if (auto it = scene.backend_options.find(solver.name()); it != scene.backend_options.end())
    for (const auto& o : it->second)
      apply(o.key, o.text, scene.source.empty() ? "<scene>" : scene.source, "backend." + solver.name() + "." + o.key);
  for (const auto& [key, text] : options.backend) apply(key, text, "command line", "--option " + key);
  return out;
}

}  // namespace

const ResolvedOptions::Entry& ResolvedOptions::find(const std::string& key, OptionSpec::Type type) const {
  for (const auto& e : entries)
    if (e.spec.key == key) {
      if (e.spec.type != type) throw std::logic_error("option '" + key + "' read with the wrong type");
      return e;
    }
  throw std::logic_error("option '" + key + "' is not declared by the back-end");
}

bool ResolvedOptions::get_bool(const std::string& key) const {
  bool b = false;
  parse_bool(find(key, OptionSpec::Type::Bool).text, b);
  return b;
}
long ResolvedOptions::get_integer(const std::string& key) const {
  return std::strtol(find(key, OptionSpec::Type::Integer).text.c_str(), nullptr, 10);
}
double ResolvedOptions::get_number(const std::string& key) const {
  return std::strtod(find(key, OptionSpec::Type::Number).text.c_str(), nullptr);
}
const std::string& ResolvedOptions::get_choice(const std::string& key) const {
  return find(key, OptionSpec::Type::Choice).text;
}
std::string ResolvedOptions::given() const {
  std::string out;
  for (const auto& e : entries)
    if (e.source != "default") out += fmt::format("{}{}={} ({})", out.empty() ? "" : ", ", e.spec.key, e.text, e.source);
  return out.empty() ? "defaults" : out;
}

Result Solver::solve(const Scene& scene, const Discretization& mesh, const Options& options) const {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  Result result;
  auto& sum = result.summary;
  try {
    validate(scene);
    Options opt = options;
    opt.resolved = resolve_options(*this, scene, options);
    sum.method_requested = opt.resolved.given();
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
      sum.raise(Status::Unsupported, cap.reason.empty() ? "nothing requested is supported" : cap.reason);
    } else {
      do_solve(scene, mesh, opt, result);
      if (!missing.empty()) {
        std::string what;
        for (const auto& m : missing) what += (what.empty() ? "" : ", ") + m;
        sum.warnings.push_back("not computed: " + what + (cap.reason.empty() ? "" : " (" + cap.reason + ")"));
      }
    }
  } catch (const InputError& e) {
    sum.raise(Status::InvalidInput, e.what());
  } catch (const std::bad_alloc&) {
    sum.raise(Status::ResourceLimit, std::string(name()) + ": out of memory (std::bad_alloc): the request is too large "
                                     "for this machine; use a coarser mesh or fewer modes");
  } catch (const std::exception& e) {
    sum.raise(Status::NumericalIssue, std::string(name()) + " failed: " + e.what());
  }
  // Nothing non-finite leaves a solver unflagged.
  bool finite = true;
  for (double w : result.frequencies_rad_s) finite = finite && std::isfinite(w);
  for (const auto& d : result.deflections)
    for (double v : {d.u, d.v, d.w, d.theta_x, d.theta_y, d.theta_z}) finite = finite && std::isfinite(v);
  for (const auto& f : result.frf) finite = finite && std::isfinite(std::abs(f.receptance));
  if (!finite && sum.status == Status::Success) sum.raise(Status::NumericalIssue, "non-finite value in the result");
  if (result.mode_families.size() != result.frequencies_rad_s.size())
    result.mode_families.resize(result.frequencies_rad_s.size(), ModeFamily::Unknown);
  sum.total_time_s = std::chrono::duration<double>(clock::now() - t0).count();
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

void Registry::check_backend_tables(const Scene& scene) const {
  for (const auto& [name, opts] : scene.backend_options) {
    bool known = false;
    for (const auto& sv : solvers_) known = known || sv->name() == name;
    if (!known) {
      std::string list;
      for (const auto& sv : solvers_) list += (list.empty() ? "" : ", ") + sv->name();
      throw InputError(scene.source, "backend." + name, "no such back-end (known: " + list + ")");
    }
  }
}

std::vector<std::string> Registry::names() const {
  std::vector<std::string> v;
  for (auto& s : solvers_) v.push_back(s->name());
  return v;
}

}  // namespace modalbench
