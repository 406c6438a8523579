// rfem's frame statics (analysis_detail.hpp, frame_statics): the frame's loads on its rigid
// elements, the static solve, the displacements at the probes and the reactions at the supports.
#include <fmt/format.h>

#include <cmath>

#include "analysis_detail.hpp"
#include "modalbench/frame.hpp"
#include "modalbench/rfem/builders.hpp"
#include "system_detail.hpp"

namespace modalbench::rfem::detail {

namespace {

Eigen::Vector3d vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

/// Adds the action [F; M] at P, rigidly attached to element e, to fq (over the body DOFs).
void add_action(const Model& m, int e, const Eigen::Vector3d& P, const Vector6d& action, Eigen::VectorXd& fq) {
  const int na = m.dofs_per_element();
  const Vector6d f = attachment(P - m.elements[static_cast<std::size_t>(e)].centre).transpose() * action;
  for (int k = 0; k < na; ++k) fq[static_cast<long>(e) * na + k] += f[m.active[static_cast<std::size_t>(k)]];
}

/// The frame's loads over the body DOFs: node loads on the anchors; each member's line loads on its
/// rigid elements, each element's share (its cell) by 2-point Gauss (a linear intensity times the
/// rigid attachment's linear lever: exact).
Eigen::VectorXd frame_loads(const Scene& s, const Model& m, const FrameLayout& lay) {
  const Frame& f = *s.frame;
  Eigen::VectorXd fq = Eigen::VectorXd::Zero(m.body_dofs());
  for (const FrameLoad& p : f.all_node_loads(s.gravity)) {
    Vector6d a;
    a << p.F[0], p.F[1], p.F[2], p.F[3], p.F[4], p.F[5];
    add_action(m, lay.anchor[static_cast<std::size_t>(p.node)], vec(f.nodes[static_cast<std::size_t>(p.node)].x), a, fq);
  }
  const double g = 0.5 / std::sqrt(3.0);
  for (const FrameLineLoad& q : f.all_line_loads(s.gravity)) {
    const auto mi = static_cast<std::size_t>(q.member);
    const FrameMember& mb = f.members[mi];
    const int nm = lay.segments[mi];
    for (int j = 0; j <= nm; ++j) {
      const double lo = std::max(0.0, (j - 0.5) / nm), hi = std::min(1.0, (j + 0.5) / nm);
      for (const double t : {0.5 - g, 0.5 + g}) {
        const double at = lo + t * (hi - lo), w = 0.5 * (hi - lo) * mb.length;
        const auto lin = [at](const std::array<double, 2>& v) { return v[0] + (v[1] - v[0]) * at; };
        Vector6d a;
        a << w * lin(q.qx), w * lin(q.qy), w * lin(q.qz), 0, 0, 0;
        add_action(m, lay.first[mi] + j, vec(f.point_on(mb, at)), a, fq);
      }
    }
  }
  return fq;
}

/// The six components (u, v, w, theta_x, theta_y, theta_z) of element e's motion at its centre.
std::array<double, 6> motion(const Model& m, const Eigen::VectorXd& q, int e) {
  std::array<double, 6> out{};
  const int na = m.dofs_per_element();
  for (int k = 0; k < na; ++k) out[static_cast<std::size_t>(m.active[static_cast<std::size_t>(k)])] = q[static_cast<long>(e) * na + k];
  return out;
}

}  // namespace

void frame_statics(const Scene& s, const Model& model, const System& sys, int n, Result& r) {
  const Frame& f = *s.frame;
  const FrameLayout lay = frame_layout(f, n);
  const Eigen::VectorXd fq = frame_loads(s, model, lay), fz = sys.T.transpose() * fq;
  const StaticSolution st = solve_static(model, sys, fz);
  if (!st.ok) {
    r.summary.raise(st.mechanism ? Status::InvalidInput : Status::NumericalIssue,
                    fmt::format("{}: supports: {}", s.source.empty() ? "command line" : s.source, st.message));
    return;
  }
  const Eigen::VectorXd q = sys.T * st.z;
  for (const FrameProbe& p : f.probes) {
    std::array<double, 6> v{};
    if (p.node >= 0) {
      v = motion(model, q, lay.anchor[static_cast<std::size_t>(p.node)]);
    } else {
      // Linear between the element centres around s (second order, as the centres' own motion).
      const auto mi = static_cast<std::size_t>(p.member);
      const double x = p.s * lay.segments[mi];
      const int j = std::min(static_cast<int>(std::floor(x)), lay.segments[mi] - 1);
      const double t = x - j;
      const auto a = motion(model, q, lay.first[mi] + j), b = motion(model, q, lay.first[mi] + j + 1);
      for (std::size_t c = 0; c < 6; ++c) v[c] = (1 - t) * a[c] + t * b[c];
    }
    r.deflections.push_back(frame_deflection(f, p, v));
  }
  frame_reactions(f, model, sys, st.z, fq, r);
  note_static_backward_error(sys, fz, st, r.summary);
}

}  // namespace modalbench::rfem::detail
