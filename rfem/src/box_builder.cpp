// A box of cubic rigid elements (builders.hpp): the 3D test structure.
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

Model build_box(const BoxSpec& sp) {
  if (sp.nx < 1 || sp.ny < 1 || sp.nz < 1 || !(sp.edge > 0))
    throw std::invalid_argument("build_box: need >= 1 cube per direction and edge > 0");
  const Material& mat = sp.material;
  if (!(mat.E > 0 && mat.G > 0 && mat.rho > 0 && mat.kappa > 0))
    throw std::invalid_argument("build_box: material E, G, rho, kappa must be > 0");
  const double d = sp.edge;
  const Section sq = rectangular_section(d, d);
  Model m;
  m.active = dofs::kSpatial;
  m.dof_family.assign(6, ModeFamily::Unknown);
  m.length_scale = d * std::max({sp.nx, sp.ny, sp.nz});
  m.loss_factor = mat.loss_factor;
  m.description = fmt::format("box: {}x{}x{} rigid cubes of edge {} m, face SDEs{}", sp.nx, sp.ny, sp.nz, d,
                              sp.clamp_x0 ? ", face x = 0 held through half-cube SDEs" : ", free");
  auto id = [&](int i, int j, int k) { return (k * sp.ny + j) * sp.nx + i; };
  for (int k = 0; k < sp.nz; ++k)
    for (int j = 0; j < sp.ny; ++j)
      for (int i = 0; i < sp.nx; ++i) {
        RigidElement r;
        r.centre = Vector3d((i + 0.5) * d, (j + 0.5) * d, (k + 0.5) * d);
        r.mass = mat.rho * d * d * d;
        r.inertia = Vector3d::Constant(r.mass * d * d / 6.0);
        r.cell = box(i * d, (i + 1) * d, j * d, (j + 1) * d, k * d, (k + 1) * d);
        r.label = fmt::format("cube ({},{},{})", i, j, k);
        m.elements.push_back(r);
      }
  Vector6d kk;
  kk << mat.E * d, mat.kappa * mat.G * d, mat.kappa * mat.G * d, mat.G * sq.J / d, mat.E * sq.Iy / d, mat.E * sq.Iz / d;
  const Eigen::Vector3d ex = Vector3d::UnitX(), ey = Vector3d::UnitY(), ez = Vector3d::UnitZ();
  Eigen::Matrix3d Rx, Ry, Rz;
  Rx << ex, ey, ez;
  Ry << ey, ez, ex;
  Rz << ez, ex, ey;
  for (int k = 0; k < sp.nz; ++k)
    for (int j = 0; j < sp.ny; ++j)
      for (int i = 0; i < sp.nx; ++i) {
        const int me = id(i, j, k);
        const Vector3d c = m.elements[static_cast<std::size_t>(me)].centre;
        auto link = [&](int other, const Eigen::Matrix3d& R, const Vector3d& dir) {
          Sde sd;
          sd.a = me;
          sd.b = other;
          sd.point = c + 0.5 * d * dir;
          sd.axes = R;
          sd.stiffness = kk;
          m.sdes.push_back(sd);
        };
        if (i + 1 < sp.nx) link(id(i + 1, j, k), Rx, ex);
        if (j + 1 < sp.ny) link(id(i, j + 1, k), Ry, ey);
        if (k + 1 < sp.nz) link(id(i, j, k + 1), Rz, ez);
        if (sp.clamp_x0 && i == 0) {  // the half cube between the held face and the centre
          Sde g;
          g.a = me;
          g.b = kGround;
          g.point = c - 0.5 * d * ex;
          g.stiffness = 2.0 * kk;
          m.sdes.push_back(g);
        }
      }
  const double Lmax = m.length_scale;
  const double bar = 0.5 * pi / Lmax * std::sqrt(mat.E / mat.rho);
  const double tmin = d * std::min({sp.nx, sp.ny, sp.nz});
  const double bend = 0.35 * std::pow(pi / Lmax, 2) * std::sqrt(mat.E * tmin * tmin / (12 * mat.rho));
  m.omega_hint = std::min(bar, bend);
  m.check();
  return m;
}

}  // namespace modalbench::rfem
