// The rigid finite element model of a plate (builders.hpp): rigid elements on a grid of fragments,
// their spring-damping elements, edge and point supports, point masses and the corner basis.
#include "modalbench/rfem/builders.hpp"

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

}  // namespace

Eigen::MatrixXd plate_fragment_correction(double D, double nu, double dl, double db) {
  // Corner order BL, BR, TL, TR; DOF offset 6 k + d.
  enum { BL = 0, BR = 1, TL = 2, TR = 3 };
  auto at = [](int corner, int dof) { return 6 * corner + dof; };
  Eigen::VectorXd gx = Eigen::VectorXd::Zero(24), gy = gx, ga = gx, gb = gx;
  // kx = -d(theta_y)/dx, averaged over the bottom and top sides.
  gx[at(BL, dofs::Ry)] = 0.5 / dl;
  gx[at(BR, dofs::Ry)] = -0.5 / dl;
  gx[at(TL, dofs::Ry)] = 0.5 / dl;
  gx[at(TR, dofs::Ry)] = -0.5 / dl;
  // ky = d(theta_x)/dy, averaged over the left and right sides.
  gy[at(TL, dofs::Rx)] = 0.5 / db;
  gy[at(BL, dofs::Rx)] = -0.5 / db;
  gy[at(TR, dofs::Rx)] = 0.5 / db;
  gy[at(BR, dofs::Rx)] = -0.5 / db;
  // twists: d(theta_x)/dx (x sides) and d(theta_y)/dy (y sides); kxy = ga - gb.
  ga[at(BR, dofs::Rx)] = 0.5 / dl;
  ga[at(BL, dofs::Rx)] = -0.5 / dl;
  ga[at(TR, dofs::Rx)] = 0.5 / dl;
  ga[at(TL, dofs::Rx)] = -0.5 / dl;
  gb[at(TL, dofs::Ry)] = 0.5 / db;
  gb[at(BL, dofs::Ry)] = -0.5 / db;
  gb[at(TR, dofs::Ry)] = 0.5 / db;
  gb[at(BR, dofs::Ry)] = -0.5 / db;
  const double A = dl * db;
  const Eigen::VectorXd s = ga + gb;
  return D * A * (nu * (gx * gy.transpose() + gy * gx.transpose()) - 0.5 * (1.0 - nu) * s * s.transpose());
}

namespace {

/// What the plate builder's phases share: the scene, the fragment mesh, the theory and the rigidities.
struct PlateSetup {
  const Scene& s;
  int nx, ny;
  double a, b, h, dl, db;
  bool kirchhoff, corners;
  double D, Gh3_6;
  /// The rigid element at corner (i, j).
  int id(int i, int j) const { return j * (nx + 1) + i; }
};

/// The share of a fragment's side that corner i of 0..n stands for (half at the edges).
double half(int i, int n) { return (i == 0 || i == n) ? 0.5 : 1.0; }

/// The plate model's DOFs and their families, its scales and its description (no bodies yet).
Model start_plate_model(const PlateSetup& g, const PlateOptions& o) {
  const int nx = g.nx, ny = g.ny;
  const bool kirchhoff = g.kirchhoff, corners = g.corners;
  Model m;
  m.active = dofs::kPlate;
  m.dof_family.assign(m.active.size(), ModeFamily::Plate);
  m.length_scale = std::max(g.a, g.b);
  m.loss_factor = g.s.material.loss_factor;
  m.description = fmt::format(
      "plate: {}x{} fragments, {}x{} RFEs at the fragment corners (Table A2.1 types 1-4), {}{}", nx, ny, nx + 1,
      ny + 1,
      !kirchhoff ? "shear springs kGh (Mindlin)"
      : corners  ? "rigid transverse shear (Kirchhoff, exact: corner-value coordinates)"
                 : "rigid transverse shear (Kirchhoff, exact: constraints with multipliers)",
      o.bending_correction ? ", per-fragment Poisson/twist correction" : ", Table A1.1 springs only (no Poisson coupling)");
  return m;
}

/// The rigid elements at the fragment corners, each with the mass and inertia of its cell, and the grid.
void add_plate_elements(Model& m, const PlateSetup& g) {
  const Material& mat = g.s.material;
  const int nx = g.nx, ny = g.ny;
  const double a = g.a, b = g.b, h = g.h, dl = g.dl, db = g.db;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      RigidElement r;
      const double x = i * dl, y = j * db, lx = dl * half(i, nx), ly = db * half(j, ny);
      r.centre = Vector3d(x, y, 0);
      r.mass = mat.rho * h * lx * ly;  // Table A2.1: full, half (types 2, 3) or quarter (type 4)
      const double rot = g.kirchhoff ? 0.0 : r.mass * h * h / 12.0;
      r.inertia = Vector3d(r.mass * ly * ly / 12.0 + rot, r.mass * lx * lx / 12.0 + rot,
                           r.mass * (lx * lx + ly * ly) / 12.0);
      r.cell = box(std::max(0.0, x - dl / 2), std::min(a, x + dl / 2), std::max(0.0, y - db / 2),
                   std::min(b, y + db / 2), -h / 2, h / 2);
      r.label = fmt::format("rfe ({},{})", i, j);
      m.elements.push_back(r);
      m.grid.element.push_back(g.id(i, j));
    }
  for (int i = 0; i <= nx; ++i) m.grid.x.push_back(i * dl);
  for (int j = 0; j <= ny; ++j) m.grid.y.push_back(j * db);
}

