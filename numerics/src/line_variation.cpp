// The line system's varying pieces (LineVariation): Magnus transfer matrices, their divided
// difference for the rigid-motion split, and the cuts that keep the count exact.
#include "line_variation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "modalbench/numerics/balancing.hpp"

namespace modalbench::detail {

namespace {

/// Magnus steps doubled until two agree to this (estimated relative error of a transfer matrix)...
constexpr double kMagnusTolerance = 1e-15;
/// ... and a transfer matrix whose estimate stays above this after 4096 steps is refused.
constexpr double kMagnusRefused = 1e-12;

}  // namespace

VaryingTransfer magnus_transfer(const std::function<Eigen::MatrixXd(double)>& A, double x0, double x1, const Eigen::VectorXd& d) {
  // Neighbouring segments of a piece need about the same steps: the first (coarse) product takes a
  // quarter of the last count, so a milder segment is accepted at half of it and a like one after
  // one more doubling (the steps, not the tolerance, depend on what came before).
  thread_local int last_steps = 4;
  VaryingTransfer t = varying_transfer(A, x0, x1, kMagnusTolerance, d, std::max(1, last_steps / 4));
  last_steps = t.steps;
  if (!(t.error <= kMagnusRefused))
    throw std::runtime_error("varying piece: the Magnus transfer matrix over [" + std::to_string(x0) + ", " +
                             std::to_string(x1) + "] is accurate only to " + std::to_string(t.error) + " after " +
                             std::to_string(t.steps) + " steps");
  return t;
}

/// K(lambda) of the varying segment [x0, x1] with its divided difference (SegmentDivided), from the
/// Magnus transfer of Van Loan's block field, scaled once by A(0)'s balancing as the uniform one.
SegmentDivided varying_divided(const LineVariation& v, double lambda, double x0, double x1) {
  if (lambda == 0.0) {
    const VaryingTransfer t = magnus_transfer([&](double x) { return v.state(0.0, x); }, x0, x1);
    return {segment_stiffness_of_transfer(t.T), Eigen::MatrixXd::Zero(t.T.rows(), t.T.cols())};
  }
  Eigen::MatrixXd B0 = v.state(0.0, 0.5 * (x0 + x1)) * (x1 - x0);
  const Eigen::Index n2 = B0.rows();
  const Eigen::VectorXd s0 = balance_in_place(B0, 20);
  Eigen::VectorXd scale(2 * n2);
  scale << s0, s0;
  const auto block = [&](double x) {
    const Eigen::MatrixXd A1 = v.state(lambda, x), A0 = v.state(0.0, x);
    Eigen::MatrixXd X = Eigen::MatrixXd::Zero(2 * n2, 2 * n2);
    X.topLeftCorner(n2, n2) = A1;
    X.topRightCorner(n2, n2) = (A1 - A0) / lambda;
    X.bottomRightCorner(n2, n2) = A0;
    return X;
  };
  const Eigen::MatrixXd E = magnus_transfer(block, x0, x1, scale).T;
  return segment_divided_from_transfers(E.topLeftCorner(n2, n2), E.bottomRightCorner(n2, n2), E.topRightCorner(n2, n2));
}

/// Cuts the gap [a, b] of a varying piece into segments each of which has |p| h <= 1 by its own
/// comparison bound (so none has a clamped frequency below lambda), at least `min_parts` of them;
/// appends the nodes after a (b last).
void cut_varying(const LineVariation& v, double lambda, double a, double b, int min_parts, std::vector<double>& xi,
                 int depth) {
  const double len = b - a, p = v.wavenumber_over(lambda, a, b);
  const bool bounded = std::isfinite(p) && p >= 0;
  if (bounded && p * len <= 1.0 && min_parts <= 1) {
    xi.push_back(b);
    return;
  }
  if (depth > 40) throw std::runtime_error("LineSystem: a varying piece's wavenumber bound does not fall as it is cut");
  const double want = bounded ? std::ceil(len * p) : 2.0;
  if (want > 1e7) throw std::runtime_error("LineSystem: more than 1e7 segments needed at this frequency");
  const int n = std::max({2, min_parts, static_cast<int>(want)});
  for (int j = 1; j <= n; ++j) cut_varying(v, lambda, a + len * (j - 1) / n, j == n ? b : a + len * j / n, 1, xi, depth + 1);
}

}  // namespace modalbench::detail
