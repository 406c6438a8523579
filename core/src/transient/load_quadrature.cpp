// Loads as weighted points for the modal forces of the transient response (load_quadrature.hpp).
#include "load_quadrature.hpp"

#include <gsl/gsl_integration.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace modalbench::detail {

namespace {

constexpr int kGaussPoints = 6;

/// Gauss-Legendre nodes and weights on [a, b].
std::vector<std::pair<double, double>> gauss(double a, double b) {
  static const std::unique_ptr<gsl_integration_glfixed_table, decltype(&gsl_integration_glfixed_table_free)> table(
      gsl_integration_glfixed_table_alloc(kGaussPoints), &gsl_integration_glfixed_table_free);
  std::vector<std::pair<double, double>> out(kGaussPoints);
  for (int i = 0; i < kGaussPoints; ++i)
    gsl_integration_glfixed_point(a, b, static_cast<std::size_t>(i), &out[static_cast<std::size_t>(i)].first,
                                  &out[static_cast<std::size_t>(i)].second, table.get());
  return out;
}

/// [a, b] cut at the breaks inside it and into pieces no longer than h.
std::vector<double> cuts(double a, double b, std::vector<double> breaks, double h) {
  breaks.push_back(a);
  breaks.push_back(b);
  std::sort(breaks.begin(), breaks.end());
  std::vector<double> out;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double lo = std::max(a, breaks[i]), hi = std::min(b, breaks[i + 1]);
    if (!(hi > lo)) continue;
    const int n = std::max(1, static_cast<int>(std::ceil((hi - lo) / h)));
    for (int k = 0; k < n; ++k) out.push_back(lo + (hi - lo) * k / n);
  }
  out.push_back(b);
  return out;
}

/// Where a beam's shapes change smoothness: piece ends, point supports, masses and point loads.
std::vector<double> beam_breaks(const Scene& s) {
  std::vector<double> x;
  for (const Segment& p : s.beam_pieces()) x.push_back(p.x_to);
  for (const PointSupport& p : s.point_supports) x.push_back(p.x);
  for (const PointMass& m : s.masses) x.push_back(m.x);
  for (const PointLoad& l : s.all_point_loads()) x.push_back(l.x);
  return x;
}

void beam_distributed(const Scene& s, int modes, std::vector<LoadPoint>& out) {
  const double L = s.geometry.length, h = L / (modes + 1.0);
  const std::vector<double> breaks = beam_breaks(s);
  for (const DistributedLoad& q : s.all_distributed_loads()) {
    const std::vector<double> c = cuts(q.from[0], q.to[0], breaks, h);
    for (std::size_t i = 0; i + 1 < c.size(); ++i)
      for (const auto& [x, w] : gauss(c[i], c[i + 1])) {
        LoadPoint p;
        p.at = {x, 0.0};
        p.weight[0] = w * q.at(q.qx, x);
        p.weight[1] = w * q.at(q.qy, x);
        p.weight[2] = w * q.at(q.qz, x);
        out.push_back(p);
      }
  }
}

void plate_distributed(const Scene& s, int modes, std::vector<LoadPoint>& out) {
  const auto [m, n] = plate_half_waves(s.geometry.length, s.geometry.width, modes + 1);
  const double hx = s.geometry.length / (2.0 * m + 2.0), hy = s.geometry.width / (2.0 * n + 2.0);
  std::vector<double> bx, by;
  for (const PointSupport& p : s.point_supports) bx.push_back(p.x), by.push_back(p.y);
  for (const PointMass& p : s.masses) bx.push_back(p.x), by.push_back(p.y);
  for (const DistributedLoad& q : s.all_distributed_loads()) {
    const std::vector<double> cx = cuts(q.from[0], q.to[0], bx, hx), cy = cuts(q.from[1], q.to[1], by, hy);
    for (std::size_t i = 0; i + 1 < cx.size(); ++i)
      for (std::size_t j = 0; j + 1 < cy.size(); ++j)
        for (const auto& [x, wx] : gauss(cx[i], cx[i + 1]))
          for (const auto& [y, wy] : gauss(cy[j], cy[j + 1])) {
            LoadPoint p;
            p.at = {x, y};
            p.weight[2] = wx * wy * q.qz[0];
            out.push_back(p);
          }
  }
}

}  // namespace

std::vector<LoadPoint> load_points(const Scene& s, int modes) {
  std::vector<LoadPoint> out;
  for (const PointLoad& l : s.all_point_loads()) {
    LoadPoint p;
    p.at = {l.x, s.is_plate() ? l.y : 0.0};
    p.weight = {l.Fx, l.Fy, l.Fz, l.Mx, l.My, l.Mz};
    out.push_back(p);
  }
  if (s.is_plate())
    plate_distributed(s, modes, out);
  else
    beam_distributed(s, modes, out);
  return out;
}

}  // namespace modalbench::detail
