#pragma once
// Integrals of smooth functions by GSL's adaptive Gauss-Kronrod quadrature (gsl_integration_qag,
// 21-point rule): modal masses, participation factors and orthogonality integrals where no
// closed form is used. GSL errors become exceptions (gsl_quiet, root_finding.hpp).

#include <functional>

namespace modalbench {

struct Integral {
  double value = 0;
  double abs_error = 0;  ///< GSL's estimate of the absolute error
  long evaluations = 0;
  bool rounding_limited = false;  ///< rounding stopped the refinement first (abs_error says how far it got)
};

/// int_a^b f(x) dx to a relative accuracy `rel_tol` (or `abs_tol`). When rounding in the integrand
/// stops the refinement first (GSL_EROUND) the value is returned with its error estimate and
/// `rounding_limited`; the caller decides whether that is accurate enough. Throws
/// std::runtime_error with GSL's reason for any other failure (e.g. a singularity) or if f is not
/// finite.
Integral integrate(const std::function<double(double)>& f, double a, double b, double rel_tol = 1e-12,
                   double abs_tol = 0.0);

}  // namespace modalbench
