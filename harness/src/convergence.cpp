#include "modalbench/harness/convergence.hpp"

#include <fmt/format.h>

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

GridConvergence grid_convergence(const std::vector<double>& h, const std::vector<double>& f) {
  GridConvergence g;
  const Richardson r = richardson(h, f);
  g.value = r.value;
  g.order = r.order;
  if (!r.ok) {
    g.note = h.size() < 3 ? "fewer than three meshes" : "the three finest meshes do not converge monotonically";
    return g;
  }
  g.ok = true;
  const std::size_t n = h.size();
  if (r.uncertainty == 0.0) {  // converged to rounding
    g.gci = 0.0;
    g.safety_factor = 1.25;
    g.asymptotic = true;
    g.note = "converged to rounding";
    return g;
  }
  if (n >= 4) {
    const Richardson coarse = richardson(std::vector<double>(h.begin(), h.end() - 1), std::vector<double>(f.begin(), f.end() - 1));
    g.asymptotic = coarse.ok && std::abs(coarse.order - r.order) <= 0.1 * r.order;
    g.note = g.asymptotic ? fmt::format("order {:.2f} confirmed by a fourth mesh ({:.2f})", r.order, coarse.order)
             : coarse.ok  ? fmt::format("not in the asymptotic range: orders {:.2f} (finest three) and {:.2f} (coarser three)",
                                        r.order, coarse.order)
                          : "not in the asymptotic range: the coarser three meshes do not converge monotonically";
  } else {
    g.note = "three meshes: the order is not confirmed by a fourth";
  }
  g.safety_factor = g.asymptotic ? 1.25 : 3.0;
  const double ratio = h[n - 2] / h[n - 1];
  g.gci = g.safety_factor * std::abs((f[n - 1] - f[n - 2]) / f[n - 1]) / (std::pow(ratio, r.order) - 1.0);
  return g;
}

double observed_order(double h1, double e1, double h2, double e2) {
  if (!(e1 > 0) || !(e2 > 0) || !std::isfinite(e1) || !std::isfinite(e2) || !(h1 > 0) || !(h2 > 0) || h1 == h2)
    return kNaN;
  return std::log(e1 / e2) / std::log(h1 / h2);
}

}  // namespace modalbench