/// The singular part of the point-load Green's function.
void add_plate_singularities(Model& m, const PlateSetup& g) {
  const Material& mat = g.s.material;
  const double h = g.h, D = g.D;
  // The point-load Green's function's singular part (PointSingularity): r^2 ln r / (8 pi D) in w
  // and its gradient in the rotations; Mindlin adds -ln r / (2 pi kappa G h) in w.
  using PS = PointSingularity;
  const double c = 1.0 / (8.0 * pi * D);
  m.singularities.push_back({dofs::Uz, dofs::Uz, PS::Kind::Biharmonic, c, PS::Derivative::None});
  m.singularities.push_back({dofs::Rx, dofs::Uz, PS::Kind::Biharmonic, c, PS::Derivative::PlusDy});
  m.singularities.push_back({dofs::Ry, dofs::Uz, PS::Kind::Biharmonic, c, PS::Derivative::MinusDx});
  if (!g.kirchhoff)
    m.singularities.push_back(
        {dofs::Uz, dofs::Uz, PS::Kind::ShearLog, 1.0 / (2.0 * pi * mat.kappa * mat.G * h), PS::Derivative::None});
}

/// The in-plane torsion spring of a fragment's SDEs (k6).
double fragment_torsion_spring(const PlateSetup& g) {
  const Material& mat = g.s.material;
  const double h = g.h, dl = g.dl, db = g.db;
  // Table A1.1 in-plane torsion constant of the fragment (inactive in plate bending; kept for completeness).
  const double lmin = std::min(dl, db), lmax = std::max(dl, db);
  double series = 0;
  for (int k = 0; k < 50; ++k)
    series += std::tanh((2 * k + 1) * pi * lmax / (2 * lmin)) / std::pow(2 * k + 1, 5);
  const double K1 = 1.0 / 3.0 - 64.0 * lmin / (std::pow(pi, 5) * lmax) * series;
  const double Js = K1 * lmin * lmin * lmin * lmax;
  return mat.G * Js / (4 * h);
}

/// The SDEs on the fragment sides: first those along x, then those along y.
void add_plate_sdes(Model& m, const PlateSetup& g, double k6) {
  const Material& mat = g.s.material;
  const int nx = g.nx, ny = g.ny;
  const double h = g.h, dl = g.dl, db = g.db, D = g.D, Gh3_6 = g.Gh3_6;
  // Kirchhoff: rigid shear (+inf: exact constraints), or none when the corner coordinates
  // satisfy it identically.
  const double shear = !g.kirchhoff ? mat.kappa * mat.G * h : g.corners ? 0.0 : kInf;
  // x-direction SDEs: sides (i, j)-(i + 1, j); tributary width: both adjacent fragments' halves.
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i < nx; ++i) {
      Sde sd;
      sd.a = g.id(i, j);
      sd.b = g.id(i + 1, j);
      sd.point = Vector3d((i + 0.5) * dl, j * db, 0);
      const double r = db * half(j, ny) / dl;
      sd.stiffness << mat.E * h * r, shear * r, shear * r, Gh3_6 * r, D * r, k6;
      m.sdes.push_back(sd);
    }
  // y-direction SDEs: local x along global y, local y along -x, local z along z.
  Eigen::Matrix3d Ry;
  Ry << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      Sde sd;
      sd.a = g.id(i, j);
      sd.b = g.id(i, j + 1);
      sd.point = Vector3d(i * dl, (j + 0.5) * db, 0);
      sd.axes = Ry;
      const double r = dl * half(i, nx) / db;
      sd.stiffness << mat.E * h * r, shear * r, shear * r, Gh3_6 * r, D * r, k6;
      m.sdes.push_back(sd);
    }
}

