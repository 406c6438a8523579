// A beam scene's supports between the ends and point masses per line, and the lines' support
// reactions per support (beam_attachments.hpp).
#include "beam_attachments.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>

namespace modalbench::exact {

/// The scene's point supports and masses as seen by one line: bending in x-z (w, theta_y: Jy),
/// in x-y (v, theta_z: Jz), axial (u), torsion (theta_x: Jx).
PointAttachments line_points(const Scene& s, ModeFamily line) {
  PointAttachments out;
  for (const PointSupport& p : s.point_supports) {
    const Support& sp = p.support;
    switch (line) {
      case ModeFamily::Axial: out.push_back({p.x, {sp.axial, 0.0}, 0.0, 0.0}); break;
      case ModeFamily::Torsion: out.push_back({p.x, {sp.torsional, 0.0}, 0.0, 0.0}); break;
      default: out.push_back({p.x, {sp.translational, sp.rotational}, 0.0, 0.0}); break;
    }
  }
  for (const PointMass& m : s.masses) {
    switch (line) {
      case ModeFamily::Axial: out.push_back({m.x, {0.0, 0.0}, m.mass, 0.0}); break;
      case ModeFamily::Torsion: out.push_back({m.x, {0.0, 0.0}, m.Jx, 0.0}); break;
      case ModeFamily::BendingXY: out.push_back({m.x, {0.0, 0.0}, m.mass, m.Jz}); break;
      default: out.push_back({m.x, {0.0, 0.0}, m.mass, m.Jy}); break;
    }
  }
  return out;
}

namespace {

/// The reaction entry of the support at x, made on first use ("x0", "xL", "points[i]").
Reaction& entry_at(const Scene& s, std::vector<Reaction>& out, double x) {
  for (Reaction& e : out)
    if (e.position[0] == x) return e;
  std::string name = x == 0.0 ? "x0" : x == s.geometry.length ? "xL" : fmt::format("x = {:g} m", x);
  for (std::size_t i = 0; i < s.point_supports.size(); ++i)
    if (std::abs(s.point_supports[i].x - x) <= 1e-12 * s.geometry.length) name = fmt::format("points[{}]", i);
  out.push_back({name, {x, 0.0}, {}, {}});
  return out.back();
}

}  // namespace

std::vector<Reaction> gather_reactions(const Scene& s, const std::vector<SupportReaction>& xz,
                                       const std::vector<SupportReaction>& axial,
                                       const std::vector<SupportReaction>& xy,
                                       const std::vector<SupportReaction>& torsion) {
  std::vector<Reaction> out;
  for (const SupportReaction& r : xz) {
    Reaction& e = entry_at(s, out, r.x);
    e.force[2] += r.force;
    e.moment[1] += r.moment;  // moment_sign applied by the line: My
  }
  for (const SupportReaction& r : axial) entry_at(s, out, r.x).force[0] += r.force;
  for (const SupportReaction& r : xy) {
    Reaction& e = entry_at(s, out, r.x);
    e.force[1] += r.force;
    e.moment[2] += r.moment;
  }
  for (const SupportReaction& r : torsion) entry_at(s, out, r.x).moment[0] += r.force;  // a torsion bar's "force" is Mx
  return out;
}

}  // namespace modalbench::exact
