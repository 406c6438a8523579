#include "modalbench/solver.hpp"

#include "modalbench/extrapolation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <new>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <fstream>
#include <sys/resource.h>
#include <unistd.h>

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

void note_frf_omissions(Summary& sum, int skipped, int points, const std::string& reason) {
  if (skipped <= 0) return;
  if (skipped <= 2) {
    sum.warnings.push_back(fmt::format("FRF: {} of {} sample(s) omitted (singular dynamic stiffness: on or within "
                                       "rounding of a natural frequency; {})", skipped, points, reason));
    return;
  }
  sum.raise(Status::NumericalIssue, fmt::format("FRF: {} of {} samples could not be computed ({})", skipped, points, reason));
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

double default_memory_limit() {
  double avail = static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  if (!(avail > 0)) avail = 8.0 * (1ull << 30);
  // An address-space limit counts what the process has mapped already (libraries, thread stacks).
  double mapped = 0;
  {
    std::ifstream statm("/proc/self/statm");
    double pages = 0;
    if (statm >> pages) mapped = pages * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  }
  // Under an address-space limit, OpenBLAS's per-thread work buffers (128 MiB each, two threads)
  // are mapped on first use and count too.
  const double blas_buffers = 2.0 * 134225920.0;
  for (int which : {RLIMIT_AS, RLIMIT_DATA}) {
    rlimit rl{};
    if (getrlimit(which, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY)
      avail = std::min(avail, std::max(0.0, static_cast<double>(rl.rlim_cur) - mapped - blas_buffers));
  }
  return 0.8 * avail;
}

namespace {

/// Maps the first pages of this thread's stack now. The main thread's stack grows on demand, and
/// under an address-space limit (ulimit -v) that growth fails once the heap has taken the rest:
/// the next deep call (Eigen keeps temporaries of up to 128 KB on the stack) is then a SIGSEGV
/// instead of a std::bad_alloc the solver can report. Linux never unmaps grown stack pages.
[[gnu::noinline]] void map_stack_pages() {
  static thread_local bool done = false;
  if (done) return;
  done = true;
  rlimit rl{};
  std::size_t bytes = std::size_t(2) << 20;
  if (getrlimit(RLIMIT_STACK, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY)
    bytes = std::min<std::size_t>(bytes, static_cast<std::size_t>(rl.rlim_cur) / 4);
  volatile char* p = static_cast<volatile char*>(__builtin_alloca(bytes));
  for (std::size_t i = 0; i < bytes; i += 4096) p[i] = 0;
}

/// Peak resident memory of this process so far (VmHWM), bytes; NaN where unknown.
double peak_resident_bytes() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmHWM:") {
      double kb = 0;
      status >> kb;
      return kb * 1024.0;
    }
    status.ignore(1 << 12, '\n');
  }
  return kNotMeasured;
}

std::string gigabytes(double bytes) { return fmt::format("{:.3g} GB", bytes / 1e9); }

// Roache's factors of safety (extrapolation.hpp): kRoacheSafetyFactor for a two-mesh estimate with
// the formal order, kRoacheGuardFactor for the guard from the next coarser pair (a coarse pair
// converges faster than its formal order as a rule, so carrying it to h with that order over-states
// the error rather than under-states it).

/// A solve of the error estimate: its mesh, how much coarser it is than the next finer one, and
/// its result.
struct MeshSolve {
  std::string spec;
  double ratio = 2.0;
  const Result* result = nullptr;
};

/// The discretization error of `fine` (result.hpp, ErrorEstimate) from `coarse` and, where given,
/// `coarser` (the next coarser mesh); returns the estimate and what exceeds the scene's
/// tolerance. With other_is_finer, `coarse` is in fact a finer mesh (the judged one has no
/// coarser): the roles of the pair swap and `coarser` is not used.
std::pair<ErrorEstimate, std::vector<std::string>> judge_discretization(const Scene& scene, double order, const Result& fine,
                                                                        const MeshSolve& coarse,
                                                                        const std::optional<MeshSolve>& coarser = std::nullopt,
                                                                        bool other_is_finer = false) {
  ErrorEstimate e;
  e.tolerance = scene.request.tolerance;
  e.coarse_mesh = coarse.spec;
  e.ratio = coarse.ratio;
  e.order = order;
  e.safety_factor = kRoacheSafetyFactor;
  const bool third = coarser && coarser->result && !other_is_finer;
  if (third) e.coarser_mesh = coarser->spec;
  const double rp = std::pow(coarse.ratio, order);
  // `fine` is the result judged; when the other mesh is the finer one, the error of the coarser
  // result is |q_H - q_h| r^p / (r^p - 1).
  const double denom = other_is_finer ? (rp - 1.0) / rp : rp - 1.0;
  const double denom2 = third ? (std::pow(coarser->ratio, order) - 1.0) * rp : 0.0;
  // max(3 e1, 1.25 e2) for one quantity: q (judged), qc (coarse), qcc (coarser, when there is one).
  // Where the three meshes show an order below first (the pair differences resolved, above the
  // solve's rounding, and shrinking by less than r), the meshes are not yet in the asymptotic
  // range: the observed order is used instead (floored at 1/4), which widens the estimate. A dtfm plate whose Kirchhoff penalty was set to 1e-3 converged at first order
  // between 7, 15 and 30 strips; the formal order gave 0.21 for an error of 0.55.
  // Frequencies only: a point load's deflection converges like h^2 log h, below its formal order
  // on every mesh, and its two-mesh estimate already holds (rfem's paper plate: 2e-4 off, estimate
  // 6e-4). `noise`: differences below it (relative; the solve's own rounding) say nothing of the order.
  double lowest_order = order;  // the lowest observed order used (frequencies)
  auto gci = [&](double q, double qc, double qcc, double scale, double noise = kNotMeasured) {
    const double d1 = std::abs(q - qc), d2 = third && std::isfinite(qcc) ? std::abs(qc - qcc) : kNotMeasured;
    double dn = denom, dn2 = denom2;
    if (std::isfinite(noise) && std::isfinite(d2) && d1 > noise * scale && d2 > noise * scale) {
      // Only below first order: between that and the formal order (a point load's h^2 log h, a
      // Mindlin plate's mixed terms) the factor of safety 3 covers it, and widening there sent
      // the default meshes' refinement of dtfm plates past minutes.
      const double cap = std::min(order, 1.0);
      const double p = observed_order(d1, d2, coarse.ratio, coarser->ratio, 0.25, cap);
      if (p < cap) {
        lowest_order = std::min(lowest_order, p);
        const double rpo = std::pow(coarse.ratio, p);
        dn = rpo - 1.0;
        dn2 = (std::pow(coarser->ratio, p) - 1.0) * rpo;
      }
    }
    double err = kRoacheSafetyFactor * d1 / dn / scale;
    if (std::isfinite(d2)) err = std::max(err, kRoacheGuardFactor * d2 / dn2 / scale);
    return std::isfinite(err) ? err : std::numeric_limits<double>::infinity();
  };
  std::vector<std::string> problems;
  if (scene.request.modes > 0 && !fine.frequencies_rad_s.empty()) {
    const auto& f = fine.frequencies_rad_s;
    const auto& c = coarse.result->frequencies_rad_s;
    const std::vector<double> none;
    const auto& cc = third ? coarser->result->frequencies_rad_s : none;
    const std::size_t n = std::min(f.size(), c.size());
    double noise = 1e-10;
    for (const Result* x : {&fine, coarse.result, third ? coarser->result : nullptr})
      if (x && std::isfinite(x->summary.diagnostic("frequency_solve_error_bound")))
        noise = std::max(noise, 10.0 * x->summary.diagnostic("frequency_solve_error_bound"));
    double worst = 0;
    std::size_t worst_mode = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (f[i] == 0 && c[i] == 0) continue;  // rigid-body modes on both meshes
      const double qcc = i < cc.size() && !(cc[i] == 0 && c[i] != 0) ? cc[i] : kNotMeasured;
      const double rel = gci(f[i], c[i], qcc, std::max(std::abs(f[i]), std::abs(c[i])), noise);
      if (!(rel <= worst)) {
        worst = rel;
        worst_mode = i + 1;
      }
    }
    // The solve's own bound (rounding): refinement does not reduce it, Richardson does not see it.
    const double solve = fine.summary.diagnostic("frequency_solve_error_bound");
    e.frequencies_solve = solve;
    e.frequencies = worst + (std::isfinite(solve) ? solve : 0.0);
    if (n < f.size())
      problems.push_back(fmt::format("frequencies: modes {}..{} have no counterpart on the coarser mesh {}, so their "
                                     "discretization error is not estimated", n + 1, f.size(), coarse.spec));
    // A solve bound past the tolerance is the back-end's own numerical issue (it says so); a
    // finer mesh is advised only where the discretization part is what exceeds it.
    if (!(e.frequencies <= e.tolerance) && !(std::isfinite(solve) && solve > e.tolerance))
      problems.push_back(fmt::format("frequencies: estimated discretization error {:.2g} (mode {}; mesh {} against {}{}, "
                                     "Richardson of order {}, factors of safety {:g} and {:g}{}) exceeds the tolerance "
                                     "{:.2g} ([request] tolerance): use a finer mesh",
                                     e.frequencies, worst_mode, fine.summary.mesh, coarse.spec,
                                     third ? " and " + coarser->spec : std::string(),
                                     lowest_order < order
                                         ? fmt::format("{:g}, down to the observed {:.2g}: not yet in the asymptotic range",
                                                       order, lowest_order)
                                         : fmt::format("{:g}", order),
                                     kRoacheSafetyFactor, kRoacheGuardFactor,
                                     std::isfinite(solve) ? fmt::format(", plus the solve's own bound {:.2g}", solve)
                                                          : std::string(),
                                     e.tolerance));
  }
  const Result& cr = *coarse.result;
  if (!scene.request.probes.empty() && fine.deflections.size() == cr.deflections.size() && !fine.deflections.empty()) {
    double scale = 0, worst = 0;
    for (const auto& d : fine.deflections) scale = std::max({scale, std::abs(d.u), std::abs(d.v), std::abs(d.w)});
    const bool third_defl = third && coarser->result->deflections.size() == fine.deflections.size();
    if (scale > 0) {
      for (std::size_t i = 0; i < fine.deflections.size(); ++i) {
        const auto& x = fine.deflections[i];
        const auto& y = cr.deflections[i];
        const double nan = kNotMeasured;
        const auto* z = third_defl ? &coarser->result->deflections[i] : nullptr;
        worst = std::max({worst, gci(x.u, y.u, z ? z->u : nan, scale), gci(x.v, y.v, z ? z->v : nan, scale),
                          gci(x.w, y.w, z ? z->w : nan, scale)});
      }
      e.deflections = worst;
      if (!(worst <= e.tolerance))
        problems.push_back(fmt::format("deflections: estimated discretization error {:.2g} of the largest deflection "
                                       "(mesh {} against {}{}) exceeds the tolerance {:.2g} ([request] tolerance): use a "
                                       "finer mesh",
                                       worst, fine.summary.mesh, coarse.spec,
                                       third_defl ? " and " + coarser->spec : std::string(), e.tolerance));
    }
  }
  if (other_is_finer)
    e.note = fmt::format("grid convergence index against the finer mesh {}: {:g} |q(mesh {}) - q(mesh {})| {:.3g}^{:g} "
                         "/ ({:.3g}^{:g} - 1), relative (no coarser mesh of the family)",
                         coarse.spec, kRoacheSafetyFactor, fine.summary.mesh, coarse.spec, coarse.ratio, order, coarse.ratio,
                         order);
  else if (third)
    e.note = fmt::format("grid convergence index: max({:g} |q(mesh {}) - q(mesh {})| / ({:.3g}^{:g} - 1), {:g} |q(mesh {}) - "
                         "q(mesh {})| / ({:.3g}^{:g} - 1) / {:.3g}^{:g}), relative; p the observed order per quantity "
                         "where the three meshes show a lower one (at least 1/4)",
                         kRoacheSafetyFactor, fine.summary.mesh, coarse.spec, coarse.ratio, order, kRoacheGuardFactor, coarse.spec,
                         coarser->spec, coarser->ratio, order, coarse.ratio, order);
  else
    e.note = fmt::format("grid convergence index: {:g} |q(mesh {}) - q(mesh {})| / ({:.3g}^{:g} - 1), relative",
                         kRoacheSafetyFactor, fine.summary.mesh, coarse.spec, coarse.ratio, order);
  if (std::isfinite(e.frequencies_solve))
    e.note += fmt::format("; frequencies plus the solve's own error bound {:.2g}", e.frequencies_solve);
  return {e, problems};
}

}  // namespace

