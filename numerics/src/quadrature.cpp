#include "modalbench/numerics/quadrature.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <cmath>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>

#include "modalbench/numerics/root_finding.hpp"

namespace modalbench {

namespace {

struct Call {
  const std::function<double(double)>* f = nullptr;
  long evaluations = 0;
  bool non_finite = false;
};

double trampoline(double x, void* p) {
  auto& c = *static_cast<Call*>(p);
  ++c.evaluations;
  const double v = (*c.f)(x);
  if (!std::isfinite(v)) c.non_finite = true;
  return v;
}

struct WorkspaceDeleter {
  void operator()(gsl_integration_workspace* w) const { gsl_integration_workspace_free(w); }
};

}  // namespace

Integral integrate(const std::function<double(double)>& f, double a, double b, double rel_tol, double abs_tol) {
  gsl_quiet();
  Integral out;
  if (a == b) return out;
  constexpr std::size_t kLimit = 200;
  std::unique_ptr<gsl_integration_workspace, WorkspaceDeleter> w(gsl_integration_workspace_alloc(kLimit));
  if (!w) throw std::bad_alloc();
  Call c{&f};
  gsl_function F{&trampoline, &c};
  const int st = gsl_integration_qag(&F, a, b, abs_tol, rel_tol, kLimit, GSL_INTEG_GAUSS21, w.get(), &out.value,
                                     &out.abs_error);
  out.evaluations = c.evaluations;
  if (c.non_finite) throw std::runtime_error("integrate: the integrand is not finite on [" + std::to_string(a) + ", " +
                                             std::to_string(b) + "]");
  if (st == GSL_EROUND) {
    out.rounding_limited = true;
    return out;
  }
  if (st != GSL_SUCCESS)
    throw std::runtime_error(std::string("integrate: GSL: ") + gsl_strerror(st) + " (estimated error " +
                             std::to_string(out.abs_error) + ")");
  return out;
}

}  // namespace modalbench
