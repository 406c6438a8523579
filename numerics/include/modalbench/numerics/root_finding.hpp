#pragma once
// One bracketing root finder for every back-end: Brent's method from GSL
// (gsl_root_fsolver_brent: inverse quadratic interpolation, secant and bisection, never leaving
// the bracket). The endpoint values the caller already has are not evaluated again.
//
// GSL's default error handler aborts the process; modalbench turns it off once
// (gsl_quiet()) and maps every GSL error code into an exception with gsl_strerror's text.
//
// Usage:
//   const BracketedRoot r = bracketed_root([](double x) { return x * x - 2; }, 1.0, 2.0, -1.0, 2.0,
//                                          0.0, 1e-15);
//   // r.root = sqrt(2) to ~1e-15, r.evaluations = the function calls it made

#include <functional>
#include <limits>

namespace modalbench {

/// Turns GSL's abort-on-error handler off (once, thread-safe); every GSL call in modalbench
/// checks its return code instead.
void gsl_quiet();

struct BracketedRoot {
  double root = std::numeric_limits<double>::quiet_NaN();
  double lower = 0, upper = 0;  ///< the final bracket
  long evaluations = 0;         ///< calls of g (the given endpoint values not counted)
  int iterations = 0;
  bool converged = false;  ///< bracket below the tolerance, or g exactly 0 (false: stopped or out of iterations)
  bool stopped = false;    ///< `stop` asked to end early
};

/// A root of g in [a, b], where ga = g(a) and gb = g(b) have opposite signs (or one is 0). Ends
/// when the bracket is narrower than abs_tol + rel_tol min(|lower|, |upper|)
/// (gsl_root_test_interval), when g is exactly 0, after max_iterations, or when `stop` (if
/// given) returns true after an evaluation (e.g. g has reached its rounding floor).
/// Throws std::invalid_argument if the signs do not differ, std::runtime_error if g returns a
/// non-finite value or GSL reports another error (its message included).
BracketedRoot bracketed_root(const std::function<double(double)>& g, double a, double b, double ga, double gb,
                             double abs_tol, double rel_tol, int max_iterations = 200,
                             const std::function<bool()>& stop = nullptr);

}  // namespace modalbench
