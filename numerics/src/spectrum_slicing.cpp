#include "modalbench/numerics/spectrum_slicing.hpp"

#include "modalbench/numerics/root_finding.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace modalbench {

std::vector<double> slice_spectrum(const std::function<int(double)>& count, int k, double lambda_lo,
                                   double lambda_hint, double rel_tol, SliceStats* stats) {
  std::vector<double> out;
  if (k <= 0) return out;
  long evals = 0;
  auto N = [&](double lam) {
    ++evals;
    return count(lam);
  };
  const int n_lo = N(lambda_lo);
  const int want = n_lo + k;
  double hi = std::max(std::abs(lambda_hint), std::abs(lambda_lo));
  if (!(hi > lambda_lo)) hi = lambda_lo + std::abs(lambda_hint);
  int n_hi = N(hi);
  for (int grow = 0; n_hi < want; ++grow) {
    if (grow > 400 || !std::isfinite(hi))
      throw std::runtime_error("spectrum slicing: could not bracket " + std::to_string(k) + " eigenvalues");
    hi = lambda_lo + 2.0 * (hi - lambda_lo);
    n_hi = N(hi);
  }
  const double abs_tol = rel_tol * 1e-8 * std::abs(lambda_hint);
  struct Interval { double lo, hi; int n_lo, n_hi; };
  std::vector<Interval> stack = {{lambda_lo, hi, n_lo, n_hi}};
  std::vector<std::pair<double, int>> found;  // value, multiplicity
  while (!stack.empty()) {
    Interval iv = stack.back();
    stack.pop_back();
    if (iv.n_lo >= want || iv.n_hi == iv.n_lo) continue;
    const double width = iv.hi - iv.lo;
    // An interval away from zero is narrowed relative to its values (so an eigenvalue of 1e-30
    // lambda_hint keeps its digits); one that reaches zero down to abs_tol.
    if (width <= std::max(rel_tol * std::max(std::abs(iv.lo), std::abs(iv.hi)), iv.lo > 0 ? 0.0 : abs_tol)) {
      found.emplace_back(0.5 * (iv.lo + iv.hi), std::min(iv.n_hi, want) - iv.n_lo);
      continue;
    }
    // Geometric midpoints while the interval spans orders of magnitude above zero.
    const double mid = iv.lo > 0 && iv.hi > 4.0 * iv.lo ? std::sqrt(iv.lo) * std::sqrt(iv.hi) : 0.5 * (iv.lo + iv.hi);
    const int n_mid = N(mid);
    if (n_mid < iv.n_lo || n_mid > iv.n_hi)
      throw std::runtime_error("spectrum slicing: count is not monotonic (numerical breakdown near lambda = " +
                               std::to_string(mid) + ")");
    stack.push_back({mid, iv.hi, n_mid, iv.n_hi});
    stack.push_back({iv.lo, mid, iv.n_lo, n_mid});
  }
  std::sort(found.begin(), found.end());
  for (auto& [v, mult] : found)
    for (int j = 0; j < mult; ++j) out.push_back(v);
  out.resize(std::min<std::size_t>(out.size(), k));
  if (stats) stats->count_evaluations += evals;
  return out;
}