/// The supports along the four edges (y0, yB, x0, xL), as SDEs to ground on the edge elements.
void add_plate_edge_supports(Model& m, const PlateSetup& g) {
  const Scene& s = g.s;
  const int nx = g.nx, ny = g.ny;
  const double dl = g.dl, db = g.db;
  // Edge supports: the per-length springs act along the RFE's share of the edge (length l, centred
  // at P). Integrated over that segment of a rigid element, the translational layer k_t gives
  // k_t l on w(P) and k_t l^3 / 12 on the tilt along the edge (rotation about the in-plane
  // normal); the rotational layer gives k_r l about the edge. A rigid edge thus holds w and the
  // tilt (the hard simple support of Mindlin plates, and w = 0 all along a Kirchhoff edge).
  auto edge = [&](const Support& sp, bool along_x, int fixed, const char* name) {
    if (sp.translational == 0 && sp.rotational == 0) return;
    const int count = along_x ? nx : ny;
    for (int k = 0; k <= count; ++k) {
      const int body = along_x ? g.id(k, fixed) : g.id(fixed, k);
      const auto& cell = m.elements[static_cast<std::size_t>(body)].cell;
      Sde sd;
      sd.a = body;
      sd.b = kGround;
      double share;
      if (along_x) {  // edge y = 0 or b: runs along x, tilt is theta_y, the edge axis is x
        share = cell.max().x() - cell.min().x();
        sd.point = Vector3d(0.5 * (cell.min().x() + cell.max().x()), fixed * db, 0);
        sd.stiffness[4] = sp.translational * share * share * share / 12.0;
        sd.stiffness[3] = sp.rotational * share;
      } else {  // edge x = 0 or a: runs along y, tilt is theta_x, the edge axis is y
        share = cell.max().y() - cell.min().y();
        sd.point = Vector3d(fixed * dl, 0.5 * (cell.min().y() + cell.max().y()), 0);
        sd.stiffness[3] = sp.translational * share * share * share / 12.0;
        sd.stiffness[4] = sp.rotational * share;
      }
      sd.stiffness[2] = sp.translational * share;
      m.supports.emplace_back(static_cast<int>(m.sdes.size()), name);  // one edge: many SDEs of one name
      m.sdes.push_back(sd);
    }
  };
  edge(s.y0, true, 0, "y0");
  edge(s.yB, true, ny, "yB");
  edge(s.x0, false, 0, "x0");
  edge(s.xL, false, nx, "xL");
}

/// The supports at points, as SDEs to ground.
void add_plate_point_supports(Model& m, const PlateSetup& g) {
  const Scene& s = g.s;
  const int nx = g.nx, ny = g.ny;
  const double dl = g.dl, db = g.db;
  // Supports at points: an SDE to ground at P on the RFE whose cell holds it (off its centre the
  // attachment kinematics carry it), k_t on w and k_r on both rotations.
  for (std::size_t k = 0; k < s.point_supports.size(); ++k) {
    const PointSupport& p = s.point_supports[k];
    Sde sd;
    sd.a = g.id(std::clamp(static_cast<int>(std::lround(p.x / dl)), 0, nx), std::clamp(static_cast<int>(std::lround(p.y / db)), 0, ny));
    sd.b = kGround;
    sd.point = Vector3d(p.x, p.y, 0);
    sd.stiffness << 0, 0, p.support.translational, p.support.rotational, p.support.rotational, 0;
    if (!sd.stiffness.any()) continue;
    m.supports.emplace_back(static_cast<int>(m.sdes.size()), fmt::format("points[{}]", k));
    m.sdes.push_back(sd);
  }
}

/// The scene's point masses, added to the rigid elements around them.
void add_plate_point_masses(Model& m, const Scene& s) {
  // Point masses: shared between the (up to) four centres around them by the bilinear weights of
  // point loads.
  for (const PointMass& pm : s.masses)
    for (auto [e, w] : point_weights(m, Vector3d(pm.x, pm.y, 0))) {
      RigidElement& r = m.elements[static_cast<std::size_t>(e)];
      r.mass += w * pm.mass;
      r.inertia += w * Vector3d(pm.Jx, pm.Jy, pm.Jz);
    }
}

