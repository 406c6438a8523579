// PrismModel: the operator of Eq. (32), loads and observations over the fields; build_model.
#include "modalbench/numerics/checked_inverse.hpp"
#include "modalbench/dtfm/prism_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "modalbench/rigid_kinematics.hpp"
#include "prism_model_detail.hpp"

namespace modalbench::dtfm {

std::string to_string(LayerModel l) {
  switch (l) {
    case LayerModel::Consistent: return "consistent";
    case LayerModel::Staggered: return "staggered";
    case LayerModel::Paper: return "paper";
  }
  return "?";
}

namespace {
using dofs::Rx;
using dofs::Ry;
using dofs::Uz;
}  // namespace

Eigen::MatrixXd PrismModel::A20() const {
  for (int k = 0; k < m; ++k)
    if (!(C(k, k) > 0)) throw std::logic_error("A20 does not exist: a strain is rigid (Euler-Bernoulli/Kirchhoff)");
  const Eigen::MatrixXd P = checked_inverse(C, "dtfm: the prism compliance C (A20 = -C^-1)");
  return -0.5 * (P + P.transpose());
}

Eigen::MatrixXd PrismModel::A10() const {
  const Eigen::MatrixXd P = -A20();
  const Eigen::MatrixXd R = P * S + X;
  return R.transpose() - R;
}

Eigen::MatrixXd PrismModel::A00() const {
  const Eigen::MatrixXd P = -A20();
  return S.transpose() * P * S + S.transpose() * X + X.transpose() * S + Q1;
}

Eigen::MatrixXd PrismModel::state_matrix(double lambda) const {
  const Eigen::MatrixXd St = S + C * X;
  const Eigen::MatrixXd Qt = Q1 - X.transpose() * C * X;
  Eigen::MatrixXd A(2 * m, 2 * m);
  A.topLeftCorner(m, m) = -St;
  A.topRightCorner(m, m) = C;
  A.bottomLeftCorner(m, m) = Qt - lambda * M;
  A.bottomRightCorner(m, m) = St.transpose();
  return A;
}

int PrismModel::field(int prism, int dof) const {
  for (int k = 0; k < m; ++k)
    if (field_prism[k] == prism && field_dof[k] == dof) return k;
  return -1;
}

namespace {
/// The two strip lines around y and the weight of the upper one.
void plate_bracket(const PrismModel& mdl, double y, int& j0, double& t) {
  const int n = static_cast<int>(mdl.prisms.size()) - 1;
  const double dl = mdl.prisms[1].y - mdl.prisms[0].y;
  j0 = std::clamp(static_cast<int>(std::floor(y / dl)), 0, n - 1);
  t = std::clamp((y - mdl.prisms[j0].y) / dl, 0.0, 1.0);
}

/// H = sum over prisms of D_i^T Lambda_i D_i over all six slots (the section's rigid-motion metric;
/// prisms cut from a rectangle are rectangles).
Matrix6d section_metric(const PrismModel& mdl) {
  Matrix6d H = Matrix6d::Zero();
  if (mdl.prisms.size() == 1) {
    // One prism is the whole section, of any shape: its own weights (A, Ip, Iy, Iz of a circle, a
    // tube, a general section), not a rectangle's; 1 on the motions the physics lacks.
    H.setIdentity();
    for (int k = 0; k < mdl.m; ++k) H(mdl.field_dof[k], mdl.field_dof[k]) = mdl.section_weights(k, k);
    return H;
  }
  for (const auto& g : mdl.prisms) {
    const Section sec = rectangular_section(g.width, g.height);
    Vector6d w;
    w << sec.A, sec.A, sec.A, sec.Ip, sec.Iy, sec.Iz;
    const Matrix6d D = attachment(Eigen::Vector3d(0, g.y, g.z));
    H += D.transpose() * w.asDiagonal() * D;
  }
  return H;
}
}  // namespace

Eigen::VectorXd PrismModel::load_vector(const PointLoad& load) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(m);
  if (kind == SceneKind::Plate) {
    int j0;
    double t;
    plate_bracket(*this, load.y, j0, t);
    // Fz on w, Mx on theta_x, My on theta_y of the two lines, as section_response interpolates them.
    for (const auto& [dof, value] : {std::pair{Uz, load.Fz}, std::pair{Rx, load.Mx}, std::pair{Ry, load.My}}) {
      const int k0 = field(j0, dof), k1 = field(j0 + 1, dof);
      if (k0 >= 0) f[k0] += (1.0 - t) * value;
      if (k1 >= 0) f[k1] += t * value;
    }
    return f;
  }
  Vector6d F;
  F << load.Fx, load.Fy, load.Fz, load.Mx, load.My, load.Mz;
  const Vector6d r = checked_symmetric_solve(section_metric(*this), F, "dtfm: the section metric (load distribution)");
  return section_weights * rigid_motions * r;
}

Eigen::VectorXd PrismModel::pressure_vector(const DistributedLoad& pressure) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(m);
  if (kind != SceneKind::Plate) return f;
  const double dl = prisms[1].y - prisms[0].y, b = prisms.back().y;
  const double lo = std::clamp(pressure.from[1], 0.0, b), hi = std::clamp(pressure.to[1], 0.0, b);
  // The integral of the hat of half-width dl centred at 0 from -inf to t.
  auto F = [dl](double t) {
    if (t <= -dl) return 0.0;
    if (t <= 0.0) return (t + dl) * (t + dl) / (2 * dl);
    if (t <= dl) return dl - (dl - t) * (dl - t) / (2 * dl);
    return dl;
  };
  for (std::size_t j = 0; j < prisms.size(); ++j) {
    const int k = field(static_cast<int>(j), Uz);
    if (k >= 0) f[k] += pressure.qz[0] * (F(hi - prisms[j].y) - F(lo - prisms[j].y));
  }
  return f;
}

