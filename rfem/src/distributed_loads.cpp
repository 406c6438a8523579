// Distributed loads on rfem's beams and plates as Gauss-point actions, integrated exactly against
// the centre grid's interpolation weights (system.hpp, distributed_actions).
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "modalbench/rfem/system.hpp"

namespace modalbench::rfem {

namespace {

/// [lo, hi] cut at the grid coordinates strictly inside it.
std::vector<double> pieces(const std::vector<double>& grid, double lo, double hi) {
  std::vector<double> cuts = {lo};
  for (double g : grid)
    if (g > lo && g < hi) cuts.push_back(g);
  cuts.push_back(hi);
  return cuts;
}

/// 2-point Gauss-Legendre on [a, b]: points and weights (exact to degree 3).
std::array<std::pair<double, double>, 2> gauss2(double a, double b) {
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a), off = half / std::sqrt(3.0);
  return {{{mid - off, half}, {mid + off, half}}};
}

}  // namespace

std::vector<PointAction> distributed_actions(const Model& model, const Scene& s) {
  std::vector<PointAction> out;
  const std::vector<DistributedLoad> loads = s.all_distributed_loads();
  if (loads.empty()) return out;
  if (model.grid.empty()) throw std::invalid_argument("rfem: distributed loads need a centre grid (beams, plates)");
  for (const DistributedLoad& q : loads) {
    const std::vector<double> xs = pieces(model.grid.x, q.from[0], q.to[0]);
    if (s.is_beam()) {
      for (std::size_t i = 0; i + 1 < xs.size(); ++i)
        for (const auto& [x, w] : load_gauss_points(q, xs[i], xs[i + 1], 1)) {
          Vector6d a = Vector6d::Zero();
          a << q.at(q.qx, x) * w, q.at(q.qy, x) * w, q.at(q.qz, x) * w, 0, 0, 0;
          out.emplace_back(Eigen::Vector3d(x, 0, 0), a);
        }
      continue;
    }
    const std::vector<double> ys = pieces(model.grid.y, q.from[1], q.to[1]);
    for (std::size_t i = 0; i + 1 < xs.size(); ++i)
      for (const auto& [x, wx] : gauss2(xs[i], xs[i + 1]))
        for (std::size_t j = 0; j + 1 < ys.size(); ++j)
          for (const auto& [y, wy] : gauss2(ys[j], ys[j + 1])) {
            Vector6d a = Vector6d::Zero();
            a[2] = q.qz[0] * wx * wy;
            out.emplace_back(Eigen::Vector3d(x, y, 0), a);
          }
  }
  return out;
}

}  // namespace modalbench::rfem
