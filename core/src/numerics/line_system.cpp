#include "modalbench/numerics/line_system.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "modalbench/numerics/segment_dynamic_stiffness.hpp"

namespace modalbench {

int AssembledLine::node_at(double x) const {
  for (std::size_t i = 0; i < xi.size(); ++i)
    if (xi[i] == x) return static_cast<int>(i);
  throw std::invalid_argument("no node at xi = " + std::to_string(x));
}

AssembledLine assemble(const LineSystem& sys, double lambda) {
  const int m = sys.m;
  if (static_cast<int>(sys.left_spring.size()) != m || static_cast<int>(sys.right_spring.size()) != m)
    throw std::invalid_argument("LineSystem: end springs must have m entries");
  // Breakpoints: 0, the required interior nodes, 1; each gap cut so that |p| h <= 1.
  std::vector<double> breaks = {0.0, 1.0};
  for (double x : sys.nodes_at) {
    if (!(x >= 0.0 && x <= 1.0)) throw std::invalid_argument("LineSystem: node outside [0, 1]");
    breaks.push_back(x);
  }
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  const double p = std::max(sys.max_wavenumber(lambda), 1e-12);
  if (!std::isfinite(p)) throw std::runtime_error("LineSystem: wavenumber bound is not finite");
  std::vector<double> xi = {0.0};
  for (std::size_t g = 0; g + 1 < breaks.size(); ++g) {
    const double len = breaks[g + 1] - breaks[g];
    const double pieces = std::ceil(len * p);
    if (pieces > 1e7) throw std::runtime_error("LineSystem: more than 1e7 segments needed at this frequency");
    const int n = std::max(1, static_cast<int>(pieces));
    for (int j = 1; j < n; ++j) xi.push_back(breaks[g] + len * j / n);
    xi.push_back(breaks[g + 1]);
  }
  AssembledLine out{BlockTridiagonal(static_cast<int>(xi.size()), m), xi};
  const Eigen::MatrixXd A = sys.state_matrix(lambda);
  // Equal-length pieces share one segment matrix.
  double last_h = -1;
  Eigen::MatrixXd k_seg;
  for (std::size_t i = 0; i + 1 < xi.size(); ++i) {
    const double h = xi[i + 1] - xi[i];
    if (std::abs(h - last_h) > 1e-15 * h) {
      k_seg = segment_dynamic_stiffness(A, h);
      last_h = h;
    }
    out.K.add_segment(static_cast<int>(i), k_seg);
  }
  const int last = static_cast<int>(xi.size()) - 1;
  for (int j = 0; j < m; ++j) {
    if (std::isinf(sys.left_spring[j])) out.K.hold(0, j);
    else out.K.add_diagonal(0, j, sys.left_spring[j]);
    if (std::isinf(sys.right_spring[j])) out.K.hold(last, j);
    else out.K.add_diagonal(last, j, sys.right_spring[j]);
  }
  return out;
}

int count_below(const LineSystem& sys, double lambda) { return assemble(sys, lambda).K.inertia().negative; }

LineSpectrum lowest_eigenvalues(const LineSystem& sys, int k, double lambda_hint, SliceStats* stats) {
  LineSpectrum out;
  const double delta = kRigidThreshold * std::abs(lambda_hint);
  auto N = [&](double lam) {
    const AssembledLine a = assemble(sys, lam);
    if (stats) stats->max_unknowns = std::max<long>(stats->max_unknowns, a.K.free_dofs());
    return a.K.inertia().negative;
  };
  const int below = N(-delta);
  if (below != 0)
    throw std::runtime_error("the system has " + std::to_string(below) +
                             " negative eigenvalue(s) omega^2 < 0: it is unstable, not a vibrating structure");
  out.rigid = std::min(N(delta), k);
  out.lambdas.assign(out.rigid, 0.0);
  auto rest = slice_spectrum(N, k - out.rigid, delta, lambda_hint, 1e-13, stats);
  out.lambdas.insert(out.lambdas.end(), rest.begin(), rest.end());
  if (stats) stats->count_evaluations += 2;
  return out;
}

}  // namespace modalbench