namespace {

struct Bracket {
  double lo, hi;
  CountDet a, b;
};

[[noreturn]] void not_monotonic(double lambda) {
  throw std::runtime_error("spectrum slicing: count is not monotonic (numerical breakdown near lambda = " +
                           std::to_string(lambda) + ")");
}

/// The one eigenvalue in (iv.lo, iv.hi) (counts n and n + 1 at the ends). `floor_width` gets the
/// relative width of the counts' bracket where the polish stopped at the determinant's rounding
/// floor (the value's error bound then), else stays as it was.
double polish_isolated(const std::function<CountDet(double)>& E, Bracket iv, double rel_tol, double abs_tol,
                       double& floor_width) {
  const int n = iv.a.count;
  int probes = 0;  // counts placed just across a stalled estimate
  auto tol_of = [&](double lo, double hi) { return std::max(rel_tol * std::max(std::abs(lo), std::abs(hi)), abs_tol); };
  // Every evaluation narrows the bracket by its count, whatever the determinant says.
  auto record = [&](double lam, const CountDet& cd) {
    if (cd.count == n) {
      if (lam > iv.lo) iv = {lam, iv.hi, cd, iv.b};
    } else if (cd.count == n + 1) {
      if (lam < iv.hi) iv = {iv.lo, lam, iv.a, cd};
    } else {
      not_monotonic(lam);
    }
  };
  for (;;) {
    if (iv.hi - iv.lo <= tol_of(iv.lo, iv.hi)) return 0.5 * (iv.lo + iv.hi);
    if (std::isfinite(iv.a.log_abs_det) && std::isfinite(iv.b.log_abs_det)) {
      const double ref = std::max(iv.a.log_abs_det, iv.b.log_abs_det);
      auto signed_det = [&](const CountDet& cd) {
        const double mag = std::exp(std::clamp(cd.log_abs_det - ref, -600.0, 600.0));
        return cd.count == n ? mag : -mag;
      };
      // Near the root the determinant reaches its rounding floor: the same value again at a
      // different lambda means further steps only sample noise. But a step from a bracket end
      // shorter than the lambda resolution of K repeats that end's value too (the secant lands
      // there when |det| spans many orders of magnitude across the bracket, as next to a dense
      // cluster of modes: a 30 m plate strip's (m, 1) family); only the count can tell the two.
      // Noise shows sooner as a step toward the root that finds |det| larger than at the bracket
      // end on its side: within kNoiseSpan of each other, where a simple root's |det| grows
      // linearly with the distance, only rounding does that (on a 40-strip plate from about
      // 1e-9 relative on, which Brent then sampled for four to six more evaluations per root).
      // A false alarm (another root within kNoiseSpan, outside the bracket) costs what a stall
      // costs: a count across the estimate or a bisection; the value stays within its counts.
      constexpr double kNoiseSpan = 1e-6;
      bool stalled = false;
      std::vector<double> seen = {iv.a.log_abs_det, iv.b.log_abs_det};
      auto g = [&](double lam) {
        const CountDet cd = E(lam);
        const bool below = cd.count == n;
        const double end = below ? iv.lo : iv.hi;
        const double end_log = below ? iv.a.log_abs_det : iv.b.log_abs_det;
        if ((below ? lam > end : lam < end) && std::abs(lam - end) <= kNoiseSpan * std::abs(lam) &&
            cd.log_abs_det > end_log)
          stalled = true;
        record(lam, cd);
        if (std::find(seen.begin(), seen.end(), cd.log_abs_det) != seen.end()) stalled = true;
        seen.push_back(cd.log_abs_det);
        return signed_det(cd);
      };
      const Bracket start = iv;
      const BracketedRoot root =
          bracketed_root(g, start.lo, start.hi, signed_det(start.a), signed_det(start.b), tol_of(start.lo, start.hi),
                         8.0 * std::numeric_limits<double>::epsilon(), 200, [&] { return stalled; });
      const double estimate = std::clamp(root.root, iv.lo, iv.hi);
      if (root.converged) return estimate;
      // Stopped: accepted only where the count confirms the estimate to the rounding floor of a
      // well-resolved root (the bracket the counts leave is itself that narrow, and is its bound).
      // The counts' bracket at the floor: its relative width becomes the value's bound.
      auto at_floor = [&] {
        const double width = (iv.hi - iv.lo) / std::max(std::abs(iv.lo), std::abs(iv.hi));
        if (!(width <= kPolishFloor)) return false;
        floor_width = std::max(floor_width, width);
        return true;
      };
      if (at_floor()) return estimate;
      // The determinant stopped next to one end of a wide bracket (a root of a 40-strip plate sat
      // 1e-12 below the end it came from, the other end 2e-3 away): one count just across the
      // estimate, on the wide side, usually confirms it; bisecting from the far end took 17.
      if (probes < 2) {
        ++probes;
        const double w = 0.5 * kPolishFloor * std::max(std::abs(iv.lo), std::abs(iv.hi));
        const double probe = estimate - iv.lo > iv.hi - estimate ? estimate - w : estimate + w;
        if (probe > iv.lo && probe < iv.hi) {
          record(probe, E(probe));
          if (at_floor()) return std::clamp(estimate, iv.lo, iv.hi);
        }
      }
    }
    // Otherwise one bisection on the count, then Brent again on the half that holds the root.
    const double mid = 0.5 * (iv.lo + iv.hi);
    if (!(mid > iv.lo && mid < iv.hi)) return mid;  // adjacent doubles: nothing left to split
    record(mid, E(mid));
  }
}

}  // namespace

std::vector<double> slice_interval_polished(const std::function<CountDet(double)>& eval, double lambda_lo,
                                            double lambda_hi, double rel_tol, double abs_tol, SliceStats* stats) {
  std::vector<double> out;
  if (!(lambda_hi > lambda_lo)) return out;
  long evals = 0;
  auto E = [&](double lam) {
    ++evals;
    return eval(lam);
  };
  std::vector<Bracket> stack = {{lambda_lo, lambda_hi, E(lambda_lo), E(lambda_hi)}};
  if (stack[0].b.count < stack[0].a.count)
    throw std::runtime_error("spectrum slicing: count decreases between lambda_lo and lambda_hi");
  auto narrow = [&](double lo, double hi) {
    return hi - lo <= std::max(rel_tol * std::max(std::abs(lo), std::abs(hi)), abs_tol);
  };
  std::vector<std::pair<double, int>> found;
  while (!stack.empty()) {
    const Bracket iv = stack.back();
    stack.pop_back();
    const int n = iv.b.count - iv.a.count;
    if (n <= 0) continue;
    if (narrow(iv.lo, iv.hi)) {
      found.emplace_back(0.5 * (iv.lo + iv.hi), n);
      continue;
    }
    if (n == 1) {
      double floor_width = 0;
      found.emplace_back(polish_isolated(E, iv, rel_tol, abs_tol, floor_width), 1);
      if (stats) stats->polish_floor_width = std::max(stats->polish_floor_width, floor_width);
      continue;
    }
    const double mid = 0.5 * (iv.lo + iv.hi);
    const CountDet cm = E(mid);
    if (cm.count < iv.a.count || cm.count > iv.b.count) not_monotonic(mid);
    stack.push_back({mid, iv.hi, cm, iv.b});
    stack.push_back({iv.lo, mid, iv.a, cm});
  }
  std::sort(found.begin(), found.end());
  for (auto& [v, mult] : found)
    for (int j = 0; j < mult; ++j) out.push_back(v);
  if (stats) stats->count_evaluations += evals;
  return out;
}

// ---- Long segments by doubling
}  // namespace modalbench
