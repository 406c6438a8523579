#include "modalbench/frame.hpp"

#include <cmath>
#include <stdexcept>

namespace modalbench {

namespace {

using Vec3 = std::array<double, 3>;

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3 unit(const Vec3& a) {
  const double n = std::sqrt(dot(a, a));
  return {a[0] / n, a[1] / n, a[2] / n};
}

}  // namespace

MemberAxes member_axes(const Vec3& from, const Vec3& to, const std::optional<Vec3>& up) {
  const Vec3 ex = unit({to[0] - from[0], to[1] - from[1], to[2] - from[2]});
  // The default up: global z, or global x for a member along z (within 1e-9 rad of it).
  Vec3 u = up.value_or(Vec3{0, 0, 1});
  if (!up && std::abs(ex[2]) > 1.0 - 1e-9) u = {1, 0, 0};
  const double along = dot(u, ex);
  const Vec3 perp = {u[0] - along * ex[0], u[1] - along * ex[1], u[2] - along * ex[2]};
  // up within 1e-6 rad of the member's axis leaves its local z to rounding.
  if (!(std::sqrt(dot(perp, perp)) > 1e-6 * std::sqrt(dot(u, u))))
    throw std::invalid_argument("`up` is parallel to the member: it must have a component across it");
  const Vec3 ez = unit(perp);
  return {ex, cross(ez, ex), ez};
}

Deflection frame_deflection(const Frame& frame, const FrameProbe& probe, const std::array<double, 6>& v) {
  Deflection d;
  d.probe = probe.label;
  d.point = frame.probe_point(probe);
  d.position = {d.point[0], d.point[2]};
  d.u = v[0];
  d.v = frame.spatial ? v[1] : 0.0;
  d.w = v[2];
  d.theta_x = frame.spatial ? v[3] : 0.0;
  d.theta_y = v[4];
  d.theta_z = frame.spatial ? v[5] : 0.0;
  return d;
}

std::vector<int> Frame::node_dofs() const {
  if (spatial) return {0, 1, 2, 3, 4, 5};
  return {0, 2, 4};
}

std::array<double, 3> Frame::point_on(const FrameMember& m, double s) const {
  const Vec3& a = nodes[static_cast<std::size_t>(m.nodes[0])].x;
  const Vec3& b = nodes[static_cast<std::size_t>(m.nodes[1])].x;
  return {a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]), a[2] + s * (b[2] - a[2])};
}

std::array<double, 3> Frame::probe_point(const FrameProbe& p) const {
  if (p.node >= 0) return nodes[static_cast<std::size_t>(p.node)].x;
  return point_on(members[static_cast<std::size_t>(p.member)], p.s);
}

std::vector<FrameLineLoad> Frame::all_line_loads(const std::optional<Vec3>& gravity) const {
  std::vector<FrameLineLoad> out = line_loads;
  if (!gravity) return out;
  for (std::size_t i = 0; i < members.size(); ++i) {
    const double w = members[i].material.rho * members[i].properties().A;
    const Vec3& g = *gravity;
    out.push_back({static_cast<int>(i), {w * g[0], w * g[0]}, {w * g[1], w * g[1]}, {w * g[2], w * g[2]}});
  }
  return out;
}

std::vector<FrameLoad> Frame::all_node_loads(const std::optional<Vec3>& gravity) const {
  std::vector<FrameLoad> out = loads;
  if (!gravity) return out;
  for (const FrameMass& m : masses)
    out.push_back({m.node, {m.mass * (*gravity)[0], m.mass * (*gravity)[1], m.mass * (*gravity)[2], 0, 0, 0}});
  return out;
}

double Frame::total_mass() const {
  double total = 0;
  for (const FrameMember& m : members) total += m.material.rho * m.properties().A * m.length;
  for (const FrameMass& m : masses) total += m.mass;
  return total;
}

}  // namespace modalbench