Deflection PrismModel::section_response(const Eigen::VectorXd& q, double y) const {
  Deflection d;
  if (kind == SceneKind::Plate) {
    int j0;
    double t;
    plate_bracket(*this, y, j0, t);
    auto value = [&](int dof) {
      const int k0 = field(j0, dof), k1 = field(j0 + 1, dof);
      return (k0 >= 0 ? (1.0 - t) * q[k0] : 0.0) + (k1 >= 0 ? t * q[k1] : 0.0);
    };
    d.w = value(Uz);
    d.theta_x = value(Rx);
    d.theta_y = value(Ry);
    return d;
  }
  const Vector6d r = checked_symmetric_solve(section_metric(*this), Vector6d(rigid_motions.transpose() * section_weights * q),
                                             "dtfm: the section metric (section response)");
  // Components the physics does not carry stay 0 (their rows are absent from rigid_motions).
  d.u = r[0];
  d.v = r[1];
  d.w = r[2];
  d.theta_x = r[3];
  d.theta_y = r[4];
  d.theta_z = r[5];
  return d;
}

Eigen::RowVectorXd PrismModel::w_observer(double y) const {
  if (kind == SceneKind::Plate) {
    int j0;
    double t;
    plate_bracket(*this, y, j0, t);
    Eigen::RowVectorXd o = Eigen::RowVectorXd::Zero(m);
    const int k0 = field(j0, Uz), k1 = field(j0 + 1, Uz);
    if (k0 >= 0) o[k0] = 1.0 - t;
    if (k1 >= 0) o[k1] = t;
    return o;
  }
  // Conjugate of a unit Fz: w_section = (load vector of Fz = 1)^T q.
  PointLoad unit;
  unit.Fz = 1.0;
  return load_vector(unit).transpose();
}

namespace {
/// Point masses lower the first mode below the builders' scale (the structure's own mass alone) as
/// a Rayleigh quotient would, stiffness over total mass: the scale sets the slicing's absolute floor
/// (1e-14 of it) and the rigid threshold, so a shaft of 1.6e-8 of its disc's mass had its first
/// whirl 2e-7 off (the floor 1e-6 of omega^2) before.
void mass_scale(PrismModel& mdl, const Scene& s) {
  double own = 0, points = 0;
  if (s.is_plate()) own = s.material.rho * s.geometry.length * s.geometry.width * s.geometry.height;
  else
    for (const Segment& p : s.beam_pieces()) own += p.material.rho * p.properties().A * p.length();
  for (const PointMass& pm : s.masses) points += pm.mass;
  if (points > 0 && own > 0) mdl.lambda_scale *= own / (own + points);
}
}  // namespace

PrismModel build_model(const Scene& scene, const Discretization& mesh, const ModelOptions& options) {
  const auto bad = [&](const std::string& why) { throw InputError("command line", "--mesh", why); };
  if (scene.is_plate()) {
    if (mesh.counts.size() != 1)
      bad("the dtfm plate mesh is the number of strips across the width, e.g. 10 (got '" + mesh.spec() + "')");
    const int n = mesh.counts[0];
    if (n < 2 || n > 400) bad("the number of strips must lie in [2, 400] (got " + std::to_string(n) + ")");
    PrismModel mdl = detail::build_plate(scene, n, options);
    detail::add_points(mdl, scene);
    mass_scale(mdl, scene);
    return mdl;
  }
  int ny = 0, nz = 0;
  if (mesh.counts.size() == 1) ny = nz = mesh.counts[0];
  else if (mesh.counts.size() == 2) {
    ny = mesh.counts[0];
    nz = mesh.counts[1];
  } else {
    bad("the dtfm beam mesh is NYxNZ prisms across the width and height, e.g. 2x2 (got '" + mesh.spec() + "')");
  }
  if (scene.physics == Physics::Lateral && ny * nz > 1)
    bad(fmt::format("a lateral (rotor) model is one prism per section in dtfm (1x1): the spin's gyroscopic moment "
                    "acts on the section's rotation, which a cut section does not have as one field (got {}x{})",
                    ny, nz));
  const int per = scene.physics == Physics::Spatial ? 6 : 3;
  const long fields = static_cast<long>(scene.physics == Physics::Spatial ? ny : 1) * nz * per;
  if (ny > 64 || nz > 64 || fields > 800)
    bad(fmt::format("{}x{} prisms give {} fields: at most 800 (and 64 prisms per side) are supported", ny, nz,
                    fields));
  if (scene.is_stepped() && ny * nz > 1)
    bad(fmt::format("a stepped beam ([[segments]]) is one prism per section in dtfm (1x1): its pieces' sections "
                    "would each need their own cut (got {}x{})", ny, nz));
  PrismModel mdl = scene.is_stepped() ? detail::build_beam(detail::piece_scene(scene, scene.segments.front()), ny, nz, options)
                                      : detail::build_beam(scene, ny, nz, options);
  if (scene.is_stepped()) detail::add_steps(mdl, scene, ny, nz, options);
  detail::add_points(mdl, scene);
  mass_scale(mdl, scene);
  return mdl;
}

}  // namespace modalbench::dtfm
