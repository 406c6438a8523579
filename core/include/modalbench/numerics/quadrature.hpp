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
};

/// int_a^b f(x) dx to a relative accuracy `rel_tol` (or `abs_tol`). Throws std::runtime_error
/// with GSL's reason if the tolerance is not reached (e.g. a singularity) or f is not finite.
Integral integrate(const std::function<double(double)>& f, double a, double b, double rel_tol = 1e-12,
                   double abs_tol = 0.0);

}  // namespace modalbench