Result Solver::solve(const Scene& scene, const Discretization& mesh, const Options& options) const {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  map_stack_pages();
  Result result;
  auto& sum = result.summary;
  sum.mesh = mesh.spec();
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
      sum.total_time_s = std::chrono::duration<double>(clock::now() - t0).count();
      return result;
    }
    // The coarser mesh of the error estimate is part of the request's cost. A mesh too coarse to
    // have a coarser one (1 beam segment, a 2 x 2 plate) is checked against a finer one instead.
    const bool wants_estimate = opt.estimate_error && (rq.modes > 0 || !rq.probes.empty()) && !mesh.counts.empty();
    std::optional<CoarserMesh> coarse = wants_estimate ? coarser_mesh(scene, mesh, opt) : std::nullopt;
    bool check_is_finer = false;
    if (wants_estimate && !coarse)
      if (const std::optional<Discretization> f = finer_mesh(scene, mesh, 2.0)) {
        coarse = CoarserMesh{*f, static_cast<double>(f->counts[0]) / mesh.counts[0], mesh_order(scene, opt)};
        check_is_finer = true;
      }
    // The next coarser mesh (2H) where the family has one: the estimate takes the larger of two
    // pairs (judge_discretization).
    const std::optional<CoarserMesh> coarser2 =
        coarse && !check_is_finer ? coarser_mesh(scene, coarse->mesh, opt) : std::nullopt;
    Scene light = scene;  // what the error estimate needs: modes and statics
    light.request.frf.reset();
    light.request.shapes.reset();
    ResourceEstimate est = estimate(scene, mesh, opt);
    // A fourth, the next coarser again, where the family extrapolates (CoarserMesh::next_order):
    // it checks the extrapolated values' own order (extrapolation.hpp), at a fraction of the cost.
    const std::optional<CoarserMesh> coarser3 =
        coarser2 && std::isfinite(coarse->next_order) ? coarser_mesh(scene, coarser2->mesh, opt) : std::nullopt;
    for (const std::optional<CoarserMesh>* c : {&std::as_const(coarse), &coarser2, &coarser3})
      if (*c) {
        const ResourceEstimate ce = estimate(light, (*c)->mesh, opt);
        est.bytes = std::max(est.bytes, ce.bytes);
        est.seconds += ce.seconds;
      }
    if (est.bytes > 0) sum.set_diagnostic("estimated_memory_bytes", est.bytes);
    if (est.seconds > 0) sum.set_diagnostic("estimated_time_s", est.seconds);
    const double memory_limit = opt.max_memory_bytes > 0 ? opt.max_memory_bytes : default_memory_limit();
    if (est.bytes > memory_limit)
      sum.raise(Status::ResourceLimit,
                fmt::format("{}: refused before allocating: estimated peak memory {} ({}) exceeds the limit of {} ({}); "
                            "raise it with --max-memory GB, or use a coarser mesh or fewer modes, loads or samples",
                            name(), gigabytes(est.bytes), est.basis, gigabytes(memory_limit),
                            opt.max_memory_bytes > 0 ? "as set" : "80 % of the memory this process may use"));
    if (est.seconds > opt.max_time_s)
      sum.raise(Status::ResourceLimit,
                fmt::format("{}: refused before starting: estimated run time {:.3g} s ({}) exceeds the limit of {:.3g} s; "
                            "raise it with --max-time S, or use a coarser mesh or fewer modes, loads or samples",
                            name(), est.seconds, est.basis, opt.max_time_s));
    if (sum.status == Status::ResourceLimit) {
      sum.total_time_s = std::chrono::duration<double>(clock::now() - t0).count();
      return result;
    }
    auto run = [&](const Scene& sc, const Discretization& m) {
      const auto ts = clock::now();
      Result x;
      x.summary.mesh = m.spec();
      do_solve(sc, m, opt, x);
      x.summary.total_time_s = std::chrono::duration<double>(clock::now() - ts).count();
      return x;
    };
    Discretization final_mesh = mesh;
    std::optional<std::pair<ErrorEstimate, std::vector<std::string>>> verdict;
    std::vector<std::string> estimate_warnings;
    std::string refined_note;
    double estimate_time = 0;
    // The coarser solves of the estimate (H, 2H, and 4H where the family extrapolates), kept for the
    // Richardson extrapolation (extrapolation.hpp).
    Result kept_H, kept_2H, kept_4H;
    double kept_ratio = kNotMeasured, kept_ratio2 = kNotMeasured, kept_ratio3 = kNotMeasured;
    bool kept_three = false, kept_four = false;
    // The fourth mesh's solve: optional, so a failure only leaves the extrapolation with three.
    auto run_fourth = [&](const Discretization& m) {
      try {
        Result x = run(light, m);
        return std::optional<Result>(std::move(x));
      } catch (const std::bad_alloc&) {
        throw;
      } catch (const std::exception&) {
        return std::optional<Result>();
      }
    };
    if (coarse && opt.refine_to_tolerance) try {
      // The default mesh: refine until the estimate meets the tolerance (light solves only; the
      // whole request is then solved once on the mesh kept).
      const auto tc = clock::now();
      auto since_start = [&] { return std::chrono::duration<double>(clock::now() - t0).count(); };
      // Three solves in a row: r2 (2H), prev (H), cur (h, judged).
      Result r2;
      std::optional<Result> r3;  // 4H, for the extrapolation's check
      double ratio3 = kNotMeasured;
      std::optional<MeshSolve> third;
      if (coarser2) {
        if (coarser3) {
          r3 = run_fourth(coarser3->mesh);
          ratio3 = coarser3->ratio;
        }
        r2 = run(light, coarser2->mesh);
        third = MeshSolve{coarser2->mesh.spec(), coarser2->ratio, &r2};
      }
      Result prev = run(light, check_is_finer ? mesh : coarse->mesh);
      Result cur = run(light, check_is_finer ? coarse->mesh : mesh);
      double ratio_prev = coarse->ratio;  // prev -> cur
      verdict = judge_discretization(scene, coarse->order, cur,
                                     MeshSolve{check_is_finer ? mesh.spec() : coarse->mesh.spec(), ratio_prev, &prev},
                                     third);
      std::string prev_spec = check_is_finer ? mesh.spec() : coarse->mesh.spec();
      if (check_is_finer) final_mesh = coarse->mesh;
      // How far the estimates are from what this machine does: later steps are predicted with it.
      double last_estimate = estimate(light, final_mesh, opt).seconds, last_time = cur.summary.total_time_s;
      for (int step = 0; step < 3 && !verdict->second.empty(); ++step) {
        // Rounding beyond the tolerance: a finer mesh would only make it worse.
        if (verdict->first.frequencies_solve > scene.request.tolerance) break;
        const double worst = std::max(std::isnan(verdict->first.frequencies) ? 0.0 : verdict->first.frequencies,
                                    std::isnan(verdict->first.deflections) ? 0.0 : verdict->first.deflections);
        const double factor = std::clamp(1.25 * std::pow(worst / scene.request.tolerance, 1.0 / coarse->order), 1.5, 4.0);
        const std::optional<Discretization> next = finer_mesh(scene, final_mesh, std::isfinite(factor) ? factor : 4.0);
        if (!next) break;
        const ResourceEstimate ne = estimate(scene, *next, opt);
        const double calibration = last_estimate > 0 && last_time > last_estimate ? last_time / last_estimate : 1.0;
        // The next light solve, then the whole request on it (about as dear, and more with an FRF).
        const double predicted = 2.0 * ne.seconds * calibration;
        if (ne.bytes > memory_limit || since_start() + predicted > opt.max_time_s) {
          estimate_warnings.push_back(fmt::format(
              "refinement stopped at mesh {}: the next, {}, is estimated at {} and {:.3g} s (after {:.3g} s), over the "
              "limits (--max-memory, --max-time)",
              final_mesh.spec(), next->spec(), gigabytes(ne.bytes), predicted, since_start()));
          break;
        }
        const double ratio = static_cast<double>(next->counts[0]) / final_mesh.counts[0];
        Result trial = run(light, *next);
        // A finer mesh whose solve fails the back-end's own checks is not taken: the mesh kept is
        // the last one that passed them, with its estimate (and its not-converged verdict).
        if (severity(trial.summary.status) >= severity(Status::NumericalIssue) &&
            severity(cur.summary.status) < severity(Status::NumericalIssue)) {
          estimate_warnings.push_back(fmt::format("refinement stopped at mesh {}: the next, {}, failed the back-end's "
                                                  "own checks ({}: {})",
                                                  final_mesh.spec(), next->spec(), to_string(trial.summary.status),
                                                  trial.summary.message));
          break;
        }
        r3 = third ? std::optional<Result>(std::move(r2)) : std::nullopt;
        ratio3 = third ? third->ratio : kNotMeasured;
        r2 = std::move(prev);
        third = MeshSolve{prev_spec, ratio_prev, &r2};
        prev = std::move(cur);
        prev_spec = final_mesh.spec();
        ratio_prev = ratio;
        cur = std::move(trial);
        last_estimate = estimate(light, *next, opt).seconds;
        last_time = cur.summary.total_time_s;
        verdict = judge_discretization(scene, coarse->order, cur, MeshSolve{prev_spec, ratio, &prev}, third);
        final_mesh = *next;
      }
      if (third) {
        kept_three = true;
        kept_ratio = ratio_prev;
        kept_ratio2 = third->ratio;
        kept_H = std::move(prev);
        kept_2H = std::move(r2);
        if (r3) {
          kept_four = true;
          kept_ratio3 = ratio3;
          kept_4H = std::move(*r3);
        }
      }
      if (cur.summary.status != Status::Success && cur.summary.status != Status::NotConverged)
        estimate_warnings.push_back(fmt::format("a solve on mesh {} of the refinement was {}: {}", final_mesh.spec(),
                                                to_string(cur.summary.status), cur.summary.message));
      estimate_time = std::chrono::duration<double>(clock::now() - tc).count();
      // Provenance of the mesh and its estimate, not a doubt about them: said in the estimate's note.
      if (final_mesh.spec() != mesh.spec())
        refined_note = fmt::format("default mesh {} refined to {} to meet the tolerance {:.2g}", mesh.spec(),
                                   final_mesh.spec(), scene.request.tolerance);
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception& e) {
      // A solve of the refinement failed: the request is solved on the default mesh, and its own
      // check (below) says what it can.
      estimate_warnings.push_back(std::string("refinement of the default mesh abandoned: ") + e.what());
      verdict.reset();
      final_mesh = mesh;
    }
    sum.mesh = final_mesh.spec();
    do_solve(scene, final_mesh, opt, result);
    if (!missing.empty()) {
      std::string what;
      for (const auto& m : missing) what += (what.empty() ? "" : ", ") + m;
      sum.warnings.push_back("not computed: " + what + (cap.reason.empty() ? "" : " (" + cap.reason + ")"));
    }
    if (coarse && !verdict && severity(sum.status) < severity(Status::ResourceLimit)) {
      const auto tc = clock::now();
      try {
        Result cr = run(light, coarse->mesh);
        Result cr2;
        std::optional<MeshSolve> third;
        if (coarser2) {
          cr2 = run(light, coarser2->mesh);
          third = MeshSolve{coarser2->mesh.spec(), coarser2->ratio, &cr2};
        }
        verdict = judge_discretization(scene, coarse->order, result, MeshSolve{coarse->mesh.spec(), coarse->ratio, &cr},
                                       third, check_is_finer);
        for (const Result* c : {&std::as_const(cr), &std::as_const(cr2)})
          if (c->summary.status != Status::Success && !(c == &cr2 && !coarser2))
            estimate_warnings.push_back(fmt::format("the coarser mesh {} of the error estimate was {}: {}",
                                                    c->summary.mesh, to_string(c->summary.status), c->summary.message));
        if (third) {
          kept_three = true;
          kept_ratio = coarse->ratio;
          kept_ratio2 = coarser2->ratio;
          kept_H = std::move(cr);
          kept_2H = std::move(cr2);
          if (coarser3)
            if (std::optional<Result> cr3 = run_fourth(coarser3->mesh)) {
              kept_four = true;
              kept_ratio3 = coarser3->ratio;
              kept_4H = std::move(*cr3);
            }
        }
      } catch (const std::bad_alloc&) {
        throw;
      } catch (const std::exception& e) {
        sum.error_estimate.note = std::string("no estimate: the coarser mesh failed: ") + e.what();
        sum.raise(Status::NotConverged, fmt::format("no discretization error estimate: the coarser mesh {} failed ({})",
                                                    coarse->mesh.spec(), e.what()));
      }
      estimate_time += std::chrono::duration<double>(clock::now() - tc).count();
    } else if (!mesh.counts.empty() && !opt.estimate_error) {
      sum.error_estimate.note = "not estimated (switched off by the caller)";
    }
    if (verdict) {
      sum.error_estimate = verdict->first;
      if (!refined_note.empty()) sum.error_estimate.note = refined_note + "; " + sum.error_estimate.note;
      for (const auto& p : verdict->second) sum.raise(Status::NotConverged, p);
    } else if (wants_estimate && !coarse) {
      // No mesh to compare with (the model is solved on exact segments: a one-prism dtfm beam), but
      // the solve's own bound (near-rigid modes): that is the estimate.
      const double solve = sum.diagnostic("frequency_solve_error_bound");
      if (std::isfinite(solve)) {
        sum.error_estimate.frequencies = sum.error_estimate.frequencies_solve = solve;
        sum.error_estimate.tolerance = scene.request.tolerance;
        sum.error_estimate.note = "no discretization error to estimate (exact segments): the solve's own bound";
      }
    }
    if (kept_three && coarse) {
      const ExtrapolationMesh fourth{&kept_4H, kept_ratio3};
      result.extrapolated = richardson_extrapolate(result, {&kept_H, kept_ratio}, {&kept_2H, kept_ratio2}, coarse->order,
                                                   coarse->next_order, sum.diagnostic("frequency_solve_error_bound"),
                                                   kept_four ? &fourth : nullptr);
    }
    for (auto& w : estimate_warnings) sum.warnings.push_back(std::move(w));
    sum.timings_s.error_estimate = estimate_time;
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
  if (sum.diagnostic("estimated_memory_bytes") > 0) sum.set_diagnostic("process_peak_resident_bytes", peak_resident_bytes());
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