/// The basis of corner-value coordinates (Kirchhoff with rigid transverse shear exact by construction).
void set_plate_corner_basis(Model& m, const PlateSetup& g) {
  const int nx = g.nx, ny = g.ny;
  const double a = g.a, b = g.b, dl = g.dl, db = g.db;
  // Coordinates c_pq, p = -1..nx, q = -1..ny: values at x_p = 0, (p + 1/2) dl, a (the ends and
  // the x-sides' midpoints of the cells) times y_q alike. Along one line of RFEs (the beam's
  // joint coordinates): w_i = (c_{i-1} + c_i) / 2 and dw/dx_i = (c_i - c_{i-1}) / dl inside,
  // w_0 = c_{-1} and w_n = c_n at the half-length ends (centred on the edge). A side's
  // midpoint then moves by the same c from both RFEs, so the shear deformation vanishes.
  struct Tap {
    int p;
    double value, slope;
  };
  auto line = [](int i, int n, double d) -> std::array<Tap, 2> {
    if (i == 0) return {{{-1, 1.0, -2.0 / d}, {0, 0.0, 2.0 / d}}};
    if (i == n) return {{{n - 1, 0.0, -2.0 / d}, {n, 1.0, 2.0 / d}}};
    return {{{i - 1, 0.5, -1.0 / d}, {i, 0.5, 1.0 / d}}};
  };
  // The map c -> (w, theta_x, theta_y) has one null vector, (-1)^(p+q) on the inner values
  // and 0 on the edge values (every cell sees its corners cancel): c_00 is fixed at 0.
  const int gauge = (nx + 2) + 1;
  auto value_index = [&](int p, int q) { return (q + 1) * (nx + 2) + (p + 1); };
  auto column = [&](int p, int q) {
    const int k = value_index(p, q);
    return k < gauge ? k : k - 1;
  };
  auto place = [](int p, int n, double d, double length) { return p < 0 ? 0.0 : p == n ? length : (p + 0.5) * d; };
  for (int q = -1; q <= ny; ++q)
    for (int p = -1; p <= nx; ++p)
      if (value_index(p, q) != gauge) {
        m.basis_names.push_back(fmt::format("c(x={:.6g}, y={:.6g})", place(p, nx, dl, a), place(q, ny, db, b)));
        m.basis_points.emplace_back(place(p, nx, dl, a), place(q, ny, db, b), 0.0);
      }
  const int kw = m.local_index(dofs::Uz), kx = m.local_index(dofs::Rx), ky = m.local_index(dofs::Ry);
  const int na = m.dofs_per_element();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(12 * (nx + 1) * (ny + 1)));
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const long row = static_cast<long>(g.id(i, j)) * na;
      for (const Tap& tx : line(i, nx, dl))
        for (const Tap& ty : line(j, ny, db)) {
          if (value_index(tx.p, ty.p) == gauge) continue;
          const int c = column(tx.p, ty.p);
          // theta_x = +dw/dy, theta_y = -dw/dx (right-handed rotations, w along +z).
          const double w = tx.value * ty.value, rx = tx.value * ty.slope, ry = -tx.slope * ty.value;
          if (w != 0.0) t.emplace_back(row + kw, c, w);
          if (rx != 0.0) t.emplace_back(row + kx, c, rx);
          if (ry != 0.0) t.emplace_back(row + ky, c, ry);
        }
    }
  m.basis.resize(m.body_dofs(), (nx + 2) * (ny + 2) - 1);
  m.basis.setFromTriplets(t.begin(), t.end());
}

}  // namespace

Model build_plate(const Scene& s, const PlateOptions& o) {
  if (!s.is_plate()) throw std::invalid_argument("build_plate: the scene is not a plate");
  if (o.nx < 1 || o.ny < 1)
    throw std::invalid_argument(fmt::format("build_plate: need >= 1 fragment per side (got {}x{})", o.nx, o.ny));
  const double a = s.geometry.length, b = s.geometry.width, h = s.geometry.height;
  const Material& mat = s.material;
  const bool kirchhoff = s.theory == Theory::Kirchhoff;
  const bool corners = kirchhoff && o.rigid_shear == RigidShear::JointCoordinates;
  const int nx = o.nx, ny = o.ny;
  const double dl = a / nx, db = b / ny;
  const double D = s.plate_D();
  const double Gh3_6 = mat.G * h * h * h / 6.0;  // = D (1 - nu): twisting rigidity
  const PlateSetup g{s, nx, ny, a, b, h, dl, db, kirchhoff, corners, D, Gh3_6};

  Model m = start_plate_model(g, o);
  add_plate_elements(m, g);
  add_plate_singularities(m, g);
  add_plate_sdes(m, g, fragment_torsion_spring(g));
  // Poisson coupling and Mindlin twist per fragment.
  if (o.bending_correction) {
    const auto Kc = std::make_shared<const Eigen::MatrixXd>(plate_fragment_correction(D, mat.nu, dl, db));
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        m.couplings.push_back({{g.id(i, j), g.id(i + 1, j), g.id(i, j + 1), g.id(i + 1, j + 1)}, Kc});
  }
  add_plate_edge_supports(m, g);
  add_plate_point_supports(m, g);
  add_plate_point_masses(m, s);
  if (corners) set_plate_corner_basis(m, g);

  m.omega_hint = 0.3 * pi * pi * (1 / (a * a) + 1 / (b * b)) * std::sqrt(D / (mat.rho * h));
  m.check();
  return m;
}

}  // namespace modalbench::rfem
