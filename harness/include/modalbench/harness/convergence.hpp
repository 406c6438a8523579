#pragma once
// Convergence analysis of a sequence of discretizations: relative errors and Richardson
// extrapolation with the observed order.

#include <cmath>
#include <limits>
#include <string>
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

/// Roache's grid convergence index (GCI) of the finest of a sequence of meshes (h decreasing):
/// the observed order p and the limit from the three finest (Richardson), and
/// GCI = Fs |f_n - f_{n-1}| / |f_n| / (r^p - 1), r = h_{n-1} / h_n, as the relative uncertainty
/// of f_n. Fs = 1.25 when the three finest meshes are in the asymptotic range -- a fourth,
/// coarser mesh gives the same order within 10 % -- and 3 otherwise (the note says why).
struct GridConvergence {
  double value = kNaN;  ///< the Richardson limit
  double order = kNaN;  ///< observed order p
  double gci = kNaN;    ///< relative uncertainty of the finest value (NaN: not monotone)
  double safety_factor = 3.0;
  bool asymptotic = false;
  bool ok = false;      ///< three finest meshes converge monotonically
  std::string note;     ///< why the safety factor is what it is
};
GridConvergence grid_convergence(const std::vector<double>& h, const std::vector<double>& f);

/// Observed order between two meshes from their errors: ln(e1 / e2) / ln(h1 / h2); NaN unless
/// both errors are positive and finite and h1 != h2.
double observed_order(double h1, double e1, double h2, double e2);

}  // namespace modalbench
