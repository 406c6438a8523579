// The rigid finite element model of a beam (builders.hpp): rigid elements at the nodes, spring-
// damping elements between them, its supports, point masses and point singularities.
#include "modalbench/rfem/builders.hpp"

#include "beam_cells.hpp"
#include "cell_box.hpp"
#include "modalbench/rfem/system.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace modalbench::rfem {

namespace {

using Eigen::Vector3d;
constexpr double pi = std::numbers::pi;

ModeFamily beam_family(int d) {
  switch (d) {
    case dofs::Ux: return ModeFamily::Axial;
    case dofs::Uy:
    case dofs::Rz: return ModeFamily::BendingXY;
    case dofs::Uz:
    case dofs::Ry: return ModeFamily::BendingXZ;
    case dofs::Rx: return ModeFamily::Torsion;
    default: return ModeFamily::Unknown;
  }
}

}  // namespace

namespace {

/// What the beam builder's phases share: the scene, its pieces and the mesh of n segments.
struct BeamSetup {
  const Scene& s;
  const std::vector<Segment>& pieces;
  int n;
  double L, d;
  bool eb, joints;
};

/// The beam model's DOFs and their families, its scales and its description (no bodies yet).
Model start_beam_model(const BeamSetup& b) {
  const Scene& s = b.s;
  const int n = b.n;
  const bool eb = b.eb, joints = b.joints;
  Model m;
  switch (s.physics) {
    case Physics::Bending: m.active = dofs::kBendingXZ; break;
    case Physics::Planar: m.active = dofs::kPlanarXZ; break;
    case Physics::Spatial: m.active = dofs::kSpatial; break;
    case Physics::Lateral: m.active = dofs::kLateral; break;
  }
  for (int dof : m.active) m.dof_family.push_back(beam_family(dof));
  m.length_scale = b.L;
  m.loss_factor = s.material.loss_factor;
  m.description = fmt::format(
      "beam: {} segments, {} RFEs (centred at the nodes, half-length ends), {} SDEs, {} {}", n, n + 1, n,
      to_string(s.physics),
      !eb ? "Timoshenko (shear SDE kGA/d)"
          : joints ? "Euler-Bernoulli (rigid shear exact: joint-displacement coordinates)"
                   : "Euler-Bernoulli (rigid shear exact: constraints with multipliers)");
  return m;
}

/// The rigid elements, each with the mass and inertia of its cell, and the grid they stand on.
void add_beam_elements(Model& m, const BeamSetup& b) {
  const Scene& s = b.s;
  const std::vector<Segment>& pieces = b.pieces;
  const int n = b.n;
  const double L = b.L, bw = s.geometry.width, bh = s.geometry.height, d = b.d;
  const bool eb = b.eb;
  // Rigid elements at the nodes x_j = j d.
  for (int j = 0; j <= n; ++j) {
    RigidElement r;
    const double x = j * d;
    const double lo = std::max(0.0, x - d / 2), hi = std::min(L, x + d / 2);
    r.centre = Vector3d(x, 0, 0);
    // The piece(s) of beam it stands for; its length's inertia about the cell's middle.
    const detail::CellMass cm = detail::cell_mass(pieces, lo, hi, 0.5 * (lo + hi));
    r.mass = cm.mass;
    // A lateral (rotor) model carries no twist: its Jx is the polar inertia of the gyroscopic
    // moment, which an Euler-Bernoulli shaft (no rotary inertia) does not have; its discs' Jx does.
    const double jx = s.physics == Physics::Lateral && eb ? 0.0 : cm.rho_Ip;
    r.inertia = Vector3d(jx, cm.length_inertia + (eb ? 0.0 : cm.rho_Iy), cm.length_inertia + (eb ? 0.0 : cm.rho_Iz));
    r.cell = box(lo, hi, -bw / 2, bw / 2, -bh / 2, bh / 2);
    r.label = fmt::format("rfe {}", j);
    m.elements.push_back(r);
    m.grid.x.push_back(x);
    m.grid.element.push_back(j);
  }
  m.grid.y = {0.0};
}

/// The point singularities of the active second-order fields, piece by piece.
void add_beam_singularities(Model& m, const BeamSetup& b) {
  const std::vector<Segment>& pieces = b.pieces;
  const bool eb = b.eb;
  // Slope jumps of the second-order fields under their own point actions (PointSingularity), with
  // the stiffness of the piece the action is on: a tapered piece's at the middle of each mesh
  // segment's share of it (the jump is O(d); the stiffness off by O(d) there, so O(d^2) in all).
  auto kinks = [&](const Segment& p, double at, double from, double to) {
    const Section ps = p.properties_at(at);
    const Material& pm = p.material;
    auto kink = [&](int dof, double stiffness) {
      if (std::find(m.active.begin(), m.active.end(), dof) == m.active.end()) return;
      m.singularities.push_back({dof, dof, PointSingularity::Kind::Kink, 0.5 / stiffness,
                                 PointSingularity::Derivative::None, from, to});
    };
    kink(dofs::Ux, pm.E * ps.A);
    if (!eb) {
      kink(dofs::Uz, p.kappa_at(at) * pm.G * ps.A);
      kink(dofs::Uy, p.kappa_at(at) * pm.G * ps.A);
    }
    kink(dofs::Rx, pm.G * ps.J);
    kink(dofs::Ry, pm.E * ps.Iy);
    kink(dofs::Rz, pm.E * ps.Iz);
  };
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const Segment& p = pieces[i];
    const double from = i == 0 ? -kInf : p.x_from, to = i + 1 == pieces.size() ? kInf : p.x_to;
    if (!p.tapered()) {
      kinks(p, p.x_from, from, to);
      continue;
    }
    for (int j = 0; j < b.n; ++j) {
      const double lo = std::max(p.x_from, j * b.d), hi = std::min(p.x_to, (j + 1) * b.d);
      if (!(hi > lo)) continue;
      kinks(p, 0.5 * (lo + hi), lo == p.x_from ? from : lo, hi == p.x_to ? to : hi);
    }
  }
}

