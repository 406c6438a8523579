#include "modalbench/numerics/root_finding.hpp"

#include <fmt/format.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <utility>
#include <vector>

namespace modalbench {

void gsl_quiet() {
  static std::once_flag once;
  std::call_once(once, [] { gsl_set_error_handler_off(); });
}

namespace {

/// What GSL's C callback sees: the function, the values known already (GSL's set() evaluates
/// both ends of a bracket; those are never evaluated twice), and the counters.
struct Callback {
  const std::function<double(double)>* g = nullptr;
  std::vector<std::pair<double, double>> known;
  long evaluations = 0;
  double last_x = 0, last_value = 1;
  bool non_finite = false;

  double operator()(double x) {
    for (const auto& [kx, kv] : known)
      if (kx == x) return kv;
    const double v = (*g)(x);
    ++evaluations;
    last_x = x;
    last_value = v;
    if (!std::isfinite(v)) non_finite = true;
    known.emplace_back(x, v);
    if (known.size() > 8) known.erase(known.begin());
    return v;
  }
};

double trampoline(double x, void* params) { return (*static_cast<Callback*>(params))(x); }

struct SolverDeleter {
  void operator()(gsl_root_fsolver* s) const { gsl_root_fsolver_free(s); }
};

void check(int status, const char* what) {
  if (status != GSL_SUCCESS) throw std::runtime_error(std::string("bracketed_root: GSL ") + what + ": " + gsl_strerror(status));
}

}  // namespace

BracketedRoot bracketed_root(const std::function<double(double)>& g, double a, double b, double ga, double gb,
                             double abs_tol, double rel_tol, int max_iterations, const std::function<bool()>& stop) {
  gsl_quiet();
  BracketedRoot out;
  if (a > b) {
    std::swap(a, b);
    std::swap(ga, gb);
  }
  out.lower = a;
  out.upper = b;
  if (ga == 0.0 || gb == 0.0) {
    out.root = ga == 0.0 ? a : b;
    out.converged = true;
    return out;
  }
  if ((ga > 0) == (gb > 0))
    throw std::invalid_argument(fmt::format("bracketed_root: g({}) = {} and g({}) = {} do not bracket a root", a, ga, b, gb));
  Callback cb;
  cb.g = &g;
  cb.known = {{a, ga}, {b, gb}};
  gsl_function F{&trampoline, &cb};
  std::unique_ptr<gsl_root_fsolver, SolverDeleter> s(gsl_root_fsolver_alloc(gsl_root_fsolver_brent));
  if (!s) throw std::bad_alloc();
  check(gsl_root_fsolver_set(s.get(), &F, a, b), "set");
  out.root = gsl_root_fsolver_root(s.get());
  auto tolerance = [&](double lo, double hi) {
    const double m = (lo > 0) == (hi > 0) ? std::min(std::abs(lo), std::abs(hi)) : 0.0;
    return abs_tol + rel_tol * m;
  };
  // The previous estimate and its value (none before the first iteration).
  double previous = std::numeric_limits<double>::quiet_NaN(), previous_g = 0;
  for (int it = 0; it < max_iterations; ++it) {
    const long before = cb.evaluations;
    const int st = gsl_root_fsolver_iterate(s.get());
    ++out.iterations;
    if (cb.non_finite)
      throw std::runtime_error(fmt::format("bracketed_root: the function is not finite at x = {}", cb.last_x));
    check(st, "iterate");
    double root = gsl_root_fsolver_root(s.get());
    double lo = gsl_root_fsolver_x_lower(s.get()), hi = gsl_root_fsolver_x_upper(s.get());
    if (cb.evaluations > before && cb.last_value == 0.0) {
      out.root = cb.last_x;
      out.lower = out.upper = cb.last_x;
      out.converged = true;
      break;
    }
    // Brent's interpolation converges on the root from one side (the estimate is one end of
    // the bracket) while the other end stays put. When the next step is due to be shorter than
    // half the tolerance (by the secant through the last two estimates; superlinear
    // convergence makes it shorter still), a step of half the tolerance across the estimate
    // closes the bracket instead: zeroin's minimal step, at no extra cost.
    const double tol = tolerance(lo, hi);
    const double gr = cb(root);
    double predicted = std::numeric_limits<double>::infinity();
    if (!std::isnan(previous) && gr != previous_g) predicted = std::abs(gr * (root - previous) / (gr - previous_g));
    previous = root;
    previous_g = gr;
    if (hi - lo > tol && predicted < 0.5 * tol && !(stop && stop())) {
      const double x = root == lo ? std::min(root + 0.5 * tol, hi) : std::max(root - 0.5 * tol, lo);
      const double gx = cb(x);
      if (cb.non_finite)
        throw std::runtime_error(fmt::format("bracketed_root: the function is not finite at x = {}", cb.last_x));
      if (gx == 0.0 || gr == 0.0) {
        out.root = gx == 0.0 ? x : root;
        out.lower = out.upper = out.root;
        out.converged = true;
        break;
      }
      if ((gx > 0) != (gr > 0)) {
        lo = std::min(root, x);
        hi = std::max(root, x);
      } else {
        // The root lies beyond x: restart GSL on [x, far end] (both values known: no evaluation).
        const double far = root == lo ? hi : lo;
        lo = std::min(x, far);
        hi = std::max(x, far);
        check(gsl_root_fsolver_set(s.get(), &F, lo, hi), "set");
      }
      root = std::abs(gx) < std::abs(gr) ? x : root;
    }
    out.root = root;
    out.lower = lo;
    out.upper = hi;
    if (gsl_root_test_interval(lo, hi, abs_tol, rel_tol) == GSL_SUCCESS) {
      out.converged = true;
      break;
    }
    if (stop && stop()) {
      out.stopped = true;
      break;
    }
  }
  out.evaluations = cb.evaluations;
  return out;
}

}  // namespace modalbench
