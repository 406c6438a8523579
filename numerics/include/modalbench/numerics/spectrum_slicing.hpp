#pragma once
// Spectrum slicing: every eigenvalue of a problem whose counting function is known (the
// Wittrick-Williams count, a Sturm count), with multiplicity, none missed or invented.
// Bisection on the count isolates each eigenvalue; an isolated one is then polished on a
// continuous function (the signed determinant) by a bracketing root finder.

#include <functional>
#include <vector>

namespace modalbench {

/// Count-driven spectrum slicing: the k eigenvalues just above `lambda_lo` of a problem
/// whose counting function is `count(lambda)` = number of eigenvalues < lambda;
/// `lambda_hint` is a scale (the bracket grows from it until it holds k more). Repeated
/// eigenvalues are returned repeatedly. Bisection to `rel_tol` relative (1e-8 of that
/// relative to `lambda_hint` in an interval that reaches zero); above a positive `lambda_lo`
/// it is geometric while an interval spans orders of magnitude, so tiny eigenvalues keep
/// their relative accuracy. Throws std::runtime_error if the count is not
/// monotonic (numerical breakdown) or cannot be bracketed.
struct SliceStats {
  long count_evaluations = 0;
  long max_unknowns = 0;  ///< largest system the counts factorized (filled by callers that know it)
  /// slice_interval_polished: the largest relative width (hi - lo) / hi of the counts' bracket
  /// around a value whose polish stopped at the determinant's rounding floor (0 if none did): a
  /// bound on those values' relative error in lambda, far above rel_tol.
  double polish_floor_width = 0;
};
std::vector<double> slice_spectrum(const std::function<int(double)>& count, int k, double lambda_lo,
                                   double lambda_hint, double rel_tol = 1e-13, SliceStats* stats = nullptr);

/// What a polished slicer needs at one lambda: the count and the log of |det K(lambda)| times
/// any positive factor that is smooth in lambda (best: prod |det Tdf| over the segments, which
/// removes det K's poles).
struct CountDet {
  int count = 0;
  double log_abs_det = 0;
};
/// Every eigenvalue in [lambda_lo, lambda_hi) of a problem whose `eval(lambda)` gives the
/// count below lambda and log |det K(lambda)|, with multiplicity, ascending. Bisection on the
/// count until an interval holds exactly one eigenvalue; that one is then polished by Brent's
/// method (root_finding.hpp: GSL) on the signed determinant (-1)^count |det K| (continuous
/// there: `eval` must use one discretization for every lambda in the range, so that det has no
/// pole and no jump).
/// Every evaluation of the polish narrows its bracket by the count, whatever the determinant
/// says. A polish that stops on a repeated determinant value (its rounding floor) is accepted
/// only when the counts bracket the root to kPolishFloor relative; otherwise it bisects once on
/// the count and polishes again (a Brent step shorter than K's lambda resolution repeats a
/// bracket end's value too: a 30 m plate strip's first mode came out as a bracket end, 1246.13
/// instead of 1244.9 rad/s).
/// Intervals narrower than rel_tol (relative; abs_tol near zero) with several eigenvalues give
/// them as a repeated value. Throws std::runtime_error if the count is not monotonic.
/// How tightly (relative) the counts must bracket a root whose polish stopped at the
/// determinant's rounding floor: far below what a reproducibility check at 1e-4 resolves, far
/// above the tolerance a polish normally meets.
inline constexpr double kPolishFloor = 1e-8;

std::vector<double> slice_interval_polished(const std::function<CountDet(double)>& eval, double lambda_lo,
                                            double lambda_hi, double rel_tol, double abs_tol,
                                            SliceStats* stats = nullptr);

}  // namespace modalbench
