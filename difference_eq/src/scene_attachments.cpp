// A scene's point supports, masses and line loads as the regular discrete beam's nodal
// attachments and element loads (attachments.hpp).
#include <fmt/format.h>

#include <cmath>

#include "attachments.hpp"

namespace modalbench::difference_eq {

long node_at(double x, double L, long R) {
  const long r = std::lround(x / L * static_cast<double>(R));
  return std::abs(x - static_cast<double>(r) * L / static_cast<double>(R)) <= 1e-9 * L ? r : -1;
}

namespace {

long node_or_throw(const Scene& s, double x, long R, const std::string& key) {
  const double L = s.geometry.length;
  const long r = node_at(x, L, R);
  if (r < 0)
    throw InputError(s.source, key,
                     fmt::format("not at a node of mesh R={}: x = {} m, nodes at multiples of L/R = {} m", R, x,
                                 L / static_cast<double>(R)));
  return r;
}

}  // namespace

std::vector<NodalAttachment> attachments_of(const Scene& s, long R) {
  std::vector<NodalAttachment> out;
  for (std::size_t i = 0; i < s.point_supports.size(); ++i) {
    const auto& p = s.point_supports[i];
    out.push_back({node_or_throw(s, p.x, R, fmt::format("supports.points[{}].x", i)), p.support.translational,
                   p.support.rotational, 0.0, 0.0});
  }
  for (std::size_t i = 0; i < s.masses.size(); ++i) {
    const auto& m = s.masses[i];
    out.push_back({node_or_throw(s, m.x, R, fmt::format("masses[{}].x", i)), 0.0, 0.0, m.mass, m.Jy});
  }
  return out;
}

std::vector<ElementLoad> element_loads_of(const Scene& s, long R) {
  std::vector<ElementLoad> out;
  const double L = s.geometry.length;
  for (std::size_t i = 0; i < s.line_loads.size(); ++i) {
    const DistributedLoad& d = s.line_loads[i];
    const long e0 = node_or_throw(s, d.from[0], R, fmt::format("line_loads[{}].x_from", i));
    const long e1 = node_or_throw(s, d.to[0], R, fmt::format("line_loads[{}].x_to", i));
    if (d.qz[0] != 0 || d.qz[1] != 0) out.push_back({e0, e1, d.from[0], d.to[0], d.qz[0], d.qz[1]});
  }
  if (s.gravity && (*s.gravity)[2] != 0) {
    const double q = s.material.rho * s.section().A * (*s.gravity)[2];
    out.push_back({0, R, 0.0, L, q, q});
  }
  return out;
}

}  // namespace modalbench::difference_eq