/// The SDEs joining neighbouring rigid elements.
void add_beam_sdes(Model& m, const BeamSetup& b) {
  const int n = b.n;
  const double d = b.d;
  const bool eb = b.eb, joints = b.joints;
  // SDEs at the segment middles: the segment's stiffnesses in series over its pieces.
  for (int j = 0; j < n; ++j) {
    Sde sd;
    sd.a = j;
    sd.b = j + 1;
    sd.point = Vector3d((j + 0.5) * d, 0, 0);
    const detail::CellStiffness k = detail::cell_stiffness(b.pieces, j * d, (j + 1) * d);
    // Euler-Bernoulli: rigid shear (+inf: exact constraints), or none when the joint coordinates
    // satisfy it identically.
    const double shear = !eb ? k.kGA : joints ? 0.0 : kInf;
    sd.stiffness << k.EA, shear, shear, k.GJ, k.EIy, k.EIz;
    m.sdes.push_back(sd);
  }
}

/// The supports at the ends and between them, as SDEs to ground.
void add_beam_supports(Model& m, const BeamSetup& b) {
  const Scene& s = b.s;
  const int n = b.n;
  const double L = b.L, d = b.d;
  // End supports: SDEs to ground at the end points (the end RFEs' centres).
  auto support = [&](const Support& sp, int body, double x, const std::string& name) {
    Sde sd;
    sd.a = body;
    sd.b = kGround;
    sd.point = Vector3d(x, 0, 0);
    sd.stiffness << sp.axial, sp.translational, sp.translational, sp.torsional, sp.rotational, sp.rotational;
    bool any = false;
    for (int c = 0; c < 6; ++c) any = any || sd.stiffness[c] != 0;
    if (!any) return;
    m.supports.emplace_back(static_cast<int>(m.sdes.size()), name);
    m.sdes.push_back(sd);
  };
  support(s.x0, 0, 0.0, "x0");
  support(s.xL, n, L, "xL");
  // Supports between the ends: SDEs to ground at the point, attached to the RFE whose cell holds
  // it (off its centre the attachment kinematics carry it: w(P) = w_j + w' (x - x_j), second order).
  for (std::size_t i = 0; i < s.point_supports.size(); ++i) {
    const PointSupport& p = s.point_supports[i];
    support(p.support, std::clamp(static_cast<int>(std::lround(p.x / d)), 0, n), p.x, fmt::format("points[{}]", i));
  }
}

/// The scene's point masses, added to the rigid elements around them.
void add_beam_point_masses(Model& m, const BeamSetup& b) {
  const int n = b.n;
  const double d = b.d;
  // Point masses: at an RFE centre its own; between two, shared as linear interpolation weights
  // (t and 1 - t: the kinetic energy's error is of order m h^2 w'^2, the model's own order).
  for (const PointMass& pm : b.s.masses) {
    const double u = std::clamp(pm.x / d, 0.0, static_cast<double>(n));
    const int j0 = std::min(static_cast<int>(std::floor(u)), n);
    const double t = u - j0;
    for (const auto& [j, share] : {std::pair{j0, 1.0 - t}, std::pair{std::min(j0 + 1, n), t}}) {
      if (share == 0.0) continue;
      RigidElement& r = m.elements[static_cast<std::size_t>(j)];
      r.mass += share * pm.mass;
      r.inertia += share * Vector3d(pm.Jx, pm.Jy, pm.Jz);
    }
  }
}

