// Beam prism models with steps, supports between the ends and point masses (add_steps, add_points).
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "prism_model_detail.hpp"

namespace modalbench::dtfm::detail {

namespace {

/// The field pattern of each unit section resultant (m x 6, columns Fx, Fy, Fz, Mx, My, Mz): how a
/// point load spreads over the prisms. Its transpose maps the fields to the section's resultant
/// motion (the work conjugate), on which supports and masses at points act.
Eigen::MatrixXd resultant_spread(const PrismModel& mdl, double y) {
  Eigen::MatrixXd S(mdl.m, 6);
  for (int d = 0; d < 6; ++d) {
    PointLoad unit;
    unit.y = y;  // a plate's point (its two strip lines); a beam's axis
    double* comp[6] = {&unit.Fx, &unit.Fy, &unit.Fz, &unit.Mx, &unit.My, &unit.Mz};
    *comp[d] = 1.0;
    S.col(d) = mdl.load_vector(unit);
  }
  // Rounding of the section metric's solve is not a spread (a motion the physics lacks).
  const double floor = 64.0 * std::numeric_limits<double>::epsilon() * S.cwiseAbs().maxCoeff();
  return S.unaryExpr([floor](double v) { return std::abs(v) <= floor ? 0.0 : v; });
}

/// Adds, to a condition, springs k (inf: held) and masses on the section's resultant motions
/// r = spread^T q of the motions the model carries (spread columns that are not zero).
void add_to(EndCondition& e, const Eigen::MatrixXd& spread, const std::array<double, 6>& k,
            const std::array<double, 6>& mass) {
  const int m = static_cast<int>(spread.rows());
  std::vector<int> held, sprung, massive;
  for (int d = 0; d < 6; ++d) {
    if (spread.col(d).norm() == 0.0) continue;
    if (std::isinf(k[d])) held.push_back(d);
    else if (k[d] > 0) sprung.push_back(d);
    if (mass[d] > 0) massive.push_back(d);
  }
  if (!held.empty()) {
    // The admissible motions left: N Z, Z spanning the null space of (N^T H)^T.
    Eigen::MatrixXd Hn(e.N.cols(), static_cast<Eigen::Index>(held.size()));
    for (std::size_t i = 0; i < held.size(); ++i) Hn.col(static_cast<Eigen::Index>(i)) = e.N.transpose() * spread.col(held[i]);
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Hn);
    qr.setThreshold(1e-10);
    const Eigen::Index r = qr.rank(), n = Hn.rows();
    const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(n, n);
    Eigen::MatrixXd Z = Q.rightCols(n - r);
    const double floor = 64.0 * std::numeric_limits<double>::epsilon();
    Z = Z.unaryExpr([floor](double v) { return std::abs(v) <= floor ? 0.0 : v; });
    e.N = (e.N * Z).eval();
    e.K = (Z.transpose() * e.K * Z).eval();
  }
  for (int d : sprung) {
    const Eigen::VectorXd g = e.N.transpose() * spread.col(d);
    e.K += k[d] * g * g.transpose();
  }
  if (!massive.empty() && e.mass.size() == 0) e.mass = Eigen::MatrixXd::Zero(m, m);
  for (int d : massive) e.mass += mass[d] * spread.col(d) * spread.col(d).transpose();
}

/// A plate with points: points off its middle line break the reflection y -> b - y (one class
/// then), and held points restrain rigid motions (springs make them near-rigid: -1).
void plate_points_done(PrismModel& mdl, const Scene& s) {
  bool symmetric = true, spring = mdl.rigid_body_motions < 0;
  const double b = s.geometry.width;
  for (const PointSupport& p : s.point_supports) {
    symmetric = symmetric && std::abs(p.y - b / 2) <= 1e-12 * b;
    for (double k : {p.support.translational, p.support.rotational}) spring = spring || (k != 0.0 && !std::isinf(k));
  }
  for (const PointMass& p : s.masses) symmetric = symmetric && std::abs(p.y - b / 2) <= 1e-12 * b;
  if (!symmetric && !mdl.reflections.empty()) {
    mdl.reflections.clear();
    mdl.classes.clear();
    build_classes(mdl, {ModeFamily::Plate}, {});
  }
  mdl.rigid_body_motions = spring ? -1 : static_cast<int>(free_plate_rigid_motions(s).size());
}

}  // namespace

