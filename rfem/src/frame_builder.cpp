// The rigid finite element model of a frame (builders.hpp): each member a beam of rigid elements,
// the members' end elements joined at the nodes by rigid links, the supports and masses at the nodes.
#include "modalbench/rfem/builders.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "cell_box.hpp"
#include "modalbench/frame.hpp"

namespace modalbench::rfem {

namespace {

using Eigen::Vector3d;

Vector3d vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

/// The global axis each local axis of a member lies along (its axes are a signed permutation of the
/// global ones), or -1 where one is not.
std::array<int, 3> aligned_axes(const FrameMember& m) {
  std::array<int, 3> out{-1, -1, -1};
  for (std::size_t a = 0; a < 3; ++a)
    for (std::size_t g = 0; g < 3; ++g)
      if (std::abs(std::abs(m.axes[a][g]) - 1.0) < 1e-12) out[a] = static_cast<int>(g);
  return out;
}

/// A member end's rigid element, for the joins at its node.
struct End {
  int element = 0;
  std::size_t member = 0;
  bool released = false;
};

}  // namespace

std::string frame_refusal(const Scene& s) {
  for (const FrameMember& m : s.frame->members) {
    const auto a = aligned_axes(m);
    if (a[0] < 0 || a[1] < 0 || a[2] < 0)
      return fmt::format("rfem's rigid elements carry their rotary inertia about axes parallel to the global ones: "
                         "member '{}' is inclined to them (its inertia tensor would not be diagonal); exact solves it",
                         m.id);
  }
  return "";
}

int frame_member_segments(const Frame& f, std::size_t member, int n) {
  double shortest = std::numeric_limits<double>::infinity();
  for (const FrameMember& m : f.members) shortest = std::min(shortest, m.length);
  return n * static_cast<int>(std::max(1L, std::lround(f.members[member].length / shortest)));
}

FrameLayout frame_layout(const Frame& f, int n) {
  FrameLayout out;
  std::vector<std::vector<std::pair<int, bool>>> ends(f.nodes.size());  // (element, hinged), in member order
  int next = 0;
  for (std::size_t mi = 0; mi < f.members.size(); ++mi) {
    const FrameMember& mb = f.members[mi];
    const int nm = frame_member_segments(f, mi, n);
    out.first.push_back(next);
    out.segments.push_back(nm);
    ends[static_cast<std::size_t>(mb.nodes[0])].push_back({next, mb.released[0]});
    ends[static_cast<std::size_t>(mb.nodes[1])].push_back({next + nm, mb.released[1]});
    next += nm + 1;
  }
  for (const auto& e : ends) {
    const auto rigid = std::find_if(e.begin(), e.end(), [](const auto& x) { return !x.second; });
    const auto& a = rigid != e.end() ? *rigid : e.front();
    out.anchor.push_back(a.first);
    out.anchor_released.push_back(a.second);
  }
  return out;
}

Model build_frame(const Scene& s, int n) {
  if (n < 1) throw std::invalid_argument("a frame needs at least 1 segment on its shortest member");
  if (const std::string why = frame_refusal(s); !why.empty()) throw std::invalid_argument(why);
  const Frame& f = *s.frame;
  const bool eb = s.theory == Theory::EulerBernoulli;
  Model m;
  m.active = f.spatial ? dofs::kSpatial : dofs::kPlanarXZ;
  m.dof_family.assign(m.active.size(), ModeFamily::Unknown);
  std::vector<std::vector<End>> at_node(f.nodes.size());
  double omega = std::numeric_limits<double>::infinity(), longest = 0;
  long segments = 0;
  for (std::size_t mi = 0; mi < f.members.size(); ++mi) {
    const FrameMember& mb = f.members[mi];
    const Section p = mb.properties();
    const Material& mt = mb.material;
    const int nm = frame_member_segments(f, mi, n);
    segments += nm;
    if (segments > 2000000) throw std::invalid_argument("more than 2000000 segments in all");
    const double L = mb.length, d = L / nm, rhoA = mt.rho * p.A;
    const auto axis = aligned_axes(mb);
    const double half = 0.5 * std::max(mb.width, mb.height);
    const int first = static_cast<int>(m.elements.size());
    // Rigid elements centred at the member's nodes s = j d, the end ones half as long (as a beam's).
    for (int j = 0; j <= nm; ++j) {
      const double lo = std::max(0.0, (j - 0.5) * d), hi = std::min(L, (j + 0.5) * d), len = hi - lo;
      RigidElement r;
      r.centre = vec(f.point_on(mb, static_cast<double>(j) / nm));
      r.mass = rhoA * len;
      const double bar = r.mass * len * len / 12.0;
      const std::array<double, 3> local = {mt.rho * p.Ip * len, bar + (eb ? 0.0 : mt.rho * p.Iy * len),
                                           bar + (eb ? 0.0 : mt.rho * p.Iz * len)};
      for (std::size_t a = 0; a < 3; ++a) r.inertia[axis[a]] = local[a];
      const Vector3d A = vec(f.point_on(mb, lo / L)), B = vec(f.point_on(mb, hi / L));
      r.cell = box(std::min(A.x(), B.x()) - half, std::max(A.x(), B.x()) + half, std::min(A.y(), B.y()) - half,
                   std::max(A.y(), B.y()) + half, std::min(A.z(), B.z()) - half, std::max(A.z(), B.z()) + half);
      r.label = fmt::format("{} rfe {}", mb.id, j);
      m.elements.push_back(r);
    }
    // SDEs at the segment middles in the member's axes (Euler-Bernoulli: rigid shear, constraints).
    Eigen::Matrix3d axes;
    for (int a = 0; a < 3; ++a) axes.col(a) = vec(mb.axes[static_cast<std::size_t>(a)]);
    const double shear = eb ? kInf : mt.kappa * mt.G * p.A;
    for (int j = 0; j < nm; ++j) {
      Sde sd;
      sd.a = first + j;
      sd.b = first + j + 1;
      sd.point = vec(f.point_on(mb, (j + 0.5) / nm));
      sd.axes = axes;
      sd.stiffness << mt.E * p.A / d, shear / d, shear / d, mt.G * p.J / d, mt.E * p.Iy / d, mt.E * p.Iz / d;
      if (eb) sd.stiffness[1] = sd.stiffness[2] = kInf;
      m.sdes.push_back(sd);
    }
    at_node[static_cast<std::size_t>(mb.nodes[0])].push_back({first, mi, mb.released[0]});
    at_node[static_cast<std::size_t>(mb.nodes[1])].push_back({first + nm, mi, mb.released[1]});
    const double EI = mt.E * (f.spatial ? std::min(p.Iy, p.Iz) : p.Iy);
    omega = std::min(omega, 22.4 / (L * L) * std::sqrt(EI / rhoA));
    longest = std::max(longest, L);
  }
  const FrameLayout layout = frame_layout(f, n);
  for (std::size_t k = 0; k < f.nodes.size(); ++k) {
    const std::vector<End>& ends = at_node[k];
    // The anchor (frame_layout): a member end joined rigidly, where one is; the others are joined to
    // it, a hinged one with its bending rotations (about its own y and z) free.
    const End anchor = *std::find_if(ends.begin(), ends.end(), [&](const End& e) { return e.element == layout.anchor[k]; });
    for (const End& e : ends) {
      if (e.element == anchor.element) continue;
      Sde sd;
      sd.a = anchor.element;
      sd.b = e.element;
      sd.point = vec(f.nodes[k].x);
      sd.stiffness.setConstant(kInf);
      if (e.released) {
        for (int a = 0; a < 3; ++a) sd.axes.col(a) = vec(f.members[e.member].axes[static_cast<std::size_t>(a)]);
        sd.stiffness[4] = sd.stiffness[5] = 0.0;
      }
      m.sdes.push_back(sd);
    }
    for (const FrameMass& pm : f.masses)
      if (pm.node == static_cast<int>(k)) {
        RigidElement& r = m.elements[static_cast<std::size_t>(anchor.element)];
        r.mass += pm.mass;
        r.inertia += Vector3d(pm.Jx, pm.Jy, pm.Jz);
      }
    for (const FrameSupport& sp : f.supports) {
      if (sp.node != static_cast<int>(k)) continue;
      Sde sd;
      sd.a = anchor.element;
      sd.b = kGround;
      sd.point = vec(f.nodes[k].x);
      for (int c = 0; c < 6; ++c) sd.stiffness[c] = sp.springs[static_cast<std::size_t>(c)];
      // Every member hinged at the node: no member end turns with it, so no spring turns one.
      if (anchor.released) sd.stiffness[3] = sd.stiffness[4] = sd.stiffness[5] = 0.0;
      if ((sd.stiffness.array() == 0.0).all()) continue;
      m.supports.emplace_back(static_cast<int>(m.sdes.size()), f.nodes[k].id);
      m.sdes.push_back(sd);
    }
  }
  m.omega_hint = omega;
  m.length_scale = longest;
  m.description = fmt::format("frame: {} members, {} segments ({} on the shortest), {} RFEs (centred at the members' "
                              "nodes, half-length ends; the ends at a node joined by rigid links, hinged ones free "
                              "to turn), {} SDEs, {} {}",
                              f.members.size(), segments, n, m.elements.size(), m.sdes.size(), to_string(s.physics),
                              eb ? "Euler-Bernoulli (rigid shear exact: constraints with multipliers)"
                                 : "Timoshenko (shear SDE kGA/d)");
  return m;
}

}  // namespace modalbench::rfem