/// The basis of joint coordinates (Euler-Bernoulli with rigid shear exact by construction).
void set_beam_joint_basis(Model& m, const BeamSetup& b) {
  const int n = b.n;
  const double L = b.L, d = b.d;
  const int na = m.dofs_per_element();
  std::vector<Eigen::Triplet<double>> t;
  int col = 0;
  // DOFs that are not transverse bending keep their own coordinate.
  for (int j = 0; j <= n; ++j)
    for (int k = 0; k < na; ++k) {
      const int dof = m.active[static_cast<std::size_t>(k)];
      if (dof == dofs::Ux || dof == dofs::Rx) {
        t.emplace_back(j * na + k, col++, 1.0);
        m.basis_names.push_back(fmt::format("{}[rfe {}]", dof_symbol(dof), j));
      }
    }
  // One plane: translation DOF `tr`, rotation DOF `rot`, rot = sign * slope.
  auto plane = [&](int tr, int rot, double sign, const char* sym) {
    const int kt = m.local_index(tr), kr = m.local_index(rot);
    if (kt < 0 || kr < 0) return;
    const int c0 = col;  // W at x = 0; joints j + 1/2 at c0 + 1 + j; x = L at c0 + n + 1
    m.basis_names.push_back(fmt::format("{}(x=0)", sym));
    for (int j = 0; j < n; ++j) m.basis_names.push_back(fmt::format("{}(x={:.6g})", sym, (j + 0.5) * d));
    m.basis_names.push_back(fmt::format("{}(x={:.6g})", sym, L));
    col += n + 2;
    for (int j = 0; j <= n; ++j) {
      const int left = (j == 0) ? c0 : c0 + j;          // point on the element's left side
      const int right = (j == n) ? c0 + n + 1 : c0 + 1 + j;
      const double len = (j == 0 || j == n) ? d / 2 : d;
      const long rt = static_cast<long>(j) * na + kt, rr = static_cast<long>(j) * na + kr;
      if (j == 0) t.emplace_back(rt, left, 1.0);
      else if (j == n) t.emplace_back(rt, right, 1.0);
      else {
        t.emplace_back(rt, left, 0.5);
        t.emplace_back(rt, right, 0.5);
      }
      t.emplace_back(rr, right, sign / len);
      t.emplace_back(rr, left, -sign / len);
    }
  };
  plane(dofs::Uz, dofs::Ry, -1.0, "w");  // theta_y = -dw/dx
  plane(dofs::Uy, dofs::Rz, +1.0, "v");  // theta_z = +dv/dx
  m.basis.resize(m.body_dofs(), col);
  m.basis.setFromTriplets(t.begin(), t.end());
}

/// The model's characteristic low frequency (omega_hint, the scale of the eigensolver's shift).
double beam_omega_hint(const Scene& s, const Section& sec, double L) {
  const Material& mat = s.material;
  // A characteristic low frequency: the lowest of bending (cantilever-like) and axial/torsion.
  double hint = 0.35 * std::pow(pi / L, 2) * std::sqrt(mat.E * std::min(sec.Iy, sec.Iz) / (mat.rho * sec.A));
  if (carries_axial(s.physics)) hint = std::min(hint, 0.5 * pi / L * std::sqrt(mat.E / mat.rho));
  if (carries_torsion(s.physics)) hint = std::min(hint, 0.5 * pi / L * std::sqrt(mat.G * sec.J / (mat.rho * sec.Ip)));
  return hint;
}

}  // namespace

Model build_beam(const Scene& s, int n, const BeamOptions& opt) {
  if (!s.is_beam()) throw std::invalid_argument("build_beam: the scene is not a beam");
  if (n < 1) throw std::invalid_argument(fmt::format("build_beam: need >= 1 segment (got {})", n));
  const double L = s.geometry.length;
  const Section sec = s.section();  // the first piece's (characteristic frequency only)
  const std::vector<Segment> pieces = s.beam_pieces();
  const bool eb = s.theory == Theory::EulerBernoulli;
  const double d = L / n;
  const bool joints = eb && opt.rigid_shear == RigidShear::JointCoordinates;
  const BeamSetup b{s, pieces, n, L, d, eb, joints};

  Model m = start_beam_model(b);
  add_beam_elements(m, b);
  add_beam_singularities(m, b);
  add_beam_sdes(m, b);
  add_beam_supports(m, b);
  add_beam_point_masses(m, b);
  // Euler-Bernoulli by joint coordinates: the transverse displacements of the end points and joints.
  if (joints) set_beam_joint_basis(m, b);
  m.omega_hint = beam_omega_hint(s, sec, L);
  m.check();
  return m;
}

}  // namespace modalbench::rfem