void add_points(PrismModel& mdl, const Scene& s) {
  if (s.point_supports.empty() && s.masses.empty()) return;
  const double L = mdl.length;
  auto condition_at = [&](double x) -> EndCondition& {
    if (std::abs(x) <= 1e-12 * L) return mdl.ends[0];
    if (std::abs(x - L) <= 1e-12 * L) return mdl.ends[1];
    for (auto& p : mdl.points)
      if (std::abs(p.x - x) <= 1e-12 * L) return p.cond;
    PointCondition pc;
    pc.x = x;
    pc.cond.N = Eigen::MatrixXd::Identity(mdl.m, mdl.m);
    pc.cond.K = Eigen::MatrixXd::Zero(mdl.m, mdl.m);
    mdl.points.push_back(pc);
    return mdl.points.back().cond;
  };
  const std::array<double, 6> none = {0, 0, 0, 0, 0, 0};
  for (std::size_t i = 0; i < s.point_supports.size(); ++i) {
    const Support& sp = s.point_supports[i].support;
    EndCondition& e = condition_at(s.point_supports[i].x);
    // A beam's section: axial, both translations, twist, both bending rotations; a plate's point:
    // w and both rotations (a pinned point holds w only: its twist is a beam's).
    const std::array<double, 6> k =
        mdl.kind == SceneKind::Plate
            ? std::array<double, 6>{0, 0, sp.translational, sp.rotational, sp.rotational, 0}
            : std::array<double, 6>{sp.axial, sp.translational, sp.translational, sp.torsional, sp.rotational, sp.rotational};
    add_to(e, resultant_spread(mdl, s.point_supports[i].y), k, none);
    e.text += fmt::format("{}points[{}]: {}", e.text.empty() ? "" : "; ", i, sp.kind);
  }
  for (std::size_t i = 0; i < s.masses.size(); ++i) {
    const PointMass& pm = s.masses[i];
    EndCondition& e = condition_at(pm.x);
    add_to(e, resultant_spread(mdl, pm.y), none, {pm.mass, pm.mass, pm.mass, pm.Jx, pm.Jy, pm.Jz});
    e.text += fmt::format("{}masses[{}]: {:g} kg", e.text.empty() ? "" : "; ", i, pm.mass);
  }
  std::sort(mdl.points.begin(), mdl.points.end(),
            [](const PointCondition& a, const PointCondition& b) { return a.x < b.x; });
  if (mdl.kind == SceneKind::Plate) plate_points_done(mdl, s);
}

void add_disc_gyro(PrismModel& mdl, const Scene& s) {
  const double L = mdl.length;
  for (const PointMass& pm : s.masses) {
    if (pm.Jx == 0.0) continue;
    EndCondition* e = nullptr;
    if (std::abs(pm.x) <= 1e-12 * L) e = &mdl.ends[0];
    else if (std::abs(pm.x - L) <= 1e-12 * L) e = &mdl.ends[1];
    for (auto& p : mdl.points)
      if (std::abs(p.x - pm.x) <= 1e-12 * L) e = &p.cond;
    if (!e) throw std::logic_error("dtfm: a disc's node is missing from the model");
    const Eigen::VectorXd my = resultant_spread(mdl, pm.y).col(4);  // the section's theta_y
    if (e->gyro.size() == 0) e->gyro = Eigen::MatrixXd::Zero(mdl.m, mdl.m);
    e->gyro += pm.Jx * my * my.transpose();
  }
}

Scene piece_scene(const Scene& s, const Segment& piece) {
  Scene u = s;
  u.segments.clear();
  u.point_supports.clear();
  u.masses.clear();
  u.geometry.width = piece.width;
  u.geometry.height = piece.height;
  u.cross_section = piece.section;
  u.material = piece.material;
  return u;
}

void add_steps(PrismModel& mdl, const Scene& s, int ny, int nz, const ModelOptions& opt) {
  const std::vector<Segment> pieces = s.beam_pieces();
  mdl.first_piece_to = pieces.front().x_to;
  for (std::size_t i = 1; i < pieces.size(); ++i) {
    const PrismModel p = build_beam(piece_scene(s, pieces[i]), ny, nz, opt);
    if (p.m != mdl.m || p.field_dof != mdl.field_dof)
      throw std::logic_error("dtfm: the pieces of a stepped beam have different fields");
    mdl.steps.push_back({pieces[i].x_to, p.M, p.C, p.S, p.X, p.Q1, {}});
  }
  mdl.description += fmt::format(", {} pieces (stepped)", pieces.size());
}

}  // namespace modalbench::dtfm::detail
