#pragma once
// Convergence analysis of a sequence of discretizations: relative errors and Richardson
// extrapolation with the observed order.

#include <cmath>
#include <limits>
#include <vector>

namespace modalbench {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// |value / reference - 1|; NaN when either is not finite or the reference is 0.
double relative_error(double value, double reference);

/// Richardson extrapolation of f(h) = f0 + C h^p from the last three points of a
/// converging sequence (h decreasing; any ratios). `ok` is false when the sequence does not
/// converge monotonically (then `value` is the last f and `uncertainty` |f3 - f2|).
struct Richardson {
  double value = kNaN;        ///< extrapolated f0
  double order = kNaN;        ///< observed p
  double uncertainty = kNaN;  ///< |f0 - f_last| (a 1.0 safety factor; stated in reports)
  bool ok = false;
};
Richardson richardson(const std::vector<double>& h, const std::vector<double>& f);

}  // namespace modalbench
