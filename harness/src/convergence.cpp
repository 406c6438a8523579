#include "modalbench/harness/convergence.hpp"

#include <cmath>

#include "modalbench/numerics/root_finding.hpp"

namespace modalbench {

double relative_error(double value, double reference) {
  if (!std::isfinite(value) || !std::isfinite(reference) || reference == 0.0) return kNaN;
  return std::abs(value / reference - 1.0);
}

Richardson richardson(const std::vector<double>& h, const std::vector<double>& f) {
  Richardson r;
  if (h.size() < 3 || h.size() != f.size()) return r;
  const std::size_t n = h.size();
  const double h1 = h[n - 3], h2 = h[n - 2], h3 = h[n - 1];
  const double f1 = f[n - 3], f2 = f[n - 2], f3 = f[n - 1];
  r.value = f3;
  r.uncertainty = std::abs(f3 - f2);
  if (!(h1 > h2 && h2 > h3 && h3 > 0) || !std::isfinite(f1 + f2 + f3)) return r;
  const double d21 = f2 - f1, d32 = f3 - f2;
  if (d32 == 0.0) {  // converged to rounding
    r.value = f3;
    r.uncertainty = 0.0;
    r.order = kNaN;
    r.ok = true;
    return r;
  }
  if (d21 == 0.0 || d32 / d21 <= 0.0) return r;  // oscillating: no extrapolation
  const double target = d32 / d21;
  // g(p) = (h3^p - h2^p) / (h2^p - h1^p) decreases from ~ln-ratio to 0 as p grows.
  auto g = [&](double p) { return (std::pow(h3, p) - std::pow(h2, p)) / (std::pow(h2, p) - std::pow(h1, p)); };
  const double lo = 0.05, hi = 20.0;
  const double glo = g(lo) - target, ghi = g(hi) - target;
  if (!(glo * ghi < 0)) return r;
  const BracketedRoot root = bracketed_root([&](double p) { return g(p) - target; }, lo, hi, glo, ghi, 1e-14, 1e-14);
  if (!root.converged) return r;
  const double p = root.root;
  const double C = d32 / (std::pow(h3, p) - std::pow(h2, p));
  r.order = p;
  r.value = f3 - C * std::pow(h3, p);
  r.uncertainty = std::abs(r.value - f3);
  r.ok = true;
  return r;
}

}  // namespace modalbench
