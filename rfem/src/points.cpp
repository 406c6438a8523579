// Point operators: where a load acts and where a response is observed between the rigid
// elements' centres, and the singular part of the continuum's response that interpolation
// between centres cannot carry.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "modalbench/rfem/system.hpp"
#include "system_detail.hpp"

namespace modalbench::rfem {

namespace {

double tolerance_length(const Model& m) { return 1e-9 * m.length_scale; }

}  // namespace

std::vector<std::pair<int, double>> containing_elements(const Model& m, const Eigen::Vector3d& P) {
  const double tol = tolerance_length(m);
  std::vector<int> hits;
  for (std::size_t e = 0; e < m.elements.size(); ++e) {
    const auto& c = m.elements[e].cell;
    if ((P.array() >= c.min().array() - tol).all() && (P.array() <= c.max().array() + tol).all())
      hits.push_back(static_cast<int>(e));
  }
  std::vector<std::pair<int, double>> out;
  for (int e : hits) out.emplace_back(e, 1.0 / static_cast<double>(hits.size()));
  return out;
}

namespace {

/// Interval of a point on an ascending grid and the weight of its upper end; a coordinate
/// within the tolerance outside the grid is clamped to it.
std::pair<std::size_t, double> bracket(const std::vector<double>& g, double v, double tol) {
  if (g.size() == 1) {
    if (std::abs(v - g[0]) > tol) return {g.size(), 0.0};
    return {0, 0.0};
  }
  if (v < g.front() - tol || v > g.back() + tol) return {g.size(), 0.0};
  const auto it = std::upper_bound(g.begin(), g.end(), v);
  std::size_t i = it == g.begin() ? 0 : static_cast<std::size_t>(it - g.begin()) - 1;
  i = std::min(i, g.size() - 2);
  const double t = std::clamp((v - g[i]) / (g[i + 1] - g[i]), 0.0, 1.0);
  return {i, t};
}

}  // namespace

std::vector<std::pair<int, double>> point_weights(const Model& m, const Eigen::Vector3d& P) {
  if (m.grid.empty()) {
    auto hits = containing_elements(m, P);
    if (hits.empty())
      throw std::invalid_argument(fmt::format("rfem: the point ({}, {}, {}) lies in no rigid element", P.x(), P.y(), P.z()));
    return hits;
  }
  const double tol = tolerance_length(m);
  const auto [i, tx] = bracket(m.grid.x, P.x(), tol);
  const auto [j, ty] = bracket(m.grid.y, P.y(), tol);
  if (i >= m.grid.x.size() || j >= m.grid.y.size() || std::abs(P.z()) > tol + 0.5 * m.length_scale)
    throw std::invalid_argument(fmt::format("rfem: the point ({}, {}, {}) lies outside the body", P.x(), P.y(), P.z()));
  const std::size_t nx = m.grid.x.size();
  std::vector<std::pair<int, double>> out;
  const std::size_t di = m.grid.x.size() > 1 ? 1 : 0, dj = m.grid.y.size() > 1 ? 1 : 0;
  for (std::size_t b = 0; b <= dj; ++b)
    for (std::size_t a = 0; a <= di; ++a) {
      const double w = (di ? (a ? tx : 1.0 - tx) : 1.0) * (dj ? (b ? ty : 1.0 - ty) : 1.0);
      if (w != 0.0) out.emplace_back(m.grid.element[(i + a) + nx * (j + b)], w);
    }
  return out;
}

Eigen::VectorXd point_load(const Model& m, const System& sys, const Eigen::Vector3d& P, const Vector6d& action) {
  return point_loads(m, sys, {{P, action}});
}

Eigen::VectorXd point_loads(const Model& m, const System& sys, const std::vector<PointAction>& actions) {
  return sys.T.transpose() * detail::point_loads_q(m, actions);
}

Eigen::VectorXd detail::point_loads_q(const Model& m, const std::vector<PointAction>& actions) {
  const int na = m.dofs_per_element();
  Eigen::VectorXd fq = Eigen::VectorXd::Zero(m.body_dofs());
  for (const auto& [P, action] : actions)
    for (auto [e, w] : point_weights(m, P)) {
      // On a grid the action goes to the centres with the interpolation weights (no lever arm:
      // the interpolant, not a rigid attachment, carries the point); otherwise rigidly attached.
      const Vector6d f = m.grid.empty()
                             ? Vector6d(attachment(P - m.elements[static_cast<std::size_t>(e)].centre).transpose() * action * w)
                             : Vector6d(action * w);
      for (int k = 0; k < na; ++k) fq[static_cast<long>(e) * na + k] += f[m.active[static_cast<std::size_t>(k)]];
    }
  return fq;
}

Eigen::VectorXd point_observer(const Model& m, const System& sys, const Eigen::Vector3d& P, int comp) {
  return point_load(m, sys, P, Vector6d::Unit(comp));
}

namespace {

/// The kernel S(P, Q) of one singularity between observation point P and load point Q.
double kernel(const PointSingularity& s, const Eigen::Vector3d& P, const Eigen::Vector3d& Q) {
  const Eigen::Vector3d d = P - Q;
  switch (s.kind) {
    case PointSingularity::Kind::Kink:
      return -s.coefficient * std::abs(d.x());
    case PointSingularity::Kind::Biharmonic: {
      const double r2 = d.x() * d.x() + d.y() * d.y();
      if (r2 == 0.0) return 0.0;  // r^2 ln r and its gradient vanish at r = 0
      const double lnr = 0.5 * std::log(r2);
      if (s.derivative == PointSingularity::Derivative::None) return s.coefficient * r2 * lnr;
      // d/dx (r^2 ln r) = x (2 ln r + 1): theta_x = +dw/dy, theta_y = -dw/dx at P.
      const double g = 2.0 * lnr + 1.0;
      return s.derivative == PointSingularity::Derivative::PlusDy ? s.coefficient * d.y() * g
                                                                  : -s.coefficient * d.x() * g;
    }
    case PointSingularity::Kind::ShearLog: {
      const double r2 = d.x() * d.x() + d.y() * d.y();
      return r2 == 0.0 ? std::numeric_limits<double>::infinity() : -0.5 * s.coefficient * std::log(r2);
    }
  }
  return 0.0;
}

}  // namespace

double point_correction(const Model& m, const Eigen::Vector3d& P, int observed, const Eigen::Vector3d& Q, int load) {
  double total = 0;
  std::vector<std::pair<int, double>> wp, wq;
  for (const auto& s : m.singularities) {
    if (s.observed != observed || s.load != load || !(Q.x() >= s.x_from && Q.x() < s.x_to)) continue;
    if (wp.empty()) {
      wp = point_weights(m, P);
      wq = point_weights(m, Q);
    }
    double interpolated = 0;
    for (auto [a, wa] : wp)
      for (auto [b, wb] : wq)
        interpolated += wa * wb *
                        kernel(s, m.elements[static_cast<std::size_t>(a)].centre, m.elements[static_cast<std::size_t>(b)].centre);
    total += kernel(s, P, Q) - interpolated;
  }
  return total;
}

}  // namespace modalbench::rfem
